"""Type stubs of Pliant's native module (re-exported by ``pliant``)."""

from os import PathLike
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__version__: str
DEFAULT_MAX_STEPS: int

HoseRef = Union[str, int]
"""A hose by name or by index (negative counts from the end)."""
Vector = Union[Sequence[float], npt.NDArray[np.floating[Any]]]
"""Three numbers [x, y, z]."""
Points = Union[Vector, Sequence[Vector], npt.NDArray[np.floating[Any]]]
"""One point [x, y, z] or several, shape (K, 3)."""
Quaternion = Union[Sequence[float], npt.NDArray[np.floating[Any]]]
"""(w, x, y, z)."""
FloatArray = npt.NDArray[np.float64]
StrPath = Union[str, "PathLike[str]"]

class SceneError(ValueError):
    """A scene could not be loaded or built; the message is the one ``pliant run`` prints."""

    field: Optional[str]
    location: Optional[Tuple[int, int]]

class SimulationDiverged(RuntimeError):
    """The simulation blew up; the message names the step, the node and the likely cause."""

    step: int
    time: float
    hose: str
    node: int
    what: str
    cause: str
    result: Optional["RunResult"]

class SolverNotConverged(RuntimeError):
    """A Newton solve ended out of balance or unstable (``Simulation(..., strict=True)``)."""

class SolverWarning(RuntimeWarning):
    """A Newton solve ended out of balance or unstable: those steps' forces are not trustworthy."""

@final
class Scene:
    """A loaded, checked scene (SI units) with its physics model built."""

    @staticmethod
    def load(path: StrPath) -> "Scene": ...
    @staticmethod
    def from_toml(
        text: str, origin: str = "<string>", base_dir: Optional[StrPath] = None
    ) -> "Scene": ...
    @staticmethod
    def from_json(
        text: str, origin: str = "<string>", base_dir: Optional[StrPath] = None
    ) -> "Scene": ...
    @staticmethod
    def from_dict(
        scene: Dict[str, Any], origin: str = "<dict>", base_dir: Optional[StrPath] = None
    ) -> "Scene": ...
    @property
    def name(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def text(self) -> str: ...
    @property
    def hose_names(self) -> List[str]: ...
    def node_count(self, hose: HoseRef) -> int: ...
    @property
    def hoses(self) -> List[Dict[str, Any]]: ...
    @property
    def part_names(self) -> List[str]: ...
    @property
    def stub_names(self) -> List[str]: ...
    @property
    def clip_names(self) -> List[str]: ...
    @property
    def record_interval(self) -> float: ...
    @property
    def time_step(self) -> float: ...
    @property
    def ergonomics(self) -> str: ...
    @property
    def timeline(self) -> List[Dict[str, Any]]: ...

def load_scene(path: StrPath) -> Scene:
    """Loads a scene file (TOML, or JSON for ``*.json``); raises SceneError."""

def demo_scene() -> Scene:
    """The built-in engine-bay demo scene."""

@final
class LoadId:
    """Handle of a load case you added, for ``Simulation.remove_load``."""

    @property
    def id(self) -> int: ...
    @property
    def kind(self) -> str: ...
    @property
    def hose(self) -> str: ...
    @property
    def node(self) -> int: ...
    def __eq__(self, other: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class HandLoad:
    """The load a hand applied in the last step and its ergonomic assessment."""

    @property
    def hand(self) -> int: ...
    @property
    def hose(self) -> str: ...
    @property
    def position(self) -> FloatArray: ...
    @property
    def force(self) -> FloatArray: ...
    @property
    def torque(self) -> FloatArray: ...
    @property
    def direction(self) -> FloatArray: ...
    @property
    def kind(self) -> Optional[str]: ...
    @property
    def ratio(self) -> float: ...
    @property
    def limit(self) -> float: ...
    @property
    def colour(self) -> float: ...
    @property
    def axial_force(self) -> float: ...
    @property
    def lateral_force(self) -> float: ...
    @property
    def twist(self) -> float: ...
    @property
    def bending(self) -> float: ...

@final
class SettleReport:
    """How ``Simulation.settle`` ended; true if it converged."""

    @property
    def converged(self) -> bool: ...
    @property
    def steps(self) -> int: ...
    @property
    def residual_force(self) -> float: ...
    @property
    def residual_moment(self) -> float: ...
    def __bool__(self) -> bool: ...

@final
class Simulation:
    """A simulation of a scene, stepped on request."""

    def __new__(
        cls,
        scene: Scene,
        *,
        initial_loads: bool = True,
        solver: str | None = None,
        strict: bool = False,
    ) -> "Simulation": ...
    @property
    def solver_warnings(self) -> List[str]: ...
    def instabilities(self) -> List[Dict[str, Any]]: ...
    @property
    def solver(self) -> str:
        """explicit, implicit or static."""
        ...
    @property
    def scene(self) -> Scene: ...
    @property
    def time(self) -> float: ...
    @property
    def time_step(self) -> float: ...
    @property
    def step_count(self) -> int: ...
    @property
    def hose_names(self) -> List[str]: ...
    def node_count(self, hose: HoseRef) -> int: ...
    # stepping and solving
    def step(self, n: int = 1) -> None: ...
    def run(self, seconds: float) -> int: ...
    def settle(
        self,
        force_tolerance: float = 1e-3,
        moment_tolerance: float = 1e-4,
        max_steps: int = 1_000_000,
        kinetic_damping: bool = True,
    ) -> SettleReport: ...
    def solve_static(
        self,
        force_tolerance: float = 1e-7,
        moment_tolerance: float = 1e-8,
        max_iterations: int = 100,
    ) -> SettleReport:
        """Static equilibrium by the quasi-static Newton solver; ``steps`` = iterations."""
        ...
    def reset(self) -> None: ...
    # load cases
    def fix(self, hose: HoseRef, node: int) -> LoadId: ...
    def drive(
        self,
        hose: HoseRef,
        node: int,
        to: Optional[Points] = None,
        *,
        by: Optional[Points] = None,
        rotate: Optional[Vector] = None,
        duration: float = 1.0,
        wait: bool = True,
    ) -> LoadId: ...
    def add_dead_load(
        self,
        hose: HoseRef,
        node: int,
        force: Optional[Vector] = None,
        moment: Optional[Vector] = None,
        *,
        ramp: float = 0.0,
    ) -> LoadId: ...
    def remove_load(self, load: LoadId) -> None: ...
    @property
    def load_cases(self) -> List[LoadId]: ...
    # hands
    def grab(
        self,
        hand: int,
        at: Optional[Vector] = None,
        *,
        hose: Optional[HoseRef] = None,
        node: Optional[int] = None,
        grip: str = "firm",
    ) -> Tuple[str, int, int]: ...
    def move_hand(
        self,
        hand: int,
        to: Optional[Points] = None,
        *,
        by: Optional[Points] = None,
        orientation: Optional[Quaternion] = None,
        rotate: Optional[Vector] = None,
        duration: Optional[float] = None,
        speed: Optional[float] = None,
        wait: bool = True,
    ) -> None: ...
    def aim_hand(self, hand: int, position: Sequence[float], orientation: Optional[Sequence[float]] = None) -> None: ...
    def release(self, hand: int) -> None: ...
    # parts moved by the script (movable parts without a `motion`)
    def move_part(
        self,
        part: str,
        to: Optional[Sequence[float]] = None,
        *,
        by: Optional[Sequence[float]] = None,
        duration: float = 1.0,
        wait: bool = True,
    ) -> None: ...
    def rotate_part(
        self,
        part: str,
        axis: Sequence[float],
        *,
        by: Optional[float] = None,
        to: Optional[float] = None,
        point: Optional[Sequence[float]] = None,
        duration: float = 1.0,
        wait: bool = True,
    ) -> None: ...
    def part_pose(self, part: str) -> Tuple[FloatArray, FloatArray]: ...
    @property
    def hands(self) -> List[int]: ...
    def hand_pose(self, hand: int) -> Tuple[FloatArray, FloatArray]: ...
    def hand_load(self, hand: int) -> HandLoad: ...
    def hand_force(self, hand: int) -> FloatArray: ...
    def hand_torque(self, hand: int) -> FloatArray: ...
    # arrays (fresh copies)
    def positions(self, hose: HoseRef) -> FloatArray: ...
    def orientations(self, hose: HoseRef) -> FloatArray: ...
    def velocities(self, hose: HoseRef) -> FloatArray: ...
    def angular_velocities(self, hose: HoseRef) -> FloatArray: ...
    def forces(self, hose: HoseRef) -> FloatArray: ...
    def moments(self, hose: HoseRef) -> FloatArray: ...
    def reaction_forces(self, hose: HoseRef) -> FloatArray: ...
    def reaction_moments(self, hose: HoseRef) -> FloatArray: ...
    def held(self, hose: HoseRef) -> npt.NDArray[np.bool_]: ...
    def contact_forces(self, hose: HoseRef) -> FloatArray: ...
    def hose_contact_forces(self, hose: HoseRef) -> FloatArray: ...
    def rest_positions(self, hose: HoseRef) -> FloatArray: ...
    def masses(self, hose: HoseRef) -> FloatArray: ...
    @property
    def kinetic_energy(self) -> float: ...
    @property
    def strain_energy(self) -> float: ...
    @property
    def gravity_energy(self) -> float: ...
    def fasteners(self) -> List[Dict[str, Any]]: ...
    def worker(self) -> Optional[Dict[str, Any]]: ...
    def sweep(self) -> Optional[Dict[str, Any]]: ...

@final
class RunResult:
    """The outcome of ``run_timeline``."""

    @property
    def standard(self) -> str: ...
    @property
    def zones(self) -> List[str]: ...
    @property
    def feasible(self) -> Optional[bool]: ...
    @property
    def reasons(self) -> List[str]: ...
    @property
    def findings(self) -> Dict[str, List[Dict[str, Any]]]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def violations(self) -> List[Dict[str, Any]]: ...
    @property
    def check_profiles(self) -> List[Dict[str, Any]]: ...
    @property
    def uncertain(self) -> bool: ...
    @property
    def completed(self) -> bool: ...
    @property
    def diverged(self) -> Optional[str]: ...
    @property
    def steps(self) -> int: ...
    @property
    def simulated_time(self) -> float: ...
    @property
    def ergonomics(self) -> str: ...
    @property
    def summary(self) -> Dict[str, Any]: ...
    @property
    def divergence(self) -> Optional[Dict[str, Any]]: ...
    @property
    def solver_record(self) -> Dict[str, Any]: ...
    @property
    def settles(self) -> List[Dict[str, Any]]: ...
    @property
    def solver_warnings(self) -> List[str]: ...
    @property
    def peaks(self) -> List[Dict[str, Any]]: ...
    @property
    def hand_peaks(self) -> List[Dict[str, Any]]: ...
    @property
    def worker(self) -> Optional[Dict[str, Any]]: ...
    @property
    def fasteners(self) -> List[Dict[str, Any]]: ...
    @property
    def contacts(self) -> List[Dict[str, Any]]: ...
    @property
    def times(self) -> FloatArray: ...
    def motion(self) -> Optional[Dict[str, FloatArray]]: ...
    def positions(self, hose: HoseRef) -> FloatArray: ...
    @property
    def hands(self) -> List[int]: ...
    def hand_series(self, hand: int) -> Dict[str, FloatArray]: ...
    def write_report(self, out: StrPath) -> None: ...

def run_timeline(scene: Scene, ergonomics: Optional[str] = None, solver: Optional[str] = None,
                 max_steps: int = ...) -> RunResult:
    """Runs the scene's whole timeline as ``pliant run`` does; refused with SceneError
    when planned beyond ``max_steps`` steps (default ``DEFAULT_MAX_STEPS``)."""

def centreline_sample_keys(frames: FloatArray, h: float) -> Any:
    """Sorted unique int64 keys of the centre-line samples of frames (T, N, 3) [m] for
    voxels of size h [m] (``pliant.studies.envelope.sample_keys``)."""

def swept_voxel_keys(samples: Any, radius: float, h: float) -> Any:
    """Sorted int64 keys of the voxels of size h [m] within reach of the samples (keys of
    ``centreline_sample_keys``) for a tube of outer radius ``radius`` [m]
    (``pliant.studies.envelope.voxels_of_samples``)."""

def part_distances(
    points: FloatArray,
    kind: str,
    position: Sequence[float],
    rotation: Sequence[Sequence[float]],
    size: Sequence[float],
    triangles: Optional[FloatArray] = None,
) -> FloatArray:
    """The distance of each point (K, 3) [m] to a part's surface: ``kind`` "box",
    "cylinder", "sphere" (``size``: edges; radius and height; radius) or "mesh"
    (``triangles`` (F, 3, 3) in world coordinates)."""

def part_clearance(
    points: FloatArray,
    offsets: FloatArray,
    kind: str,
    position: Sequence[float],
    rotation: Sequence[Sequence[float]],
    size: Sequence[float],
    triangles: Optional[FloatArray] = None,
) -> float:
    """min over the points (K, 3) of (distance to the part − offset) [m], as
    ``part_distances(...) - offsets`` would give; +inf for no points."""

def material_library_toml() -> str:
    """The built-in material library as shipped (TOML text), each value with its source."""

class CalibrationError(ValueError):
    """A calibration could not be done; the message is the one ``pliant calibrate``
    prints (file, line, column, what is wrong)."""

    file: str
    line: Optional[int]
    column: Optional[int]

@final
class CalibrationFit:
    """One fitted test curve (docs/calibration.md)."""

    @property
    def kind(self) -> str: ...
    @property
    def csv(self) -> str: ...
    @property
    def symbol(self) -> str:
        """E_t, E_c, EI or GJ."""
    @property
    def unit(self) -> str:
        """Display unit of ``value_display`` (MPa or N·m²)."""
    @property
    def value(self) -> float:
        """The stiffness in SI: Pa (E_t, E_c) or N·m² (EI, GJ)."""
    @property
    def std_error(self) -> float: ...
    @property
    def ci95(self) -> Tuple[float, float]:
        """Two-sided 95 % confidence interval (Student t, n − 2 degrees of freedom), SI."""
    @property
    def value_display(self) -> float: ...
    @property
    def ci95_display(self) -> Tuple[float, float]: ...
    @property
    def slope(self) -> float: ...
    @property
    def intercept(self) -> float: ...
    @property
    def residual_rms(self) -> float: ...
    @property
    def residual_std(self) -> float: ...
    @property
    def r_squared(self) -> float: ...
    @property
    def range(self) -> Dict[str, Any]:
        """The linear range: first_row, last_row (0-based), first_line, last_line (CSV),
        points, total_points, x_from, x_to, y_from, y_to (plot units), x_label, y_label,
        noise_std."""
    @property
    def formula(self) -> str: ...
    @property
    def x(self) -> FloatArray:
        """The fitted curve's abscissa, SI (strain, deflection, angle or curvature)."""
    @property
    def y(self) -> FloatArray:
        """Its ordinate, SI (stress, force or torque)."""

@final
class Calibration:
    """A finished calibration: fits, the material with its sources, the files."""

    @property
    def fits(self) -> List[CalibrationFit]: ...
    @property
    def laws(self) -> List[Dict[str, Any]]:
        """The inelastic laws fitted (plastic_bending, relaxation, cyclic_bending,
        cyclic_torsion): kind, csv, fit (estimates with name, value, ci95, identified),
        formula, checks."""
    @property
    def material(self) -> Dict[str, Any]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def material_toml(self) -> str:
        """The ``[materials.NAME]`` table for a scene file."""
    @property
    def library_toml(self) -> str:
        """The entry in the built-in library's format."""
    @property
    def html(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]:
        """calibration.json as a dict."""
    def write(self, out: StrPath) -> List[str]:
        """Writes material.toml, library_entry.toml, calibration.json, calibration.html."""

def calibrate(
    spec: Optional[StrPath] = None,
    *,
    kind: Optional[str] = None,
    csv: Optional[StrPath] = None,
    data: Optional[Dict[str, Sequence[float]]] = None,
    length_mm: Optional[float] = None,
    d_outer_mm: Optional[float] = None,
    d_inner_mm: float = 0.0,
    name: str = "calibrated",
    density_kg_m3: float = 1100.0,
    poisson: Optional[float] = None,
    terms: Optional[int] = None,
    held_strain: Optional[float] = None,
    out: Optional[StrPath] = None,
) -> Calibration:
    """Fits a material's stiffness to measured test curves: a calibration file, or one
    test (``kind`` with ``csv`` or ``data``). A relaxation test alone needs
    ``held_strain`` (gives E0); ``terms`` forces its Prony term count. See
    docs/calibration.md."""
