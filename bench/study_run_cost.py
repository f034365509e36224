"""What one run of a study costs in one process, part by part (CPU time; a benchmark,
not a test): the timeline, the result row with the part clearances and centre-line
samples, and the batch's dilation to voxels per run. Runs the study's first variants in
batches like a Dask worker does, without Dask.

    .venv/bin/python bench/study_run_cost.py [--study examples/engine_bay_study.toml] [--runs 32] [--batch 16]
"""

import argparse
import os
import time

import numpy as np


def study_arguments(runs: int) -> argparse.ArgumentParser:
    """--study (default: the demo study) and --runs, for the study benchmarks; one
    engine thread per run, as on a study's workers."""
    os.environ.setdefault("PLIANT_THREADS", "1")
    ap = argparse.ArgumentParser()
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--study", default=os.path.join(here, "..", "examples", "engine_bay_study.toml"))
    ap.add_argument("--runs", type=int, default=runs)
    return ap


def main():
    ap = study_arguments(32)
    ap.add_argument("--batch", type=int, default=16)
    a = ap.parse_args()

    import pliant
    from pliant.studies import envelope, load_study, runner
    from pliant.studies.cluster import _prepare, Layout  # noqa: F401  (the worker's view)
    import tempfile
    import json
    from pliant.studies import sampling, variant, geometry

    study = load_study(a.study, runs=a.runs)
    out = tempfile.mkdtemp(prefix="study-cost-")
    layout = _prepare(study, out)
    base = variant.absolute_meshes(study.scene, os.path.dirname(study.scene_path))
    radii = variant.hose_radii(base)
    hoses = study.envelope_hoses or [h["name"] for h in study.scene.get("hoses", [])]
    voxel = study.envelope_voxel_m or min(0.005, min(radii.values()) / 2)
    parts = geometry.parts(base)
    tasks = []
    for i, s in enumerate(sampling.samples(study)):
        scene = variant.apply(study, s)
        text = json.dumps(variant.relative_meshes(scene, layout.runs))
        tasks.append(runner.Task(f"run-{i:05d}", i, text, os.path.abspath(layout.runs), radii, hoses, voxel, parts))

    timeline, rest, dilate, steps = [], [], [], []
    for b in range(0, len(tasks), a.batch):
        chunk, samples = tasks[b:b + a.batch], {}
        for t in chunk:
            c0 = time.process_time()
            scene = pliant.Scene.from_json(t.scene_json, base_dir=t.base_dir)
            result = pliant.run_timeline(scene)
            c1 = time.process_time()
            row = runner._result_row(result, t)
            for h, keys in runner._sweep(result, t, row).items():
                samples[h] = envelope.union(samples[h], keys) if h in samples else keys
            c2 = time.process_time()
            timeline.append(c1 - c0)
            rest.append(c2 - c1)
            steps.append(result.steps)
        c0 = time.process_time()
        for h, keys in samples.items():
            envelope.voxels_of_samples(keys, radii[h], voxel)
        dilate.append((time.process_time() - c0) / len(chunk))
    med = lambda v: float(np.median(v))
    total = med(timeline) + med(rest) + med(dilate)
    print(f"{len(tasks)} runs of {os.path.basename(a.study)} in batches of {a.batch} (median CPU-s per run; "
          f"load average {os.getloadavg()[0]:.1f}):")
    print(f"  timeline    {med(timeline):.4f}  ({med(steps):.0f} steps)")
    print(f"  row+samples {med(rest):.4f}")
    print(f"  dilation    {med(dilate):.4f}")
    print(f"  total       {total:.4f}  → 10 000 runs on 2 dedicated cores ≈ {10_000 * total / 2 / 60:.1f} min (without Dask)")


if __name__ == "__main__":
    main()
