"""The study file (format "pliant-study", docs/study.md): read, check, and hold it.

Errors are :class:`StudyError` (a ``ValueError``) naming the file, the field, the value
and the reason, like the scene format's: ``study.toml: parameters[2].std = -1: must be > 0``.
Lengths in the file are in its ``length_unit``, angles in degrees; inside, everything is
SI (metres, radians, pascals).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import stat
import re
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

from .toml_positions import locate

try:  # Python ≥ 3.11
    import tomllib as _toml
except ImportError:  # pragma: no cover - older Pythons need tomli
    import tomli as _toml  # type: ignore

FORMAT = "pliant-study"
VERSION = 1
METHODS = ("monte_carlo", "latin_hypercube", "grid", "saltelli")
SOLVERS = ("explicit", "implicit", "static")
SETTLE_FINISHES = ("dynamic", "static", "static_equilibrium")  # a settle action's `finish` (docs/scene-format.md)
DISTRIBUTIONS = ("normal", "uniform", "triangular", "choice")
UNITS_M = {"m": 1.0, "mm": 1e-3}

# What a parameter varies: its target fields, default way of applying, and the unit of
# its value inside ("1" a factor or number, "m" a length, "rad" an angle, "" a choice).
KINDS: Dict[str, Tuple[Tuple[str, ...], str]] = {
    "material": (("material", "property"), "scale"),
    "hose_length": (("hose",), "scale"),
    "clip_position": (("clip", "direction"), "offset"),
    "stub_position": (("stub", "direction"), "offset"),
    "clip_rotation": (("clip", "axis"), "offset"),
    "stub_rotation": (("stub", "axis"), "offset"),
    "grab_offset": (("action", "direction"), "offset"),
    "hand_path_offset": (("action", "direction"), "offset"),
    "ergonomics": ((), "set"),
    "solver": ((), "set"),
    "scene_value": (("path",), "set"),
    "motion": (("part", "property"), "scale"),
}
# What a `motion` parameter changes of a part's `motion` (docs/study.md).
MOTION_PROPERTIES = ("range", "speed")
# Material properties a study may vary, with their factor to SI.
MATERIAL_PROPERTIES = {
    "e_mpa": 1e6,  # E_t, E_c (and E_b if given) together: a batch's stiffness
    "e_tension_mpa": 1e6,
    "e_compression_mpa": 1e6,
    "e_bending_mpa": 1e6,
    "density_kg_m3": 1.0,
    "poisson": 1.0,
    "min_bend_radius_mm": 1e-3,
    "yield_stress_mpa": 1e6,  # a metal line's σ_y (docs/scene-format.md)
    "hardening_modulus_mpa": 1e6,
}
PARAMETER_KEYS = {
    "name", "vary", "apply", "distribution", "mean", "std", "min", "max", "mode",
    "choices", "levels", "material", "property", "hose", "clip", "stub", "part", "direction",
    "axis", "action", "path",
}


class StudyError(ValueError):
    """A study file could not be read: the message names the file (with the line and
    column of the field, when it is written in the file), the field and why.
    ``where`` is the field's path (``parameters[2].std``), ``None`` for a whole-file
    problem."""

    def __init__(self, message: str, where: Optional[str] = None):
        super().__init__(message)
        self.where = where


@dataclass
class Distribution:
    """A bounded or unbounded distribution of one parameter's value (SI inside)."""

    kind: str
    mean: float = 0.0
    std: float = 0.0
    low: float = -math.inf
    high: float = math.inf
    mode: float = 0.0
    choices: Tuple[Any, ...] = ()

    def ppf(self, u):
        """The values at quantiles ``u`` ∈ (0, 1) (numpy array); a choice gives indices."""
        import numpy as np
        from scipy import stats

        u = np.asarray(u, dtype=float)
        if self.kind == "uniform":
            return self.low + u * (self.high - self.low)
        if self.kind == "triangular":
            scale = self.high - self.low
            return stats.triang.ppf(u, (self.mode - self.low) / scale, loc=self.low, scale=scale)
        if self.kind == "normal":  # truncated to [low, high] by the inverse CDF
            a = stats.norm.cdf((self.low - self.mean) / self.std)
            b = stats.norm.cdf((self.high - self.mean) / self.std)
            return self.mean + self.std * stats.norm.ppf(a + u * (b - a))
        return np.minimum((u * len(self.choices)).astype(int), len(self.choices) - 1)


@dataclass
class Parameter:
    """One varied quantity: what it acts on, how, and its distribution."""

    name: str
    vary: str
    apply: str
    unit: str
    distribution: Distribution
    target: Dict[str, Any] = field(default_factory=dict)
    levels: Optional[List[Any]] = None  # grid levels (SI), when given explicitly

    @property
    def categorical(self) -> bool:
        return self.distribution.kind == "choice"

    @property
    def column(self) -> str:
        """The Parquet column of this parameter's value."""
        return "p_" + self.name


@dataclass
class Study:
    """A checked study: base scene, parameters, sampling and envelope settings."""

    name: str
    origin: str
    base_dir: str
    scene_path: str
    scene: Dict[str, Any]
    parameters: List[Parameter]
    method: str
    runs: int
    seed: int
    grid_levels: int
    solver: Optional[str]
    ergonomics: Optional[str]
    scene_values: Dict[str, Any]
    mass_scaling: Optional[float]
    settle: Optional[str]  # every settle action's `finish`; None: the scene's
    rerun_unsettled: bool  # a run whose settles do not all rest (or, mass-scaled, whose clip ends free) runs again plain
    envelope_voxel_m: Optional[float]
    envelope_hoses: Optional[List[str]]
    source: Dict[str, Any] = field(repr=False, default_factory=dict)

    def fingerprint(self) -> str:
        """Hash of everything that decides the runs: a resumed study must match it."""
        blob = json.dumps(
            {"study": self.source, "runs": self.runs, "scene": self.scene},
            sort_keys=True, default=str,
        )
        return hashlib.sha256(blob.encode()).hexdigest()[:16]


def _fail(origin: str, where: str, value: Any, why: str) -> StudyError:
    shown = json.dumps(value, default=str) if not isinstance(value, str) else value
    return StudyError(f"{origin}: {where} = {shown}: {why}", where)


def _number(origin, where, value, *, positive=False, allow_none=False) -> Optional[float]:
    if value is None and allow_none:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _fail(origin, where, value, "must be a number")
    if not math.isfinite(value):
        raise _fail(origin, where, value, "must be finite")
    if positive and value <= 0:
        raise _fail(origin, where, value, "must be > 0")
    return float(value)


def _vector(origin, where, value) -> List[float]:
    if not isinstance(value, list) or len(value) != 3:
        raise _fail(origin, where, value, "must be three numbers [x, y, z]")
    v = [_number(origin, f"{where}[{i}]", x) for i, x in enumerate(value)]
    n = math.sqrt(sum(x * x for x in v))
    if n == 0:
        raise _fail(origin, where, value, "must not be zero")
    return [x / n for x in v]


def _is_one_of(value: Any, names) -> bool:
    """Whether a value read from the file is one of the given names: a list or table where a
    name belongs is not (and is no key to look up)."""
    return isinstance(value, str) and value in names


def _distribution(origin, where, p: Dict[str, Any], unit_factor: float) -> Distribution:
    kind = p.get("distribution")
    if kind not in DISTRIBUTIONS:
        raise _fail(origin, f"{where}.distribution", kind, f"must be one of {', '.join(DISTRIBUTIONS)}")
    if kind == "choice":
        choices = p.get("choices")
        if not isinstance(choices, list) or not choices:
            raise _fail(origin, f"{where}.choices", choices, "must be a non-empty list")
        return Distribution("choice", choices=tuple(choices))
    f = unit_factor

    def num(key, **kw):
        return _number(origin, f"{where}.{key}", p.get(key), **kw)

    def si(key, value):
        """``value`` of field ``key`` in SI; refused when the conversion overflows."""
        if value is None:
            return None
        v = value * f
        if not math.isfinite(v):
            raise _fail(origin, f"{where}.{key}", value, f"is beyond the largest number once converted to SI units (× {f:g})")
        return v

    low = num("min", allow_none=True)
    high = num("max", allow_none=True)
    if kind == "normal":
        mean, std = num("mean"), num("std", positive=True)
        low = -math.inf if low is None else low
        high = math.inf if high is None else high
        if not low < high or not low <= mean <= high:
            raise _fail(origin, f"{where}.min", p.get("min"), "need min < max with min ≤ mean ≤ max")
        mean, std = si("mean", mean), si("std", std)
        low = -math.inf if p.get("min") is None else si("min", low)
        high = math.inf if p.get("max") is None else si("max", high)
        if not std > 0:
            raise _fail(origin, f"{where}.std", p.get("std"), "is zero once converted to SI units")
        if not low < high or not low <= mean <= high:
            raise _fail(origin, f"{where}.min", p.get("min"), "need min < max with min ≤ mean ≤ max also in SI units")
        return Distribution("normal", mean=mean, std=std, low=low, high=high)
    if low is None or high is None:
        raise _fail(origin, f"{where}.{'min' if low is None else 'max'}", None, f"required for a {kind} distribution")
    if not low < high:
        raise _fail(origin, f"{where}.max", high, f"must be greater than min ({low})")
    if not si("min", low) < si("max", high):
        raise _fail(origin, f"{where}.max", high, f"must be greater than min ({low}) also in SI units")
    if kind == "uniform":
        return Distribution("uniform", low=si("min", low), high=si("max", high))
    mode = num("mode")
    if not low <= mode <= high:
        raise _fail(origin, f"{where}.mode", mode, f"must lie in [min, max] = [{low}, {high}]")
    return Distribution("triangular", low=si("min", low), high=si("max", high), mode=si("mode", mode))


def _parameter(origin, i, p, scene, length_factor) -> Parameter:
    where = f"parameters[{i}]"
    if not isinstance(p, dict):
        raise _fail(origin, where, p, "must be a table")
    for key in p:
        if key not in PARAMETER_KEYS:
            raise _fail(origin, f"{where}.{key}", p[key], f"unknown field; expected one of {', '.join(sorted(PARAMETER_KEYS))}")
    vary = p.get("vary")
    if not _is_one_of(vary, KINDS):
        raise _fail(origin, f"{where}.vary", vary, f"must be one of {', '.join(KINDS)}")
    targets, default_apply = KINDS[vary]
    apply = p.get("apply", default_apply)
    if apply not in ("scale", "offset", "set"):
        raise _fail(origin, f"{where}.apply", apply, "must be scale, offset or set")
    if vary in ("ergonomics", "solver"):
        if p.get("distribution", "choice") != "choice" or apply != "set":
            raise _fail(origin, f"{where}.distribution", p.get("distribution"), f"{vary} takes `choices` only")
        p = dict(p, distribution="choice")
        if vary == "solver":
            for j, c in enumerate(p.get("choices") or []):
                if c not in SOLVERS:
                    raise _fail(origin, f"{where}.choices[{j}]", c, f"must be one of {', '.join(SOLVERS)}")
        if vary == "ergonomics":
            for j, c in enumerate(p.get("choices") or []):
                if not isinstance(c, str):
                    raise _fail(origin, f"{where}.choices[{j}]", c, 'must be a profile string like "posture=sitting, population=men"')
    target: Dict[str, Any] = {}
    for key in targets:
        if key not in p:
            raise _fail(origin, f"{where}.{key}", None, f"required for vary = {vary}")
        target[key] = p[key]
    # What the value means inside (SI) and the factor from the file's unit.
    if vary.endswith("_rotation"):
        unit, factor = "rad", math.pi / 180.0
        target["axis"] = _vector(origin, f"{where}.axis", target["axis"])
    elif vary.endswith("_position") or vary in ("grab_offset", "hand_path_offset"):
        if apply != "offset":
            raise _fail(origin, f"{where}.apply", apply, f"{vary} is an offset")
        unit, factor = "m", length_factor
        target["direction"] = _vector(origin, f"{where}.direction", target["direction"])
    elif vary == "material":
        prop = target["property"]
        if not _is_one_of(prop, MATERIAL_PROPERTIES):
            raise _fail(origin, f"{where}.property", prop, f"must be one of {', '.join(MATERIAL_PROPERTIES)}")
        if apply == "offset" or (apply == "set" and prop == "e_mpa"):
            raise _fail(origin, f"{where}.apply", apply, "materials are scaled (factor) or set (for one property)")
        unit, factor = ("1", 1.0) if apply == "scale" else ("si", MATERIAL_PROPERTIES[prop])
    elif vary == "hose_length":
        if apply != "scale":
            raise _fail(origin, f"{where}.apply", apply, "hose_length is a factor (scale)")
        unit, factor = "1", 1.0
    elif vary == "scene_value":
        if not isinstance(target["path"], str) or not target["path"]:
            raise _fail(origin, f"{where}.path", target["path"], 'must be a path like "hoses[0].section.d_outer"')
        unit, factor = "scene", 1.0
    elif vary == "motion":
        unit, factor = _motion_unit(origin, where, target, apply, scene, length_factor)
    else:
        unit, factor = "", 1.0
    _check_target(origin, where, vary, target, scene)
    dist = _distribution(origin, where, p, factor)
    levels = p.get("levels")
    if levels is not None:
        if not isinstance(levels, list) or not levels:
            raise _fail(origin, f"{where}.levels", levels, "must be a non-empty list")
        if dist.kind != "choice":
            levels = [_number(origin, f"{where}.levels[{j}]", v) * factor for j, v in enumerate(levels)]
            for j, v in enumerate(levels):
                if not math.isfinite(v):
                    raise _fail(origin, f"{where}.levels[{j}]", p["levels"][j], f"is beyond the largest number once converted to SI units (× {factor:g})")
    name = p.get("name") or "_".join(
        [vary] + [str(target[k]) for k in ("part", "material", "property", "hose", "clip", "stub", "action") if k in target]
    )
    name = "".join(c if c.isalnum() else "_" for c in str(name)).strip("_").lower()
    return Parameter(name, vary, apply, unit, dist, target, levels)


def _motion_unit(origin, where, target, apply, scene, length_factor) -> Tuple[str, float]:
    """The unit and file factor of a `motion` parameter on a part of the base scene: a
    factor (`scale`) on its range or speed, or (`set`) the largest excursion of a hinge
    (degrees in the file, radians inside) or a slide (length unit, metres inside)."""
    prop = target["property"]
    if prop not in MOTION_PROPERTIES:
        raise _fail(origin, f"{where}.property", prop, f"must be one of {', '.join(MOTION_PROPERTIES)}")
    parts = [x for x in scene.get("parts", []) if isinstance(x, dict) and x.get("name") == target["part"]]
    if not parts:
        raise _fail(origin, f"{where}.part", target["part"], f"no such part in the scene ({', '.join(map(str, _names(scene, 'parts')))})")
    motion = parts[0].get("motion")
    kind = motion.get("kind") if isinstance(motion, dict) else None
    if kind not in ("hinge", "slide", "periodic"):
        raise _fail(origin, f"{where}.part", target["part"],
                    "has no hinge, slide or periodic `motion` to vary" if kind is None else f"its {kind} motion has no range or speed to vary")
    target["kind"] = kind
    if apply == "scale":
        return "1", 1.0
    if apply == "set" and prop == "range" and kind == "hinge":
        return "rad", math.pi / 180.0
    if apply == "set" and prop == "range" and kind == "slide":
        return "m", length_factor
    raise _fail(origin, f"{where}.apply", apply,
                "a motion's range is scaled (factor) or set (a hinge's or slide's largest excursion); its speed is scaled")


def _names(scene, key) -> List[str]:
    return [x.get("name") for x in scene.get(key, []) if isinstance(x, dict)]


def _check_target(origin, where, vary, target, scene) -> None:
    """The named material, hose, clip, stub or action must exist in the base scene."""
    for key, table in (("hose", "hoses"), ("clip", "clips"), ("stub", "stubs")):
        if key in target and target[key] not in _names(scene, table):
            raise _fail(origin, f"{where}.{key}", target[key], f"no such {key} in the scene ({', '.join(map(str, _names(scene, table)))})")
    if "material" in target:
        used = {h.get("material") for h in scene.get("hoses", [])}
        if target["material"] not in used:
            raise _fail(origin, f"{where}.material", target["material"], f"no hose of the scene is made of it (used: {', '.join(sorted(map(str, used)))})")
    if "action" in target:
        timeline = scene.get("timeline", [])
        a = target["action"]
        want = "grab" if vary == "grab_offset" else "move_hand"
        if isinstance(a, bool) or not isinstance(a, int) or not -len(timeline) <= a < len(timeline):
            raise _fail(origin, f"{where}.action", a, f"must be an index into the scene's timeline (0 … {len(timeline) - 1})")
        act = timeline[a]
        if act.get("action") != want:
            raise _fail(origin, f"{where}.action", a, f"timeline[{a}] is a {act.get('action')!r} action, not {want!r}")
        if want == "grab" and "at" not in act:
            raise _fail(origin, f"{where}.action", a, f"timeline[{a}] has no `at` to offset")
        if want == "move_hand" and "to" not in act and "by" not in act:
            raise _fail(origin, f"{where}.action", a, f"timeline[{a}] has neither `to` nor `by` to offset")


#: Largest study or scene file read [bytes] (regular files only), as the engine's
#: scene reader.
MAX_FILE_BYTES = 64 * 1024 * 1024


def read_regular_file(path: str, what: str, limit: int = MAX_FILE_BYTES) -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` of them: a FIFO, a device
    (``/dev/zero``) or a folder is refused before it is opened, also behind a link, and
    again on the opened file (opened non-blocking, so a FIFO swapped in cannot block)."""
    def check(st: os.stat_result) -> None:
        if not stat.S_ISREG(st.st_mode):
            raise StudyError(f"{path}: the {what} is not a regular file (only regular files are read)")
        if st.st_size > limit:
            raise StudyError(f"{path}: the {what} has {st.st_size} bytes; at most {limit} are read")

    try:
        check(os.stat(path))
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        raise StudyError(f"{path}: {what} not found") from None
    except OSError as e:
        raise StudyError(f"{path}: cannot read the {what}: {e.strerror}") from None
    with os.fdopen(fd, "rb") as f:
        check(os.fstat(f.fileno()))
        data = f.read(limit + 1)
    if len(data) > limit:
        raise StudyError(f"{path}: the {what} has more than {limit} bytes; at most {limit} are read")
    return data


def _read_toml(path: str, what: str) -> Tuple[Dict[str, Any], str]:
    """The parsed file and its text; a syntax error says ``path:line:column``."""
    try:
        text = read_regular_file(path, what).decode("utf-8")
        return _toml.loads(text), text
    except FileNotFoundError:
        raise StudyError(f"{path}: {what} not found") from None
    except UnicodeDecodeError as e:
        raise StudyError(f"{path}: not UTF-8 text (byte {e.start})") from None
    except _toml.TOMLDecodeError as e:
        m = re.search(r"^(.*) \(at line (\d+), column (\d+)\)$", str(e))
        if m:
            raise StudyError(f"{path}:{m.group(2)}:{m.group(3)}: syntax error: {m.group(1)}") from None
        raise StudyError(f"{path}: syntax error: {e}") from None


def _with_position(e: StudyError, origin: str, text: str) -> StudyError:
    """``e`` with ``origin:line:column`` in front, where its field is written."""
    at = locate(text, e.where) if e.where else None
    if at is None or not str(e).startswith(origin + ": "):
        return e
    return StudyError(f"{origin}:{at[0]}:{at[1]}: {str(e)[len(origin) + 2:]}", e.where)


def load_study(study: Any, *, runs: Optional[int] = None) -> Study:
    """Reads and checks a study: a path to a study TOML file or a dict of its content
    (relative paths in a dict are taken from the current directory)."""
    if isinstance(study, dict):
        raw, origin, base_dir = study, "<dict>", os.getcwd()
    else:
        origin = os.fspath(study)
        raw, text = _read_toml(origin, "study file")
        base_dir = os.path.dirname(os.path.abspath(origin))
        try:
            return parse_study(raw, origin, base_dir, runs=runs)
        except StudyError as e:
            raise _with_position(e, origin, text) from None
    return parse_study(raw, origin, base_dir, runs=runs)


TOP_KEYS = {"format", "version", "name", "scene", "length_unit", "solver", "mass_scaling", "settle",
            "rerun_unsettled", "ergonomics", "scene_values",
            "sampling", "parameters", "envelope"}
MAX_MASS_SCALING = 1e4  # as the physics core (pliant_core::model::MAX_MASS_SCALING)


def _scene_values(origin: str, table: Any, scene: Dict[str, Any], scene_dir: str) -> Dict[str, Any]:
    """[scene_values]: values set in every run's scene before the parameters vary it
    ("simulation.time_step_safety" = 0.9), in the scene's own units; each path must lead
    into a table or list the base scene has, and the engine must accept the result."""
    import pliant

    from .variant import set_path

    if not isinstance(table, dict):
        raise _fail(origin, "scene_values", table, 'must be a table of paths and values, e.g. "simulation.time_step_safety" = 0.9')
    trial = json.loads(json.dumps(scene))
    for path, value in table.items():
        if isinstance(value, (dict, list)) or value is None:
            raise _fail(origin, f"scene_values.{path}", value, "must be a number, a string or a boolean")
        try:
            set_path(trial, path, value, "set")
        except StudyError as e:
            raise _fail(origin, f"scene_values.{path}", value, str(e)) from None
    if table:
        try:
            pliant.Scene.from_json(json.dumps(trial), origin="the base scene with [scene_values]", base_dir=scene_dir)
        except pliant.SceneError as e:
            raise _fail(origin, "scene_values", table, f"the scene refuses them: {e}") from None
    return dict(table)


def parse_study(raw: Dict[str, Any], origin: str, base_dir: str, *, runs: Optional[int] = None) -> Study:
    """Checks a study's content (see :func:`load_study`)."""
    for key in raw:
        if key not in TOP_KEYS:
            raise _fail(origin, key, raw[key], f"unknown field; expected one of {', '.join(sorted(TOP_KEYS))}")
    if raw.get("format") != FORMAT:
        raise _fail(origin, "format", raw.get("format"), f'must be "{FORMAT}"')
    if raw.get("version") != VERSION:
        raise _fail(origin, "version", raw.get("version"), f"unsupported study format version; this build reads version {VERSION}")
    unit = raw.get("length_unit", "m")
    if not _is_one_of(unit, UNITS_M):
        raise _fail(origin, "length_unit", unit, "must be mm or m")
    scene_ref = raw.get("scene")
    if not isinstance(scene_ref, str) or not scene_ref:
        raise _fail(origin, "scene", scene_ref, "required: the base scene file, relative to the study file")
    scene_path = scene_ref if os.path.isabs(scene_ref) else os.path.join(base_dir, scene_ref)
    if not os.path.isfile(scene_path):
        raise _fail(origin, "scene", scene_ref, f"no such file ({scene_path})")
    if scene_path.endswith(".json"):
        try:
            scene = json.loads(read_regular_file(scene_path, "scene").decode("utf-8"))
        except (UnicodeDecodeError, ValueError) as e:
            if isinstance(e, StudyError):
                raise
            raise StudyError(f"{scene_path}: the scene is not JSON: {e}") from None
    else:
        scene = _read_toml(scene_path, "scene")[0]
    solver = raw.get("solver")
    if solver is not None and solver not in SOLVERS:
        raise _fail(origin, "solver", solver, f"must be one of {', '.join(SOLVERS)}")
    mass_scaling = raw.get("mass_scaling")
    if mass_scaling is not None and (isinstance(mass_scaling, bool) or not isinstance(mass_scaling, (int, float))
                                     or not 1 <= mass_scaling <= MAX_MASS_SCALING):
        raise _fail(origin, "mass_scaling", mass_scaling,
                    f"must be a number in 1 … {MAX_MASS_SCALING:g} (every run's [simulation] mass_scaling)")
    settle = raw.get("settle")
    if settle is not None and settle not in SETTLE_FINISHES:
        raise _fail(origin, "settle", settle,
                    f"must be one of {', '.join(SETTLE_FINISHES)} (every settle action's finish)")
    rerun_unsettled = raw.get("rerun_unsettled", False)
    if not isinstance(rerun_unsettled, bool):
        raise _fail(origin, "rerun_unsettled", rerun_unsettled, "must be true or false")
    ergonomics = raw.get("ergonomics")
    if ergonomics is not None and not isinstance(ergonomics, str):
        raise _fail(origin, "ergonomics", ergonomics, 'must be a profile string like "posture=sitting, population=men"')
    scene_values = _scene_values(origin, raw.get("scene_values", {}), scene, os.path.dirname(scene_path))
    sampling = raw.get("sampling", {})
    if not isinstance(sampling, dict):
        raise _fail(origin, "sampling", sampling, "must be a table")
    for key in sampling:
        if key not in ("method", "runs", "seed", "levels"):
            raise _fail(origin, f"sampling.{key}", sampling[key], "unknown field; expected method, runs, seed or levels")
    method = sampling.get("method", "monte_carlo")
    if method not in METHODS:
        raise _fail(origin, "sampling.method", method, f"must be one of {', '.join(METHODS)}")
    n = runs if runs is not None else sampling.get("runs", 100)
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise _fail(origin, "sampling.runs", n, "must be an integer ≥ 1")
    seed = sampling.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise _fail(origin, "sampling.seed", seed, "must be an integer ≥ 0")
    levels = sampling.get("levels", 3)
    if isinstance(levels, bool) or not isinstance(levels, int) or levels < 1:
        raise _fail(origin, "sampling.levels", levels, "must be an integer ≥ 1")
    params_raw = raw.get("parameters")
    if not isinstance(params_raw, list) or not params_raw:
        raise _fail(origin, "parameters", params_raw, "at least one [[parameters]] table is required")
    params = [_parameter(origin, i, p, scene, UNITS_M[unit]) for i, p in enumerate(params_raw)]
    seen = set()
    for i, p in enumerate(params):
        if p.name in seen:
            raise _fail(origin, f"parameters[{i}].name", p.name, "taken by another parameter")
        seen.add(p.name)
    env = raw.get("envelope", {})
    if not isinstance(env, dict):
        raise _fail(origin, "envelope", env, "must be a table")
    for key in env:
        if key not in ("voxel", "hoses"):
            raise _fail(origin, f"envelope.{key}", env[key], "unknown field; expected voxel or hoses")
    voxel = _number(origin, "envelope.voxel", env.get("voxel"), positive=True, allow_none=True)
    hoses = env.get("hoses")
    if hoses is not None:
        names = _names(scene, "hoses")
        if not isinstance(hoses, list):
            raise _fail(origin, "envelope.hoses", hoses, "must be a list of hose names")
        for j, h in enumerate(hoses):
            if h not in names:
                raise _fail(origin, f"envelope.hoses[{j}]", h, f"no such hose ({', '.join(map(str, names))})")
    return Study(
        name=str(raw.get("name") or os.path.splitext(os.path.basename(origin))[0]),
        origin=origin,
        base_dir=base_dir,
        scene_path=os.path.abspath(scene_path),
        scene=scene,
        parameters=params,
        method=method,
        runs=n,
        seed=seed,
        grid_levels=levels,
        solver=solver,
        ergonomics=ergonomics,
        scene_values=scene_values,
        mass_scaling=None if mass_scaling is None else float(mass_scaling),
        settle=settle,
        rerun_unsettled=rerun_unsettled,
        envelope_voxel_m=None if voxel is None else voxel * UNITS_M[unit],
        envelope_hoses=hoses,
        source=raw,
    )
