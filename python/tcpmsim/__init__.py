"""tcpmsim from Python: build a scenario, run it, get numpy arrays.

    import tcpmsim
    scenario = tcpmsim.Scenario.from_yaml("configs/ch7_identification.yaml")
    scenario.set("muscle.mechanics.k2", "3 mN/mm")
    result = scenario.run(duration=60)
    force = result["muscle/force"]          # numpy array, result.units["muscle/force"] == "N"
    result.save("results/k2_3.h5")           # the record `tcpmsim run` writes

The module is thin: every model, unit and error comes from the C++ engine (tcpmsim._core).
"""

from ._core import (ConfigError, ParameterError, Result, Scenario, Simulator, SolverFailure,
                    UnitError, UsageError,
                    __version__, analyze, control_task, git_commit, run_many)

__all__ = ["ConfigError", "ParameterError", "Result", "Scenario", "Simulator", "SolverFailure",
           "UnitError",
           "UsageError",
           "__version__", "analyze", "control_task", "git_commit", "run_many", "sweep"]


def sweep(scenario, path, values, jobs=0):
    """Runs `scenario` once per value of `path` (as Scenario.set takes it) on `jobs` threads
    (0: one per core); returns the Results in the order of `values`."""
    runs = [scenario.copy().set(path, value) for value in values]
    return run_many(runs, jobs)
