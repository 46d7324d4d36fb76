"""`import actuator`: the module against the command line, bit for bit; threads; errors; arrays."""
import concurrent.futures
import functools
import json
import math
import multiprocessing
import os
import subprocess
import time

import numpy as np
import pytest

import actuator

BIN = os.environ.get("ACTUATOR_BIN", "actuator")


def simulate(*args):
    out = subprocess.run([BIN, "simulate", *args], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def test_evaluate_matches_the_command_line_bit_for_bit():
    ours = actuator.evaluate(actuator.sine(4.1, (0.5, math.pi - 0.5)), model="thesis")
    cli = simulate("--model", "thesis", "--shape", "sine", "--amplitude", "4.1", "--phase", "0.5,pi-0.5")
    assert ours.status == "ok"
    assert ours.fitness.hex() == float(cli["fitness"]).hex()
    assert ours.contraction_percent.hex() == float(cli["contraction_percent"]).hex()


def test_defaults_are_the_cpp_structs():
    p = actuator.ThesisParams()
    assert p.iterations == 10000 and p.load == "inflate"
    assert actuator.Mesh().resolution == 30
    assert actuator.Geometry().radius_mm == 5.0
    assert actuator.Load().pressure_kpa > 0
    short = actuator.ThesisParams(iterations=2000)
    assert short.iterations == 2000 and short.spring_constant == p.spring_constant


def test_evaluate_many_keeps_order_and_equals_one_at_a_time_whatever_the_threads():
    shapes = [actuator.sine(a, (0.5, math.pi - 0.5)) for a in (1.0, 2.5, 4.1, 6.0)]
    params = actuator.ThesisParams(iterations=3000)
    one = [actuator.evaluate(s, params=params, model="thesis").fitness for s in shapes]
    for threads in (1, 2):
        many = [r.fitness for r in actuator.evaluate_many(shapes, threads=threads, params=params, model="thesis")]
        assert [f.hex() for f in many] == [f.hex() for f in one]


def test_positions_are_n_by_3_arrays():
    r = actuator.evaluate(actuator.cylinder(), params=actuator.ThesisParams(iterations=100), model="thesis")
    assert isinstance(r.final, np.ndarray)
    assert r.final.shape == (900, 3) and r.initial.shape == (900, 3)
    assert np.allclose(np.hypot(r.initial[:, 0], r.initial[:, 1]), 1.0)


def test_shell_model_contraction_at_pressure():
    load = actuator.Load(pressure_kpa=1.0, steps=2)
    r = actuator.evaluate(actuator.cylinder(), model="shell", geometry=actuator.Geometry(ring_vertices=12, rings=16), load=load)
    assert r.status == "ok"
    assert r.fitness == r.contraction_percent


def test_shell_outputs_are_named_and_valued_as_on_the_command_line():
    ours = actuator.evaluate(actuator.cylinder(), model="shell", geometry=actuator.Geometry(ring_vertices=12, rings=16),
                             load=actuator.Load(pressure_kpa=1.0, steps=2), fibres=actuator.Fibres(fibres="braid"))
    cli = simulate("--shape", "cylinder", "--model", "shell", "--ring-vertices", "12", "--rings", "16", "--pressure-kpa", "1",
                   "--steps", "2", "--fibres", "braid")
    numbers = [k for k, v in cli.items() if k not in ("status", "fitness", "contraction_percent", "elapsed_ms") and not isinstance(v, (dict, list, str))]
    assert "pressure_kpa" in numbers and "blocking_force_n" in numbers and "max_fibre_strain" in numbers
    for key in numbers:
        assert key in ours.shell, f"the command line's {key} is missing from Result.shell"
        value = ours.shell[key]
        if cli[key] is None:  # JSON has no NaN or infinity (min_gap_mm: inf when no wall is near)
            assert not math.isfinite(value), key
        else:
            assert float(value).hex() == float(cli[key]).hex(), key
    assert [p["pressure_kpa"] for p in cli["curve"]] == list(ours.shell["curve_pressure_kpa"])
    assert [p["contraction_percent"] for p in cli["curve"]] == list(ours.shell["curve_contraction_percent"])


def test_bad_input_raises_value_error_with_the_message():
    with pytest.raises(ValueError, match="out of range"):
        actuator.ThesisParams(iterations=-5)
    with pytest.raises(ValueError, match="unknown field 'iteration'"):
        actuator.ThesisParams(iteration=5)
    with pytest.raises(ValueError, match="choose"):
        actuator.evaluate(actuator.cylinder(), model="fem")
    with pytest.raises(ValueError, match="control points"):
        actuator.evaluate(actuator.bspline([[1, 2]]), model="thesis")
    with pytest.raises(ValueError, match="thesis model's"):
        actuator.evaluate(actuator.cylinder(), model="shell", params=actuator.ThesisParams())


def test_numerical_failure_is_a_status_not_an_exception():
    params = actuator.ThesisParams(step_scale=50.0, iterations=2000)
    r = actuator.evaluate(actuator.sine(4.1, (0.5, math.pi - 0.5)), params=params, model="thesis")
    assert r.status != "ok"


SWEEP = {
    "id": "py", "title": "python sweep", "model": {"name": "thesis"}, "sim": {"iterations": 2000},
    "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]},
              "axes": [{"parameter": "amplitude", "from": 1, "to": 4, "points": 3}]},
    "render": {"figures": False, "thumbnails": False},
}


def test_a_sweep_returns_its_table_and_equals_evaluate(tmp_path):
    out = actuator.sweep(SWEEP, str(tmp_path / "s"), threads=2)
    results = out["tables"]["results"]
    assert list(results["amplitude"]) == [1.0, 2.5, 4.0]
    one = actuator.evaluate(actuator.sine(2.5, (0.5, math.pi - 0.5)), params=actuator.ThesisParams(iterations=2000), model="thesis")
    assert float(results["fitness"][1]).hex() == one.fitness.hex()
    assert out["summary"]["simulations"] == 3


def test_a_small_ga_logs_every_generation(tmp_path):
    ga = {"id": "g", "seed": 3, "model": {"name": "thesis"}, "sim": {"iterations": 1500},
          "evolve": {"runs": 1, "population": 6, "generations": 2, "genome": {"kind": "bspline", "length": [4, 6]}},
          "render": {"figures": False, "thumbnails": False}}
    out = actuator.evolve(ga, str(tmp_path / "g"))
    logbook = out["tables"]["run_1_logbook"]
    assert list(logbook["generation"]) == [0, 1, 2]
    assert all(logbook["best"] >= logbook["median"])
    # Every table the folder has, the same rows as its CSV files.
    tables = out["tables"]
    assert set(tables) == {"evaluations", "run_1_logbook", "run_1_halloffame", "run_1_best_per_generation"}
    for name, relative in [("evaluations", "evaluations.csv"), ("run_1_halloffame", "run_1/halloffame.csv"),
                           ("run_1_best_per_generation", "run_1/best_per_generation.csv")]:
        rows = (tmp_path / "g" / relative).read_text().strip().splitlines()
        assert len(tables[name]) == len(rows) - 1 > 0, name
    assert len(tables["evaluations"]) == out["summary"]["simulations"]
    assert tables["run_1_halloffame"]["fitness"][0] == max(logbook["best"])


def test_bad_experiments_raise_value_error(tmp_path):
    with pytest.raises(ValueError, match="sim.iteration"):
        actuator.run({"id": "x", "model": {"name": "thesis"}, "sim": {"iteration": 5}, "sweep": SWEEP["sweep"]}, str(tmp_path / "x"))
    with pytest.raises(ValueError, match="is a 'sweep' one"):
        actuator.evolve(SWEEP, str(tmp_path / "y"))
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "keep.txt").write_text("mine")
    with pytest.raises(ValueError):
        actuator.sweep(SWEEP, str(tmp_path / "full"))
    assert (tmp_path / "full" / "keep.txt").read_text() == "mine"


# ---- where evaluations run: threads, servers, any map -------------------------------------------

SHAPES = [actuator.sine(a, (0.5, math.pi - 0.5)) for a in (1.0, 2.5, 4.1, 6.0, 8.0)]
SHORT = actuator.ThesisParams(iterations=2000)


def hexes(results):
    return [(r.status, r.fitness.hex(), r.final.tobytes()) for r in results]


def test_any_map_gives_the_local_results_bit_for_bit():
    local = hexes(actuator.evaluate_many(SHAPES, threads=2, params=SHORT, model="thesis"))
    assert hexes(actuator.evaluate_many(SHAPES, map=map, params=SHORT, model="thesis")) == local
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        assert hexes(actuator.evaluate_many(SHAPES, map=pool.map, params=SHORT, batch=2, model="thesis")) == local
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        assert hexes(actuator.evaluate_many(SHAPES, map=pool.map, params=SHORT, model="thesis")) == local
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        assert hexes(actuator.evaluate_many(SHAPES, map=pool.map, params=SHORT, model="thesis")) == local


def test_shell_results_through_a_map_keep_their_curves():
    kw = dict(model="membrane", geometry=actuator.Geometry(ring_vertices=12, rings=16), load=actuator.Load(pressure_kpa=1.0, steps=3))
    local = actuator.evaluate_many(SHAPES[:2], threads=1, **kw)
    mapped = actuator.evaluate_many(SHAPES[:2], map=map, **kw)
    for a, b in zip(local, mapped):
        assert a.fitness.hex() == b.fitness.hex()
        assert a.shell["curve_contraction_percent"].tobytes() == b.shell["curve_contraction_percent"].tobytes()
        assert a.shell["max_stretch"] == b.shell["max_stretch"] and len(a.shell["curve_pressure_kpa"]) == 3


def test_a_map_that_misbehaves_is_a_value_error():
    with pytest.raises(ValueError, match="neither callable"):
        actuator.evaluate_many(SHAPES, map=42, model="thesis")
    with pytest.raises(ValueError, match="gave back 4 results for 5 jobs"):
        actuator.evaluate_many(SHAPES, map=lambda f, xs: [f(x) for x in list(xs)[:4]], params=SHORT, model="thesis")
    with pytest.raises(ValueError, match="where actuator._evaluate_job's bytes were expected"):
        actuator.evaluate_many(SHAPES, map=lambda f, xs: [0 for _ in xs], params=SHORT, model="thesis")
    with pytest.raises(ValueError, match="give one of them"):
        actuator.evaluate_many(SHAPES, map=map, workers=["local"], model="thesis")
    with pytest.raises(ValueError, match="not a job message"):
        actuator._evaluate_job(b"not capnp")


def test_an_experiment_through_a_map_equals_the_local_run(tmp_path):
    ga = {"id": "m", "seed": 5, "model": {"name": "thesis"}, "sim": {"iterations": 1500},
          "evolve": {"runs": 1, "population": 8, "generations": 3, "genome": {"kind": "bspline", "length": [4, 6]}},
          "render": {"figures": False, "thumbnails": False}}
    actuator.evolve(ga, str(tmp_path / "local"), threads=2)
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        actuator.evolve(ga, str(tmp_path / "mapped"), map=pool.map)
    for name in ("run_1/logbook.csv", "run_1/halloffame.csv", "run_1/checkpoint.json"):
        assert (tmp_path / "mapped" / name).read_bytes() == (tmp_path / "local" / name).read_bytes(), name


def test_evaluation_servers_give_the_local_results(tmp_path):
    server = subprocess.Popen([BIN, "serve", "--listen", "127.0.0.1:0", "--threads", "1"], stdout=subprocess.PIPE, text=True)
    try:
        line = server.stdout.readline()
        assert line.startswith("listening on "), line
        address = line.split()[2]  # "listening on ADDRESS:PORT (1 worker threads)"
        local = hexes(actuator.evaluate_many(SHAPES, threads=1, params=SHORT, model="thesis"))
        assert hexes(actuator.evaluate_many(SHAPES, workers=[address], params=SHORT, model="thesis")) == local
        assert hexes(actuator.evaluate_many(SHAPES, workers=address + ",local", threads=1, params=SHORT, model="thesis")) == local
    finally:
        server.kill()
        server.wait()


# ---- tables, pictures, archives -----------------------------------------------------------------

def test_tables_are_dataframes_with_pandas_and_structured_arrays_without(tmp_path):
    pandas = pytest.importorskip("pandas")  # Debian's python3-pandas is in scripts/install-deps.sh
    frames = actuator.sweep(SWEEP, str(tmp_path / "f"), threads=2)["tables"]["results"]
    arrays = actuator.sweep(SWEEP, str(tmp_path / "a"), threads=2, as_frame=False)["tables"]["results"]
    assert isinstance(frames, pandas.DataFrame) and isinstance(arrays, np.ndarray)
    assert list(frames.columns) == list(arrays.dtype.names)
    assert [f.hex() for f in frames["fitness"]] == [float(f).hex() for f in arrays["fitness"]]


def _decode_png(data):
    """RGBA pixels of a PNG, read by another library (Pillow)."""
    import io
    from PIL import Image
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGBA"))


def test_render_returns_rgba_pixels_and_writes_a_png_once(tmp_path):
    r = actuator.evaluate(actuator.sine(4.1, (0.5, math.pi - 0.5)), params=SHORT, model="thesis")
    image = actuator.render(r, width=320, height=240)
    assert image.shape == (240, 320, 4) and image.dtype == np.uint8
    assert (image[..., 3] == 255).all()
    # The deformed mesh is coloured (viridis), the rest mesh grey: the picture is not blank.
    assert len(np.unique(image.reshape(-1, 4), axis=0)) > 500
    turned = actuator.render(r, view="turntable", angle_deg=90, width=320, height=240)
    assert not np.array_equal(turned, image)
    png = tmp_path / "r.png"
    assert actuator.render(r, str(png), width=320, height=240) is None
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    before = png.read_bytes()
    with pytest.raises(ValueError, match="exists"):
        actuator.render(r, str(png), width=64, height=64)
    assert png.read_bytes() == before
    with pytest.raises(ValueError, match="choose"):
        actuator.render(r, view="side")
    with pytest.raises(ValueError, match="colouring"):
        actuator.render(r, colouring="stress")  # the thesis model has no stress
    # Jupyter shows a result as its before-and-after figure: the picture render() draws by default.
    shown = r._repr_png_()
    assert shown[:8] == b"\x89PNG\r\n\x1a\n"
    assert np.array_equal(actuator.render(r), _decode_png(shown))


def test_an_archive_reads_as_records_in_order(tmp_path):
    # 300 records: more than the reader takes at a time (256).
    sweep = json.loads(json.dumps(SWEEP))
    sweep["sim"]["iterations"] = 50
    sweep["sweep"]["axes"] = [{"parameter": "amplitude", "from": 0.5, "to": 3, "points": 300}]
    out = actuator.sweep(sweep, str(tmp_path / "s"), threads=2, as_frame=False)
    archive = str(tmp_path / "s" / "evaluations.capnp")
    records = list(actuator.open_archive(archive))
    assert [r.id for r in records] == list(range(300))
    assert {r.role for r in records} == {"grid"}
    assert [r.result.fitness.hex() for r in records] == [float(f).hex() for f in out["tables"]["results"]["fitness"]]
    assert records[7].result.final.shape == (900, 3)
    again = actuator.evaluate(records[7].result.shape, params=actuator.ThesisParams(iterations=50), model="thesis")
    assert again.fitness.hex() == records[7].result.fitness.hex()
    quick = list(actuator.open_archive(archive, meshes=False))
    assert len(quick) == 300 and quick[0].result.final.shape == (0, 3)
    with pytest.raises(ValueError, match="no meshes"):
        actuator.render(quick[0].result)
    assert quick[0]._repr_png_() is None and quick[0].result._repr_png_() is None, "Jupyter falls back to the repr"
    assert records[7]._repr_png_() == records[7].result._repr_png_()
    with pytest.raises(ValueError, match="cannot open"):
        actuator.open_archive(str(tmp_path / "none.capnp"))


def test_a_torn_archive_tail_ends_the_records_and_damage_is_an_error(tmp_path):
    actuator.sweep(SWEEP, str(tmp_path / "s"), threads=2)
    archive = tmp_path / "s" / "evaluations.capnp"
    whole = archive.read_bytes()
    archive.write_bytes(whole[:-10])
    assert len(list(actuator.open_archive(str(archive)))) == 2
    damaged = bytearray(whole)
    damaged[len(whole) // 2] ^= 0xFF
    archive.write_bytes(bytes(damaged))
    with pytest.raises(ValueError, match="damaged|does not decode"):
        list(actuator.open_archive(str(archive)))


def test_resume_from_python_ends_as_an_uninterrupted_run(tmp_path):
    ga = {"id": "r", "seed": 9, "model": {"name": "thesis"}, "sim": {"iterations": 6000},
          "evolve": {"runs": 1, "population": 12, "generations": 5, "genome": {"kind": "bspline", "length": [4, 6]}},
          "render": {"figures": False, "thumbnails": False}}
    whole = tmp_path / "whole"
    actuator.evolve(ga, str(whole), threads=2)
    # An interrupted run: the CLI killed after its first checkpoints, then resumed from Python.
    cut = tmp_path / "cut"
    path = tmp_path / "ga.json"
    path.write_text(json.dumps(ga))
    proc = subprocess.Popen([BIN, "evolve", str(path), "--out", str(cut), "--threads", "1"], stderr=subprocess.DEVNULL)
    deadline = time.time() + 60
    while not (cut / "run_1" / "checkpoint.json").exists() and time.time() < deadline and proc.poll() is None:
        time.sleep(0.005)
    proc.kill()
    proc.wait()
    assert proc.returncode == -9, "the run ended before it could be interrupted"
    actuator.evolve(str(path), str(cut), threads=2, resume=True)
    for name in ("run_1/logbook.csv", "run_1/halloffame.csv", "run_1/checkpoint.json"):
        assert (cut / name).read_bytes() == (whole / name).read_bytes(), name
    with pytest.raises(ValueError):
        actuator.evolve(str(path), str(tmp_path / "nothing"), resume=True)


def test_a_map_that_fails_mid_run_loses_nothing_and_the_run_resumes(tmp_path):
    ga = {"id": "f", "seed": 4, "model": {"name": "thesis"}, "sim": {"iterations": 1500},
          "evolve": {"runs": 1, "population": 8, "generations": 4, "genome": {"kind": "bspline", "length": [4, 6]}},
          "render": {"figures": False, "thumbnails": False}}
    actuator.evolve(ga, str(tmp_path / "whole"), threads=2)
    calls = []

    def failing_map(f, items):  # a cluster that goes away during the third batch
        calls.append(1)
        if len(calls) == 3:
            raise ConnectionError("the cluster went away")
        return map(f, items)

    with pytest.raises(ConnectionError, match="went away"):
        actuator.evolve(ga, str(tmp_path / "cut"), map=failing_map)
    records = list(actuator.open_archive(str(tmp_path / "cut" / "evaluations.capnp"), meshes=False))
    assert records and [r.id for r in records] == list(range(len(records)))
    actuator.evolve(ga, str(tmp_path / "cut"), map=map, resume=True)
    for name in ("run_1/logbook.csv", "run_1/halloffame.csv", "run_1/checkpoint.json"):
        assert (tmp_path / "cut" / name).read_bytes() == (tmp_path / "whole" / name).read_bytes(), name


def test_shapes_defs_and_results_pickle_exactly_for_process_pools():
    import pickle
    shape = actuator.bspline([[1, 3, 5, 2, 0]], "entire")
    assert pickle.loads(pickle.dumps(shape)).title == shape.title
    material = actuator.Material.from_preset("dragon-skin-10")
    material.mu_kpa = 123.0
    back = pickle.loads(pickle.dumps(material))
    assert repr(back) == repr(material) and back.preset == "dragon-skin-10"
    r = actuator.evaluate(actuator.sine(2.0), params=SHORT, model="thesis")
    again = pickle.loads(pickle.dumps(r))
    assert (again.fitness.hex(), again.final.tobytes(), again.model) == (r.fitness.hex(), r.final.tobytes(), r.model)
    # actuator.evaluate itself in a process pool, shapes and params sent by pickle.
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        far = list(pool.map(functools.partial(actuator.evaluate, model="thesis", params=actuator.ThesisParams(iterations=2000)), SHAPES))
    assert hexes(far) == hexes(actuator.evaluate_many(SHAPES, threads=1, params=SHORT, model="thesis"))
    with pytest.raises(ValueError, match="choose"):
        actuator.Material.from_preset("rubber")


def test_ctrl_c_stops_a_long_local_run_and_it_resumes(tmp_path):
    import signal
    import threading
    shapes = [actuator.sine(1 + 0.01 * k, (0.5, math.pi - 0.5)) for k in range(400)]  # about 5 s on 2 threads
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    started = time.time()
    with pytest.raises(KeyboardInterrupt):
        actuator.evaluate_many(shapes, threads=2, model="thesis")
    assert time.time() - started < 2.5
    # An experiment stopped so keeps what it recorded, and resumes to the uninterrupted end.
    sweep = json.loads(json.dumps(SWEEP))
    sweep["sim"]["iterations"] = 10000
    sweep["sweep"]["axes"] = [{"parameter": "amplitude", "from": 1, "to": 4, "points": 120}]
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    with pytest.raises(KeyboardInterrupt):
        actuator.sweep(sweep, str(tmp_path / "cut"), threads=2)
    kept = len(list(actuator.open_archive(str(tmp_path / "cut" / "evaluations.capnp"), meshes=False)))
    assert 0 < kept < 120
    actuator.sweep(sweep, str(tmp_path / "cut"), threads=2, resume=True)
    actuator.sweep(sweep, str(tmp_path / "whole"), threads=2)
    assert (tmp_path / "cut" / "results.csv").read_bytes() == (tmp_path / "whole" / "results.csv").read_bytes()


def test_paths_are_taken_as_python_takes_them_and_wrong_types_are_type_errors(tmp_path):
    import pathlib
    r = actuator.evaluate(actuator.sine(4.1), params=actuator.ThesisParams(iterations=200), model="thesis")
    # bytes and os.PathLike name the file they name (not "b'x.png'").
    actuator.render(r, os.fsencode(str(tmp_path / "bytes.png")), width=64, height=48)
    actuator.render(r, tmp_path / "pathlike.png", width=64, height=48)
    assert (tmp_path / "bytes.png").exists() and (tmp_path / "pathlike.png").exists()
    assert not any("b'" in p.name for p in tmp_path.iterdir())
    with pytest.raises(TypeError, match="path: expected a path"):
        actuator.render(r, 42)
    experiment = tmp_path / "s.json"
    experiment.write_text(json.dumps({"id": "s", "model": {"name": "thesis"}, "sim": {"iterations": 100}, "render": {"figures": False, "thumbnails": False},
                                      "sweep": {"shape": {"family": "sine"}, "axes": [{"parameter": "amplitude", "values": [1, 2]}]}}))
    out = actuator.sweep(pathlib.Path(experiment), pathlib.Path(tmp_path / "run"))
    assert len(out["tables"]["results"]) == 2
    with pytest.raises(TypeError, match="experiment: expected a dict or a path"):
        actuator.sweep(3.5, tmp_path / "other")
    assert len(list(actuator.open_archive(pathlib.Path(tmp_path / "run" / "evaluations.capnp"), meshes=False))) == 2
    # Numbers are finite and fields are typed, naming the field.
    for call in (lambda: actuator.sine(float("nan")), lambda: actuator.sine(1, (0, float("inf"))),
                 lambda: actuator.bspline([[1, 2, float("nan"), 4, 5]]), lambda: actuator.render(r, view="turntable", angle_deg=float("nan"))):
        with pytest.raises(ValueError, match="not a finite number"):
            call()
    with pytest.raises(ValueError, match="fibre_angle_deg"):
        actuator.Fibres(fibre_angle_deg=float("nan"))
    with pytest.raises(TypeError, match="pressure_kpa: expected a number, got str"):
        actuator.Load(pressure_kpa="3")
    with pytest.raises(TypeError, match="steps: expected an int, got float"):
        actuator.Load(steps=2.5)
    assert actuator.Load(steps=np.int64(3)).steps == 3
    with pytest.raises(ValueError, match="not an experiment in JSON"):
        actuator.sweep({"id": "n", "note": float("nan")}, tmp_path / "nan")
    # A deeply nested experiment file is refused, not a crash.
    deep = tmp_path / "deep.json"
    deep.write_text('{"id": "d", "note": ' + "[" * 100000 + "]" * 100000 + "}")
    with pytest.raises(ValueError, match="levels deep"):
        actuator.sweep(deep, tmp_path / "deep")


def test_a_field_without_effect_is_refused_as_on_the_command_line():
    with pytest.raises(ValueError, match="stroke_percent: has no effect: it applies when kind is blocked, not inflate"):
        actuator.evaluate(actuator.cylinder(), model="shell", load=actuator.Load(stroke_percent=3))
    with pytest.raises(ValueError, match="torque_n_mm: has no effect: it applies when twist is loaded, not free"):
        actuator.evaluate(actuator.cylinder(), model="shell", ends=actuator.Ends(torque_n_mm=3))
    with pytest.raises(ValueError, match="fibre_angle_deg: has no effect"):
        actuator.evaluate(actuator.cylinder(), model="shell", fibres=actuator.Fibres(fibre_angle_deg=40))
    small = actuator.Geometry(ring_vertices=12, rings=16)
    r = actuator.evaluate(actuator.cylinder(), model="shell", geometry=small, load=actuator.Load(pressure_kpa=1, steps=1),
                          fibres=actuator.Fibres(fibres="braid", fibre_angle_deg=40))
    assert r.status == "ok" and r.contraction_percent > 0
    # The tip (lateral translation and tilt): held by default, its holding loads reported; free on request.
    assert r.shell["tip_moment_n_mm"] < 1e-6 and np.isnan(r.shell["tip_tilt_deg"])
    free = actuator.evaluate(actuator.cylinder(), model="shell", geometry=small, load=actuator.Load(pressure_kpa=1, steps=1),
                             fibres=actuator.Fibres(fibres="braid", fibre_angle_deg=40), ends=actuator.Ends(tip="free"))
    assert free.status == "ok" and free.shell["tip_tilt_deg"] < 1e-6 and np.isnan(free.shell["tip_moment_n_mm"])
    assert free.contraction_percent == pytest.approx(r.contraction_percent, rel=1e-6)
    with pytest.raises(ValueError, match="tip"):
        actuator.evaluate(actuator.cylinder(), model="shell", geometry=actuator.Geometry(ends="sliding"), ends=actuator.Ends(tip="free"))


def test_every_load_kind_runs_from_python_as_from_the_command_line():
    small = dict(model="membrane", geometry=actuator.Geometry(ring_vertices=12, rings=16), fibres=actuator.Fibres(fibres="braid", fibre_angle_deg=30))
    load = actuator.Load(kind="blocked", pressure_kpa=10, stroke_percent=2, steps=2)
    assert load.kind == "blocked"
    r = actuator.evaluate(actuator.cylinder(), load=load, **small)
    assert r.status == "ok"
    # The isobaric test: the braid pulls on the top held at 2 %, and more as the pressure rises.
    forces = r.shell["curve_force_n"]
    assert len(forces) == 2 and 0 < forces[0] < forces[1] == r.shell["stroke_force_n"]
    out = subprocess.run([os.environ["ACTUATOR_BIN"], "simulate", "--model", "membrane", "--ring-vertices", "12", "--rings", "16",
                          "--fibres", "braid", "--fibre-angle-deg", "30", "--load", "blocked", "--pressure-kpa", "10", "--stroke-percent", "2",
                          "--steps", "2"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    cli = json.loads(out.stdout)
    assert cli["stroke_force_n"] == pytest.approx(r.shell["stroke_force_n"], rel=1e-12)
    with pytest.raises(ValueError, match="kind: unknown value 'push' \\(choose inflate, gas, volume, force or blocked\\)"):
        actuator.Load(kind="push")
    with pytest.raises(ValueError, match="stroke_percent: has no effect: it applies when kind is blocked, not force"):
        actuator.evaluate(actuator.cylinder(), load=actuator.Load(kind="force", stroke_percent=5), **small)


def test_fibre_bands_and_sectors_are_the_experiment_files(tmp_path):
    small = {"ring_vertices": 12, "rings": 16}
    bands = [{"from": 0, "to": 0.5, "angle_deg": 25}, {"from": 0.5, "to": 1, "angle_deg": 40}]
    fibres = actuator.Fibres(fibres="braid", fibre_bands=bands)
    assert fibres.fibre_bands == bands and fibres.fibre_sectors_deg == []
    assert actuator.Fibres(fibres="braid", fibre_bands=[(0, 1, 30)]).fibre_bands == [{"from": 0.0, "to": 1.0, "angle_deg": 30.0}]
    load = actuator.Load(pressure_kpa=2, steps=1)
    r = actuator.evaluate(actuator.cylinder(), model="membrane", geometry=actuator.Geometry(**small), load=load, fibres=fibres)
    sectors = actuator.evaluate(actuator.cylinder(), model="membrane", geometry=actuator.Geometry(**small), load=load,
                                fibres=actuator.Fibres(fibres="single", fibre_sectors_deg=[0, 90]))
    experiment = {"id": "b", "render": {"figures": False, "thumbnails": False}, "evaluate": {"shapes": [{"family": "cylinder"}]}}
    for name, model, result in [("bands", {"fibres": "braid", "fibre_bands": bands}, r),
                                ("sectors", {"fibres": "single", "fibre_sectors_deg": [0, 90]}, sectors)]:
        e = dict(experiment, model={"name": "membrane", "geometry": small, "load": {"pressure_kpa": 2, "steps": 1}, **model})
        table = actuator.run(e, str(tmp_path / name), as_frame=False)["tables"]["evaluations"]
        assert result.status == "ok" and float(table["fitness"][0]).hex() == result.fitness.hex(), name
    # A pickled def keeps its lists (process pools send it so).
    import pickle
    assert pickle.loads(pickle.dumps(fibres)).fibre_bands == bands
    # Wrong lists name the entry; a band that leaves a gap is the def's own refusal, as for a file.
    for value, error, message in [
            ([{"from": 0, "to": 2, "angle_deg": 30}], ValueError, r"fibre_bands\[0\].to: 2 is out of range \(0 to 1\)"),
            ([{"from": 0, "to": 1}], ValueError, r"fibre_bands\[0\]: missing 'angle_deg'"),
            ([{"from": 0, "to": 1, "angle": 3}], ValueError, r"fibre_bands\[0\]: unknown key 'angle' \(valid: from, to, angle_deg\)"),
            ([(0, 1, "30")], TypeError, r"fibre_bands\[0\].angle_deg: expected a number, got str"),
            ([(0, 1, float("nan"))], ValueError, r"out of range"),
            (5, TypeError, r"fibre_bands: expected a list, got int")]:
        with pytest.raises(error, match=message):
            actuator.Fibres(fibres="braid", fibre_bands=value)
    with pytest.raises(ValueError, match="fibre_sectors_deg: 5 entries, at most 4"):
        actuator.Fibres(fibres="single", fibre_sectors_deg=[0, 1, 2, 3, 4])
    with pytest.raises(ValueError, match="must cover the length"):
        actuator.evaluate(actuator.cylinder(), model="membrane", fibres=actuator.Fibres(fibres="braid", fibre_bands=[(0, 0.4, 20), (0.6, 1, 30)]))


def test_characterize_gives_the_command_lines_curves(tmp_path):
    small = dict(model="membrane", geometry=actuator.Geometry(ring_vertices=12, rings=16), load=actuator.Load(steps=2),
                 fibres=actuator.Fibres(fibres="braid", fibre_angle_deg=30))
    got = actuator.characterize(actuator.cylinder(), pressures_kpa=[4, 8], points=3, threads=2, **small)
    curves, summary = got["curves"], got["summary"]
    out = subprocess.run([os.environ["ACTUATOR_BIN"], "characterize", "--model", "membrane", "--ring-vertices", "12", "--rings", "16", "--steps", "2",
                          "--fibres", "braid", "--fibre-angle-deg", "30", "--pressures-kpa", "4,8", "--points", "3", "--threads", "1",
                          "--out", str(tmp_path / "c")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    cli = np.genfromtxt(tmp_path / "c" / "characteristic.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    assert list(curves["curve"]) == list(cli["curve"])
    for column in ("pressure_kpa", "contraction_percent", "force_n"):
        np.testing.assert_array_equal(curves[column], cli[column].astype(float))
    # Each isobaric curve falls from the force at no contraction to none at the free stroke.
    for pressure, row in zip((4, 8), summary["isobaric"]):
        forces = [f for c, p, f in zip(curves["curve"], curves["pressure_kpa"], curves["force_n"]) if c == "isobaric" and p == pressure]
        assert len(forces) == 3 and forces[0] == row["force_at_no_contraction_n"] > forces[1] > forces[2] == 0
        assert row["work_per_stroke_mj"] > 0 and row["work_per_gram_mj_per_g"] == pytest.approx(row["work_per_stroke_mj"] / summary["silicone_mass_g"])
    assert json.loads(out.stdout)["isobaric"] == summary["isobaric"]
    with pytest.raises(ValueError, match="pressures_kpa: give the pressures in increasing order"):
        actuator.characterize(actuator.cylinder(), pressures_kpa=[8, 4], **small)
    with pytest.raises(ValueError, match="characterize needs the membrane or shell model"):
        actuator.characterize(actuator.cylinder(), model="thesis")
    with pytest.raises(ValueError, match="load blocked: characterize sets the load"):
        actuator.characterize(actuator.cylinder(), load=actuator.Load(kind="blocked"))


def test_a_material_file_is_a_material_as_a_preset_is(tmp_path):
    # A material file as `actuator material fit` writes it: the same tube under it and under the
    # same constants set by hand.
    (tmp_path / "mix.json").write_text(json.dumps({
        "format": "actuator-material", "version": 1, "name": "mix",
        "material": {"law": "yeoh", "c10_kpa": 12.0, "c20_kpa": 0.3, "stretch_limit": 3.0}, "fit": None}))
    material = actuator.Material.from_file(str(tmp_path / "mix.json"))
    assert (material.law, material.c10_kpa, material.c20_kpa, material.stretch_limit, material.preset) == ("yeoh", 12.0, 0.3, 3.0, "custom")
    by_hand = actuator.Material.from_preset("custom")
    by_hand.law, by_hand.c10_kpa, by_hand.c20_kpa, by_hand.stretch_limit = "yeoh", 12.0, 0.3, 3.0
    geometry = actuator.Geometry(ring_vertices=16, rings=20)
    load = actuator.Load(pressure_kpa=1.0, steps=2)
    a = actuator.evaluate(actuator.cylinder(), model="membrane", geometry=geometry, material=material, load=load)
    b = actuator.evaluate(actuator.cylinder(), model="membrane", geometry=geometry, material=by_hand, load=load)
    assert a.status == "ok" and a.contraction_percent == b.contraction_percent
    (tmp_path / "typo.json").write_text('{"format": "actuator-material", "version": 1, "material": {"law": "yeoh", "c10kpa": 3}}')
    with pytest.raises(ValueError, match="c10kpa': unknown key"):
        actuator.Material.from_file(str(tmp_path / "typo.json"))
    with pytest.raises(ValueError, match="absent.json"):
        actuator.Material.from_file(str(tmp_path / "absent.json"))


def test_export_writes_the_command_lines_part(tmp_path):
    geometry = actuator.Geometry(ring_vertices=16, rings=24)
    shape = actuator.sine(1.3)
    out = actuator.export(shape, tmp_path / "py", geometry=geometry, sampling=1, mold=actuator.Mold(margin_mm=4))
    cli = subprocess.run([os.environ["ACTUATOR_BIN"], "export", "--model", "shell", "--shape", "sine", "--amplitude", "1.3", "--ring-vertices", "16",
                          "--rings", "24", "--sampling", "1", "--margin-mm", "4", "--out", str(tmp_path / "cli")], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    summary = json.loads(cli.stdout)
    assert out["silicone_volume_mm3"] == summary["silicone_volume_mm3"] and out["files"] == summary["files"]
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == names
    for name in names:
        if name.endswith(".stl"):
            assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    manifest = json.loads((tmp_path / "cli" / "manifest.json").read_text())
    assert out["manifest"]["pour"] == manifest["pour"] and out["manifest"]["mold"]["margin_mm"] == 4
    # A result exports its own design and model.
    r = actuator.evaluate(shape, geometry=geometry, load=actuator.Load(pressure_kpa=1, steps=1))
    again = actuator.export(r, tmp_path / "from_result", sampling=1, mold=actuator.Mold(margin_mm=4))
    assert (tmp_path / "from_result" / "actuator.stl").read_bytes() == (tmp_path / "cli" / "actuator.stl").read_bytes()
    assert again["silicone_volume_mm3"] == out["silicone_volume_mm3"]
    # Refusals name the argument, and write nothing.
    for kwargs, message in [(dict(unit_mm=5), "unit_mm: is for thesis-model designs"), (dict(cast="thirds"), "cast: unknown value 'thirds'"),
                            (dict(port_mm=3), "port_mm: goes with fittings=True"), (dict(flange_mm=3), "--flange-mm goes with --cast halves"),
                            (dict(printer_mm="big"), "--printer-mm")]:
        with pytest.raises(ValueError, match=message):
            actuator.export(shape, tmp_path / "bad", geometry=geometry, sampling=1, **kwargs)
        assert not (tmp_path / "bad").exists()
    with pytest.raises(ValueError, match="cannot demould"):
        actuator.export(actuator.bspline([[1, 3, 3, 3, 1]]), tmp_path / "bulb", geometry=geometry, sampling=1)
    assert not (tmp_path / "bulb").exists()
    with pytest.raises(TypeError, match="shape: expected an actuator.Shape or an actuator.Result"):
        actuator.export("sine", tmp_path / "x")
    with pytest.raises(ValueError, match="already|not empty|new or empty"):
        actuator.export(shape, tmp_path / "py", geometry=geometry, sampling=1)


def test_any_command_runs_in_process_as_on_the_command_line(tmp_path):
    args = ["simulate", "--model", "thesis", "--shape", "sine", "--amplitude", "2", "--iterations", "300"]
    inside = actuator.cli(*args)
    assert inside["exit_code"] == 0
    assert json.loads(inside["stdout"]) == json.loads(subprocess.run([BIN, *args], check=True, capture_output=True, text=True).stdout) | {
        "elapsed_ms": json.loads(inside["stdout"])["elapsed_ms"]}
    r = actuator.evaluate(actuator.sine(2), model="thesis", params=actuator.ThesisParams(iterations=300))
    assert json.loads(inside["stdout"])["fitness"] == r.fitness
    # Paths as Python takes them; a folder the command writes.
    out = actuator.cli("render", "--model", "thesis", "--iterations", "200", "--size", "80x64", "--supersample", "1", "--out", tmp_path / "pictures")
    assert out["exit_code"] == 0 and (tmp_path / "pictures" / "inflation.png").exists()
    with pytest.raises(ValueError, match="cli: unknown command 'simulat' \\(choose .*simulate"):
        actuator.cli("simulat")
    with pytest.raises(ValueError, match="--bogus"):
        actuator.cli("simulate", "--bogus")
    with pytest.raises(ValueError, match="cli: give a command"):
        actuator.cli()
    with pytest.raises(TypeError, match="argument: expected a path"):
        actuator.cli("simulate", "--iterations", 300)
    # The command's output went to the result, not to this process's stdout: std::cout is restored.
    again = actuator.cli(*args)
    assert json.loads(again["stdout"])["fitness"] == r.fitness


def test_vacuum_with_contact_equals_the_command_line():
    args = ["--model", "shell", "--shape", "cylinder", "--length-mm", "60", "--ring-vertices", "20", "--rings", "16",
            "--pressure-kpa", "-0.5", "--contact", "on"]
    cli = simulate(*args)
    ours = actuator.evaluate(actuator.cylinder(), model="shell", geometry=actuator.Geometry(length_mm=60, ring_vertices=20, rings=16),
                             load=actuator.Load(pressure_kpa=-0.5), contact=actuator.Contact(contact="on"))
    assert ours.status == cli["status"] == "ok"
    assert ours.contraction_percent.hex() == float(cli["contraction_percent"]).hex()
    assert ours.shell["contact_pairs"] == cli["contact_pairs"] > 0
    assert 0 < ours.shell["min_gap_mm"] == cli["min_gap_mm"] < 0.1
    with pytest.raises(ValueError, match="contact_gap_fraction: has no effect: it applies when contact is on, not off"):
        actuator.evaluate(actuator.cylinder(), model="shell", contact=actuator.Contact(contact="off", contact_gap_fraction=0.05))


def test_mesh_check_is_the_command_lines():
    args = ["--model", "shell", "--shape", "sine", "--amplitude", "1.3", "--length-mm", "60", "--ring-vertices", "20", "--rings", "16",
            "--pressure-kpa", "1", "--mesh-check"]
    cli = simulate(*args)["mesh_check"]
    ours = actuator.evaluate(actuator.sine(1.3), model="shell", geometry=actuator.Geometry(length_mm=60, ring_vertices=20, rings=16),
                             load=actuator.Load(pressure_kpa=1)).mesh_check()
    assert ours == cli
    assert ours["status"] == "ok" and ours["mesh"].startswith("40 vertices per ring")
    assert ours["converged"] == (ours["relative_difference_percent"] <= 5 or abs(ours["contraction_percent"]) < 1 and ours["difference_points"] <= 0.05)
    assert ours["blocking_force_n"] < 0 and isinstance(ours["blocking_force_converged"], bool)
    with pytest.raises(ValueError, match="mesh_check: the thesis model"):
        actuator.evaluate(actuator.sine(4.1), model="thesis").mesh_check()
