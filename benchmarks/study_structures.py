"""Study: which heat paths let the measurements be explained (issue 32, the nut side and the base).

Run:  .venv/bin/python benchmarks/study_structures.py [--variants declared,base_on_feet,...] [--json]

Each variant is the bundled paper bench with one structural change, made in memory; none is
declared in the bench.  For each, the study reports

- the inference's chi-square per condition (`feedtherm infer`'s: every heat free, sigma 0.5 K and
  2 um, six measured values per condition; issue 32's target is at most 3 x 6 = 18), and the heat
  it puts on the nut side (nut motor + nut bearing), beside the loss models';
- physics mode, nothing fitted: the largest |simulated - measured| temperature over the five
  conditions (`feedtherm validate`'s figure).

Variants:

- ``declared``: the bench as bundled.
- ``base_on_feet``: the base plate's underside exchanges 5 W/(m^2 K) with what is under it (the
  lower end of the foundation's declared calibration range: a plate on levelling feet, as the
  declared 3-2-1 supports describe) instead of the declared 800 (bolted to a bed at the ambient).
- ``nut_bearing_balls``: the nut bearing as two rings that exchange heat only through the balls,
  0.5 W/K between them (a Hertz-contact estimate, below), each ring taking half its friction heat;
  ``nut_bearing_balls_x10`` the same with 5 W/K.
- ``both``: ``base_on_feet`` and ``nut_bearing_balls``.

The 0.5 W/K: a 7010 pair has two rows of about 18 balls; each ball touches its two raceways over
Hertz ellipses of about 0.3 mm equivalent radius at the light preload, and each contact's
constriction resistance between two steel half-spaces is 1/(2 k a) = 1/(2 * 40 * 0.3e-3) = 42 K/W
(Yovanovich's circular-contact result), so a ball conducts 1/84 W/K and 36 balls 0.43 W/K; the
grease around the balls adds a little.  An order of magnitude, which is why the x10 variant is run.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from feedtherm.analysis.inverse import Noise, infer_conditions
from feedtherm.analysis.validation import measurements_of, validate
from feedtherm.system.load import parse_toml, read_text, validate_data

RESULTS = Path(__file__).resolve().parent / "results"
VARIANTS = ("declared", "base_on_feet", "nut_bearing_balls", "nut_bearing_balls_x10", "both")
NUT_SIDE = ("nut_motor", "nut_bearing")


def _base_on_feet(data: dict) -> None:
    data["surfaces"]["base_bottom"]["convection"]["coefficient"] = "5 W/(m^2*K)"


def _nut_bearing_balls(conductance_w_per_k: float):
    def edit(data: dict) -> None:
        bearing = data["parts"]["nut_bearing"]
        ring = dict(bearing["cylinders"][0])
        inner = {**ring, "outer_diameter": "65 mm"}
        bearing["cylinders"] = [{**ring, "inner_diameter": "65 mm"}]
        data["parts"]["nut_bearing_inner"] = {"material": bearing["material"], "moving": True, "cylinders": [inner]}
        area = 3.14159265 * 0.065 * 0.032  # the rings' common cylinder, pi * 65 mm * 32 mm
        for joint in data["joints"]:
            if sorted(joint["between"]) == ["nut", "nut_bearing"]:
                joint["between"] = ["nut_bearing_inner", "nut"]
        data["joints"].append({"between": ["nut_bearing", "nut_bearing_inner"],
                               "tcr": f"{area / conductance_w_per_k!r} m^2*K/W", "area": f"{area!r} m^2",
                               "description": "through the balls"})
        data["sources"]["nut_bearing"]["into"] = {"nut_bearing": 0.5, "nut_bearing_inner": 0.5}
    return edit


EDITS = {
    "declared": [],
    "base_on_feet": [_base_on_feet],
    "nut_bearing_balls": [_nut_bearing_balls(0.5)],
    "nut_bearing_balls_x10": [_nut_bearing_balls(5.0)],
    "both": [_base_on_feet, _nut_bearing_balls(0.5)],
}


def variant(name: str):
    text, origin = read_text("paper")
    data = parse_toml(text, origin)
    for edit in EDITS[name]:
        edit(data)
    return validate_data(data, f"bundled:paper ({name})")


def study(name: str) -> dict:
    loaded = variant(name)
    data = measurements_of(loaded, None)
    conditions = data.conditions()
    inferred = infer_conditions(loaded, data, conditions, noise=Noise(0.5, 2e-6))
    worst = validate(loaded).largest("temperature")
    return {
        "variant": name,
        "chi2": {i.condition: round(i.chi2, 1) for i in inferred},
        "nut_side_inferred_W": {i.condition: round(sum(e.inferred for e in i.estimates if e.group in NUT_SIDE), 1)
                                for i in inferred},
        "nut_side_loss_models_W": {i.condition: round(sum(e.loss_model for e in i.estimates if e.group in NUT_SIDE), 1)
                                   for i in inferred},
        "physics_worst_temperature": f"{abs(worst.deviation):.1f} K ({worst.condition} {worst.quantity})",
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", default=",".join(VARIANTS))
    parser.add_argument("--json", action="store_true", help="print the results as JSON too")
    args = parser.parse_args()
    names = [v.strip() for v in args.variants.split(",") if v.strip()]
    unknown = [v for v in names if v not in EDITS]
    if unknown:
        parser.error(f"--variants: unknown {', '.join(unknown)}; known: {', '.join(VARIANTS)}")
    started = time.perf_counter()
    rows = []
    for name in names:
        row = study(name)
        rows.append(row)
        chi2 = ", ".join(f"{v:.1f}" for v in row["chi2"].values())
        nut = ", ".join(f"{v:.0f}" for v in row["nut_side_inferred_W"].values())
        prior = ", ".join(f"{v:.0f}" for v in row["nut_side_loss_models_W"].values())
        print(f"{name:22s} chi2 {chi2}; nut side inferred {nut} W (loss models {prior}); "
              f"physics worst {row['physics_worst_temperature']}")
    RESULTS.mkdir(exist_ok=True)
    out = RESULTS / "study_structures.json"
    out.write_text(json.dumps({"rows": rows, "wall_time_s": time.perf_counter() - started}, indent=2, default=str))
    if args.json:
        print(json.dumps(rows, indent=2, default=str))
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
