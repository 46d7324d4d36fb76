"""actuator.optuna: Optuna objectives over the workbench's models.

    import optuna, actuator
    def design(trial):
        return actuator.sine(trial.suggest_float("amplitude", 1, 1.6)), {
            "fibres": actuator.Fibres(fibres="braid", fibre_angle_deg=trial.suggest_float("angle", 20, 60))}
    objective = actuator.optuna.Objective(design, load=actuator.Load(pressure_kpa=3, steps=2))
    study = optuna.create_study(direction="maximize",
                                sampler=optuna.samplers.TPESampler(seed=1, constraints_func=actuator.optuna.constraints))
    study.optimize(objective, n_trials=40)

A design that fails (any status but ok: a limit point, a self-intersection, a wall stretched past
its limit, ...) is a fact about the design, not an error, and Optuna is told so in one of three ways
(`failed=`):
  "constraint" (default)  the trial completes with `failed_value` and user attribute "constraint"
                          [1.0] (ok designs: [-1.0]); pass `constraints_func=actuator.optuna.constraints`
                          to a sampler that takes one (TPE, NSGA-II) and it learns to avoid them;
  "prune"                 optuna.TrialPruned: the trial is PRUNED, samplers skip it;
  "fail"                  the objective returns NaN: Optuna marks the trial FAIL.
Every trial stores its result's outputs as user attributes (status, fitness, contraction_percent,
elapsed_ms and, under the membrane and shell models, every number of `actuator simulate`'s JSON,
units in the names), so study.trials_dataframe() holds them.
"""
import math

_FAILED = ("constraint", "prune", "fail")


def constraints(trial):
    """The constraints_func for Optuna's samplers: [1.0] for a failed design, [-1.0] for an ok one."""
    return trial.user_attrs.get("constraint", [1.0])


def outputs(result):
    """A result's numbers as plain Python values (what a trial stores): NaN as None, curves left out."""
    values = {"status": result.status, "fitness": result.fitness, "contraction_percent": result.contraction_percent,
              "elapsed_ms": result.elapsed_ms}
    for name, value in result.shell.items():
        if isinstance(value, (int, float)):
            values[name] = value
    return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in values.items()}


class Objective:
    """An Optuna objective: design(trial) gives a Shape, or (Shape, dict of actuator.evaluate's keyword
    arguments for this trial); `settings` are evaluate's keyword arguments for every trial (model,
    geometry, material, load, fibres, ...). The value is the result's fitness (the contraction in %
    under the membrane and shell models), or `value(result)` when given."""

    def __init__(self, design, failed="constraint", failed_value=0.0, value=None, **settings):
        if failed not in _FAILED:
            raise ValueError(f"failed: unknown value '{failed}' (choose {', '.join(_FAILED)})")
        if not callable(design):
            raise TypeError(f"design: expected a callable design(trial), got {type(design).__name__}")
        if not isinstance(failed_value, (int, float)) or isinstance(failed_value, bool) or not math.isfinite(failed_value):
            raise ValueError(f"failed_value: expected a finite number, got {failed_value!r}")
        self.design, self.failed, self.failed_value, self.value, self.settings = design, failed, float(failed_value), value, settings

    def __call__(self, trial):
        import actuator
        import optuna
        made = self.design(trial)
        extra = {}
        if isinstance(made, tuple):
            if len(made) != 2 or not isinstance(made[1], dict):
                raise TypeError("design(trial) must return a Shape or (Shape, dict of evaluate's keyword arguments)")
            made, extra = made
        if not isinstance(made, actuator.Shape):
            raise TypeError(f"design(trial) must return an actuator.Shape, got {type(made).__name__}")
        result = actuator.evaluate(made, **{**self.settings, **extra})
        for name, value in outputs(result).items():
            trial.set_user_attr(name, value)
        ok = result.status == "ok"
        trial.set_user_attr("constraint", [-1.0] if ok else [1.0])
        if ok:
            return float(self.value(result)) if self.value else result.fitness
        if self.failed == "prune":
            raise optuna.TrialPruned(f"status {result.status}")
        if self.failed == "fail":
            return math.nan
        return self.failed_value
