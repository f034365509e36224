"""One variant: the base scene (as a dict, in the scene file's own units) with one
sample's parameter values applied. The result is an ordinary scene: written as JSON it
is the run's replay input (``pliant run runs/<id>.json``).

How each kind acts (values are SI; the scene's ``length_unit`` is respected):

- ``material``: a library material is first copied into ``[materials]`` as
  ``<name>_study`` (with the library hose's section on the hoses made of it), then the
  property is scaled or set; ``e_mpa`` scales E_t, E_c (and an explicit E_b) together.
- ``hose_length``: the hose's centre line (every point of its path) is scaled about its
  start, so the rest length scales by the factor; ``spans`` scale with it.
- ``clip_position`` / ``stub_position``: the origin moves by value × direction.
- ``clip_rotation`` / ``stub_rotation``: the clip's ``opening`` and ``orientation`` (the
  stub's ``axis``) turn by the angle about ``axis`` through the origin.
- ``grab_offset``: the grab action's ``at`` moves by value × direction.
- ``hand_path_offset``: every waypoint of the move_hand action (``to`` or ``by``) moves.
- ``ergonomics`` / ``solver``: the scene's ``[ergonomics]`` / ``[simulation] solver``.
- the study's ``settle``: every settle action's ``finish`` (dynamic, static or
  static_equilibrium).
- ``scene_value``: any number at a path like ``hoses[0].section.d_outer`` (scene units).
"""

from __future__ import annotations

import math
import pickle
import os
import re
from functools import lru_cache
from typing import Any, Dict, List

from . import scene_files
from .spec import MATERIAL_PROPERTIES, UNITS_M, Study, StudyError

try:
    import tomllib as _toml
except ImportError:  # pragma: no cover
    import tomli as _toml  # type: ignore


@lru_cache(maxsize=1)
def library() -> Dict[str, Dict[str, Any]]:
    """The built-in material library: {name: {key: value}} in the keys' units."""
    from .. import _pliant

    raw = _toml.loads(_pliant.material_library_toml())
    return {
        name: {k: (v["value"] if isinstance(v, dict) else v) for k, v in entry.items()}
        for name, entry in raw.items()
    }


def length_factor(scene: Dict[str, Any]) -> float:
    """Metres per length unit of the scene."""
    return UNITS_M.get(scene.get("length_unit", "m"), 1.0)


def plain_copy(scene: Dict[str, Any]) -> Dict[str, Any]:
    """A deep copy of a scene — plain data from TOML or JSON: dicts, lists, strings,
    numbers — by a pickle round trip, ~10× faster than ``copy.deepcopy`` (a study's driver
    copies the scene twice per run while the workers wait for tasks)."""
    return pickle.loads(pickle.dumps(scene, protocol=pickle.HIGHEST_PROTOCOL))


def absolute_meshes(scene: Dict[str, Any], scene_dir: str) -> Dict[str, Any]:
    """A copy of the scene whose relative file paths (meshes, STEP files, route and
    motion files: :func:`scene_files.references`) are made absolute."""
    return scene_files.change_paths(
        plain_copy(scene), lambda p: p if os.path.isabs(p) else os.path.normpath(os.path.join(scene_dir, p)))


def relative_meshes(scene: Dict[str, Any], folder: str) -> Dict[str, Any]:
    """A copy of the scene whose file paths are relative to ``folder`` (where it is saved)."""
    return scene_files.change_paths(plain_copy(scene), lambda p: os.path.relpath(p, folder) if os.path.isabs(p) else p)


def _rotate(v: List[float], axis: List[float], angle: float) -> List[float]:
    """Rodrigues' rotation of v about the unit axis by angle [rad]."""
    c, s = math.cos(angle), math.sin(angle)
    kx, ky, kz = axis
    x, y, z = v
    dot = kx * x + ky * y + kz * z
    cross = (ky * z - kz * y, kz * x - kx * z, kx * y - ky * x)
    return [v[i] * c + cross[i] * s + axis[i] * dot * (1 - c) for i in range(3)]


def _shift(points: Any, offset: List[float]) -> Any:
    """One point [x, y, z] or a list of points, moved by offset."""
    if points and isinstance(points[0], (list, tuple)):
        return [[p[i] + offset[i] for i in range(3)] for p in points]
    return [points[i] + offset[i] for i in range(3)]


def _named(scene, table, name) -> Dict[str, Any]:
    return next(x for x in scene.get(table, []) if x.get("name") == name)


def _own_material(scene: Dict[str, Any], name: str) -> Dict[str, Any]:
    """The scene's own material table for ``name``: a library material is copied in
    (its hoses then name the copy and carry the library hose's section)."""
    materials = scene.setdefault("materials", {})
    if name in materials:
        return materials[name]
    lib = library().get(name)
    if lib is None:
        raise StudyError(f"material {name!r} is neither in the scene's [materials] nor in the library")
    copy_name = f"{name}_study"
    if copy_name not in materials:
        # every law of the entry (a metal line's yield stress and hardening with its
        # moduli): only the description and the section stay behind
        materials[copy_name] = {
            k: v for k, v in lib.items() if k not in ("description", "d_inner_mm", "d_outer_mm")
        }
        unit = length_factor(scene)
        for hose in scene.get("hoses", []):
            if hose.get("material") == name:
                hose["material"] = copy_name
                hose.setdefault("section", {
                    "d_inner": lib["d_inner_mm"] * 1e-3 / unit,
                    "d_outer": lib["d_outer_mm"] * 1e-3 / unit,
                })
    return materials[copy_name]


def _apply_number(old: float, value: float, how: str) -> float:
    return old * value if how == "scale" else old + value if how == "offset" else value


PATH_TOKEN = re.compile(r"([^.\[\]]+)|\[(-?\d+)\]")


def set_path(scene: Dict[str, Any], path: str, value: Any, how: str) -> None:
    """Sets (``set``), scales or offsets the value at a path like
    ``hoses[0].section.d_outer``; ``set`` adds missing table keys on the way
    (``simulation.time_step_safety`` in a scene without ``[simulation]``; the engine then
    checks the names), list items must exist."""
    keys = [m.group(1) if m.group(1) is not None else int(m.group(2)) for m in PATH_TOKEN.finditer(path)]
    node: Any = scene
    try:
        if not keys:
            raise KeyError(path)
        for k, after in zip(keys[:-1], keys[1:]):
            if how == "set" and isinstance(node, dict) and isinstance(k, str) and isinstance(after, str):
                node = node.setdefault(k, {})
            else:
                node = node[k]
        if how == "set" and isinstance(node, dict) and isinstance(keys[-1], str):
            node[keys[-1]] = value
            return
        old = node[keys[-1]]
    except (KeyError, IndexError, TypeError):
        raise StudyError(f"path {path!r}: no such value in the scene") from None
    if how != "set" and (isinstance(old, bool) or not isinstance(old, (int, float))):
        raise StudyError(f"path {path!r}: {old!r} is not a number to {how}")
    node[keys[-1]] = _apply_number(old, value, how)


def _scale_hose(hose: Dict[str, Any], s: float) -> None:
    start = hose["start"]

    def scaled(p):
        return [start[i] + s * (p[i] - start[i]) for i in range(3)]

    for segment in hose.get("path", []):
        for body in segment.values():
            for key in ("to", "via"):
                if key in body:
                    body[key] = scaled(body[key])
            if "through" in body:
                body["through"] = [scaled(p) for p in body["through"]]
    for span in hose.get("spans", []):
        span["from"] *= s
        span["to"] *= s
    if "element_length" in hose:
        hose["element_length"] *= s


def parse_ergonomics(profile: str) -> Dict[str, Any]:
    """"posture=sitting, moments_decide=true" as an [ergonomics] table."""
    table: Dict[str, Any] = {}
    for item in filter(None, (x.strip() for x in profile.split(","))):
        key, sep, value = item.partition("=")
        if not sep:
            raise StudyError(f"ergonomics {profile!r}: {item!r} is not key=value")
        value = value.strip()
        table[key.strip()] = {"true": True, "false": False}.get(value.lower(), value)
    return table


def set_settle_finish(scene: Dict[str, Any], finish: str) -> None:
    """Sets every settle action's ``finish``."""
    for action in scene.get("timeline", []):
        if isinstance(action, dict) and action.get("action") == "settle":
            action["finish"] = finish


def apply(study: Study, sample: Dict[str, Any]) -> Dict[str, Any]:
    """The variant scene (a new dict) for one sample of the study."""
    scene = absolute_meshes(study.scene, os.path.dirname(study.scene_path))
    unit = length_factor(scene)
    if study.solver:
        scene.setdefault("simulation", {})["solver"] = study.solver
    if study.mass_scaling is not None:
        scene.setdefault("simulation", {})["mass_scaling"] = study.mass_scaling
    if study.settle is not None:
        set_settle_finish(scene, study.settle)
    if study.ergonomics:
        scene["ergonomics"] = parse_ergonomics(study.ergonomics)
    for path, value in study.scene_values.items():
        set_path(scene, path, value, "set")
    for p in study.parameters:
        v = sample[p.name]
        t = p.target
        if p.vary == "material":
            mat = _own_material(scene, t["material"])
            prop = t["property"]
            keys = ["e_tension_mpa", "e_compression_mpa", "e_bending_mpa"] if prop == "e_mpa" else [prop]
            for key in keys:
                if key in mat:
                    mat[key] = mat[key] * v if p.apply == "scale" else v / MATERIAL_PROPERTIES[prop]
                elif key == prop:  # e.g. min_bend_radius_mm or e_bending_mpa not given yet
                    if p.apply == "scale":
                        raise StudyError(f"parameter {p.name}: material {t['material']} has no {prop} to scale; use apply = \"set\"")
                    mat[key] = v / MATERIAL_PROPERTIES[prop]
        elif p.vary == "hose_length":
            _scale_hose(_named(scene, "hoses", t["hose"]), v)
        elif p.vary in ("clip_position", "stub_position"):
            item = _named(scene, p.vary.split("_")[0] + "s", t[p.vary.split("_")[0]])
            item["origin"] = _shift(item["origin"], [d * v / unit for d in t["direction"]])
        elif p.vary == "clip_rotation":
            clip = _named(scene, "clips", t["clip"])
            for key in ("opening", "orientation"):
                if key in clip:
                    clip[key] = _rotate(clip[key], t["axis"], v)
        elif p.vary == "stub_rotation":
            stub = _named(scene, "stubs", t["stub"])
            stub["axis"] = _rotate(stub["axis"], t["axis"], v)
        elif p.vary in ("grab_offset", "hand_path_offset"):
            action = scene["timeline"][t["action"]]
            offset = [d * v / unit for d in t["direction"]]
            for key in ("at",) if p.vary == "grab_offset" else ("to", "by"):
                if key in action:
                    action[key] = _shift(action[key], offset)
        elif p.vary == "ergonomics":
            scene["ergonomics"] = parse_ergonomics(v)
        elif p.vary == "solver":
            scene.setdefault("simulation", {})["solver"] = v
        elif p.vary == "scene_value":
            set_path(scene, t["path"], v, p.apply)
        elif p.vary == "motion":
            _vary_motion(_named(scene, "parts", t["part"])["motion"], t["property"], v, p.apply, unit)
    return scene


def _vary_motion(motion: Dict[str, Any], prop: str, v: float, how: str, unit: float) -> None:
    """A part's `motion` with its range or speed changed (docs/study.md): `range` scales
    every keyframe value (a periodic motion's every amplitude) by `v`, or (`set`) so that
    the largest excursion becomes `v` (rad for a hinge, m for a slide); `speed` runs the
    motion `v` times as fast (keyframe times over `v`, frequencies times `v`)."""
    kind = motion["kind"]
    if prop == "speed" and not v > 0:
        raise StudyError(f"a motion's speed factor must be greater than 0, not {v}")
    if kind == "periodic":
        axes = [motion[k] for k in ("x", "y", "z", "roll", "pitch", "yaw") if isinstance(motion.get(k), dict)]
        for axis in axes:
            key = "amplitude" if prop == "range" else "frequency_hz"
            if key in axis:
                axis[key] = axis[key] * v
        return
    frames = motion["angle_deg" if kind == "hinge" else "distance"]
    if prop == "speed":
        frames["times_s"] = [t / v for t in frames["times_s"]]
        return
    values = frames["values"]
    if how == "set":
        largest = max((abs(x) for x in values), default=0.0)
        if largest == 0.0:
            raise StudyError(f"the {kind}'s keyframes never leave 0: nothing to set the range of")
        target = math.degrees(v) if kind == "hinge" else v / unit
        v = target / largest
    frames["values"] = [x * v for x in values]


def hose_radii(scene: Dict[str, Any]) -> Dict[str, float]:
    """Each hose's largest outer radius [m] (sections, spans, or its library hose)."""
    unit = length_factor(scene)
    radii = {}
    for hose in scene.get("hoses", []):
        sections = [hose.get("section")] + [s.get("section") for s in hose.get("spans", [])]
        d = [s["d_outer"] * unit for s in sections if isinstance(s, dict) and "d_outer" in s]
        if not d:
            lib = library().get(hose.get("material"), {})
            d = [lib.get("d_outer_mm", 0.0) * 1e-3]
        radii[hose["name"]] = max(d) / 2
    return radii
