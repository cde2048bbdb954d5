"""Equations of the four-inertia drive-train (seed Eq. 3.4, model-spec §10), its energy, and an exact step.

Coordinates q = (phi_L, phi_S, phi_M, phi_G) in rad (phi_M on the motor side), state
x = (q, omega, omega_f) with omega_f the filtered motor speed of the controller.
    J_L w_L' = C_L(phi_G - phi_L) + D_L(w_G - w_L) - F_L R
    J_S w_S' = C_S(phi_G - phi_S) + D_S(w_G - w_S) - F_S R
    J_M w_M' = C_M(j_G phi_G - phi_M) + D_M(j_G w_G - w_M) + T_M
    J_G w_G' = C_L(phi_L - phi_G) + C_S(phi_S - phi_G) + j_G C_M(phi_M - j_G phi_G) + (same with D, w)
    omega_f' = (w_M - omega_f) / tau_f
All four mechanical equations derive from the potential V = 1/2 C_L(phi_G - phi_L)^2 +
1/2 C_S(phi_G - phi_S)^2 + 1/2 C_M(phi_M - j_G phi_G)^2 and the same form in D for the
dissipation. Between communication points the inputs (F_L, F_S, T_M) are held constant;
the linear system is then integrated exactly by the matrix exponential (zero-order hold),
so the step size limits only the coupling to the contact and controller, not the
mechanics: with D = 0 and no input the energy is conserved to round-off.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import expm

from .params import Drivetrain

IL, IS, IM, IG = 0, 1, 2, 3  # indices of the inertias in q
NQ = 4
NX = 9  # q (4), omega (4), omega_f


def _spring_matrix(dt: Drivetrain, cl: float, cs: float, cm: float) -> np.ndarray:
    """Symmetric matrix of the quadratic form 1/2 cl(qG-qL)^2 + 1/2 cs(qG-qS)^2 + 1/2 cm(qM-jG qG)^2."""
    K = np.zeros((NQ, NQ))
    for c, vec in (
        (cl, {IL: -1.0, IG: 1.0}),
        (cs, {IS: -1.0, IG: 1.0}),
        (cm, {IM: 1.0, IG: -dt.j_G}),
    ):
        v = np.zeros(NQ)
        for i, a in vec.items():
            v[i] = a
        K += c * np.outer(v, v)
    return K


def mass_matrix(dt: Drivetrain) -> np.ndarray:
    return np.diag([dt.J_L, dt.J_S, dt.J_M, dt.J_G])


def stiffness_matrix(dt: Drivetrain) -> np.ndarray:
    return _spring_matrix(dt, dt.C_L, dt.C_S, dt.C_M)


def damping_matrix(dt: Drivetrain) -> np.ndarray:
    return _spring_matrix(dt, dt.D_L, dt.D_S, dt.D_M)


def input_matrix(dt: Drivetrain) -> np.ndarray:
    """Generalized forces per input u = (F_L [N], F_S [N], T_M [N m])."""
    B = np.zeros((NQ, 3))
    B[IL, 0] = -dt.R
    B[IS, 1] = -dt.R
    B[IM, 2] = 1.0
    return B


def state_space(dt: Drivetrain, tau_f: float, extra_damping=None):
    """Continuous x' = A x + B u for x = (q, omega, omega_f), u = (F_L, F_S, T_M).

    extra_damping: optional 4x4 matrix added to D (used by the linear analysis for the
    contact damping of Eq. 6.4)."""
    M = mass_matrix(dt)
    K = stiffness_matrix(dt)
    D = damping_matrix(dt)
    if extra_damping is not None:
        D = D + extra_damping
    Minv = np.diag(1.0 / np.diag(M))
    A = np.zeros((NX, NX))
    A[:NQ, NQ:2 * NQ] = np.eye(NQ)
    A[NQ:2 * NQ, :NQ] = -Minv @ K
    A[NQ:2 * NQ, NQ:2 * NQ] = -Minv @ D
    if tau_f > 0:
        A[8, NQ + IM] = 1.0 / tau_f
        A[8, 8] = -1.0 / tau_f
    B = np.zeros((NX, 3))
    B[NQ:2 * NQ, :] = Minv @ input_matrix(dt)
    return A, B


def discretize(A: np.ndarray, B: np.ndarray, h: float):
    """Exact zero-order-hold discretization: x+ = Phi x + Gamma u."""
    n, m = B.shape
    aug = np.zeros((n + m, n + m))
    aug[:n, :n] = A
    aug[:n, n:] = B
    E = expm(aug * h)
    return E[:n, :n].copy(), E[:n, n:].copy()


def energy(dt: Drivetrain, x: np.ndarray) -> float:
    """Kinetic + elastic energy (J) of the mechanical state x[:8]."""
    q = x[:NQ]
    w = x[NQ:2 * NQ]
    kin = 0.5 * (dt.J_L * w[IL] ** 2 + dt.J_S * w[IS] ** 2 + dt.J_M * w[IM] ** 2 + dt.J_G * w[IG] ** 2)
    pot = 0.5 * (
        dt.C_L * (q[IG] - q[IL]) ** 2
        + dt.C_S * (q[IG] - q[IS]) ** 2
        + dt.C_M * (q[IM] - dt.j_G * q[IG]) ** 2
    )
    return kin + pot


def rolling_state(dt: Drivetrain, v: float, c: float = 0.0) -> np.ndarray:
    """State of steady rolling with creepage c on both wheels, untwisted shafts."""
    w = v * (1.0 + c) / dt.R
    x = np.zeros(NX)
    x[NQ + IL] = x[NQ + IS] = x[NQ + IG] = w
    x[NQ + IM] = dt.j_G * w
    x[8] = dt.j_G * w
    return x


def creepages(dt: Drivetrain, x: np.ndarray, v: float):
    """(c_L, c_S, c_M): wheel creepages c = (omega R - v)/v (traction positive) and the motor creepage Eq. 6.3."""
    w = x[NQ:2 * NQ]
    return (
        (w[IL] * dt.R - v) / v,
        (w[IS] * dt.R - v) / v,
        (w[IM] * dt.R / dt.j_G - v) / v,
    )


class Stepper:
    """Exact fixed-step integrator of the drive-train with inputs held over the step (used by simulate).

    The absolute angles grow with the rolling motion while only their differences act;
    after each step the state is shifted along the rigid-rotation null vector
    (1, 1, j_G, 1) so that phi_G = 0. This changes no force and keeps the twists free of
    the round-off of large angles (without it the energy drifts ~1e-9 in 10 s, with it ~1e-11).
    """

    def __init__(self, dt: Drivetrain, tau_f: float, h: float):
        self.h = h
        A, B = state_space(dt, tau_f)
        self.Phi, self.Gamma = discretize(A, B, h)
        self.null = np.array([1.0, 1.0, dt.j_G, 1.0])

    def step(self, x: np.ndarray, u) -> np.ndarray:
        y = self.Phi @ x + self.Gamma @ np.asarray(u, float)
        y[:NQ] -= y[IG] * self.null
        return y
