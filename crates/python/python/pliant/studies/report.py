"""The study report (``OUT/report.html``, one self-contained page with inline SVG drawn
by matplotlib, :mod:`pliant.studies.histogram`):
feasibility rate with its Wilson 95 % interval, histograms of peak loads against their
limits, a sensitivity ranking (Spearman rank correlation), the worst variants with links
to their replay scenes, and the tolerance envelope with its clearances."""

from __future__ import annotations

import html
import math
import os
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import sobol
from .histogram import histogram_svg
from .runner import column_name
from .spec import Study

Z95 = 1.959963984540054


def wilson(k: int, n: int, z: float = Z95) -> Tuple[float, float]:
    """Wilson score interval of a proportion k/n (95 % by default)."""
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return (max(0.0, centre - half), min(1.0, centre + half))


def sensitivity(frame, study: Study, outputs: List[str]) -> List[Dict[str, Any]]:
    """Spearman's ρ (and p-value) of each numeric parameter against each output, over
    the runs where both are known; sorted by the largest |ρ|."""
    from scipy.stats import spearmanr

    rows = []
    for p in study.parameters:
        if p.categorical:
            continue
        entry: Dict[str, Any] = {"parameter": p.name, "column": p.column}
        for out in outputs:
            if out not in frame:
                continue
            x = frame[p.column].astype(float)
            y = frame[out].astype(float)
            ok = x.notna() & y.notna()
            if ok.sum() < 3 or x[ok].nunique() < 2 or y[ok].nunique() < 2:
                entry[out] = (None, None)
                continue
            r = spearmanr(x[ok], y[ok])
            entry[out] = (float(r.statistic), float(r.pvalue))
            entry["s1_" + out] = first_order_index(x[ok], y[ok])
        entry["rank_by"] = max((abs(v[0]) for k, v in entry.items() if isinstance(v, tuple) and v[0] is not None), default=0.0)
        entry["rank_by"] = max([entry["rank_by"]] + [math.sqrt(v) for k, v in entry.items() if k.startswith("s1_") and v])
        rows.append(entry)
    return sorted(rows, key=lambda e: -e["rank_by"])


def sobol_estimates(frame, study: Study) -> Optional[Dict[str, List[Optional[sobol.Index]]]]:
    """The Saltelli design's first-order and total-effect Sobol' indices of every
    parameter (in study order) for every outcome of :data:`OUTPUTS` (:mod:`.sobol`);
    ``None`` unless the study is a complete Saltelli design. Runs that did not complete
    normally count as missing outcomes."""
    d, base = len(study.parameters), study.runs
    if study.method != "saltelli" or len(frame) != sobol.runs_of(base, d):
        return None
    ordered = frame.sort_values("index")
    if list(ordered["index"]) != list(range(len(ordered))):
        return None
    good = (ordered["status"] == "ok").to_numpy()
    out: Dict[str, List[Optional[sobol.Index]]] = {}
    for name, _ in OUTPUTS:
        if name not in ordered:
            continue
        y = np.where(good, ordered[name].astype(float).to_numpy(), np.nan)
        out[name] = sobol.indices(y, base, d, seed=study.seed)
    return out


def sobol_table(frame, study: Study) -> str:
    """:func:`sobol_estimates` as an HTML section."""
    d, base = len(study.parameters), study.runs
    estimates = sobol_estimates(frame, study)
    if estimates is None:
        return (f"<p>Sobol' indices: the study is incomplete ({len(frame)} of "
                f"{sobol.runs_of(base, d)} runs of the Saltelli design); resume it to get them.</p>")
    rows = [[f"<code>{html.escape(p.name)}</code>"] for p in study.parameters]
    for out, _ in OUTPUTS:
        for j, ix in enumerate(estimates.get(out, [None] * d)):
            rows[j].append("–" if ix is None else
                           f"S₁ = {ix.first:.2f} <small>[{ix.first_ci[0]:.2f}, {ix.first_ci[1]:.2f}]</small><br>"
                           f"S<sub>T</sub> = {ix.total:.2f} <small>[{ix.total_ci[0]:.2f}, {ix.total_ci[1]:.2f}]</small>"
                           + ("" if ix.points == base else f"<br><small>{ix.points} of {base} points</small>"))
    return ("<h3>Sobol' indices (Saltelli design)</h3>"
            f"<p>{base} base points × ({d} + 2) blocks. First-order index S₁ (Saltelli et al. 2010) "
            "and total-effect index S<sub>T</sub> (Jansen 1999) of each parameter, with 95 % bootstrap "
            "intervals over the base points: S₁ is the share of the outcome's variance the parameter "
            "explains alone, S<sub>T</sub> the share it takes part in, interactions included "
            "(S<sub>T</sub> − S₁ is its interaction share). Failed runs leave their base points out.</p>"
            + _table(["parameter"] + [label for _, label in OUTPUTS], rows))


def first_order_index(x, y, bins: int = 10) -> Optional[float]:
    """Given-data estimate of the first-order Sobol index S₁ = Var(E[y | x]) / Var(y): the
    share of y's variance explained by x alone, from x's quantile bins (no Saltelli
    design needed; biased upwards by about (bins − 1)/n for an x without effect). Catches
    non-monotonic effects that rank correlation misses."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    k = min(bins, len(x) // 5)
    if k < 2 or np.var(y) == 0:
        return None
    edges = np.quantile(x, np.linspace(0, 1, k + 1))
    b = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, k - 1)
    total = ((y - y.mean()) ** 2).sum()
    between = sum(((b == i).sum() * (y[b == i].mean() - y.mean()) ** 2) for i in range(k) if (b == i).any())
    return float(between / total)


def _fmt(x: Any, digits: int = 4) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if isinstance(x, float):
        return f"{x:.{digits}g}"
    return html.escape(str(x))


def _table(head: List[str], rows: List[List[str]]) -> str:
    h = "".join(f"<th>{html.escape(c)}</th>" for c in head)
    b = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in r) + "</tr>" for r in rows)
    return f"<table><thead><tr>{h}</tr></thead><tbody>{b}</tbody></table>"


def agreement_section(summary: Dict[str, Any]) -> str:
    """The report's paragraph on the verdicts checked against a reference solver."""
    from .agreement import sentence

    text = (f"<h3>Verdicts checked against the {html.escape(summary['reference_solver'])} solver</h3>"
            f"<p>{html.escape(sentence(summary))}. A verdict is the run's "
            + ", ".join(f"<code>{html.escape(c)}</code>" for c in summary["verdict_columns"])
            + "; the checked runs were drawn at random (the study's seed); "
            "<code>agreement.parquet</code> holds both verdicts of each.</p>")
    if summary["disagreeing"]:
        text += _table(["run", "differs in"], [
            [f'<a href="runs/{html.escape(d["run_id"])}.json">{html.escape(d["run_id"])}</a>',
             html.escape(", ".join(d["columns"]))] for d in summary["disagreeing"][:50]])
    return text


OUTPUTS = [("worst_hand_ratio", "worst hand load / limit"), ("feasible", "feasible (1) or not (0)"),
           ("peak_hand_force_n", "peak hand force"), ("min_bend_radius_ratio", "smallest bend radius / allowed")]


def write_report(study: Study, out: str, frame, envelope_info: Dict[str, Any],
                 agreement: Optional[Dict[str, Any]] = None) -> str:
    """Writes OUT/report.html; returns its path. ``agreement``: the summary of
    :func:`pliant.studies.agreement.compare`, when the verdicts were checked."""
    n = len(frame)
    feasible = int((frame["feasible"] == True).sum()) if n else 0  # noqa: E712
    status = frame["status"].value_counts().to_dict() if n else {}
    lo, hi = wilson(feasible, n)
    ok = frame[frame["status"] == "ok"] if n else frame
    k_ok = int((ok["feasible"] == True).sum()) if len(ok) else 0  # noqa: E712
    lo_ok, hi_ok = wilson(k_ok, len(ok))
    parts: List[str] = []
    parts.append(f"<h1>Study: {html.escape(study.name)}</h1>")
    parts.append(
        f"<p>Base scene <code>{html.escape(study.scene_path)}</code>; {n} runs by "
        f"<b>{study.method.replace('_', ' ')}</b> (seed {study.seed}). Units: SI.</p>")
    parts.append("<h2>Feasibility</h2>")
    parts.append(
        f'<p class="big">Feasible in <b>{feasible} of {n}</b> runs: <b>{100 * feasible / max(n, 1):.1f} %</b>, '
        f"95 % confidence interval <b>{100 * lo:.1f} % – {100 * hi:.1f} %</b> (Wilson score interval; "
        f"runs that diverged or failed count as not feasible).</p>"
        f"<p>Among the {len(ok)} runs that completed normally: {k_ok} feasible, "
        f"{100 * k_ok / max(len(ok), 1):.1f} % (95 % CI {100 * lo_ok:.1f} % – {100 * hi_ok:.1f} %).</p>")
    parts.append(_table(["status", "runs"], [[html.escape(s), str(c)] for s, c in sorted(status.items())]))
    if agreement:
        parts.append(agreement_section(agreement))
    if n and frame["uncertain"].fillna(False).any():
        parts.append(f"<p>{int(frame['uncertain'].fillna(False).sum())} runs are UNCERTAIN (a Newton solve ended out of balance).</p>")
    parts.append("<h2>Parameters</h2>")
    prow = []
    for p in study.parameters:
        d = p.distribution
        desc = {"normal": f"normal μ={d.mean:.4g}, σ={d.std:.4g}, in [{d.low:.4g}, {d.high:.4g}]",
                "uniform": f"uniform [{d.low:.4g}, {d.high:.4g}]",
                "triangular": f"triangular [{d.low:.4g}, {d.high:.4g}], mode {d.mode:.4g}",
                "choice": "one of " + ", ".join(map(str, d.choices))}[d.kind]
        tgt = ", ".join(f"{k}={v}" for k, v in p.target.items())
        prow.append([f"<code>{html.escape(p.column)}</code>", html.escape(p.vary), html.escape(tgt),
                     html.escape(p.apply), html.escape(p.unit or "choice"), html.escape(desc)])
    parts.append(_table(["column", "varies", "target", "applied as", "unit", "distribution (SI)"], prow))
    parts.append("<h2>Peak loads against their limits</h2>")
    if n:
        limits = sorted({float(x) for x in frame["worst_hand_limit_n"].dropna()})[:3]
        parts.append(histogram_svg(frame["peak_hand_force_n"], "Peak hand force", "N", limits))
        parts.append(histogram_svg(frame["worst_hand_ratio"], "Worst hand load / its ergonomic limit", "ratio", [1.0]))
        for kind, table in (("stub", "stubs"), ("clip", "clips")):
            for item in study.scene.get(table, []):
                col = column_name(kind, item["name"]) + "_force_n"
                if col in frame:
                    lim = [float(item["snap_force_n"])] if "snap_force_n" in item else []
                    parts.append(histogram_svg(frame[col], f"Peak force of {kind} '{item['name']}'"
                                               + (" (line: its snap force)" if lim else ""), "N", lim))
        if frame["min_bend_radius_ratio"].notna().any():
            parts.append(histogram_svg(frame["min_bend_radius_ratio"], "Smallest bend radius / allowed", "ratio", [1.0]))
    parts.append("<h2>What drives the outcome</h2>")
    sens = sensitivity(ok, study, [o for o, _ in OUTPUTS]) if len(ok) else []
    parts.append(
        "<p>Method: <b>Spearman rank correlation</b> ρ between each numeric parameter and each "
        "outcome over the runs that completed normally (scipy.stats.spearmanr; p-value of no "
        "monotonic relation), and beside it the <b>first-order Sobol index S₁</b> = Var(E[y | x]) / Var(y), "
        "estimated from the same runs over 10 quantile bins of the parameter (given-data estimator, "
        "biased up by about 9/n for a parameter without effect): the share of the outcome's variance "
        "the parameter explains alone, non-monotonic effects included. Ranked by the largest of |ρ| "
        "and √S₁. Interactions need total-effect indices: run the study with "
        "<code>sampling.method = \"saltelli\"</code> (table below when it was).</p>")
    srows = []
    for e in sens:
        cells = [f"<code>{html.escape(e['parameter'])}</code>"]
        for o, _ in OUTPUTS:
            v = e.get(o, (None, None))
            s1 = e.get("s1_" + o)
            cells.append("–" if v[0] is None else f"{v[0]:+.3f} <small>(p={v[1]:.2g})</small>"
                         + ("" if s1 is None else f"<br>S₁ = {s1:.2f}"))
        srows.append(cells)
    parts.append(_table(["parameter"] + [label for _, label in OUTPUTS], srows))
    if study.method == "saltelli" and n:
        parts.append(sobol_table(frame, study))
    for p in study.parameters:
        if p.categorical and n:
            g = frame.groupby(p.column)["feasible"].agg(lambda s: (s == True).mean())  # noqa: E712
            parts.append(f"<p>Feasibility by <code>{html.escape(p.column)}</code>: "
                         + ", ".join(f"{html.escape(str(k))}: {100 * v:.0f} %" for k, v in g.items()) + "</p>")
    parts.append("<h2>Worst variants</h2>")
    parts.append("<p>Open one: <code>pliant run OUT/runs/&lt;id&gt;.json</code> or "
                 "<code>pliant serve OUT/runs/&lt;id&gt;.json</code> (the viewer).</p>")
    worst = ok.sort_values("worst_hand_ratio", ascending=False).head(10) if len(ok) else ok
    wrows = []
    for _, r in worst.iterrows():
        link = f'<a href="runs/{html.escape(r["run_id"])}.json">{html.escape(r["run_id"])}</a>'
        params = ", ".join(f"{p.name}={_fmt(r[p.column])}" for p in study.parameters)
        reasons = "<br>".join(html.escape(x) for x in (r["reasons"] if r["reasons"] is not None else []))
        wrows.append([link, _fmt(r["worst_hand_ratio"], 3), _fmt(r["peak_hand_force_n"]),
                      "yes" if r["feasible"] is True else "no", html.escape(params), reasons])
    parts.append(_table(["run", "worst load / limit", "peak hand force N", "feasible", "parameters", "reasons"], wrows))
    bad = frame[frame["status"] != "ok"] if n else frame
    if len(bad):
        parts.append(f"<h3>Runs that did not complete normally ({len(bad)})</h3>")
        parts.append(_table(["run", "status", "message"], [
            [f'<a href="runs/{html.escape(r["run_id"])}.json">{html.escape(r["run_id"])}</a>',
             html.escape(r["status"]), html.escape(str(r["message"])[:400])]
            for _, r in bad.head(50).iterrows()]))
    parts.append("<h2>Tolerance envelope</h2>")
    parts.append(
        f"<p>The volume each hose swept over all runs and all recorded instants (voxels of "
        f"{1000 * envelope_info['voxel_m']:.1f} mm; conservative by about one voxel; "
        f'<a href="envelope/envelope.glb">envelope.glb</a> for glTF viewers, one STL per hose for ParaView).</p>')
    erows = [[html.escape(h), f'<a href="envelope/{html.escape(i["stl"])}">{html.escape(i["stl"])}</a>',
              f"{i['volume_m3'] * 1e3:.3f}", str(i["triangles"]), "yes" if i["closed"] else "no"]
             for h, i in envelope_info["hoses"].items()]
    parts.append(_table(["hose", "mesh", "volume [litre]", "triangles", "closed"], erows))
    crows = []
    for part, t in envelope_info["tube_clearance"].items():
        mesh_c = [i["mesh_clearance_m"].get(part) for i in envelope_info["hoses"].values()]
        mesh_c = [x for x in mesh_c if x is not None]
        crows.append([html.escape(part), _fmt(None if t["clearance_m"] is None else 1000 * t["clearance_m"], 3),
                      html.escape(t["run_id"] or "–"), _fmt(1000 * min(mesh_c), 3) if mesh_c else "–"])
    parts.append("<p>Smallest clearance to each part [mm]: of the hose surfaces over every run "
                 "(exact tube, from the recorded centre lines) and of the envelope mesh (voxel "
                 "surface). Negative: the hose surface reached into the part (contact).</p>")
    parts.append(_table(["part", "tube clearance mm", "in run", "envelope mesh clearance mm"], crows))
    style = ("body{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}"
             "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:3px 8px;"
             "font-size:13px;vertical-align:top}.big{font-size:1.2em}figure{display:inline-block;margin:0.5em}")
    page = (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Study {html.escape(study.name)}</title>"
            f"<style>{style}</style></head><body>{''.join(parts)}</body></html>")
    path = os.path.join(out, "report.html")
    with open(path, "w") as f:
        f.write(page)
    return path
