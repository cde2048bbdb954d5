"""Compares two builds of the ecf_contact FMU bit for bit: the same scripted call sequence on each, every value, status and log message recorded, plus serialized states loaded across builds.

Usage: .venv/bin/python scripts/compare-fmu.py A B   (each an .fmu file or an unzipped FMU folder)
Prints the number of recorded items and the first differences; exit status 1 if any differ.
"""

import ctypes
import hashlib
import os
import struct
import sys
import tempfile

from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)


def bits(x):
    return struct.pack("<d", x).hex()


class Build:
    def __init__(self, path):
        self.dir = path if os.path.isdir(path) else extract(path, unzipdir=tempfile.mkdtemp())
        self.md = read_model_description(os.path.join(self.dir, "modelDescription.xml"))
        self.vars = list(self.md.modelVariables)
        self.vr = {v.name: v.valueReference for v in self.vars}


class Run:
    """One instance of a build; every call's result goes to `rec`."""

    def __init__(self, build, rec, name="cmp"):
        self.b, self.rec = build, rec
        self.cb = fmi2CallbackFunctions()
        self._logger = fmi2CallbackLoggerTYPE(self._log)
        self.cb.logger = self._logger
        self.cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(lambda n, s: None)
        self.cb.freeMemory = fmi2CallbackFreeMemoryTYPE(lambda p: None)
        self.s = FMU2Slave(guid=build.md.guid, unzipDirectory=build.dir,
                           modelIdentifier="ecf_contact", instanceName=name)
        self.s.instantiate(callbacks=self.cb, loggingOn=True)

    def _log(self, env, name, status, category, message):
        self.rec.append(("log", status, category.decode(), message.decode()))

    def call(self, label, f, *a):
        try:
            r = f(*a)
            self.rec.append((label, "ok"))
            return r
        except FMICallException as e:
            self.rec.append((label, "status", e.status))
            return None

    def set(self, name, x):
        vr = [self.b.vr[name]]
        if isinstance(x, bool):
            self.call(f"setBoolean {name}", self.s.setBoolean, vr, [x])
        elif isinstance(x, int):
            self.call(f"setInteger {name}", self.s.setInteger, vr, [x])
        elif isinstance(x, str):
            self.call(f"setString {name}", self.s.setString, vr, [x])
        else:
            self.call(f"setReal {name}", self.s.setReal, vr, [x])

    def get_all(self, label):
        for v in self.b.vars:
            vr = [v.valueReference]
            if v.type == "Real":
                r = self.call(f"{label} getReal {v.name}", self.s.getReal, vr)
                self.rec.append((label, v.name, None if r is None else bits(r[0])))
            elif v.type == "Integer":
                r = self.call(f"{label} getInteger {v.name}", self.s.getInteger, vr)
                self.rec.append((label, v.name, None if r is None else r[0]))
            elif v.type == "Boolean":
                r = self.call(f"{label} getBoolean {v.name}", self.s.getBoolean, vr)
                self.rec.append((label, v.name, None if r is None else bool(r[0])))
            else:
                r = self.call(f"{label} getString {v.name}", self.s.getString, vr)
                self.rec.append((label, v.name, None if r is None else r[0]))

    def outputs(self, label):
        for v in self.b.vars:
            if v.causality == "output":
                r = self.call(f"{label} getReal {v.name}", self.s.getReal, [v.valueReference])
                self.rec.append((label, v.name, None if r is None else bits(r[0])))

    def raw(self, fname, *args):
        """An exported function called directly with instance handle and integer/NULL arguments."""
        f = getattr(self.s.dll, fname)
        f.restype = ctypes.c_int
        f.argtypes = [ctypes.c_void_p] + [ctypes.c_void_p] * len(args)
        self.rec.append((fname, f(self.s.component, *args)))

    def free(self):
        self.s.freeInstance()


class Lcg:
    def __init__(self, seed):
        self.x = seed

    def u(self):
        self.x = (6364136223846793005 * self.x + 1442695040888963407) % 2**64
        return (self.x >> 11) / 2**53


def drive(run, steps, seed, t0=0.0, vary=True):
    """Steps with pseudo-random inputs and step sizes; records the outputs after each step."""
    g = Lcg(seed)
    t = t0
    for k in range(steps):
        if vary:
            run.set("cx", -0.05 + 0.1 * g.u())
            run.set("cy", -0.02 + 0.04 * g.u())
            run.set("spin", -1.0 + 2.0 * g.u())
            run.set("v", -5.0 + 35.0 * g.u())
            run.set("FN", -1e4 + 1.6e5 * g.u())
            run.set("T_bulk", 60.0 * g.u())
            run.set("aux1", g.u())
        h = [1e-4, 5e-4, 1e-3, 2e-3][int(4 * g.u())]
        run.call(f"doStep {k}", run.s.doStep, t, h)
        t += h
        run.outputs(f"step {k}")
    return t


def init(run, params):
    run.call("setupExperiment", run.s.setupExperiment, None, 0.0)
    for n, x in params:
        run.set(n, x)
    run.call("enterInitializationMode", run.s.enterInitializationMode)
    run.get_all("init")
    run.call("exitInitializationMode", run.s.exitInitializationMode)
    run.get_all("after init")


SCENARIOS = {
    "default": [],
    "grid_dry_curvatures_continuous": [("nx", 12), ("ny", 6), ("preset", "dry"), ("geometry", 2),
                                       ("Rx", 0.5), ("Ry", 0.25), ("scheme", 1), ("threads", 2)],
    "semi_axes_effects": [("nx", 16), ("ny", 7), ("geometry", 1), ("a_ref", 6e-3), ("FN_ref", 9e4),
                          ("effect_transient", False), ("mu", 0.3)],
    "ignored_geometry_warning": [("nx", 10), ("ny", 5), ("Rx", 0.4), ("a_ref", 5e-3)],
    "fastsim": [("model", "fastsim"), ("nx", 10), ("ny", 5)],
    "polach": [("model", "polach")],
    "wet_sanded": [("preset", "wet_sanded"), ("nx", 10), ("ny", 5)],
}


def scenario(build, name, params):
    rec = []
    r = Run(build, rec, name)
    init(r, params)
    drive(r, 60, sum(map(ord, name)))
    r.call("terminate", r.s.terminate)
    r.get_all("terminated")
    r.call("reset", r.s.reset)
    r.free()
    return rec


def errors(build):
    rec = []
    r = Run(build, rec, "errors")
    r.call("doStep before init", r.s.doStep, 0.0, 1e-3)
    r.set("nx", 1)
    r.set("threads", 0)
    r.set("model", "nonsense")
    r.set("preset", "nonsense")
    r.set("columns", "x=aux9")
    r.set("Fx", 1.0)
    r.call("unknown vr", r.s.setReal, [9999], [1.0])
    r.call("wrong type", r.s.setInteger, [build.vr["cx"]], [1])
    init(r, [("nx", 10), ("ny", 5)])
    r.set("mu", 0.3)
    r.set("cx", float("nan"))
    r.set("cx", 2.0)
    r.set("FN", -5.0)
    r.call("doStep at wrong time", r.s.doStep, 1.0, 1e-3)
    r.call("doStep negative h", r.s.doStep, 0.0, -1.0)
    for fname, n in [("fmi2EnterEventMode", 0), ("fmi2SetTime", 0), ("fmi2NewDiscreteStates", 1),
                     ("fmi2GetDerivatives", 2), ("fmi2GetDirectionalDerivative", 6),
                     ("fmi2SetRealInputDerivatives", 4), ("fmi2GetRealOutputDerivatives", 4),
                     ("fmi2CancelStep", 0), ("fmi2EnterContinuousTimeMode", 0),
                     ("fmi2CompletedIntegratorStep", 3), ("fmi2SetContinuousStates", 2),
                     ("fmi2GetEventIndicators", 2), ("fmi2GetContinuousStates", 2),
                     ("fmi2GetNominalsOfContinuousStates", 2)]:
        if fname == "fmi2SetTime":
            f = getattr(r.s.dll, fname)
            f.restype, f.argtypes = ctypes.c_int, [ctypes.c_void_p, ctypes.c_double]
            rec.append((fname, f(r.s.component, 0.5)))
        else:
            r.raw(fname, *([None] * n))
    r.call("terminate", r.s.terminate)
    r.call("doStep after terminate", r.s.doStep, 0.0, 1e-3)
    r.set("cx", 0.01)
    r.get_all("terminated")
    r.free()
    return rec


def states(build, foreign=None):
    """FMU states: get/set, serialize; returns (records, serialized bytes at step 30). With
    `foreign` (bytes of the other build), a fresh instance continues from them."""
    rec = []
    r = Run(build, rec, "states")
    init(r, [("nx", 12), ("ny", 6), ("columns", "humidity=aux1")])
    t = drive(r, 30, 7)
    st = r.call("getFMUstate", r.s.getFMUstate)
    data = bytes(r.call("serializeFMUstate", r.s.serializeFMUstate, st))
    rec.append(("serialized", len(data), hashlib.sha256(data).hexdigest()))
    drive(r, 10, 8, t)
    r.call("setFMUstate", r.s.setFMUstate, st)
    drive(r, 10, 8, t)
    r.call("freeFMUstate", r.s.freeFMUstate, st)
    r.free()
    src = foreign if foreign is not None else data
    r2 = Run(build, rec, "restored")
    init(r2, [("nx", 12), ("ny", 6), ("columns", "humidity=aux1")])
    st2 = r2.call("deSerializeFMUstate", r2.s.deSerializeFMUstate, src)
    r2.call("setFMUstate", r2.s.setFMUstate, st2)
    r2.get_all("restored")
    drive(r2, 10, 8, t)
    again = bytes(r2.call("serializeFMUstate", r2.s.serializeFMUstate,
                          r2.call("getFMUstate", r2.s.getFMUstate)))
    rec.append(("re-serialized", len(again), hashlib.sha256(again).hexdigest()))
    r2.free()
    return rec, data


def main():
    a, b = Build(sys.argv[1]), Build(sys.argv[2])
    results = {}
    for label, fn in [(n, (lambda bb, n=n, p=p: scenario(bb, n, p))) for n, p in SCENARIOS.items()] + [
            ("errors", errors)]:
        results[label] = (fn(a), fn(b))
    sa, da = states(a)
    sb, db = states(b)
    results["states"] = (sa, sb)
    # serialized states of each build continue in the other
    results["states A->B"] = (states(a, da)[0], states(b, da)[0])
    results["states B->A"] = (states(a, db)[0], states(b, db)[0])
    total = diff = 0
    for label, (ra, rb) in results.items():
        n = max(len(ra), len(rb))
        d = [i for i in range(n) if i >= len(ra) or i >= len(rb) or ra[i] != rb[i]]
        total += n
        diff += len(d)
        print(f"{label}: {n} items, {len(d)} differ")
        for i in d[:5]:
            print("   A:", ra[i] if i < len(ra) else None)
            print("   B:", rb[i] if i < len(rb) else None)
    nreal = sum(1 for ra, _ in results.values() for x in ra if len(x) == 3 and isinstance(x[2], str)
                and len(x[2]) == 16)
    print(f"total: {total} recorded items ({nreal} Real values as bit patterns), {diff} differ")
    sys.exit(1 if diff else 0)


if __name__ == "__main__":
    main()
