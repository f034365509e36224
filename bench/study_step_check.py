"""Does a larger explicit time step change a study's answers? Runs the first variants of
a study twice in this process — with the scene's own `time_step_safety` and with another
one (default 0.9, LS-DYNA's default time-step scale factor) — and compares each run's
verdict and peaks (a benchmark and a convergence check, not a test).

    .venv/bin/python bench/study_step_check.py [--study examples/engine_bay_study.toml] [--runs 48] [--safety 0.9]
"""

import json
import os
import time

import numpy as np
from study_run_cost import study_arguments  # bench/ is the script's folder

COLUMNS = ["peak_hand_force_n", "peak_hand_torque_nm", "min_bend_radius_ratio", "max_twist_rad_per_m"]


def main():
    ap = study_arguments(48)
    ap.add_argument("--safety", type=float, default=0.9)
    ap.add_argument("--reference", type=float, default=0.5, help="time_step_safety of the reference runs")
    a = ap.parse_args()

    import pliant
    from pliant.studies import load_study, runner, sampling, variant

    study = load_study(a.study, runs=a.runs)
    rows = {a.reference: [], a.safety: []}
    cpu = {a.reference: 0.0, a.safety: 0.0}
    for s in sampling.samples(study):
        scene = variant.apply(study, s)
        for safety in rows:
            scene.setdefault("simulation", {})["time_step_safety"] = safety
            task = runner.Task("r", 0, json.dumps(scene), os.path.dirname(study.scene_path), {}, [], 0.0)
            c = time.process_time()
            rows[safety].append(runner.run_variant(task)["row"])
            cpu[safety] += time.process_time() - c
    ref, new = rows[a.reference], rows[a.safety]
    print(f"{len(ref)} variants of {os.path.basename(a.study)}: time_step_safety {a.safety} against {a.reference}")
    print(f"  CPU {cpu[a.safety]:.1f} s against {cpu[a.reference]:.1f} s (×{cpu[a.reference] / cpu[a.safety]:.2f} faster); "
          f"steps {np.mean([r['steps'] for r in new]):.0f} against {np.mean([r['steps'] for r in ref]):.0f}")
    print(f"  status equal in {sum(r['status'] == n['status'] for r, n in zip(ref, new))} of {len(ref)} runs; "
          f"verdict equal in {sum(r.get('feasible') == n.get('feasible') for r, n in zip(ref, new))}; "
          f"violated checks equal in {sum(r.get('violated_checks') == n.get('violated_checks') for r, n in zip(ref, new))}")
    forces = [k for k in ref[0] if k.endswith("_force_n")]
    for col in COLUMNS + [k for k in forces if k not in COLUMNS]:
        pairs = [(r.get(col), n.get(col)) for r, n in zip(ref, new) if r.get(col) is not None and n.get(col) is not None]
        if not pairs:
            continue
        x, y = np.array(pairs, float).T
        rel = np.abs(y - x) / np.maximum(np.abs(x), 1e-12)
        w = int(np.argmax(rel))
        print(f"  {col:40s} relative difference: median {np.median(rel):.2e}, max {rel.max():.2e} "
              f"(variant {w}: {y[w]:.6g} against {x[w]:.6g})")


if __name__ == "__main__":
    main()
