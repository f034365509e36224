"""Pliant: real-time simulation of flexible hoses for assembly studies.

Load a scene (or build one in code), step or settle it, add and remove load cases, grab
and move hands, read positions, orientations and forces as numpy arrays, run a whole
timeline and write the same reports as the ``pliant`` command. All values are SI
(metres, newtons, seconds, radians); vectors are in global axes; quaternions are
(w, x, y, z).

>>> import pliant
>>> scene = pliant.demo_scene()
>>> sim = pliant.Simulation(scene)
>>> _ = sim.grab(0, hose="lower", node=-1)
>>> sim.move_hand(0, by=[0.0, 0.0, 0.05], duration=0.2)
>>> sim.positions("lower").shape, sim.hand_force(0).shape
((16, 3), (3,))

See docs/python.md in the repository for a guide.
"""

from ._pliant import (
    DEFAULT_MAX_STEPS,
    Calibration,
    CalibrationError,
    CalibrationFit,
    HandLoad,
    LoadId,
    RunResult,
    Scene,
    SceneError,
    SettleReport,
    Simulation,
    SimulationDiverged,
    SolverNotConverged,
    SolverWarning,
    __version__,
    calibrate,
    demo_scene,
    load_scene,
    run_timeline,
)



def study(study, out=None, **options):
    """Runs (or resumes) a variant or tolerance study on Dask and returns its
    ``StudyResult`` (``.frame``: pandas DataFrame, one row per run). See
    ``pliant.studies.study`` for the options and docs/study.md for the format; needs the
    study extras (dask[distributed], pyarrow, pandas, scipy, scikit-image)."""
    from .studies import study as run

    return run(study, out, **options)


__all__ = [
    "DEFAULT_MAX_STEPS",
    "Calibration",
    "CalibrationError",
    "CalibrationFit",
    "HandLoad",
    "LoadId",
    "RunResult",
    "Scene",
    "SceneError",
    "SettleReport",
    "Simulation",
    "SimulationDiverged",
    "SolverNotConverged",
    "SolverWarning",
    "__version__",
    "calibrate",
    "demo_scene",
    "load_scene",
    "run_timeline",
    "study",
]
