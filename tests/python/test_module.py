"""`import actuator`: the module against the command line, bit for bit; threads; errors; arrays."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import actuator

BIN = os.environ.get("ACTUATOR_BIN", "actuator")


def simulate(*args):
    out = subprocess.run([BIN, "simulate", *args], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def test_evaluate_matches_the_command_line_bit_for_bit():
    ours = actuator.evaluate(actuator.sine(4.1, (0.5, math.pi - 0.5)))
    cli = simulate("--shape", "sine", "--amplitude", "4.1", "--phase", "0.5,pi-0.5")
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
    one = [actuator.evaluate(s, params=params).fitness for s in shapes]
    for threads in (1, 2):
        many = [r.fitness for r in actuator.evaluate_many(shapes, threads=threads, params=params)]
        assert [f.hex() for f in many] == [f.hex() for f in one]


def test_positions_are_n_by_3_arrays():
    r = actuator.evaluate(actuator.cylinder(), params=actuator.ThesisParams(iterations=100))
    assert isinstance(r.final, np.ndarray)
    assert r.final.shape == (900, 3) and r.initial.shape == (900, 3)
    assert np.allclose(np.hypot(r.initial[:, 0], r.initial[:, 1]), 1.0)


def test_shell_model_contraction_at_pressure():
    load = actuator.Load(pressure_kpa=1.0, steps=2)
    r = actuator.evaluate(actuator.cylinder(), model="shell", geometry=actuator.Geometry(ring_vertices=12, rings=16), load=load)
    assert r.status == "ok"
    assert r.fitness == r.contraction_percent


def test_bad_input_raises_value_error_with_the_message():
    with pytest.raises(ValueError, match="out of range"):
        actuator.ThesisParams(iterations=-5)
    with pytest.raises(ValueError, match="unknown field 'iteration'"):
        actuator.ThesisParams(iteration=5)
    with pytest.raises(ValueError, match="choose"):
        actuator.evaluate(actuator.cylinder(), model="fem")
    with pytest.raises(ValueError, match="control points"):
        actuator.evaluate(actuator.bspline([[1, 2]]))
    with pytest.raises(ValueError, match="thesis model's"):
        actuator.evaluate(actuator.cylinder(), model="shell", params=actuator.ThesisParams())


def test_numerical_failure_is_a_status_not_an_exception():
    params = actuator.ThesisParams(step_scale=50.0, iterations=2000)
    r = actuator.evaluate(actuator.sine(4.1, (0.5, math.pi - 0.5)), params=params)
    assert r.status != "ok"


SWEEP = {
    "id": "py", "title": "python sweep", "sim": {"iterations": 2000},
    "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]},
              "axes": [{"parameter": "amplitude", "from": 1, "to": 4, "points": 3}]},
    "render": {"figures": False, "thumbnails": False},
}


def test_a_sweep_returns_its_table_and_equals_evaluate(tmp_path):
    out = actuator.sweep(SWEEP, str(tmp_path / "s"), threads=2)
    results = out["tables"]["results"]
    assert list(results["amplitude"]) == [1.0, 2.5, 4.0]
    one = actuator.evaluate(actuator.sine(2.5, (0.5, math.pi - 0.5)), params=actuator.ThesisParams(iterations=2000))
    assert float(results["fitness"][1]).hex() == one.fitness.hex()
    assert out["summary"]["simulations"] == 3


def test_a_small_ga_logs_every_generation(tmp_path):
    ga = {"id": "g", "seed": 3, "sim": {"iterations": 1500},
          "evolve": {"runs": 1, "population": 6, "generations": 2, "genome": {"kind": "bspline", "length": [4, 6]}},
          "render": {"figures": False, "thumbnails": False}}
    out = actuator.evolve(ga, str(tmp_path / "g"))
    logbook = out["tables"]["run_1_logbook"]
    assert list(logbook["generation"]) == [0, 1, 2]
    assert all(logbook["best"] >= logbook["median"])


def test_bad_experiments_raise_value_error(tmp_path):
    with pytest.raises(ValueError, match="sim.iteration"):
        actuator.run({"id": "x", "sim": {"iteration": 5}, "sweep": SWEEP["sweep"]}, str(tmp_path / "x"))
    with pytest.raises(ValueError, match="is a 'sweep' one"):
        actuator.evolve(SWEEP, str(tmp_path / "y"))
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "keep.txt").write_text("mine")
    with pytest.raises(ValueError):
        actuator.sweep(SWEEP, str(tmp_path / "full"))
    assert (tmp_path / "full" / "keep.txt").read_text() == "mine"
