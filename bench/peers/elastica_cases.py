"""PyElastica 1.0 side of the peer benchmarks: Cosserat rod (shear and extension
included), PositionVerlet, AnalyticalLinearDamper; static answers by damped dynamics run to
rest. Wall time covers the time-stepping loop only (system finalize and numba JIT
compilation, done by a warm-up run, are excluded)."""

import math
import time

import numpy as np
import elastica as ea

from common import EXACT_W, emit, load_params, main_dispatch, rest_tracker

# time step = SAFETY * min(element length / axial wave speed, r_eq / shear wave speed);
# halved and rerun if the run goes non-finite or an element stretches past twice its
# length (at SAFETY = 1 the drop blows up without going non-finite).
import os
SAFETY = float(os.environ.get("PE_SAFETY", "0.5"))


class Sim(ea.BaseSystemCollection, ea.Constraints, ea.Forcing, ea.Damping, ea.Contact):
    pass


def stable_dt(p, dl):
    c_axial = math.sqrt(p["e_bending_pa"] / p["rho_eq"])
    c_shear = math.sqrt(p["shear_modulus_pa"] / p["rho_eq"])
    return SAFETY * min(dl / c_axial, p["r_eq"] / c_shear)


def make_rod(p, n, start, length):
    return ea.CosseratRod.straight_rod(
        n, start=np.asarray(start, float), direction=np.array([1.0, 0.0, 0.0]),
        normal=np.array([0.0, 0.0, 1.0]), base_length=length, base_radius=p["r_eq"],
        density=p["rho_eq"], youngs_modulus=p["e_bending_pa"],
        shear_modulus=p["shear_modulus_pa"])


def cantilever_once(p, n, tol, cap_s, dt):
    L = p["cantilever_length_m"]
    w1 = p["cantilever_omega1"]
    dl = L / n
    sim = Sim()
    rod = make_rod(p, n, [0.0, 0.0, 0.0], L)
    sim.append(rod)
    sim.constrain(rod).using(ea.OneEndFixedBC, constrained_position_idx=(0,),
                             constrained_director_idx=(0,))
    sim.add_forcing_to(rod).using(ea.EndpointForces, start_force=np.zeros(3),
                                  end_force=np.array([0.0, -p["tip_load_n"], 0.0]),
                                  ramp_up_time=dt)
    sim.dampen(rod).using(ea.AnalyticalLinearDamper, uniform_damping_constant=2.0 * w1,
                          time_step=dt)
    sim.finalize()
    stepper = ea.PositionVerlet()
    v_stop = tol * L * w1
    chunk = max(1, int(round(0.05 / w1 / dt)))
    t_min = math.pi / w1  # half a period of the first mode before testing for rest
    t = np.float64(0.0)
    steps = 0
    converged = False
    start = time.perf_counter()
    while True:
        for _ in range(chunk):
            t = stepper.step(sim, t, dt)
        steps += chunk
        v = rod.velocity_collection
        if not np.all(np.isfinite(v)) or np.max(rod.lengths) > 2.0 * dl:
            return None
        vmax = np.max(np.linalg.norm(v, axis=0))
        if vmax > 1e3:
            return None
        if t >= t_min and vmax < v_stop:
            converged = True
            break
        if time.perf_counter() - start > cap_s:
            break
    wall = time.perf_counter() - start
    tip = rod.position_collection[:, -1]
    w = -tip[1] / L
    return {
        "tool": "pyelastica", "solver": "damped", "elements": n, "tol": tol,
        "converged": converged, "w_over_l": w, "u_over_l": (L - tip[0]) / L,
        "error": abs(w - EXACT_W) / EXACT_W, "steps": steps, "time_step_s": dt,
        "simulated_s": float(t), "wall_s": wall,
        "note": f"AnalyticalLinearDamper uniform 2*omega1 = {2*w1:.3f} 1/s; stop when max speed < tol*L*omega1",
    }


def cantilever(p, n, tol, cap_s):
    dt = stable_dt(p, p["cantilever_length_m"] / n)
    for _ in range(6):
        r = cantilever_once(p, n, tol, cap_s, dt)
        if r is not None:
            return r
        dt *= 0.5
    return {"tool": "pyelastica", "elements": n, "tol": tol, "converged": False,
            "error": None, "wall_s": None, "note": "diverged at every time step tried"}


def drop_once(p, n, cap_s, dt):
    L = p["drop_length_m"]
    R = p["cylinder_radius_m"]
    r_o = p["r_outer"]
    z0 = R + p["drop_gap_m"] + r_o
    dl = L / n
    sim = Sim()
    rod = make_rod(p, n, [-0.5 * L, 0.0, z0], L)
    sim.append(rod)
    # the peers' rod is thinner (r_eq < r_o): grow the cylinder to keep R + r_o
    cyl = ea.Cylinder(start=np.array([0.0, -0.1, 0.0]), direction=np.array([0.0, 1.0, 0.0]),
                      normal=np.array([0.0, 0.0, 1.0]), base_length=0.2,
                      base_radius=R + r_o - p["r_eq"], density=1000.0)
    sim.append(cyl)
    sim.constrain(cyl).using(ea.FixedConstraint, constrained_position_idx=(0,),
                             constrained_director_idx=(0,))
    g = p["drop_gravity_m_s2"]
    sim.add_forcing_to(rod).using(ea.GravityForces, acc_gravity=np.array([0.0, 0.0, -g]))
    sim.dampen(rod).using(ea.AnalyticalLinearDamper,
                          uniform_damping_constant=p["drop_damping_per_s"], time_step=dt)
    # penalty contact: stiffness so the whole hose weight on one element sinks 0.05 mm,
    # critical contact damping for one element's mass, friction regularised over
    # 0.1 mm/s of slip (capped at mu N)
    m_el = p["mass_per_length_kg_m"] * L / n
    k = p["mass_per_length_kg_m"] * L * g / 5e-5
    nu = 2.0 * math.sqrt(k * m_el)
    c_slip = p["drop_friction"] * m_el * g / 1e-4
    c_slip = min(c_slip, 0.5 * m_el / dt)
    sim.detect_contact_between(rod, cyl).using(
        ea.RodCylinderContact, k=k, nu=nu, velocity_damping_coefficient=c_slip,
        friction_coefficient=p["drop_friction"])
    sim.finalize()
    stepper = ea.PositionVerlet()
    sample = p["drop_sample_s"]
    chunk = max(1, int(round(sample / dt)))
    update, st = rest_tracker(p)
    t = np.float64(0.0)
    steps = 0
    mass = rod.mass
    start, cpu = time.perf_counter(), time.process_time()
    while t < p["drop_max_time_s"]:
        for _ in range(chunk):
            t = stepper.step(sim, t, dt)
        steps += chunk
        v = rod.velocity_collection
        if not np.all(np.isfinite(v)) or np.max(rod.lengths) > 2.0 * dl:
            return None
        ke = 0.5 * float(np.sum(mass * np.sum(v * v, axis=0)))
        if update(float(t), ke):
            break
        if time.perf_counter() - start > cap_s:
            break
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    x = rod.position_collection
    return {
        "tool": "pyelastica", "elements": n, "at_rest": st["rest"],
        "rest_time_s": st["quiet_since"] if st["rest"] else None,
        "simulated_s": float(t), "wall_s": wall, "cpu_s": cpu, "time_step_s": dt, "steps": steps,
        "tip_z_m": 0.5 * (x[2, 0] + x[2, -1]), "mid_z_m": float(x[2, n // 2]),
        "half_span_m": 0.5 * (x[0, -1] - x[0, 0]),
        "shape_xz": [[float(a), float(b)] for a, b in zip(x[0], x[2])],
        "note": f"PositionVerlet; AnalyticalLinearDamper uniform {p['drop_damping_per_s']} 1/s; RodCylinderContact k={k:.3g} N/m nu={nu:.3g} N s/m mu={p['drop_friction']}",
    }


def drop(p, n, cap_s):
    dt = stable_dt(p, p["drop_length_m"] / n)
    for _ in range(6):
        r = drop_once(p, n, cap_s, dt)
        if r is not None:
            return r
        dt *= 0.5
    return {"tool": "pyelastica", "elements": n, "at_rest": False, "wall_s": None,
            "note": "diverged at every time step tried"}


def warmup(p):
    """Compiles the numba kernels (cached on disk) outside the timed region."""
    cantilever_once(p, 6, 1.0, 0.5, stable_dt(p, 1.0 / 6))
    drop_once(p, 6, 0.5, stable_dt(p, 0.5 / 6))


if __name__ == "__main__":
    main_dispatch({"cantilever": cantilever, "drop": drop, "warmup": warmup})
