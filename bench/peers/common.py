"""Shared problem data for the peer benchmarks (read from `pliant peer params`, so every
tool is fed the numbers of Pliant's material library) and the equivalent solid section
the peers need: PyElastica and MuJoCo's cable model a solid circular section of one
radius, so the tube (d_i 10, d_a 16 mm) becomes a solid rod of the same bending stiffness
(radius r_eq with pi r_eq^4 / 4 = I) and the same mass per length (density rho A / (pi r_eq^2)).
Contact distances are kept: the peers' cylinder grows by r_o - r_eq so that the hose's
centre line rests at R + r_o from the cylinder axis in every tool."""

import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
EXACT_W = 0.493457  # w/L at lambda = 2, Mattiasson 1981 (elliptic integrals)
LAMBDA = 2.0


def pliant_bin():
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.environ.get("PLIANT_BIN", os.path.join(target, "release", "pliant"))


def load_params():
    out = subprocess.run([pliant_bin(), "peer", "params"], check=True,
                         capture_output=True, text=True).stdout
    p = json.loads(out)
    p["r_outer"] = 0.5 * p["d_outer_m"]
    p["r_eq"] = (4.0 * p["second_moment_m4"] / math.pi) ** 0.25
    p["rho_eq"] = p["mass_per_length_kg_m"] / (math.pi * p["r_eq"] ** 2)
    p["tip_load_n"] = LAMBDA * p["ei_n_m2"] / p["cantilever_length_m"] ** 2
    return p


def rest_tracker(p):
    """Returns update(t, ke) -> bool (True once at rest) and the state dict."""
    st = {"quiet_since": None, "rest": False}

    def update(t, ke):
        if ke < p["rest_energy_j"]:
            if st["quiet_since"] is None:
                st["quiet_since"] = t
            if t - st["quiet_since"] >= p["rest_window_s"]:
                st["rest"] = True
        else:
            st["quiet_since"] = None
        return st["rest"]

    return update, st


def emit(obj):
    print(json.dumps(obj), flush=True)


LEVELS = [1e-2, 1e-3, 1e-4]          # accuracy levels of the table (relative error of w/L)
TOLS = [1e-3, 1e-4, 1e-5, 1e-6]      # convergence tolerances tried at each resolution


def sweep_cantilever(run, sizes, cap_s, quick=False):
    """Runs `run(n, tol, cap)` over resolutions (coarse to fine) and, at each, tolerances
    (loose to tight) until the error stops improving (discretisation-limited), the finest
    accuracy level is reached, or the tool's time budget `cap_s` is spent. Every run is
    returned; the table keeps, per level, the fastest run that reached it."""
    runs = []
    spent = 0.0
    for n in sizes:
        prev = None
        for tol in TOLS[:1] if quick else TOLS:
            left = cap_s - spent
            if left <= 0:
                break
            r = run(n, tol, left)
            r.setdefault("elements", n)
            r.setdefault("tol", tol)
            runs.append(r)
            spent += r.get("wall_s") or 0.0
            err = r.get("error")
            if err is None or not r.get("converged"):
                break
            if prev is not None and abs(err - prev) <= 0.05 * prev:
                break  # the tolerance no longer matters at this resolution
            if err <= LEVELS[-1] * 0.5:
                break
            prev = err
        best = min((x["error"] for x in runs if x.get("error") is not None and x.get("converged")),
                   default=None)
        if quick or spent >= cap_s or (best is not None and best <= LEVELS[-1]):
            break
    return runs


def main_dispatch(cases):
    """`python X_cases.py sweep CAP_CANTILEVER CAP_DROP SIZES DROP_SIZES [quick]`: one
    JSON line per run (`{"case": ...}`), in one process (imports and JIT paid once)."""
    mode = sys.argv[1]
    if mode != "sweep":
        raise SystemExit("usage: X_cases.py sweep CAP_CANT CAP_DROP N1,N2,.. D1,D2,.. [quick]")
    cap_c, cap_d = float(sys.argv[2]), float(sys.argv[3])
    sizes = [int(a) for a in sys.argv[4].split(",") if a]
    drop_sizes = [int(a) for a in sys.argv[5].split(",") if a]
    quick = len(sys.argv) > 6 and sys.argv[6] == "quick"
    p = load_params()
    t0 = __import__("time").perf_counter()
    cases["warmup"](p)
    emit({"case": "warmup", "wall_s": __import__("time").perf_counter() - t0})

    def run_c(n, tol, left):
        r = cases["cantilever"](p, n, tol, left)
        r["case"] = "cantilever"
        emit(r)
        return r

    sweep_cantilever(run_c, sizes, cap_c, quick)
    spent = 0.0
    for n in drop_sizes:
        if spent >= cap_d:
            break
        r = cases["drop"](p, n, cap_d - spent)
        r["case"] = "drop"
        emit(r)
        spent += r.get("wall_s") or 0.0
