"""`feedtherm run --model fem` and `--model reduced` as a user runs them: the thermal error's files.

Each run writes the displacement field into its VTU series (a point array ``displacement``, three
components, that ParaView's Warp By Vector reads), the positioning error along the stroke, and the
image of the screw's axial deformation; the reduced model's match the FE model's.
"""

import csv
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest


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
        result = run(cwd, "--condition", "I", "--model", model, "--mesh", "coarse", "--duration", "600",
                     "--out", model, env=env)
        assert result.returncode == 0, result.stderr[-2000:]
        out[model] = cwd / model
    return out


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
