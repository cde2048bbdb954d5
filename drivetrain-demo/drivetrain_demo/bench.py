"""Where the time of a co-simulation goes: Python loop + drive-train, FMU call overhead, contact physics.

python -m drivetrain_demo bench [--grid NXxNY] [--h-ms H] [--v-mps V]
 1. loop: the co-simulation loop with a zero-cost stand-in contact (Python, numpy, controller);
 2. FFI: fmi2SetReal + fmi2GetReal per step without fmi2DoStep (ctypes + FMU entry points);
 3. doStep: one contact stepping transient ECF at constant creepage 15 % (the physics + its FFI call);
 4. two contacts serial vs in two threads (the GIL is released inside the FMU calls).
"""

from __future__ import annotations

import ctypes
import threading
import time

import numpy as np

from . import contact, cosim
from .params import Params
from .scenarios import DEFAULT_GRID


class _NullContact:
    kind = "null"

    def step(self, t, h, cx):
        return 30000.0 * np.tanh(100 * cx), 0.3

    def extra(self):
        return {}

    def close(self):
        pass


def _per_step(fn, n):
    t0 = time.perf_counter()
    fn(n)
    return (time.perf_counter() - t0) / n


def run_bench(p: Params, fmu_path, grid=DEFAULT_GRID, h=2.5e-4, v=5.0, t_sim=1.0, model="ecf"):
    n = int(round(t_sim / h))
    out = {"grid": list(grid), "h_s": h, "v_mps": v, "steps_per_simulated_s": 1.0 / h}
    # 1. loop with null contacts
    _, st = cosim.simulate(p, _NullContact(), _NullContact(), v, lambda t: 0.15, t_sim, h, progress=False)
    out["loop_python_per_step_us"] = 1e6 * (st["wall_s"] - st["contact_s"]) / n
    out["loop_python_s_per_simulated_s"] = (st["wall_s"] - st["contact_s"]) / t_sim
    # 2. FFI overhead per step
    c = contact.FMUContact(fmu_path, model=model, v=v, grid=grid)
    vr = (ctypes.c_uint * 1)(c.vr("cx"))
    val = (ctypes.c_double * 1)(0.15)

    def ffi(k):
        for _ in range(k):
            c._setReal(c._c, vr, 1, val)
            c._getReal(c._c, c._vr_out, len(c._out_names), c._val_out)

    out["ffi_set_get_per_step_us"] = 1e6 * _per_step(ffi, 20000)

    # 3. doStep physics, one contact at 15 %
    clock = {"t": 0.0}

    def one(k):
        t = clock["t"]
        for _ in range(k):
            c.step(t, h, 0.15)
            t += h
        clock["t"] = t

    one(int(0.1 / h))  # warm-up: contact filled
    out["contact_step_per_step_us"] = 1e6 * _per_step(one, n)
    out["contact_s_per_simulated_s"] = out["contact_step_per_step_us"] * 1e-6 / h
    c.close()
    # 4. two contacts, serial vs threads
    cL = contact.FMUContact(fmu_path, model=model, v=v, grid=grid, name="L")
    cS = contact.FMUContact(fmu_path, model=model, v=v, grid=grid, name="S")

    clock2 = {"t": 0.0}

    def serial(k):
        t = clock2["t"]
        for _ in range(k):
            cL.step(t, h, 0.15)
            cS.step(t, h, 0.15)
            t += h
        clock2["t"] = t

    out["two_contacts_serial_s_per_simulated_s"] = _per_step(serial, n) * n / t_sim
    pair = cosim._ParallelPair(cL, cS)

    def par(k):
        t = clock2["t"]
        for _ in range(k):
            pair.step(t, h, 0.15, 0.15)
            t += h
        clock2["t"] = t

    out["two_contacts_threads_s_per_simulated_s"] = _per_step(par, n) * n / t_sim
    pair.close()
    cL.close()
    cS.close()
    out["threads_available"] = threading.active_count()
    return out


def format_bench(b: dict) -> str:
    return "\n".join([
        f"grid {b['grid'][0]}x{b['grid'][1]}, h = {1e3 * b['h_s']:g} ms ({b['steps_per_simulated_s']:.0f} steps per simulated s), "
        f"v = {b['v_mps']:g} m/s",
        f"  Python loop + drive-train + controller: {b['loop_python_per_step_us']:7.1f} us/step "
        f"= {b['loop_python_s_per_simulated_s']:.3f} s per simulated s",
        f"  FFI (fmi2SetReal + fmi2GetReal):        {b['ffi_set_get_per_step_us']:7.1f} us/step per contact",
        f"  one contact, fmi2DoStep (physics):      {b['contact_step_per_step_us']:7.1f} us/step "
        f"= {b['contact_s_per_simulated_s']:.3f} s per simulated s",
        f"  two contacts serial:                    {b['two_contacts_serial_s_per_simulated_s']:.3f} s per simulated s",
        f"  two contacts in two threads:            {b['two_contacts_threads_s_per_simulated_s']:.3f} s per simulated s",
    ])
