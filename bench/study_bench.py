"""Study throughput: runs per minute against the number of Dask workers (a benchmark,
not a test). For each worker count a local cluster of single-threaded worker processes
is started first (its start-up is not timed), then the same study runs on it from
scratch; a baseline runs the same variants one after another in this process, without
Dask. ``--cluster tcp`` starts the cluster as on separate machines instead: a
``dask scheduler`` process and ``dask worker --nworkers N`` (single-threaded workers
under a nanny, in their own working directory; the scene's files are sent to them).
``--solver`` runs every variant with that solver, ``--settle static`` finishes every settle
with the static solver (the study's ``settle``), ``--mass-scaling S`` scales the inertia (the
study's ``mass_scaling``), ``--rerun-unsettled`` runs again with the scene's own physics the
runs whose settles do not rest (the study's ``rerun_unsettled``). Usage:

    .venv/bin/python bench/study_bench.py [--study examples/engine_bay_study.toml]
        [--runs 24] [--workers 1,2] [--batch N] [--cluster local|tcp] [--solver S]
        [--settle dynamic|static|static_equilibrium] [--mass-scaling S] [--rerun-unsettled] [--json]

Results go to docs/performance.md ("Studies") by hand, as ratios: the absolute numbers
depend on the machine and on what else runs on it.
"""

import argparse
import contextlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time


def tree_cpu_s() -> float:
    """CPU seconds (user + system) of this process and its live children (the workers)."""
    import psutil

    procs = [psutil.Process()] + psutil.Process().children(recursive=True)
    total = 0.0
    for p in procs:
        try:
            c = p.cpu_times()
            total += c.user + c.system
        except psutil.NoSuchProcess:
            pass
    return total


@contextlib.contextmanager
def tcp_cluster(workers: int):
    """A ``dask scheduler`` and ``dask worker`` processes, as docs/study.md starts them
    (no malloc trim threshold, no statistical profiler); yields a client."""
    from distributed import Client

    folder = tempfile.mkdtemp(prefix="study-bench-cluster-")
    info = os.path.join(folder, "scheduler.json")
    env = dict(os.environ, DASK_DISTRIBUTED__NANNY__PRE_SPAWN_ENVIRON="{'MALLOC_TRIM_THRESHOLD_': None}",
               DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED="False")
    quiet = {"cwd": folder, "env": env, "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    procs = [subprocess.Popen([sys.executable, "-m", "dask", "scheduler", "--port", "0", "--dashboard-address", ":0",
                               "--scheduler-file", info], **quiet)]
    try:
        while not (os.path.exists(info) and os.path.getsize(info)):
            time.sleep(0.05)
        with open(info) as f:
            address = json.load(f)["address"]
        procs.append(subprocess.Popen([sys.executable, "-m", "dask", "worker", address, "--nworkers", str(workers),
                                       "--nthreads", "1", "--local-directory", folder], **quiet))
        client = Client(address)
        client.wait_for_workers(workers)
        try:
            yield client
        finally:
            client.close()
    finally:
        for p in reversed(procs):
            p.terminate()
            p.wait()
        shutil.rmtree(folder, ignore_errors=True)


@contextlib.contextmanager
def local_client(workers: int):
    from distributed import Client
    from pliant.studies.cluster import local_cluster

    cluster = local_cluster(workers)  # the study's own kind of local cluster
    client = Client(cluster)
    try:
        yield client
    finally:
        client.close()
        cluster.close()


def main():
    ap = argparse.ArgumentParser()
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--study", default=os.path.join(here, "..", "examples", "engine_bay_study.toml"))
    ap.add_argument("--runs", type=int, default=24)
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--baseline", type=int, default=None, help="runs of the no-Dask baseline (default: --runs / 2)")
    ap.add_argument("--batch", type=int, default=None, help="runs per Dask task (default: the study's choice)")
    ap.add_argument("--cluster", choices=("local", "tcp"), default="local")
    ap.add_argument("--solver", choices=("explicit", "implicit", "static"), default=None,
                    help="every run with this solver (default: the study's)")
    ap.add_argument("--settle", choices=("dynamic", "static", "static_equilibrium"), default=None,
                    help="every settle finished so (default: the study's)")
    ap.add_argument("--mass-scaling", type=float, default=None, help="every run's mass scaling (default: the study's)")
    ap.add_argument("--rerun-unsettled", action="store_true", help="runs whose settles do not rest run again plain")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()

    import pliant
    from pliant.studies import load_study, samples, variant_scene

    study = load_study(a.study, runs=a.runs)
    if a.solver:
        study.solver = a.solver
    if a.settle:
        study.settle = a.settle
    if a.mass_scaling:
        study.mass_scaling = a.mass_scaling
    if a.rerun_unsettled:
        study.rerun_unsettled = True
    results = {"study": os.path.basename(a.study), "runs": a.runs, "cores": os.cpu_count(), "workers": {},
               "cluster": a.cluster, "solver": a.solver, "settle": a.settle, "mass_scaling": a.mass_scaling,
               "rerun_unsettled": a.rerun_unsettled}

    # baseline: the same variants in this process, one after another, no Dask, no envelope
    nb = max(1, a.runs // 2) if a.baseline is None else a.baseline
    scenes = [json.dumps(variant_scene(study, s)) for s in samples(study)[:nb]]
    t = time.perf_counter()
    for text in scenes:
        try:
            pliant.run_timeline(pliant.Scene.from_json(text))
        except pliant.SimulationDiverged:
            pass
    results["baseline_runs_per_min"] = nb / (time.perf_counter() - t) * 60 if nb else None
    results["load_average_before"] = os.getloadavg()[0]

    for n in [int(x) for x in a.workers.split(",")]:
        out = tempfile.mkdtemp(prefix=f"study-bench-{n}-")
        with (tcp_cluster(n) if a.cluster == "tcp" else local_client(n)) as client:
            cpu0 = tree_cpu_s()
            t = time.perf_counter()
            extra = {"batch": a.batch} if a.batch else {}
            r = pliant.study(study, out, client=client, progress=False, **extra)
            dt = time.perf_counter() - t
            tree = (tree_cpu_s() - cpu0) / a.runs
            results["workers"][n] = {"seconds": dt, "runs_per_min": a.runs / dt * 60,
                                     "mean_run_wall_s": float(r.frame["wall_time_s"].mean()),
                                     "mean_run_cpu_s": float(r.frame["cpu_time_s"].mean()),
                                     # what n dedicated cores would do: n workers, each busy cpu_s per run
                                     "dedicated_runs_per_min": n * 60 / float(r.frame["cpu_time_s"].mean()),
                                     # runs in progress at once, on average: sum of run times / elapsed
                                     "concurrency": float(r.frame["wall_time_s"].sum() / dt),
                                     # CPU of this process (driver, scheduler) and all workers per
                                     # run: what the whole study costs, whatever else runs
                                     "tree_cpu_s_per_run": tree,
                                     "minutes_for_10000_runs_on_all_cores": 10_000 * tree / (os.cpu_count() * 60),
                                     "load_average_1min": os.getloadavg()[0]}
        shutil.rmtree(out, ignore_errors=True)
    base = results["workers"].get(1, {}).get("runs_per_min")
    for n, w in results["workers"].items():
        w["speed_up_vs_1_worker"] = w["runs_per_min"] / base if base else None
    if a.json:
        print(json.dumps(results, indent=2))
        return
    print(f"{results['study']}: {a.runs} runs, {results['cores']} cores")
    if results["baseline_runs_per_min"]:
        print(f"  no Dask, one process: {results['baseline_runs_per_min']:.1f} runs/min")
    for n, w in results["workers"].items():
        print(f"  {n} worker(s): {w['runs_per_min']:.1f} runs/min ({w['seconds']:.1f} s; "
              + (f"×{w['speed_up_vs_1_worker']:.2f} vs 1 worker; " if w["speed_up_vs_1_worker"] else "")
              + f"mean run {w['mean_run_wall_s']:.2f} s; "
              f"{w['concurrency']:.2f} runs at once; load average {w['load_average_1min']:.1f}; "
              f"CPU {w['mean_run_cpu_s']:.2f} s per run → {w['dedicated_runs_per_min']:.0f} runs/min on dedicated cores; "
              f"whole process tree {w['tree_cpu_s_per_run']:.2f} CPU-s per run → 10 000 runs in "
              f"{w['minutes_for_10000_runs_on_all_cores']:.0f} min on {results['cores']} dedicated cores)")


if __name__ == "__main__":
    main()
