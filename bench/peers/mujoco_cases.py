"""MuJoCo 3.3 side of the peer benchmarks: `<composite type="cable">` with the
`mujoco.elasticity.cable` plugin (inextensible, bending and twist; removed in MuJoCo 4.0),
implicitfast integrator, damping through the cable's joint damping (the knob MuJoCo's
cable example uses); static answers by damped dynamics run to rest. Wall time covers
mj_step only (XML compilation excluded)."""

import math
import time

import numpy as np
import mujoco

from common import EXACT_W, emit, load_params, main_dispatch, rest_tracker

# time step = SAFETY * 2 / omega_max, omega_max ~ 4 sqrt(12 EI / (rho A l^4)) the zig-zag
# mode of the segment chain (joint stiffness EI/l against segment inertia m l^2/12);
# started beyond that estimate and halved until the run stays finite (MuJoCo's
# bad-qacc warning or a speed above 1 km/s also count as divergence).
import os
SAFETY = float(os.environ.get("MJ_SAFETY", "4"))


def stable_dt(p, l):
    w_max = 4.0 * math.sqrt(12.0 * p["ei_n_m2"] / (p["mass_per_length_kg_m"] * l ** 4))
    return SAFETY * 2.0 / w_max


def capsule_density(p, l):
    # capsules overlap at the joints by their end caps: keep the mass per length
    r = p["r_eq"]
    return p["mass_per_length_kg_m"] * l / (math.pi * r * r * l + 4.0 / 3.0 * math.pi * r ** 3)


def cable_xml(p, n, length, offset, initial, dt, damping, gravity, extra_world="",
              geom_extra="", option_extra="", actuator=""):
    l = length / n
    return f"""<mujoco>
  <extension><plugin plugin="mujoco.elasticity.cable"/></extension>
  <option timestep="{dt!r}" integrator="implicitfast" gravity="0 0 {-gravity!r}" {option_extra}/>
  <worldbody>
    <site name="ref" pos="0 0 0"/>
    {extra_world}
    <composite type="cable" curve="s" count="{n + 1} 1 1" size="{length!r}"
               offset="{offset[0]!r} {offset[1]!r} {offset[2]!r}" initial="{initial}">
      <plugin plugin="mujoco.elasticity.cable">
        <config key="twist" value="{p['shear_modulus_pa']!r}"/>
        <config key="bend" value="{p['e_bending_pa']!r}"/>
      </plugin>
      <joint kind="main" damping="{damping!r}"/>
      <geom type="capsule" size="{p['r_eq']!r}" density="{capsule_density(p, l)!r}" {geom_extra}/>
    </composite>
  </worldbody>
  {actuator}
</mujoco>"""


def cantilever_once(p, n, tol, cap_s, dt):
    L = p["cantilever_length_m"]
    w1 = p["cantilever_omega1"]
    l = L / n
    # stiffness-proportional joint damping, critical for the first mode: beta = 2 / omega1
    damping = 2.0 / w1 * p["ei_n_m2"] / l
    xml = cable_xml(p, n, L, (0.0, 0.0, 0.0), "none", dt, damping, 0.0,
                    geom_extra='condim="1" contype="0" conaffinity="0"',
                    actuator='<actuator><motor site="S_last" refsite="ref" gear="0 -1 0 0 0 0"/></actuator>')
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    d.ctrl[0] = p["tip_load_n"]
    v_stop = tol * L * w1
    chunk = max(1, int(round(0.05 / w1 / dt)))
    t_min = math.pi / w1  # half a period of the first mode before testing for rest
    steps = 0
    converged = False
    tip_site = m.site("S_last").id
    start = time.perf_counter()
    while True:
        mujoco.mj_step(m, d, nstep=chunk)
        steps += chunk
        if not np.all(np.isfinite(d.qvel)) or d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number:
            return None
        # speed of the body origins (joint points) and the tip
        vmax = 0.0
        cv = d.cvel
        root = d.subtree_com[0]
        lin = cv[:, 3:] + np.cross(cv[:, :3], d.xpos - root)
        vmax = float(np.max(np.linalg.norm(lin, axis=1)))
        if vmax > 1e3:
            return None
        if d.time >= t_min and vmax < v_stop:
            converged = True
            break
        if time.perf_counter() - start > cap_s:
            break
    wall = time.perf_counter() - start
    mujoco.mj_forward(m, d)
    tip = d.site_xpos[tip_site]
    w = -tip[1] / L
    return {
        "tool": "mujoco", "solver": "damped", "elements": n, "tol": tol,
        "converged": converged, "w_over_l": float(w), "u_over_l": float((L - tip[0]) / L),
        "error": abs(w - EXACT_W) / EXACT_W, "steps": steps, "time_step_s": dt,
        "simulated_s": float(d.time), "wall_s": wall,
        "note": f"cable plugin, implicitfast; joint damping (2/omega1)*EI/l = {damping:.3g} N m s; stop when max speed < tol*L*omega1",
    }


def cantilever(p, n, tol, cap_s):
    dt = stable_dt(p, p["cantilever_length_m"] / n)
    for _ in range(6):
        r = cantilever_once(p, n, tol, cap_s, dt)
        if r is not None:
            return r
        dt *= 0.5
    return {"tool": "mujoco", "elements": n, "tol": tol, "converged": False, "error": None,
            "wall_s": None, "note": "diverged at every time step tried"}


def drop_once(p, n, cap_s, dt):
    L = p["drop_length_m"]
    R = p["cylinder_radius_m"]
    r_o = p["r_outer"]
    l = L / n
    z0 = R + p["drop_gap_m"] + r_o
    # the same damping ratio as the others' mass damping alpha gives the first mode of a
    # 250 mm arm, zeta = alpha / (2 omega_arm), as stiffness-proportional joint damping
    w_arm = p["drop_arm_omega1"]
    zeta = p["drop_damping_per_s"] / (2.0 * w_arm)
    damping = 2.0 * zeta / w_arm * p["ei_n_m2"] / l
    mu = p["drop_friction"]
    # stiffer contacts than the default solref (0.02 s, which lets the hose sink ~2.5 mm):
    # time constant 2 dt, the smallest MuJoCo recommends
    solref = f'solref="{2.0 * dt!r} 1"'
    cyl = (f'<geom name="cyl" type="cylinder" size="{R + r_o - p["r_eq"]!r} 0.1" zaxis="0 1 0" '
           f'friction="{mu!r} 0.005 0.0001" condim="3" {solref}/>')
    xml = cable_xml(p, n, L, (-0.5 * L, 0.0, z0), "free", dt, damping,
                    p["drop_gravity_m_s2"], extra_world=cyl,
                    geom_extra=f'condim="3" friction="{mu!r} 0.005 0.0001" {solref}',
                    option_extra='cone="elliptic"')
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    sample = p["drop_sample_s"]
    chunk = max(1, int(round(sample / dt)))
    update, st = rest_tracker(p)
    mass = m.body_mass[:, None]
    steps = 0
    start, cpu = time.perf_counter(), time.process_time()
    while d.time < p["drop_max_time_s"]:
        mujoco.mj_step(m, d, nstep=chunk)
        steps += chunk
        if not np.all(np.isfinite(d.qvel)) or d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number:
            return None
        if np.min(d.xpos[1:, 2]) < -L:
            return None  # fell off the cylinder: the step was too large for the contact
        cv = d.cvel
        root = d.subtree_com[m.body_rootid]
        lin = cv[:, 3:] + np.cross(cv[:, :3], d.xipos - root)
        ke = 0.5 * float(np.sum(mass * lin * lin))
        if update(float(d.time), ke):
            break
        if time.perf_counter() - start > cap_s:
            break
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    bodies = [i for i in range(m.nbody) if m.body(i).name.startswith("B_")]
    pts = [d.xpos[i].copy() for i in bodies]
    pts.append(d.site_xpos[m.site("S_last").id].copy())
    x = np.array(pts)
    return {
        "tool": "mujoco", "elements": n, "at_rest": st["rest"],
        "rest_time_s": st["quiet_since"] if st["rest"] else None,
        "simulated_s": float(d.time), "wall_s": wall, "cpu_s": cpu, "time_step_s": dt, "steps": steps,
        "tip_z_m": float(0.5 * (x[0, 2] + x[-1, 2])), "mid_z_m": float(x[n // 2, 2]),
        "half_span_m": float(0.5 * (x[-1, 0] - x[0, 0])),
        "shape_xz": [[float(a), float(b)] for a, b in zip(x[:, 0], x[:, 2])],
        "note": f"cable plugin, implicitfast, elliptic cones, solref 2*dt; joint damping {damping:.3g} N m s (zeta {zeta:.3f} on the arm mode); mu={mu}",
    }


def drop(p, n, cap_s):
    dt = stable_dt(p, p["drop_length_m"] / n)
    for _ in range(6):
        r = drop_once(p, n, cap_s, dt)
        if r is not None:
            return r
        dt *= 0.5
    return {"tool": "mujoco", "elements": n, "at_rest": False, "wall_s": None,
            "note": "diverged at every time step tried"}


def warmup(p):
    pass


if __name__ == "__main__":
    main_dispatch({"cantilever": cantilever, "drop": drop, "warmup": warmup})
