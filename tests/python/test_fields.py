"""Field files (VTU, PVD) read by two real clients, meshio and VTK, against the result's own outputs."""
import json
import math
import os
import subprocess
import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest

import actuator

meshio = pytest.importorskip("meshio")
vtk = pytest.importorskip("vtkmodules.vtkIOXML")
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

BIN = os.environ.get("ACTUATOR_BIN", "actuator")
BRAID = ["--model", "shell", "--shape", "sine", "--amplitude", "1.3", "--fibres", "braid", "--fibre-angle-deg", "40", "--steps", "3"]


def run(*args, check=True):
    return subprocess.run([BIN, *args], check=check, capture_output=True, text=True)


def read_vtk(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    grid = reader.GetOutput()
    assert grid.GetNumberOfPoints() > 0, f"VTK read no points from {path}"

    def arrays(data):
        return {data.GetArrayName(k): vtk_to_numpy(data.GetAbstractArray(k)) for k in range(data.GetNumberOfArrays())}

    points = vtk_to_numpy(grid.GetPoints().GetData())
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 3)
    return points, cells, arrays(grid.GetPointData()), arrays(grid.GetCellData()), arrays(grid.GetFieldData())


def enclosed_volume(points, triangles):
    a, b, c = points[triangles[:, 0]], points[triangles[:, 1]], points[triangles[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", a, np.cross(b, c))) / 6)


@pytest.fixture(scope="module")
def braid(tmp_path_factory):
    folder = tmp_path_factory.mktemp("braid")
    out = json.loads(run("simulate", *BRAID, "--save-vtu", str(folder / "wall.vtu"), "--save-pvd", str(folder / "steps")).stdout)
    assert out["status"] == "ok"
    return folder, out


def test_both_clients_read_every_field_and_it_matches_the_outputs(braid):
    folder, out = braid
    m = meshio.read(folder / "wall.vtu")
    points, cells, point, cell, field = read_vtk(folder / "wall.vtu")
    # The two clients read the same numbers.
    assert np.array_equal(m.points, points) and np.array_equal(m.cells[0].data, cells)
    for name, values in cell.items():
        assert np.array_equal(m.cell_data[name][0], values, equal_nan=True), name
    for name, values in point.items():
        assert np.array_equal(m.point_data[name], values), name
    wall = cell["region"] != 2
    assert set(np.unique(cell["region"])) == {0, 1, 2}, "free wall, clamped wall and caps"
    # Every field against the result's own numbers.
    assert np.nanmax(cell["max_principal_stretch"]) == out["max_stretch"]
    assert np.nanmax(cell["max_principal_stress_kpa"]) == pytest.approx(out["max_stress_kpa"], rel=1e-12)
    fibre = np.concatenate([cell["fibre_1_strain"], cell["fibre_2_strain"]])
    assert np.nanmax(fibre) == out["max_fibre_strain"]
    assert np.nanmean(fibre) == pytest.approx(out["mean_fibre_strain"], rel=1e-9)
    assert enclosed_volume(points, cells) == pytest.approx(out["volume_mm3"], rel=1e-12)
    assert np.all(np.isnan(cell["max_principal_stretch"][~wall])), "the caps are the fixture's, not silicone"
    assert np.all(cell["max_principal_stretch"][wall] >= cell["min_principal_stretch"][wall])
    # Incompressible: the wall thins as it stretches.
    rest_thickness = 1.0
    assert np.allclose(cell["thickness_mm"][wall] * cell["max_principal_stretch"][wall] * cell["min_principal_stretch"][wall], rest_thickness, rtol=1e-12)
    # Fibre directions are unit vectors, tensions the energy's derivative and zero when slack.
    d = cell["fibre_1_direction"][wall]
    assert np.allclose(np.linalg.norm(d, axis=1), 1, atol=1e-12)
    strain, tension = cell["fibre_1_strain"][wall], cell["fibre_1_tension_n_per_mm"][wall]
    stretch = 1 + strain
    taut = strain > 0
    assert np.all(tension[~taut] == 0) and np.all(tension[taut] > 0)
    ratio = tension[taut] / (stretch[taut] * (stretch[taut] ** 2 - 1))
    assert np.allclose(ratio, ratio[0], rtol=1e-9), "one stiffness k: T = k lambda (lambda^2 - 1)"
    # Points: deformed positions; displacement from the rest position.
    assert np.allclose(point["rest_position_mm"] + point["displacement_mm"], points, atol=1e-12)
    # Field data: the outputs and the material's limits.
    assert field["stretch_limit"][0] == out["stretch_limit"] and field["tensile_strength_kpa"][0] == out["tensile_strength_kpa"]
    assert field["contraction_percent"][0] == out["contraction_percent"]
    assert "lengths in mm" in (folder / "wall.vtu").read_text()[:600]


def test_the_series_has_every_load_step_and_ends_at_the_final_state(braid):
    folder, out = braid
    collection = ElementTree.parse(folder / "steps" / "series.pvd").getroot()
    assert collection.get("type") == "Collection"
    entries = collection.find("Collection").findall("DataSet")
    assert len(entries) == 3, "one file per load step of --steps 3"
    pressures = []
    for entry in entries:
        points, cells, point, cell, field = read_vtk(folder / "steps" / entry.get("file"))
        pressures.append(field["step_pressure_kpa"][0])
        assert enclosed_volume(points, cells) == pytest.approx(field["step_volume_mm3"][0], rel=1e-12)
    assert pressures == sorted(pressures) and pressures[-1] == pytest.approx(out["pressure_kpa"], rel=1e-12)
    last, final = read_vtk(folder / "steps" / entries[-1].get("file")), read_vtk(folder / "wall.vtu")
    assert np.array_equal(last[0], final[0])


def test_thesis_results_carry_their_fields_in_mesh_units(tmp_path):
    out = json.loads(run("simulate", "--model", "thesis", "--shape", "sine", "--iterations", "500", "--save-vtu", str(tmp_path / "t.vtu")).stdout)
    points, cells, point, cell, field = read_vtk(tmp_path / "t.vtu")
    assert set(point) == {"displacement_mesh_units", "rest_position_mesh_units", "spring_strain"} and not cell
    assert "mesh units" in (tmp_path / "t.vtu").read_text()[:600]
    assert field["fitness"][0] == out["fitness"]
    # Spring strain per vertex: the mean over the springs that meet there, rebuilt from the file alone.
    rest = point["rest_position_mesh_units"]
    r = actuator.evaluate(actuator.sine(), model="thesis", params=actuator.ThesisParams(iterations=500))
    assert np.array_equal(r.final, points) and np.array_equal(r.initial, rest)
    assert np.array_equal(r.fields()["point"]["spring_strain"], point["spring_strain"])
    resolution = 30
    strain, count = np.zeros(len(points)), np.zeros(len(points))
    for offset in (1, resolution - 1, resolution, resolution + 1):
        a = np.arange(len(points) - offset)
        e = np.linalg.norm(points[a + offset] - points[a], axis=1) / np.linalg.norm(rest[a + offset] - rest[a], axis=1) - 1
        np.add.at(strain, a, e)
        np.add.at(strain, a + offset, e)
        np.add.at(count, a, 1)
        np.add.at(count, a + offset, 1)
    assert np.allclose(strain / count, point["spring_strain"], rtol=1e-9, atol=1e-15)


def test_python_writes_the_same_file_and_gives_the_same_arrays(tmp_path):
    r = actuator.evaluate(actuator.sine(1.3), model="shell", fibres=actuator.Fibres(fibres="braid", fibre_angle_deg=40), load=actuator.Load(steps=3))
    # The default mesh: 30 vertices on each of 40 rings (30 graded toward the clamps), and the two caps' fans.
    assert r.faces.shape == (2 * 30 * 39 + 2 * 30, 3) and r.faces.dtype == np.int32
    r.to_vtu(tmp_path / "py.vtu")
    run("simulate", *BRAID, "--save-vtu", str(tmp_path / "cli.vtu"))
    py, cli = read_vtk(tmp_path / "py.vtu"), read_vtk(tmp_path / "cli.vtu")
    assert np.array_equal(py[0], cli[0]) and np.array_equal(py[1], r.faces)
    for name, values in cli[3].items():
        assert np.array_equal(py[3][name], values, equal_nan=True), name
    fields = r.fields()
    assert np.array_equal(fields["cell"]["max_principal_stretch"], cli[3]["max_principal_stretch"], equal_nan=True)
    assert fields["field"]["max_stretch"] == r.shell["max_stretch"]
    m = r.to_meshio()
    assert np.array_equal(m.points, r.final) and np.array_equal(m.cells[0].data, r.faces)
    assert np.array_equal(m.cell_data["thickness_mm"][0], fields["cell"]["thickness_mm"], equal_nan=True)
    with pytest.raises(ValueError, match="exists; pass overwrite=True"):
        r.to_vtu(tmp_path / "py.vtu")
    with pytest.raises(ValueError, match="must end in .vtu"):
        r.to_vtu(tmp_path / "py.obj")
    with pytest.raises(TypeError, match="path: expected a path"):
        r.to_vtu(3)


def test_inspect_exports_an_archives_designs_and_never_overwrites(tmp_path):
    experiment = {"id": "f", "model": {"name": "thesis"}, "sim": {"iterations": 100}, "render": {"figures": False, "thumbnails": False},
                  "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1, 2]}]}}
    actuator.sweep(experiment, str(tmp_path / "run"))
    archive = str(tmp_path / "run" / "evaluations.capnp")
    run("inspect", archive, "--export-vtu", str(tmp_path / "vtu"))
    records = list(actuator.open_archive(archive))
    for record in records:
        points, cells, point, cell, field = read_vtk(tmp_path / "vtu" / f"evaluation_{record.id:06}.vtu")
        assert np.array_equal(points, record.result.final)
        assert field["fitness"][0] == record.result.fitness
    again = run("inspect", archive, "--export-vtu", str(tmp_path / "vtu"), check=False)
    assert again.returncode == 2 and "already exists" in again.stderr
    # One evaluation by its id, as render, simulate and export --from take it; an id it does not hold is refused.
    run("inspect", archive, "--index", "1", "--export-vtu", str(tmp_path / "one"))
    assert [p.name for p in (tmp_path / "one").iterdir()] == ["evaluation_000001.vtu"]
    missing = run("inspect", archive, "--index", "7", "--export-vtu", str(tmp_path / "none"), check=False)
    assert missing.returncode == 2 and "--index: no evaluation 7" in missing.stderr and "(ids 0 to 1)" in missing.stderr
    assert not (tmp_path / "none").exists(), "a refusal leaves no folder"
    # OBJ meshes are never written over either.
    run("inspect", archive, "--index", "0", "--export-obj", str(tmp_path / "obj"))
    before = (tmp_path / "obj" / "evaluation_000000_final.obj").read_bytes()
    again = run("inspect", archive, "--export-obj", str(tmp_path / "obj"), check=False)
    assert again.returncode == 2 and "already exists" in again.stderr
    assert (tmp_path / "obj" / "evaluation_000000_final.obj").read_bytes() == before and len(list((tmp_path / "obj").iterdir())) == 2


def test_bad_field_outputs_are_refused_and_write_nothing(tmp_path):
    for args, message in [(["--model", "thesis", "--save-pvd", str(tmp_path / "p")], "no load steps"),
                          (["--model", "shell", "--save-vtu", str(tmp_path / "x.obj")], "must end in .vtu")]:
        result = run("simulate", *args, check=False)
        assert result.returncode == 2 and message in result.stderr
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "keep.txt").write_text("mine")
    result = run("simulate", "--model", "shell", "--save-pvd", str(tmp_path / "full"), check=False)
    assert result.returncode == 2 and "not an empty folder" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["full"] and (tmp_path / "full" / "keep.txt").read_text() == "mine"
    # A field file that exists is refused before anything runs, and left as it was.
    (tmp_path / "mine.vtu").write_text("mine")
    result = run("simulate", "--model", "shell", "--save-vtu", str(tmp_path / "mine.vtu"), check=False)
    assert result.returncode == 2 and "already exists" in result.stderr and result.stdout == ""
    assert (tmp_path / "mine.vtu").read_text() == "mine"
