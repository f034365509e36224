"""How far a study's answers can be trusted when its runs use a cheaper solver: a sample
of finished runs is run again with a reference solver (the explicit one by default) and
each run's **verdict** is compared.

A run's verdict is its ``status``, ``feasible``, its ``violated_checks`` and whether each
stub and clip ended assembled (the ``*_assembled`` columns): everything the study answers
with yes or no. Two runs agree when all of these are equal. The share of agreeing runs is
reported with its Wilson 95 % score interval (the same interval as the report's
feasibility). The sample is drawn without replacement from the study's finished runs by
numpy's PCG64 seeded with the study's seed, so the same study checks the same runs.

Outputs: ``OUT/agreement.parquet`` (one row per checked run: both verdicts and the peak
hand force of each) and ``OUT/agreement.json`` (the summary).
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional

import numpy as np

from .report import wilson

AGREEMENT_FILE = "agreement.json"
AGREEMENT_ROWS = "agreement.parquet"
FIXED_VERDICT = ("status", "feasible", "violated_checks")


def verdict_columns(columns: List[str]) -> List[str]:
    """The verdict's columns among a result table's columns."""
    return list(FIXED_VERDICT) + sorted(c for c in columns if c.endswith("_assembled"))


def _plain(value: Any) -> Any:
    """A verdict value comparable with ``==`` (lists and numpy arrays as sorted tuples,
    missing as None)."""
    if value is None:
        return None
    if isinstance(value, (list, tuple, np.ndarray)):
        return tuple(sorted(str(v) for v in value))
    if isinstance(value, float) and value != value:
        return None
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    return value


def verdict(row: Dict[str, Any], columns: List[str]) -> Dict[str, Any]:
    """A run's verdict: its values of the verdict columns, made comparable."""
    return {c: _plain(row.get(c)) for c in columns}


def choose(done: List[int], n: int, seed: int) -> List[int]:
    """``n`` run indices drawn without replacement from ``done`` (all when fewer), sorted."""
    if n <= 0 or not done:
        return []
    rng = np.random.default_rng(seed)
    picked = rng.choice(np.asarray(sorted(done)), size=min(n, len(done)), replace=False)
    return sorted(int(i) for i in picked)


def compare(study_rows: Dict[int, Dict[str, Any]], reference_rows: Dict[int, Dict[str, Any]],
            solver: str, reference_solver: str) -> Dict[str, Any]:
    """Compares the verdicts of the runs in both tables (by run index). Returns the
    summary (``agreeing``, ``checked``, ``share``, ``ci95``, the disagreeing runs with the
    columns that differ, the mean CPU time of a run under each solver) and the rows."""
    indices = sorted(set(study_rows) & set(reference_rows))
    columns = verdict_columns(sorted(set().union(*(r.keys() for r in study_rows.values())))) if study_rows else []
    rows, differing = [], []
    for i in indices:
        mine, ref = study_rows[i], reference_rows[i]
        a, b = verdict(mine, columns), verdict(ref, columns)
        differs = [c for c in columns if a[c] != b[c]]
        row = {"run_id": mine["run_id"], "index": i, "agree": not differs, "differs": differs,
               "solver": solver, "reference_solver": reference_solver,
               "peak_hand_force_n": mine.get("peak_hand_force_n"),
               "reference_peak_hand_force_n": ref.get("peak_hand_force_n"),
               "cpu_time_s": mine.get("cpu_time_s"), "reference_cpu_time_s": ref.get("cpu_time_s"),
               "steps": mine.get("steps"), "reference_steps": ref.get("steps")}
        for c in columns:
            row[c], row["reference_" + c] = _json_value(a[c]), _json_value(b[c])
        rows.append(row)
        if differs:
            differing.append({"run_id": mine["run_id"], "columns": differs})
    n, k = len(rows), sum(r["agree"] for r in rows)
    lo, hi = wilson(k, n)
    summary = {
        "solver": solver, "reference_solver": reference_solver, "checked": n, "agreeing": k,
        "share": k / n if n else None, "ci95": [lo, hi], "interval": "Wilson score, 95 %",
        "verdict_columns": columns, "disagreeing": differing,
        "cpu_time_s": _mean(r["cpu_time_s"] for r in rows),
        "reference_cpu_time_s": _mean(r["reference_cpu_time_s"] for r in rows),
        "peak_hand_force_largest_relative_difference": _largest_relative(
            (r["peak_hand_force_n"], r["reference_peak_hand_force_n"]) for r in rows),
    }
    return {"summary": summary, "rows": rows}


def _json_value(v: Any) -> Any:
    return list(v) if isinstance(v, tuple) else v


def _mean(values) -> Optional[float]:
    xs = [float(v) for v in values if v is not None]
    return float(np.mean(xs)) if xs else None


def _largest_relative(pairs) -> Optional[float]:
    diffs = [abs(a - b) / abs(b) for a, b in pairs if a is not None and b is not None and b != 0]
    return float(max(diffs)) if diffs else None


def write(out: str, result: Dict[str, Any]) -> None:
    """Writes agreement.json and agreement.parquet into ``out``."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    rows = [{k: (json.dumps(v) if isinstance(v, list) else v) for k, v in r.items()} for r in result["rows"]]
    pq.write_table(pa.Table.from_pylist(rows), os.path.join(out, AGREEMENT_ROWS))
    with open(os.path.join(out, AGREEMENT_FILE), "w") as f:
        json.dump(result["summary"], f, indent=2)


def read(out: str) -> Optional[Dict[str, Any]]:
    """The agreement summary of a study folder, or None when none was measured."""
    path = os.path.join(out, AGREEMENT_FILE)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def sentence(summary: Dict[str, Any]) -> str:
    """One line for the terminal and the report."""
    lo, hi = summary["ci95"]
    speed = ""
    if summary.get("cpu_time_s") and summary.get("reference_cpu_time_s"):
        speed = (f"; a run cost {summary['cpu_time_s']:.3g} CPU-s (envelope and clearances included) against "
                 f"{summary['reference_cpu_time_s']:.3g} with the {summary['reference_solver']} solver (without them)")
    return (f"verdicts agree with the {summary['reference_solver']} solver's in {summary['agreeing']} of "
            f"{summary['checked']} checked runs ({100 * (summary['share'] or 0):.1f} %, 95 % CI "
            f"{100 * lo:.1f} – {100 * hi:.1f} %){speed}")
