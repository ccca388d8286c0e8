"""FE field output: fields.pvd + .vtu snapshots (read back with meshio and with VTK's own reader) and
the PNG images.

The field is synthetic: a fixed "base" box and a moving "table" box on top of it, meshed
separately on the same grid lines (no shared nodes), with a temperature rising along x; for
the displacement outputs, a fixed slender "screw" bar beside them and a displacement field.
"""

from __future__ import annotations

import struct
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from skfem import MeshTet

from feedtherm.outputs import field_images, render
from feedtherm.outputs.field_images import (
    SCREW_AXIAL_DEFORMATION_PNG,
    SCREW_DEFORMATION_PNG,
    TEMPERATURE_FIELD_PNG,
    Surface,
    View,
    plot_screw_axial_deformation,
    plot_screw_deformation,
    write_field_images,
)
from feedtherm.outputs.fields import FieldSeries, boundary_triangles, write_pvd
from feedtherm.outputs.vtu import TetSeriesWriter

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
K = 273.15
TIMES = np.array([0.0, 600.0, 1800.0])
OFFSETS = np.array([0.0, 0.05, -0.05])  # [m]: whole grid cells, so the table's faces stay on the base's


def box(x0, x1, y0, y1, z0, z1, n=(4, 2, 1)):
    mesh = MeshTet.init_tensor(np.linspace(x0, x1, n[0] + 1), np.linspace(y0, y1, n[1] + 1), np.linspace(z0, z1, n[2] + 1))
    return mesh.p.T, mesh.t.T


def make_series(**changes) -> FieldSeries:
    """Base 0.4 × 0.2 × 0.05 m (fixed), table 0.2 × 0.2 × 0.03 m on top (moving); T = 20 °C + 100 K/m · x."""
    base_p, base_t = box(0.0, 0.4, 0.0, 0.2, 0.0, 0.05, (8, 4, 1))
    table_p, table_t = box(0.1, 0.3, 0.0, 0.2, 0.05, 0.08, (4, 4, 1))
    points = np.vstack([base_p, table_p])
    tets = np.vstack([base_t, table_t + len(base_p)])
    part_id = np.r_[np.zeros(len(base_t), int), np.ones(len(table_t), int)]
    rise = np.array([0.0, 0.5, 1.0])[:, None]
    temperatures = K + 20.0 + rise * 100.0 * points[:, 0][None, :]
    screw_x = np.linspace(0.0, 0.4, 41)
    displacement = rise * 11.5e-6 * 100.0 * screw_x[None, :] ** 2 / 2  # ∫ α ΔT dx with ΔT = 100 K/m · x
    values = dict(
        points=points, tets=tets, part_id=part_id, part_names=["base", "table"], moving_part=[False, True],
        snapshot_times=TIMES, temperatures=temperatures, offsets=OFFSETS, screw_x=screw_x,
        screw_displacement=displacement, title="two boxes, test",
    )
    values.update(changes)
    return FieldSeries(**values)


def make_screw_series(**changes) -> FieldSeries:
    """make_series's boxes and a fixed "screw" bar beside them (0.4 × 0.02 × 0.02 m, its own nodes), with a
    displacement field: u_x = α · (100 K/m) · x² / 2 [m] grows along x, small u_y and u_z; zero at t = 0."""
    boxes = make_series()
    screw_p, screw_t = box(0.0, 0.4, 0.25, 0.27, 0.0, 0.02, (20, 1, 1))
    points = np.vstack([boxes.points, screw_p])
    rise = np.array([0.0, 0.5, 1.0])[:, None]
    x, y, z = points.T
    unit_field = np.column_stack([11.5e-6 * 100.0 * x**2 / 2, 1e-6 * y, 2e-6 * z])
    values = dict(
        points=points, tets=np.vstack([boxes.tets, screw_t + len(boxes.points)]),
        part_id=np.r_[boxes.part_id, np.full(len(screw_t), 2)], part_names=["base", "table", "screw"],
        moving_part=[False, True, False], temperatures=K + 20.0 + rise * 100.0 * x[None, :],
        displacements=rise[:, :, None] * unit_field[None, :, :],
    )
    values.update(changes)
    return make_series(**values)


@pytest.fixture(scope="module")
def series():
    return make_series()


@pytest.fixture(scope="module")
def screw_series():
    return make_screw_series()


def read_vtu(path):
    """The grid of a .vtu as VTK's XML reader (ParaView's) sees it."""
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    assert reader.GetErrorCode() == 0
    return reader.GetOutput()


def png_size(path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC, f"{path.name} is not a PNG"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def png_pixels(path) -> np.ndarray:
    from matplotlib.image import imread

    return imread(path)[..., :3]


# --------------------------------------------------------------------------- FieldSeries


def test_series_rejects_inconsistent_shapes():
    with pytest.raises(ValueError, match="temperatures has shape"):
        make_series(temperatures=np.zeros((2, 5)))
    with pytest.raises(ValueError, match="snapshot_times must increase"):
        make_series(snapshot_times=[0.0, 600.0, 600.0])
    with pytest.raises(ValueError, match="part_id outside"):
        make_series(part_names=["base"], moving_part=[False])


def test_series_rejects_node_shared_by_moving_and_fixed_part():
    p, t = box(0.0, 0.2, 0.0, 0.1, 0.0, 0.1, (2, 1, 1))
    part_id = (p[t].mean(axis=1)[:, 0] > 0.1).astype(int)  # one conforming mesh cut in two parts
    with pytest.raises(ValueError, match="belong to both a moving and a fixed part"):
        make_series(points=p, tets=t, part_id=part_id, temperatures=np.full((3, len(p)), 300.0))


def test_moving_nodes_are_displaced_along_x(series):
    moved = series.displaced_points(1) - series.points
    table = np.unique(series.tets[series.part_id == 1])
    base = np.unique(series.tets[series.part_id == 0])
    np.testing.assert_allclose(moved[table], [[0.05, 0.0, 0.0]] * len(table))
    np.testing.assert_array_equal(moved[base], 0.0)


def test_boundary_triangles_are_the_outer_faces_oriented_outwards():
    p, t = box(0.0, 0.4, 0.0, 0.2, 0.0, 0.1, (4, 2, 1))
    triangles, owner = boundary_triangles(p, t)
    # a box of 4 × 2 × 1 hexahedra, each face cell cut in 2 triangles
    assert len(triangles) == 2 * (2 * 4 * 2 + 2 * 4 * 1 + 2 * 2 * 1)
    a, b, c = (p[triangles[:, j]] for j in range(3))
    # divergence theorem: (1/3) ∮ x·n dA is the volume, only if every normal points outwards
    volume = np.einsum("ij,ij->", np.cross(b - a, c - a) / 2, (a + b + c) / 3) / 3
    assert volume == pytest.approx(0.4 * 0.2 * 0.1)
    assert np.all(np.isin(triangles, t[owner]).all(axis=1))


def test_surface_drops_the_faces_two_parts_share(series):
    """The table's bottom and the base's top under it coincide: both copies are inside."""
    surface = Surface.of(series, 0)
    a, b, c = (surface.points[surface.triangles[:, j]] for j in range(3))
    area = np.linalg.norm(np.cross(b - a, c - a), axis=1).sum() / 2
    base = 2 * (0.4 * 0.2 + 0.4 * 0.05 + 0.2 * 0.05)
    table = 2 * (0.2 * 0.2 + 0.2 * 0.03 + 0.2 * 0.03)
    assert area == pytest.approx(base + table - 2 * 0.2 * 0.2)


# --------------------------------------------------------------------------- ParaView files


def test_write_pvd_collection_lists_every_snapshot(series, tmp_path):
    paths = write_pvd(series, tmp_path)
    assert [p.name for p in paths] == ["fields.pvd", "fields_0000.vtu", "fields_0001.vtu", "fields_0002.vtu"]
    root = ET.parse(tmp_path / "fields.pvd").getroot()
    assert root.tag == "VTKFile" and root.get("type") == "Collection"
    assert root.get("byte_order") == "LittleEndian" and root.get("version")
    (collection,) = list(root)
    assert collection.tag == "Collection"
    datasets = list(collection)
    assert [d.tag for d in datasets] == ["DataSet"] * 3
    assert [float(d.get("timestep")) for d in datasets] == TIMES.tolist()
    for d in datasets:
        assert d.get("part") == "0"
        assert not d.get("file").startswith("/") and (tmp_path / d.get("file")).is_file()


def test_vtu_snapshots_read_back_with_celsius_part_id_and_moved_table(series, tmp_path):
    write_pvd(series, tmp_path)
    table = np.unique(series.tets[series.part_id == 1])
    for k in range(series.n_snapshots):
        mesh = meshio.read(tmp_path / f"fields_{k:04d}.vtu")
        assert len(mesh.points) == len(series.points)
        np.testing.assert_array_equal(mesh.cells_dict["tetra"], series.tets)
        np.testing.assert_array_equal(mesh.cell_data["part_id"][0], series.part_id)
        np.testing.assert_allclose(mesh.point_data["temperature_C"], series.temperatures[k] - K)
        # the table is drawn where it was: its nodes moved by the offset, the base's not
        np.testing.assert_allclose(mesh.points[table, 0], series.points[table, 0] + OFFSETS[k])
        np.testing.assert_allclose(mesh.points[:, 1:], series.points[:, 1:])
    # temperature in °C: 20 °C + 100 K/m · x at rest, at the last snapshot
    last = meshio.read(tmp_path / "fields_0002.vtu")
    np.testing.assert_allclose(last.point_data["temperature_C"], 20.0 + 100.0 * series.points[:, 0])


def test_vtk_reads_every_snapshot_the_collection_names(series, tmp_path):
    """ParaView reads .vtu files with VTK's XML reader: the files must satisfy it, not only meshio."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import VTK_TETRA
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    write_pvd(series, tmp_path)
    datasets = list(ET.parse(tmp_path / "fields.pvd").getroot().find("Collection"))
    assert len(datasets) == series.n_snapshots
    for k, dataset in enumerate(datasets):
        reader = vtkXMLUnstructuredGridReader()
        reader.SetFileName(str(tmp_path / dataset.get("file")))
        reader.Update()
        assert reader.GetErrorCode() == 0
        grid = reader.GetOutput()
        assert grid.GetNumberOfPoints() == len(series.points) and grid.GetNumberOfCells() == len(series.tets)
        assert {grid.GetCellType(i) for i in range(grid.GetNumberOfCells())} == {VTK_TETRA}
        temperature = vtk_to_numpy(grid.GetPointData().GetArray("temperature_C"))
        np.testing.assert_allclose(temperature, series.temperatures[k] - K)
        np.testing.assert_array_equal(vtk_to_numpy(grid.GetCellData().GetArray("part_id")), series.part_id)


def test_write_pvd_removes_older_snapshots_only(series, tmp_path):
    write_pvd(series, tmp_path)
    (tmp_path / "notes.vtu").write_text("mine")
    shorter = make_series(snapshot_times=TIMES[:2], temperatures=series.temperatures[:2], offsets=OFFSETS[:2],
                          screw_displacement=series.screw_displacement[:2])
    write_pvd(shorter, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fields.pvd", "fields_0000.vtu", "fields_0001.vtu", "notes.vtu"]


# --------------------------------------------------------------------------- images


def test_rasteriser_keeps_the_nearest_triangle_whatever_the_order():
    square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    xy = np.vstack([square, square])
    depth = np.r_[np.zeros(4), np.ones(4)]  # the second square is nearer
    triangles = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
    for order in (triangles, triangles[::-1]):
        frame = render._rasterise(xy, depth, order, 12, 12)
        won = order[frame.triangle[:10, :10]]
        assert (won >= 4).all()
        assert (frame.triangle[10:, :] == -1).all() and (frame.triangle[:, 10:] == -1).all()


def test_field_images_are_pngs_with_colour_bar(series, tmp_path, monkeypatch):
    monkeypatch.setattr(field_images, "_DPI", 80)  # smaller figures: the test is about content
    paths = write_field_images(series, tmp_path, width_px=300)
    assert [p.name for p in paths] == [TEMPERATURE_FIELD_PNG, SCREW_DEFORMATION_PNG]
    for path in paths:
        width, height = png_size(path)
        assert width > 400 and height > 250
        pixels = png_pixels(path)
        colours = np.unique((pixels * 255).round().astype(np.uint8).reshape(-1, 3), axis=0)
        assert len(colours) > 200, f"{path.name}: {len(colours)} colours"
    # both ends of the colour scale appear unshaded: the colour bar is drawn
    from matplotlib import colormaps

    pixels = png_pixels(paths[0]).reshape(-1, 3)
    for end in (0.0, 1.0):
        colour = np.array(colormaps["turbo"](end)[:3])
        assert np.abs(pixels - colour).max(axis=1).min() < 4 / 255


def test_temperature_field_states_the_snapshot_range(series, tmp_path):
    """The last snapshot spans 20 … 60 °C, the first is uniform 20 °C; the text says so."""
    from matplotlib.figure import Figure

    texts = []
    original = Figure.text

    def spy(self, x, y, s, *args, **kwargs):
        texts.append(s)
        return original(self, x, y, s, *args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(Figure, "text", spy)
        field_images.plot_temperature_field(series, tmp_path / "last.png", width_px=150)
        field_images.plot_temperature_field(series, tmp_path / "first.png", snapshot=0, width_px=150)
    assert texts[1::2] == ["min 20.0 °C, max 60.0 °C", "min 20.0 °C, max 20.0 °C"]


def test_screw_deformation_needs_screw_data(series, tmp_path):
    empty = make_series(screw_x=np.empty(0), screw_displacement=np.empty((3, 0)))
    with pytest.raises(ValueError, match="no screw displacement"):
        plot_screw_deformation(empty, tmp_path / "s.png")


def test_vtu_blocks_split_over_many_zlib_streams_read_back(series, tmp_path, monkeypatch):
    """An array longer than one block (every array of a fine mesh) is split into several zlib streams:
    VTK and meshio must read them back joined, in order."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

    from feedtherm.outputs import vtu

    monkeypatch.setattr(vtu, "BLOCK_BYTES", 100)  # not a multiple of 8: values straddle the blocks
    write_pvd(series, tmp_path)
    path = tmp_path / "fields_0002.vtu"
    mesh = meshio.read(path)
    np.testing.assert_array_equal(mesh.cells_dict["tetra"], series.tets)
    np.testing.assert_array_equal(mesh.points, series.displaced_points(2))
    np.testing.assert_array_equal(mesh.point_data["temperature_C"], series.celsius(2))
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    assert reader.GetErrorCode() == 0
    grid = reader.GetOutput()
    np.testing.assert_array_equal(vtk_to_numpy(grid.GetPoints().GetData()), series.displaced_points(2))
    np.testing.assert_array_equal(vtk_to_numpy(grid.GetPointData().GetArray("temperature_C")), series.celsius(2))
    np.testing.assert_array_equal(vtk_to_numpy(grid.GetCellData().GetArray("part_id")), series.part_id)


# --------------------------------------------------------------------------- displacements


def test_vtu_displacement_array_is_the_series_thermal_displacement_in_metres(screw_series, tmp_path):
    """Three components per point, in the points' unit (m), read back by VTK: ready for Warp By Vector."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    write_pvd(screw_series, tmp_path)
    for k in range(screw_series.n_snapshots):
        grid = read_vtu(tmp_path / f"fields_{k:04d}.vtu")
        array = grid.GetPointData().GetArray("displacement")
        assert array is not None and array.GetNumberOfComponents() == 3
        np.testing.assert_array_equal(vtk_to_numpy(array), screw_series.displacements[k])
        # the points carry the table's offset and no thermal displacement: a warp adds it once
        np.testing.assert_array_equal(vtk_to_numpy(grid.GetPoints().GetData()), screw_series.displaced_points(k))
        temperature = vtk_to_numpy(grid.GetPointData().GetArray("temperature_C"))
        np.testing.assert_allclose(temperature, screw_series.celsius(k))
    last = meshio.read(tmp_path / "fields_0002.vtu")
    np.testing.assert_array_equal(last.point_data["displacement"], screw_series.displacements[2])
    assert 90e-6 < last.point_data["displacement"][:, 0].max() < 93e-6  # 92 µm, written in metres


def test_vtu_has_no_displacement_array_without_displacements(series, tmp_path):
    write_pvd(series, tmp_path)
    grid = read_vtu(tmp_path / "fields_0001.vtu")
    assert grid.GetPointData().GetArray("displacement") is None
    assert grid.GetPointData().GetNumberOfArrays() == 1


def test_vtu_writer_rejects_point_data_of_the_wrong_length(series, tmp_path):
    writer = TetSeriesWriter(len(series.points), series.tets, {})
    with pytest.raises(ValueError, match="point data 'displacement' has shape"):
        writer.write(tmp_path / "x.vtu", series.points, {"displacement": np.zeros((3, 3))})


def test_surface_of_chosen_parts_has_their_faces_only(screw_series):
    surface = Surface.of(screw_series, 2, parts=[2])
    assert set(surface.part.tolist()) == {2}
    a, b, c = (surface.points[surface.triangles[:, j]] for j in range(3))
    area = np.linalg.norm(np.cross(b - a, c - a), axis=1).sum() / 2
    assert area == pytest.approx(4 * 0.4 * 0.02 + 2 * 0.02 * 0.02)
    assert set(Surface.of(screw_series, 2).part.tolist()) == {0, 1, 2}


def test_screw_picture_frame_puts_machine_x_across(screw_series):
    """The frame the screw image is drawn in: from the front, its width is x, the bar inside a small margin."""
    surface = Surface.of(screw_series, 2, parts=[2])
    view = View.from_angles(*field_images.SCREW_VIEW)
    scale = 1000.0  # px/m
    left, right, bottom, top = surface.frame(view, scale)
    margin = 0.03 * 0.4
    assert (left, right) == (pytest.approx(-margin), pytest.approx(0.4 + margin, abs=1.5 / scale))
    from matplotlib import colormaps
    from matplotlib.colors import Normalize

    image = render.render_surface(surface, screw_series.displacements[2, :, 0], view, Normalize(0, 1e-4),
                                  colormaps["turbo"], scale)
    assert image.shape[:2] == (round((top - bottom) * scale), round((right - left) * scale))


def test_field_images_add_the_screw_axial_deformation(screw_series, tmp_path, monkeypatch):
    monkeypatch.setattr(field_images, "_DPI", 80)
    paths = write_field_images(screw_series, tmp_path, width_px=300, screw_part="screw")
    assert [p.name for p in paths] == [TEMPERATURE_FIELD_PNG, SCREW_DEFORMATION_PNG, SCREW_AXIAL_DEFORMATION_PNG]
    width, height = png_size(paths[-1])
    assert width > 300 and height > 100
    # the colour bar's two ends appear, unshaded
    from matplotlib import colormaps

    pixels = png_pixels(paths[-1]).reshape(-1, 3)
    for end in (0.0, 1.0):
        colour = np.array(colormaps["turbo"](end)[:3])
        assert np.abs(pixels - colour).max(axis=1).min() < 4 / 255


def test_screw_axial_deformation_states_the_screws_range_in_micrometres(screw_series, tmp_path):
    """u_x on the screw spans 0 … 92 µm at the last snapshot; the table and base are not drawn."""
    from matplotlib.figure import Figure

    texts, labels = [], []
    original_text, original_savefig = Figure.text, Figure.savefig

    def spy_text(self, x, y, s, *args, **kwargs):
        texts.append(s)
        return original_text(self, x, y, s, *args, **kwargs)

    def spy_savefig(self, *args, **kwargs):
        labels.extend(ax.get_xlabel() for ax in self.axes)
        return original_savefig(self, *args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(Figure, "text", spy_text)
        patch.setattr(Figure, "savefig", spy_savefig)
        plot_screw_axial_deformation(screw_series, tmp_path / "u.png", "screw", width_px=300)
    assert texts[0].startswith("Axial deformation of the screw at t = 1800 s — two boxes")  # the suptitle
    assert texts[-1] == "min 0.0 µm, max 92.0 µm"
    assert "axial position x [mm]" in labels and "axial displacement u_x [µm]" in labels


def test_no_screw_axial_deformation_without_displacements_or_screw_name(series, screw_series, tmp_path):
    paths = write_field_images(series, tmp_path / "a", width_px=150, screw_part="table")
    assert [p.name for p in paths] == [TEMPERATURE_FIELD_PNG, SCREW_DEFORMATION_PNG]
    paths = write_field_images(screw_series, tmp_path / "b", width_px=150)
    assert [p.name for p in paths] == [TEMPERATURE_FIELD_PNG, SCREW_DEFORMATION_PNG]
    assert not list(tmp_path.glob("*/" + SCREW_AXIAL_DEFORMATION_PNG))
    with pytest.raises(ValueError, match="no displacement field"):
        plot_screw_axial_deformation(series, tmp_path / "u.png", "table")
    with pytest.raises(ValueError, match="no part 'spindle'.*base, table, screw"):
        plot_screw_axial_deformation(screw_series, tmp_path / "u.png", "spindle")
