"""actuator.optuna: a failed design is Optuna's constraint, pruning or failure as asked; outputs are
trial attributes; the example study runs, finds a design that re-evaluates to its value, and repeats."""
import json
import math
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import actuator

optuna = pytest.importorskip("optuna")
optuna.logging.set_verbosity(optuna.logging.ERROR)
warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)
ROOT = Path(__file__).resolve().parents[2]
SMALL = {"geometry": actuator.Geometry(ring_vertices=12, rings=16)}


def test_a_failed_design_is_a_constraint_a_pruned_trial_or_a_failed_one():
    # A plain tube at 20 kPa is past its pressure maximum (about 2.4 kPa): status limit-point.
    def balloon(trial):
        trial.suggest_float("x", 0, 1)
        return actuator.cylinder()
    load = actuator.Load(pressure_kpa=20, steps=2)
    states = {}
    for failed in ("constraint", "prune", "fail"):
        study = optuna.create_study(direction="maximize", sampler=optuna.samplers.RandomSampler(seed=0))
        study.optimize(actuator.optuna.Objective(balloon, failed=failed, failed_value=-5, load=load, **SMALL), n_trials=1, catch=())
        t = study.trials[0]
        assert t.user_attrs["status"] == "limit-point" and t.user_attrs["constraint"] == [1.0]
        assert t.user_attrs["limit_pressure_kpa"] > 1, "the outputs are stored, the limit among them"
        assert t.user_attrs["contraction_percent"] is None, "NaN is stored as None (JSON-safe)"
        states[failed] = (t.state, t.value)
    assert states["constraint"] == (optuna.trial.TrialState.COMPLETE, -5)
    assert states["prune"] == (optuna.trial.TrialState.PRUNED, None)
    assert states["fail"][0] == optuna.trial.TrialState.FAIL
    frozen = optuna.trial.create_trial(params={}, distributions={}, value=1.0, user_attrs={"constraint": [-1.0]})
    assert actuator.optuna.constraints(frozen) == [-1.0]


def test_an_ok_design_returns_its_fitness_and_stores_every_output():
    study = optuna.create_study(direction="maximize", sampler=optuna.samplers.RandomSampler(seed=0))
    load = actuator.Load(pressure_kpa=3, steps=2)

    def braid(trial):
        return actuator.cylinder(), {"fibres": actuator.Fibres(fibres="braid", fibre_angle_deg=trial.suggest_float("angle", 25, 35))}
    study.optimize(actuator.optuna.Objective(braid, load=load, **SMALL), n_trials=2)
    for t in study.trials:
        r = actuator.evaluate(actuator.cylinder(), load=load, fibres=actuator.Fibres(fibres="braid", fibre_angle_deg=t.params["angle"]), **SMALL)
        assert t.value == r.fitness == t.user_attrs["contraction_percent"] and t.user_attrs["constraint"] == [-1.0]
        assert t.user_attrs["blocking_force_n"] == r.shell["blocking_force_n"]
        assert set(t.user_attrs) >= {"status", "fitness", "elapsed_ms", "max_stretch", "volume_mm3", "max_fibre_strain"}
    # value= chooses another objective: here the blocking force.
    study = optuna.create_study(direction="maximize")
    study.optimize(actuator.optuna.Objective(braid, value=lambda r: r.shell["blocking_force_n"], load=load, **SMALL), n_trials=1)
    assert study.trials[0].value == study.trials[0].user_attrs["blocking_force_n"]


def test_bad_arguments_are_refused_naming_them():
    with pytest.raises(ValueError, match="failed: unknown value 'skip' \\(choose constraint, prune, fail\\)"):
        actuator.optuna.Objective(lambda t: actuator.cylinder(), failed="skip")
    with pytest.raises(TypeError, match="design: expected a callable"):
        actuator.optuna.Objective(actuator.cylinder())
    with pytest.raises(ValueError, match="failed_value: expected a finite number"):
        actuator.optuna.Objective(lambda t: actuator.cylinder(), failed_value=math.inf)
    study = optuna.create_study()
    with pytest.raises(TypeError, match="must return an actuator.Shape, got str"):
        study.optimize(actuator.optuna.Objective(lambda t: "sine"), n_trials=1, catch=())
    with pytest.raises(ValueError, match="geometry"):  # evaluate's own refusal: the thesis model has no geometry
        study.optimize(actuator.optuna.Objective(lambda t: actuator.cylinder(), model="thesis", **SMALL), n_trials=1, catch=())


def test_the_example_study_finds_a_design_that_re_evaluates_to_its_value_and_repeats(tmp_path):
    def study(name):
        out = subprocess.run([sys.executable, str(ROOT / "examples" / "optuna_study.py"), "--trials", "10", "--quick", "--json", str(tmp_path / name)],
                             capture_output=True, text=True, timeout=300)
        assert out.returncode == 0, out.stderr
        return json.loads((tmp_path / name).read_text()), out.stdout
    first, text = study("a.json")
    assert len(first["trials"]) == 10 and "best: trial" in text
    best = first["best"]
    r = actuator.evaluate(actuator.sine(best["params"]["amplitude"]), load=actuator.Load(pressure_kpa=3, steps=2),
                          fibres=actuator.Fibres(fibres="braid", fibre_angle_deg=best["params"]["braid_angle_deg"]), **SMALL)
    assert r.status == "ok" and r.fitness == best["value"] > 5, "a braid under the magic angle contracts"
    assert best["value"] == max(t["value"] for t in first["trials"] if t["attrs"]["status"] == "ok")
    again, _ = study("b.json")
    for trial in first["trials"] + again["trials"]:
        del trial["attrs"]["elapsed_ms"]  # wall time: the one output that differs between runs
    assert again == first, "the same seed, the same study"
    refused = subprocess.run([sys.executable, str(ROOT / "examples" / "optuna_study.py"), "--json", str(tmp_path / "a.json")], capture_output=True, text=True)
    assert refused.returncode == 2 and "exists" in refused.stderr
