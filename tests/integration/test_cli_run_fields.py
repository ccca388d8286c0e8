"""`feedtherm run --model fem` and `--model reduced` as a user runs them: the thermal error's files,
and the reduced model's projection read back from the cache the command filled.

Each run writes the displacement field into its VTU series (a point array ``displacement``, three
components, that ParaView's Warp By Vector reads), the positioning error along the stroke, and the
image of the screw's axial deformation; the reduced model's match the FE model's.  The runs share
one fresh cache, so the reduced model's projection is built once (by the command) and the tests
after it read it back.
"""

import csv
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest


DURATION = "600"  # [s]


def run(cwd, *args, env=None):
    return subprocess.run([sys.executable, "-m", "feedtherm", "run", *args], capture_output=True, text=True,
                          timeout=600, cwd=cwd, env=env)


def displacement_arrays(folder):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    arrays = []
    for dataset in ET.parse(folder / "fields.pvd").getroot().find("Collection"):
        reader = vtkXMLUnstructuredGridReader()
        reader.SetFileName(str(folder / dataset.get("file")))
        reader.Update()
        assert reader.GetErrorCode() == 0
        arrays.append(vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("displacement")))
    return arrays


def positioning(folder):
    with open(folder / "positioning_error.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    return rows[0], np.array(rows[1:], dtype=float)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    import os

    cwd = tmp_path_factory.mktemp("fields")
    env = {**os.environ, "FEEDTHERM_CACHE": str(cwd / "cache")}
    out = {}
    for model in ("fem", "reduced"):
        result = run(cwd, "--condition", "I", "--model", model, "--mesh", "coarse", "--duration", DURATION,
                     "--out", model, env=env)
        assert result.returncode == 0, result.stderr[-2000:]
        out[model] = cwd / model
    out["cache"] = cwd / "cache"
    return out


def sensors(folder):
    with open(folder / "sensors.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    return {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}


@pytest.mark.parametrize("model", ["fem", "reduced"])
def test_the_run_writes_the_displacement_field_the_positioning_error_and_the_image(runs, model):
    folder = runs[model]
    arrays = displacement_arrays(folder)
    assert len(arrays) >= 2 and all(a.ndim == 2 and a.shape[1] == 3 for a in arrays)
    assert np.abs(arrays[-1]).max() > 1e-6  # metres: a warm bench moves by micrometres
    assert np.all(np.isfinite(arrays[-1]))
    header, table = positioning(folder)
    assert header[0] == "time_s" and all(h.startswith("x_mm=") for h in header[1:])
    assert table.shape[1] == len(header) and np.all(np.isfinite(table))
    png = (folder / "screw_axial_deformation.png").read_bytes()
    assert png.startswith(b"\x89PNG")
    summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    assert summary["positioning_error"]["max_abs_um"] > 0.0


def test_the_reduced_models_fields_follow_the_fe_models(runs):
    fem, reduced = displacement_arrays(runs["fem"]), displacement_arrays(runs["reduced"])
    assert len(fem) == len(reduced)
    # within 2 % of the field's largest value everywhere: the belt (α = 1.5e-4 1/K, ten times the
    # steel's) turns the basis's small temperature errors into the field's largest differences
    scale = np.abs(fem[-1]).max()
    for a, b in zip(fem, reduced):
        assert np.abs(a - b).max() <= 0.02 * scale
    (_, e_fem), (_, e_reduced) = positioning(runs["fem"]), positioning(runs["reduced"])
    assert np.abs(e_fem[:, 1:] - e_reduced[:, 1:]).max() <= 0.2  # µm, as D (test_reduced_model.py)


def test_the_reduced_runs_readings_follow_the_fe_runs(runs):
    fem, reduced = sensors(runs["fem"]), sensors(runs["reduced"])
    np.testing.assert_array_equal(fem["time_s"], reduced["time_s"])
    for name in ("T1", "T2", "T3", "T4", "T5"):
        assert np.abs(reduced[name] - fem[name]).max() <= 0.1, name  # K
    assert np.abs(reduced["D_um"] - fem["D_um"]).max() <= 0.2  # µm
    summary = json.loads((runs["reduced"] / "summary.json").read_text(encoding="utf-8"))
    stats = summary["mesh"]
    assert not stats["projection_cached"]  # the command built it in the fresh cache
    assert stats["trained_over"] == "description"  # a single run's basis: at its own numbers (models/reduced/store.py)
    assert stats["basis_size"] < stats["reduced_from"] // 20


def test_the_next_reduced_run_reads_the_projection_back_without_building_the_fe_model(runs, paper, monkeypatch):
    from feedtherm.models import registry
    from feedtherm.simulate import execute, plan_run

    monkeypatch.setenv("FEEDTHERM_CACHE", str(runs["cache"]))

    def no_fe_model(*args):
        raise AssertionError("a cached reduced model built its FE model")

    monkeypatch.setattr(registry, "_fem", no_fe_model)
    again = execute(plan_run(paper, condition="I", duration=float(DURATION), model="reduced", mesh="coarse"))
    assert again.info["mesh_statistics"]["projection_cached"]
    written = sensors(runs["reduced"])
    for name in ("T1", "T2", "T3", "T4", "T5"):  # the command's values, to the file's 4 decimals
        np.testing.assert_allclose(again.sensors[name] - 273.15, written[name], rtol=0.0, atol=6e-5)
    np.testing.assert_allclose(again.elongation * 1e6, written["D_um"], rtol=0.0, atol=6e-5)
    assert again.fields is not None and again.fields.displacements.shape[0] == len(displacement_arrays(runs["reduced"]))
    np.testing.assert_allclose(again.fields.displacements[-1], displacement_arrays(runs["reduced"])[-1],
                               rtol=0.0, atol=1e-6 * np.abs(again.fields.displacements[-1]).max())


def test_the_fe_models_reading_rows_are_its_probes(runs, paper, monkeypatch):
    import scipy.sparse as sp

    from feedtherm.simulate import plan_run

    monkeypatch.setenv("FEEDTHERM_CACHE", str(runs["cache"]))  # its mesh is cached there
    plan = plan_run(paper, condition="I", duration=float(DURATION), model="fem", mesh="coarse")
    fe = plan.model.build(paper.system, plan.options)
    rows, offset = fe.probe_rows(0)
    assert fe.probe_rows(17)[0] is rows  # the FE model's readings do not depend on the position
    T = 293.15 + np.random.default_rng(5).normal(size=fe.n_nodes)
    read, probed = rows @ T + offset, fe.probe(T, 17)
    assert np.allclose(read[:-1], probed[:-1], rtol=1e-14, atol=0.0)
    assert abs(read[-1] - probed[-1]) <= 1e-15  # D [m]: the thermoelastic reading row, the same either way
    assert sp.issparse(fe.conductance(0))
