"""Runs the head-to-head benchmarks (Pliant, PyElastica 1.0, MuJoCo 3.3 cable) in one go,
writes bench/peers/results.json and rewrites the marked section of docs/performance.md.
Called by run.sh (which builds Pliant and sets up the venv); `--quick` is the smoke mode
(one small resolution per tool, docs not rewritten)."""

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time

from common import (EXACT_W, HERE, LEVELS, ROOT, load_params, pliant_bin,
                    sweep_cantilever)

MARK_BEGIN = "<!-- peers:begin -->"
MARK_END = "<!-- peers:end -->"


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def pliant_cantilever(solver):
    def run(n, tol, left):
        cmd = [pliant_bin(), "peer", "cantilever", "--elements", str(n), "--solver", solver,
               "--tol", repr(tol)]
        try:
            out = subprocess.run(cmd, check=True, capture_output=True, text=True,
                                 timeout=max(1.0, left))
            r = json.loads(out.stdout)
            r["error"] = abs(r["w_over_l"] - EXACT_W) / EXACT_W
        except subprocess.TimeoutExpired:
            r = {"tool": "pliant", "solver": solver, "elements": n, "tol": tol,
                 "converged": False, "error": None, "wall_s": left, "note": "time cap"}
        except subprocess.CalledProcessError as e:
            r = {"tool": "pliant", "solver": solver, "elements": n, "tol": tol,
                 "converged": False, "error": None, "wall_s": None,
                 "note": e.stderr.strip()[-300:]}
        r["case"] = "cantilever"
        log(f"  pliant/{solver} N={n} tol={tol:g}: error {fmt_err(r.get('error'))} in {fmt_s(r.get('wall_s'))}")
        return r
    return run


def children_cpu_s():
    """CPU seconds (user + system) of this process's finished children."""
    import resource

    u = resource.getrusage(resource.RUSAGE_CHILDREN)
    return u.ru_utime + u.ru_stime


def pliant_drop(n, left):
    cmd = [pliant_bin(), "peer", "drop", "--elements", str(n)]
    try:
        cpu = children_cpu_s()
        out = subprocess.run(cmd, check=True, capture_output=True, text=True,
                             timeout=max(1.0, left))
        r = json.loads(out.stdout)
        # the whole process (start-up and model set-up included): an upper bound of the
        # run's CPU, as the peers' process_time covers their run only
        r["cpu_s"] = children_cpu_s() - cpu
    except subprocess.TimeoutExpired:
        r = {"tool": "pliant", "elements": n, "at_rest": False, "wall_s": left, "note": "time cap"}
    r["case"] = "drop"
    log(f"  pliant drop N={n}: rest at {r.get('rest_time_s')} s in {fmt_s(r.get('wall_s'))}")
    return r


def peer(script, cap_c, cap_d, sizes, drop_sizes, quick):
    cmd = [sys.executable, os.path.join(HERE, script), "sweep", str(cap_c), str(cap_d),
           ",".join(map(str, sizes)), ",".join(map(str, drop_sizes))] + (["quick"] if quick else [])
    runs = []
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, text=True, cwd=HERE)
    for line in proc.stdout:
        r = json.loads(line)
        runs.append(r)
        if r["case"] == "cantilever":
            log(f"  {r['tool']} N={r['elements']} tol={r['tol']:g}: error {fmt_err(r.get('error'))} in {fmt_s(r.get('wall_s'))}")
        elif r["case"] == "drop":
            log(f"  {r['tool']} drop N={r['elements']}: rest at {r.get('rest_time_s')} s in {fmt_s(r.get('wall_s'))}")
        else:
            log(f"  {script}: warm-up (imports, JIT) {fmt_s(r.get('wall_s'))} (not counted)")
    if proc.wait() != 0:
        raise SystemExit(f"{script} failed")
    return runs


def fmt_s(s):
    if s is None:
        return "—"
    if s < 1e-3:
        return f"{s * 1e6:.0f} µs"
    if s < 1:
        return f"{s * 1e3:.1f} ms"
    return f"{s:.2f} s"


def fmt_err(e):
    return "—" if e is None else f"{e:.2e}"


def best_per_level(runs):
    """Fastest run per accuracy level. A run counts for a level only if its own error is
    within it AND the tightest-tolerance run at the same resolution is too: a loosely
    converged run can stop mid-approach and land nearer the exact answer than its own
    resolution converges to (luck, not accuracy)."""
    ok = [r for r in runs if r.get("converged") and r.get("error") is not None]
    settled = {}
    for r in ok:
        n = r["elements"]
        if n not in settled or r["tol"] < settled[n]["tol"]:
            settled[n] = r
    out = {}
    for lv in LEVELS:
        hits = [r for r in ok if r["error"] <= lv and settled[r["elements"]]["error"] <= lv]
        if hits:
            b = min(hits, key=lambda r: r["wall_s"])
            out[str(lv)] = {"reached": True, "wall_s": b["wall_s"], "elements": b["elements"],
                            "tol": b["tol"], "error": b["error"]}
        else:
            be = min(settled.values(), key=lambda r: r["error"]) if settled else None
            out[str(lv)] = {"reached": False,
                            "best_error": be["error"] if be else None,
                            "best_elements": be["elements"] if be else None}
    return out


def machine():
    cpu = platform.processor() or "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    vers = {}
    try:
        import importlib.metadata as md
        for pkg in ("pyelastica", "mujoco", "numpy", "numba"):
            try:
                vers[pkg] = md.version(pkg)
            except md.PackageNotFoundError:
                vers[pkg] = None
    except ImportError:
        pass
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else None
    return {"cpu": cpu, "logical_cores": os.cpu_count(), "platform": platform.platform(),
            "python": platform.python_version(), "versions": vers, "load_1min_at_start": load,
            "date": datetime.datetime.now().isoformat(timespec="seconds")}


TOOLS = [("pliant-static", "Pliant, quasi-static Newton (one solve)"),
         ("pliant-relax", "Pliant, dynamic relaxation (kinetic damping)"),
         ("pliant-damped", "Pliant, explicit + mass damping to rest"),
         ("pyelastica", "PyElastica 1.0, damped dynamics to rest"),
         ("mujoco", "MuJoCo 3.3 cable plugin, damped dynamics to rest")]
PLIANT = [key for key, _ in TOOLS if key.startswith("pliant")]
PEERS = [(key, label) for key, label in TOOLS if not key.startswith("pliant")]


def markdown(res):
    m = res["machine"]
    L = []
    L.append(MARK_BEGIN)
    L.append("<!-- generated by bench/peers/run.sh; do not edit by hand -->")
    L.append("")
    L.append(f"Measured in one run of `bench/peers/run.sh` on {m['date']}: **{m['cpu']}, "
             f"{m['logical_cores']} logical cores** ({m['platform']}; 1-min load "
             f"{m['load_1min_at_start']:.2f} at the start — a shared machine, expect ±25 %), "
             f"Python {m['python']}, PyElastica {m['versions'].get('pyelastica')}, MuJoCo "
             f"{m['versions'].get('mujoco')}, numba {m['versions'].get('numba')}; Pliant release "
             "build, one thread. Wall times are of the solve only (no imports, model building "
             "or JIT compilation). Raw runs: `bench/peers/results.json`.")
    L.append("")
    L.append("**(a) Cantilever under a tip load**, λ = PL²/EI = 2, library hose 1, L = 1 m, "
             f"exact w/L = {EXACT_W} (elliptic integrals). Wall time of the fastest converged run "
             "whose tip error is within the level and whose resolution, converged at its tightest "
             "tolerance, is within it too (a loose stop can land near the answer by luck). "
             "Resolution N and stopping tolerance swept, coarse to fine; N and tol of that run in "
             "brackets; 'not reached': best converged error within the tool's time budget "
             "(PyElastica and MuJoCo clamp by fixing the first element, which converges like 1/N; "
             "see bench/peers/README.md):")
    L.append("")
    L.append("| tool | " + " | ".join(f"{lv * 100:g} %" for lv in LEVELS) + " |")
    L.append("|---|" + "---:|" * len(LEVELS))
    for key, label in TOOLS:
        if key not in res["cantilever_best"]:
            continue
        cells = []
        for lv in LEVELS:
            b = res["cantilever_best"][key][str(lv)]
            if b["reached"]:
                cells.append(f"{fmt_s(b['wall_s'])} (N {b['elements']}, tol {b['tol']:g})")
            else:
                be = b["best_error"]
                cells.append("not reached" + (f" (best {be * 100:.2g} % at N {b['best_elements']})" if be is not None else ""))
        L.append(f"| {label} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("Ratio of wall times, Pliant (fastest Pliant path per level) / peer — below 1 "
             "means Pliant is faster; the speed-up is the inverse:")
    L.append("")
    L.append("| peer | " + " | ".join(f"{lv * 100:g} %" for lv in LEVELS) + " |")
    L.append("|---|" + "---:|" * len(LEVELS))
    for key, label in PEERS:
        if key not in res["ratios"]:
            continue
        cells = []
        for lv in LEVELS:
            r = res["ratios"][key][str(lv)]
            if r is None:
                cells.append("—")
            elif r == "peer not reached":
                cells.append("peer: not reached")
            else:
                cells.append(f"{r:.3g} ({1 / r:.3g}× faster)" if r < 1 else f"{r:.3g} ({r:.3g}× slower)")
        L.append(f"| {label} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("**(b) 500 mm of hose 1 dropped onto a horizontal cylinder** (R = 50 mm, hose 10 mm "
             "above it, gravity, μ = 0.5, mass damping 8 /s — MuJoCo: joint damping giving the "
             "same damping ratio to the first mode of a 250 mm arm). Rest: translational kinetic "
             "energy below 1 µJ for 0.2 s of simulated time; wall time covers the whole run up "
             "to then. Shape at rest: height of the ends (tip) and middle above the cylinder axis, "
             "half the span between the ends.")
    L.append("")
    reps = res.get("drop_repeats", 1)
    if reps > 1:
        L.append(f"Pliant and MuJoCo ran the drop {reps} times each, alternately; the table gives the "
                 "median of the runs (min–max beside it) and compares the medians of the CPU times, "
                 "which the machine's other work inflates far less than wall time (Pliant: its whole "
                 "process, start-up included; peers: their run). PyElastica ran once.")
        L.append("")
    L.append("| tool | N | Δt [µs] | rest at [s sim] | wall to rest (median; min–max) | CPU to rest (median; min–max) | real-time factor | tip z [mm] | mid z [mm] | half span [mm] | CPU Pliant/this |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    groups = drop_groups(res["drop"])
    for (tool, n), g in groups.items():
        r = g["median_run"]
        rest = r.get("rest_time_s")
        wall, cpu = g["wall_s"], g["cpu_s"]
        rtf = (r["simulated_s"] / wall) if wall and r.get("simulated_s") else None
        ratio = ""
        pl = groups.get(("pliant", n))
        if tool != "pliant" and pl and pl["at_rest"] and g["at_rest"]:
            if cpu and pl["cpu_s"]:
                ratio = f"{pl['cpu_s'] / cpu:.3g}"
            elif wall and pl["wall_s"]:  # results from before CPU times were kept
                ratio = f"{pl['wall_s'] / wall:.3g} (wall)"
        mm = lambda v: "—" if v is None else f"{v * 1e3:.1f}"
        spread = lambda k: "" if len(g[k + "_all"]) < 2 else \
            f" ({fmt_s(min(g[k + '_all']))}–{fmt_s(max(g[k + '_all']))})"
        L.append(f"| {tool} | {n} | {r.get('time_step_s', 0) * 1e6:.1f} | "
                 f"{'not at rest' if not g['at_rest'] else f'{rest:.3f}'} | {fmt_s(wall)}{spread('wall_s')} | "
                 f"{fmt_s(cpu)}{spread('cpu_s')} | "
                 f"{'—' if rtf is None else f'{rtf:.3g}'} | {mm(r.get('tip_z_m'))} | "
                 f"{mm(r.get('mid_z_m'))} | {mm(r.get('half_span_m'))} | {ratio} |")
    L.append("")
    L.append(f"Whole run: {res['total_wall_s']:.0f} s.")
    L.append(MARK_END)
    return "\n".join(L)


def drop_groups(drop):
    """The drop runs per (tool, elements), in first-seen order: median wall and CPU time
    over the repeats, every repeat's times, whether all came to rest, and the run whose
    wall time is the median (its shape and rest time are shown)."""
    import statistics

    groups = {}
    for r in drop:
        groups.setdefault((r["tool"], r["elements"]), []).append(r)
    out = {}
    for key, rs in groups.items():
        wall = [r["wall_s"] for r in rs if r.get("wall_s") is not None]
        cpu = [r["cpu_s"] for r in rs if r.get("cpu_s") is not None]
        by_wall = sorted((r for r in rs if r.get("wall_s") is not None), key=lambda r: r["wall_s"])
        out[key] = {
            "wall_s": statistics.median(wall) if wall else None, "wall_s_all": wall,
            "cpu_s": statistics.median(cpu) if cpu else None, "cpu_s_all": cpu,
            "at_rest": all(r.get("at_rest") for r in rs),
            "median_run": by_wall[(len(by_wall) - 1) // 2] if by_wall else rs[0],
        }
    return out


def write_docs(md):
    path = os.path.join(ROOT, "docs", "performance.md")
    with open(path) as f:
        text = f.read()
    if MARK_BEGIN in text and MARK_END in text:
        a = text.index(MARK_BEGIN)
        b = text.index(MARK_END) + len(MARK_END)
        text = text[:a] + md + text[b:]
    else:
        text = text.rstrip("\n") + "\n\n## Head-to-head with PyElastica and MuJoCo\n\n" \
            "See `bench/peers/README.md` for the method.\n\n" + md + "\n"
    with open(path, "w") as f:
        f.write(text)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="smoke mode: one small case per tool")
    ap.add_argument("--no-docs", action="store_true")
    ap.add_argument("--render", metavar="RESULTS_JSON",
                    help="re-score and re-render the tables from a finished run's raw runs")
    ap.add_argument("--drop-repeats", type=int, default=None,
                    help="runs of the drop case per tool and size, Pliant and MuJoCo alternately "
                         "(default 3; 1 with --quick); the table shows medians")
    args = ap.parse_args()
    if args.drop_repeats is None:
        args.drop_repeats = 1 if args.quick else 3
    if args.render:
        with open(args.render) as f:
            res = json.load(f)
        score(res)
        with open(args.render, "w") as f:
            json.dump(res, f, indent=1)
        md = markdown(res)
        print(md)
        if not res.get("quick") and not args.no_docs:
            write_docs(md)
        return
    q = args.quick
    t0 = time.perf_counter()
    res = {"machine": machine(), "quick": q, "exact_w_over_l": EXACT_W, "levels": LEVELS}
    res["params"] = load_params()
    sizes = [8] if q else [4, 8, 16, 32, 64, 128, 256, 512]
    peer_sizes = [8] if q else [8, 16, 32, 64, 128, 256]
    drop_sizes = [10] if q else [10, 20, 40]
    cap_pl, cap_peer, cap_drop = (20, 60, 30) if q else (60, 110, 50)
    runs = []
    for solver in ("static", "relax", "damped"):
        log(f"pliant {solver}:")
        rs = sweep_cantilever(pliant_cantilever(solver), sizes, cap_pl, q)
        for r in rs:
            r["tool"] = f"pliant-{solver}"
        runs += rs
    drop = []
    spent = 0.0
    for n in drop_sizes:
        r = pliant_drop(n, cap_drop - spent)
        r["repeat"] = 0
        drop.append(r)
        spent += r.get("wall_s") or 0
    for script in ("elastica_cases.py", "mujoco_cases.py"):
        log(f"{script}:")
        for r in peer(script, cap_peer, cap_drop, peer_sizes, drop_sizes, q):
            if r["case"] == "cantilever":
                runs.append(r)
            elif r["case"] == "drop":
                drop.append(r)
            else:
                res.setdefault("warmups", []).append({"script": script, **r})
    # the drop again, Pliant and MuJoCo alternately: a shared machine's load changes
    # within minutes, so one run each can be off by 3× (docs/performance.md)
    for k in range(1, args.drop_repeats):
        log(f"drop, repeat {k + 1} of {args.drop_repeats}:")
        spent = 0.0
        for n in drop_sizes:
            r = pliant_drop(n, cap_drop - spent)
            spent += r.get("wall_s") or 0
            drop.append({**r, "repeat": k})
        drop += [{**r, "repeat": k} for r in peer("mujoco_cases.py", 0, cap_drop, [], drop_sizes, q)
                 if r["case"] == "drop"]
    for r in drop:
        r.setdefault("repeat", 0)
    res["drop_repeats"] = args.drop_repeats
    res["cantilever_runs"] = runs
    res["drop"] = drop
    res["total_wall_s"] = time.perf_counter() - t0
    score(res)
    out = os.path.join(HERE, "results-quick.json" if q else "results.json")
    with open(out, "w") as f:
        json.dump(res, f, indent=1)
    md = markdown(res)
    print(md)
    if not q and not args.no_docs:
        write_docs(md)
        log("docs/performance.md updated")
    log(f"wrote {out}; total {res['total_wall_s']:.0f} s")


def score(res):
    runs = res["cantilever_runs"]
    best = {}
    for key, _ in TOOLS:
        rs = [r for r in runs if r["tool"] == key]
        if rs:
            best[key] = best_per_level(rs)
    res["cantilever_best"] = best
    ratios = {}
    for key, _ in PEERS:
        if key not in best:
            continue
        ratios[key] = {}
        for lv in LEVELS:
            pts = [best[k][str(lv)] for k in PLIANT if k in best]
            pts = [b["wall_s"] for b in pts if b["reached"]]
            pb = best[key][str(lv)]
            if not pts:
                ratios[key][str(lv)] = None
            elif not pb["reached"]:
                ratios[key][str(lv)] = "peer not reached"
            else:
                ratios[key][str(lv)] = min(pts) / pb["wall_s"]
    res["ratios"] = ratios


if __name__ == "__main__":
    main()
