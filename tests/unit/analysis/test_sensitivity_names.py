"""Sensitivity rows name a joint by the parts it joins, not only by its index."""

from feedtherm.analysis.sensitivity import perturbable_paths, readable_name
from feedtherm.system.load import load_system


def test_joint_paths_get_the_names_of_their_parts():
    paper = load_system("paper")
    index = next(i for i, j in enumerate(paper.system.joints) if set(j.between) == {"nut", "screw"})
    a, b = paper.system.joints[index].between
    assert readable_name(paper, f"joints[{index}].tcr") == f"joint {a}–{b}: tcr"
    assert readable_name(paper, "sources.front_bearing.preload") == ""  # already a name
    assert readable_name(paper, "joints[999].tcr") == ""  # no such joint: the path stays as it is


def test_every_perturbed_joint_value_has_a_name():
    paper = load_system("paper")
    joint_paths = [p for p in perturbable_paths(paper) if p.startswith("joints[")]
    assert joint_paths and all(readable_name(paper, p).startswith("joint ") for p in joint_paths)
