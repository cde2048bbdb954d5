"""Fixed-step co-simulation of the drive-train with one contact instance per wheel.

Per communication step h (t_n -> t_n + h):
 1. creepages c_L, c_S of the wheels from the state at t_n (traction positive);
 2. each contact gets its creepage, held over the step, and advances by h (fmi2DoStep)
    -> forces F(t_n + h); optionally the two contacts run in parallel threads;
 3. the controller (PI on the filtered motor speed, Eq. 6.1/6.2) sets T_M >= 0, <= T_max;
 4. the drive-train advances exactly (matrix exponential) with T_M and the contact forces
    held at the mean of F(t_n) and F(t_n + h) (second order in h).
"""

from __future__ import annotations

import sys
import threading
import time

import numpy as np

from . import model
from .params import Params

COLUMNS = (
    "t_s", "cx_des", "cx_L", "cx_S", "cx_M", "f_L", "f_S", "Fx_L_N", "Fx_S_N", "T_M_Nm",
    "omega_L_rad_s", "omega_S_rad_s", "omega_M_rad_s", "omega_G_rad_s",
    "T_axle_L_Nm", "T_axle_S_Nm", "T_max_L_C", "P_fric_L_W",
)


class _ParallelPair:
    """Steps contact S in a worker thread while the caller steps contact L (ctypes releases the GIL)."""

    def __init__(self, cL, cS):
        self.cL, self.cS = cL, cS
        self._go = threading.Semaphore(0)
        self._done = threading.Semaphore(0)
        self._args = None
        self._res = None
        self._err = None
        self._stop = False
        self._th = threading.Thread(target=self._run, daemon=True)
        self._th.start()

    def _run(self):
        while True:
            self._go.acquire()
            if self._stop:
                return
            try:
                self._res = self.cS.step(*self._args)
            except BaseException as e:  # noqa: BLE001 - re-raised in the caller
                self._err = e
            self._done.release()

    def step(self, t, h, cl, cs):
        self._args = (t, h, cs)
        self._go.release()
        rl = self.cL.step(t, h, cl)
        self._done.acquire()
        if self._err:
            raise self._err
        return rl, self._res

    def close(self):
        self._stop = True
        self._go.release()
        self._th.join(timeout=1.0)


def simulate(p: Params, contact_L, contact_S, v: float, c_des, t_end: float, h: float,
             parallel: bool = False, progress: bool = True, label: str = "", timing: dict | None = None):
    """Runs the co-simulation; c_des(t) is the desired creepage. Returns (dict of arrays, stats)."""
    if not (h > 0 and t_end > 0):
        raise ValueError("h and t_end must be > 0")
    dt, ct = p.drivetrain, p.controller
    stepper = model.Stepper(dt, ct.tau_f, h)
    n = int(round(t_end / h))
    x = model.rolling_state(dt, v, 0.0)
    Ki = ct.K_p / ct.T_i if ct.T_i > 0 else 0.0
    z = 0.0
    rec = np.full((n + 1, len(COLUMNS)), np.nan)
    R, jG, FN = dt.R, dt.j_G, p.contact.F_N

    def row(k, t, cd, F, f, T, ex):
        cl, cs, cm = model.creepages(dt, x, v)
        w = x[model.NQ:2 * model.NQ]
        q = x[:model.NQ]
        rec[k] = (t, cd, cl, cs, cm, f[0], f[1], F[0], F[1], T, w[0], w[1], w[2], w[3],
                  dt.C_L * (q[3] - q[0]), dt.C_S * (q[3] - q[1]),
                  ex.get("T_max", np.nan), ex.get("P_fric", np.nan))

    F_old = [0.0, 0.0]
    f_old = [0.0, 0.0]
    row(0, 0.0, c_des(0.0), F_old, f_old, 0.0, {})
    pair = _ParallelPair(contact_L, contact_S) if parallel else None
    t_contact = 0.0
    wall0 = time.perf_counter()
    last = wall0
    try:
        for k in range(n):
            t = k * h
            cl = (x[model.NQ] * R - v) / v
            cs = (x[model.NQ + 1] * R - v) / v
            tc = time.perf_counter()
            if pair is not None:
                (FL, fL), (FS, fS) = pair.step(t, h, cl, cs)
            else:
                FL, fL = contact_L.step(t, h, cl)
                FS, fS = contact_S.step(t, h, cs)
            t_contact += time.perf_counter() - tc
            cd = c_des(t)
            e = jG * v * (1.0 + cd) / R - x[8]
            T = ct.K_p * e + Ki * z
            if T >= ct.T_max:
                T = ct.T_max
                if e < 0:
                    z += h * e
            elif T <= 0.0:
                T = 0.0
                if e > 0:
                    z += h * e
            else:
                z += h * e
            u = np.array((0.5 * (F_old[0] + FL), 0.5 * (F_old[1] + FS), T))
            x = stepper.step(x, u)
            F_old = [FL, FS]
            row(k + 1, t + h, cd, F_old, (fL, fS), T, contact_L.extra())
            if not np.all(np.isfinite(x)):
                raise RuntimeError(f"state not finite at t = {t + h:.4f} s")
            if progress and (k & 255) == 0:
                now = time.perf_counter()
                if now - last > 2.0:
                    last = now
                    print(f"  {label} t = {t + h:.3f}/{t_end:g} s, c_L = {100 * cl:.2f} %, "
                          f"wall {now - wall0:.1f} s", file=sys.stderr, flush=True)
    finally:
        if pair is not None:
            pair.close()
    wall = time.perf_counter() - wall0
    stats = {"wall_s": wall, "contact_s": t_contact, "steps": n, "h_s": h, "t_end_s": t_end,
             "real_time_factor": wall / t_end, "parallel_contacts": bool(parallel)}
    if timing is not None:
        timing.update(stats)
    return {c: rec[:, i] for i, c in enumerate(COLUMNS)}, stats
