"""A run's range-of-motion findings as study columns (a scene with a ``[sweep]``,
docs/scene-format.md): from ``RunResult.motion()`` — the columns of ``motion.csv`` — the
smallest bend radius of any hose over the motion and the motion coordinate where it
occurred, in SI."""

from __future__ import annotations

import math
from typing import Any, Dict, List, Tuple

import numpy as np

# motion.csv's coordinate columns and their factor to SI, with the SI column's unit.
COORDINATES = {"angle_deg": (math.pi / 180.0, "rad"), "travel_mm": (1e-3, "m"), "phase_deg": (math.pi / 180.0, "rad")}
BEND_RADIUS = ": min_bend_radius_m"


def fields(scene: Dict[str, Any]) -> List[Tuple[str, str]]:
    """The motion columns (name, "float" or "string") of a study whose base scene has a
    ``[sweep]``; none otherwise."""
    if "sweep" not in scene:
        return []
    return [("motion_min_bend_radius_m", "float"), ("motion_worst_position", "float"),
            ("motion_coordinate", "string")]


def columns(result) -> Dict[str, Any]:
    """``motion_min_bend_radius_m`` (smallest over every hose and checked instant),
    ``motion_worst_position`` (the motion coordinate there, SI) and ``motion_coordinate``
    (its kind and unit: ``angle_rad``, ``travel_m``, ``phase_rad`` or ``time_s``); empty
    without a sweep or a checked instant."""
    table = result.motion()
    if not table:
        return {}
    names = list(table)
    coordinate = next((n for n in names if n in COORDINATES), "time_s")
    factor, unit = COORDINATES.get(coordinate, (1.0, "s"))
    radii = [np.asarray(table[n], dtype=float) for n in names if n.endswith(BEND_RADIUS)]
    if not radii or len(radii[0]) == 0:
        return {}
    smallest = np.nanmin(np.vstack(radii), axis=0)  # per instant, over the hoses
    if not np.isfinite(smallest).any():
        return {}
    worst = int(np.nanargmin(smallest))
    return {
        "motion_min_bend_radius_m": float(smallest[worst]),
        "motion_worst_position": float(np.asarray(table[coordinate])[worst]) * factor,
        "motion_coordinate": coordinate.rsplit("_", 1)[0] + "_" + unit,
    }
