"""Modal analysis and linear stability of the drive-train with contact damping (seed Eq. 6.4).

At an operating point (vehicle speed v, creepage c on both wheels) the contact force of a
wheel is linearized along the steady characteristic f(c): F = F_N f(c), c = (omega R - v)/v,
so dF/domega = F_N f'(c) R / v and the torque -F R adds the damping
    d_w = F_N f'(c) R^2 / v        [N m s/rad]  (= D_C R^2 with D_C = -F_N f'/v ... Eq. 6.4)
on each wheel. A falling characteristic (f' < 0) is negative damping. The PI speed
controller is linearized as well (when 0 < T_M < T_max at the operating point). The
eigenvalues of the closed loop then give the frequencies and damping ratios; an
eigenvalue with positive real part predicts a self-excited oscillation at its frequency.
"""

from __future__ import annotations

from dataclasses import dataclass, asdict

import numpy as np
from scipy.linalg import eig, eigh

from . import model
from .params import Params

NAMES = ("wheel L", "wheel S", "motor", "gear")


@dataclass
class Mode:
    frequency_hz: float  # damped frequency Im(lambda)/(2 pi)
    damping_ratio: float  # -Re(lambda)/|lambda|
    growth_rate: float  # Re(lambda), 1/s
    shape: list  # |amplitude| of (wheel L, wheel S, motor/j_G, gear), max = 1, axle side
    phase_deg: list  # phase of each amplitude relative to wheel L
    description: str


def _describe(shape, phase):
    """Text of a mode shape; participants above 0.25 grouped by phase (in phase with the largest / against it)."""
    parts = [f"{n} {a:.2f}@{p:+.0f}deg" for n, a, p in zip(NAMES, shape, phase)]
    imax = int(np.argmax(shape))
    big = [i for i in np.argsort(shape)[::-1] if shape[i] > 0.25]
    rel = [((phase[i] - phase[imax] + 180.0) % 360.0) - 180.0 for i in range(len(shape))]
    same = [NAMES[i] for i in big if abs(rel[i]) <= 90.0]
    other = [NAMES[i] for i in big if abs(rel[i]) > 90.0]
    txt = " + ".join(same) + (" against " + " + ".join(other) if other else " (in phase)")
    return ", ".join(parts) + " | " + txt


def undamped_modes(p: Params):
    """Natural frequencies (Hz) and mode shapes of the free drive-train (no contact, no damping)."""
    dt = p.drivetrain
    w2, V = eigh(model.stiffness_matrix(dt), model.mass_matrix(dt))
    out = []
    for k in range(len(w2)):
        vec = V[:, k].copy()
        vec[model.IM] /= dt.j_G  # motor angle referred to the axle
        ref = vec[np.argmax(np.abs(vec))]
        vec = vec / ref
        f = float(np.sqrt(max(w2[k], 0.0)) / (2 * np.pi))
        shape = list(np.abs(vec))
        phase = [0.0 if s >= 0 else 180.0 for s in np.sign(vec / (vec[0] if abs(vec[0]) > 1e-9 else 1))]
        out.append(Mode(f, 0.0, 0.0, [float(s) for s in shape], phase, _describe(shape, phase)))
    return out


def closed_loop_matrix(p: Params, v: float, dfdc: float, controller_active: bool = True):
    """A of x = (q, omega, omega_f, z): drive-train + contact damping + linear PI controller."""
    dt, ct, cp = p.drivetrain, p.controller, p.contact
    dw = cp.F_N * dfdc * dt.R ** 2 / v
    extra = np.diag([dw, dw, 0.0, 0.0])
    A9, B9 = model.state_space(dt, ct.tau_f, extra)
    n = model.NX + 1
    A = np.zeros((n, n))
    A[:9, :9] = A9
    if controller_active:
        Kp = ct.K_p
        Ki = ct.K_p / ct.T_i if ct.T_i > 0 else 0.0
        # T_M = Kp (w_des - w_f) + Ki z,  z' = w_des - w_f (w_des constant: drops out)
        wf = 8 if ct.tau_f > 0 else model.NQ + model.IM
        A[:9, wf] += -Kp * B9[:, 2]
        A[:9, 9] += Ki * B9[:, 2]
        A[9, wf] = -1.0
    return A, dw


def operating_point(p: Params, f0: float):
    """Steady motor torque (N m) for traction coefficient f0 on both wheels, and whether the controller is active."""
    dt, ct, cp = p.drivetrain, p.controller, p.contact
    T0 = 2.0 * f0 * cp.F_N * dt.R / dt.j_G
    return T0, (0.0 < T0 < ct.T_max)


def analyse(p: Params, v: float, c: float, f0: float, dfdc: float):
    """Eigen-analysis at creepage c: returns dict with modes, prediction and contact damping."""
    T0, active = operating_point(p, f0)
    A, dw = closed_loop_matrix(p, v, dfdc, active)
    lam, V = eig(A)
    modes = []
    for k, l in enumerate(lam):
        if abs(l) < 1e-6:  # rigid rotation angle (no restoring force)
            continue
        if l.imag < -1e-9:
            continue
        vec = V[: model.NQ, k].copy()
        vec[model.IM] /= p.drivetrain.j_G
        i = int(np.argmax(np.abs(vec)))
        vec = vec / vec[i]
        ref = vec[0] if abs(vec[0]) > 1e-9 else 1.0
        shape = [float(a) for a in np.abs(vec)]
        phase = [float(np.degrees(np.angle(a / ref))) for a in vec]
        modes.append(
            Mode(
                float(l.imag / (2 * np.pi)),
                float(-l.real / abs(l)),
                float(l.real),
                shape,
                phase,
                _describe(shape, phase),
            )
        )
    modes.sort(key=lambda m: (m.frequency_hz, m.growth_rate))
    osc = [m for m in modes if m.frequency_hz > 5.0]
    crit = max(osc, key=lambda m: m.growth_rate) if osc else None
    unstable = any(m.growth_rate > 1e-9 for m in modes)
    D_C = -p.contact.F_N * dfdc / v
    return {
        "v_mps": v,
        "cx": c,
        "f": f0,
        "dfdc": dfdc,
        "D_C_Ns_per_m": D_C,
        "wheel_damping_Nms_per_rad": dw,
        "motor_torque_Nm": T0,
        "controller_active": active,
        "modes": [asdict(m) for m in modes],
        "predicted_unstable": bool(unstable),
        "predicted_frequency_hz": crit.frequency_hz if crit else float("nan"),
        "predicted_damping_ratio": crit.damping_ratio if crit else float("nan"),
        "predicted_growth_rate": crit.growth_rate if crit else float("nan"),
    }


def format_report(res: dict) -> str:
    lines = [
        f"operating point: v = {res['v_mps']:g} m/s, c_x = {100 * res['cx']:.2f} %, f = {res['f']:.4f}, "
        f"df/dc_x = {res['dfdc']:.4f}",
        f"contact damping Eq. 6.4: D_C = -F_N f'/v = {res['D_C_Ns_per_m']:.1f} N s/m "
        f"(wheel: {res['wheel_damping_Nms_per_rad']:.1f} N m s/rad), motor torque {res['motor_torque_Nm']:.0f} N m, "
        f"controller {'active' if res['controller_active'] else 'saturated (open loop)'}",
        f"{'freq/Hz':>9} {'zeta':>9} {'Re/(1/s)':>10}  mode shape (axle side, |amp|@phase)",
    ]
    for m in res["modes"]:
        lines.append(f"{m['frequency_hz']:9.2f} {m['damping_ratio']:9.4f} {m['growth_rate']:10.3f}  {m['description']}")
    lines.append(
        f"prediction: {'UNSTABLE' if res['predicted_unstable'] else 'stable'}; least damped torsional mode "
        f"{res['predicted_frequency_hz']:.2f} Hz, zeta = {res['predicted_damping_ratio']:.4f}"
    )
    return "\n".join(lines)
