"""Contact of one wheel: the ECF contact FMU through fmpy's FMU2Slave, or a steady-curve stand-in.

Both offer the same small interface used by the co-simulation:
    c = make_contact(kind, model=..., v=..., F_N=..., ...)
    out = c.step(t, h, cx)   # inputs held over [t, t+h], returns (Fx [N], f [-]) at t+h
    c.extra()                # dict of the other outputs (T_max, P_fric, fractions)
    c.steady_f(cx_array)     # steady characteristic f(cx) at the same operating point
    c.close()
FMU variables used (names as in the FMU's modelDescription): inputs cx, cy, spin, v, FN,
T_bulk; outputs Fx, f, T_max, P_fric, frac_*; parameters model, preset, transient, grid.
The hot path calls fmpy's public low-level functions fmi2SetReal/fmi2DoStep/fmi2GetReal of
FMU2Slave (status checked by fmpy) with pre-built ctypes arrays (the convenience wrappers
setReal/getReal allocate arrays on every call).
"""

from __future__ import annotations

import ctypes
import functools
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from .errors import ConfigError, DrivetrainError, FMUError, FMUNotFoundError

REPO = Path(__file__).resolve().parents[2]
FMU_DEFAULT = REPO / "dist" / "ecf_contact.fmu"
ECF_CLI = REPO / "target" / "release" / "ecf"
EXTRA_OUTPUTS = ("T_max", "T_mean", "P_fric", "frac_elastic", "frac_plastic", "frac_sliding")


FMU_ENV_VARS = ("ECF_FMU_PATH", "ECF_CONTACT_FMU")


def find_fmu(path: str | os.PathLike | None = None) -> Path | None:
    """The contact FMU: the explicit `path`, else $ECF_FMU_PATH, else $ECF_CONTACT_FMU, else
    dist/ecf_contact.fmu of the source tree; None when none of them is set/present.

    Raises FMUNotFoundError when an explicit path or a set environment variable names a file
    that does not exist (a typo should not silently fall back to another FMU)."""
    if path:
        if not Path(path).is_file():
            raise FMUNotFoundError(f"FMU {path} not found")
        return Path(path)
    for var in FMU_ENV_VARS:
        cand = os.environ.get(var)
        if cand:
            if not Path(cand).is_file():
                raise FMUNotFoundError(f"${var} = {cand}: file not found")
            return Path(cand)
    return FMU_DEFAULT if FMU_DEFAULT.is_file() else None


@functools.lru_cache(maxsize=16)
def _fmu_identity(path: str, mtime: float, size: int) -> dict:
    from fmpy import read_model_description
    md = read_model_description(path)
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    # the .fmu's own hash changes with the zip's time stamps on every rebuild; the content hash
    # (names and bytes of the members) changes only when the FMU does
    import zipfile
    c = hashlib.sha256()
    with zipfile.ZipFile(path) as z:
        for n in sorted(z.namelist()):
            c.update(n.encode() + b"\0" + hashlib.sha256(z.read(n)).digest())
    return {"path": str(path), "sha256": h.hexdigest(), "content_sha256": c.hexdigest(), "model_name": md.modelName,
            "guid": md.guid, "version": md.version, "generation_tool": md.generationTool}


def fmu_identity(path) -> dict:
    """What identifies the FMU a result was made with: path, sha256 of the .fmu file, content_sha256
    (of its members' names and bytes: equal for identical rebuilds), modelName, guid, version and
    generationTool from its modelDescription.xml."""
    st = os.stat(path)
    return dict(_fmu_identity(str(path), st.st_mtime, st.st_size))


class CurveContact:
    """Stand-in: quasi-steady force f(cx) from the Python package ecf (`ecf.curve`) when it is
    installed, else from the `ecf curve` CLI: the same numbers (no contact dynamics)."""

    kind = "curve"

    def __init__(self, model="ecf", v=5.0, F_N=110e3, T_bulk=20.0, preset=None, grid=None, **_):
        self.model, self.v, self.F_N = model, v, F_N
        cx = np.concatenate([np.linspace(0, 0.02, 41), np.linspace(0.0205, 0.8, 400)])
        self._cx = cx
        self._f = self._curve(cx, model, v, F_N, T_bulk, preset, grid)
        self.f = 0.0

    @staticmethod
    def _curve(cx, model, v, F_N, T_bulk, preset, grid):
        # the creepages as the CLI receives them (6 significant digits): the same f either way
        cx = np.array([float(f"{c:.6g}") for c in cx])
        try:
            import ecf
        except ImportError:
            ecf = None
        if ecf is not None and hasattr(ecf, "curve"):
            t = ecf.curve(cx=cx, model=model, v_mps=float(v), fn_kN=float(F_N / 1e3), t_bulk_C=float(T_bulk),
                          preset=preset or None, grid=f"{grid[0]}x{grid[1]}" if grid else None)
            # rounded to the 8 decimals of the CLI's CSV: the demo's results do not depend on the path
            return np.array([float(f"{x:.8f}") for x in t["f"]])
        if not ECF_CLI.is_file():
            raise DrivetrainError(f"{ECF_CLI} missing: run `cargo build --release -p ecf-cli`")
        args = [str(ECF_CLI), "curve", "--model", model, "--v-mps", str(v), "--fn-kn", str(F_N / 1e3),
                "--t-bulk-c", str(T_bulk), "--cx", ",".join(f"{c:.6g}" for c in cx)]
        if preset:
            args += ["--preset", preset]
        if grid:
            args += ["--grid", f"{grid[0]}x{grid[1]}"]
        out = subprocess.run(args, check=True, capture_output=True, text=True).stdout.splitlines()
        return np.array([float(l.split(",")[1]) for l in out[1:]])

    def _interp(self, c):
        c = np.asarray(c, float)
        return np.sign(c) * np.interp(np.abs(c), self._cx, self._f)

    def step(self, t, h, cx):
        self.f = float(self._interp(cx))
        return self.f * self.F_N, self.f

    def extra(self):
        return {}

    def steady_f(self, cx):
        return self._interp(cx)

    def close(self):
        pass


class FMUContact:
    """One instance of the contact FMU (FMI 2.0 co-simulation) for one wheel."""

    kind = "fmu"
    _unzipped: dict = {}

    def __init__(self, fmu_path, model="ecf", v=5.0, F_N=110e3, T_bulk=20.0, preset=None, grid=None,
                 transient=True, params=None, name="contact", start_time=0.0):
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave

        fmu_path = str(fmu_path)
        key = (fmu_path, os.path.getmtime(fmu_path))
        if key not in FMUContact._unzipped:
            md = read_model_description(fmu_path)
            FMUContact._unzipped[key] = (extract(fmu_path), md)
        unzipdir, md = FMUContact._unzipped[key]
        self.md = md
        self.vars = {sv.name: sv for sv in md.modelVariables}
        self.F_N, self.v = F_N, v
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        self.name = name
        self.log_counts = {}
        self.log_lines = []
        self._callbacks = self._make_callbacks()
        from fmpy.fmi1 import FMICallException
        self._instantiated = False
        try:
            self.fmu.instantiate(callbacks=self._callbacks)
            self._instantiated = True
            self.fmu.setupExperiment(startTime=start_time)
            self._set_parameters(model, preset, grid, transient, params or {})
            self.fmu.enterInitializationMode()
            self._set_real({"cx": 0.0, "cy": 0.0, "spin": 0.0, "v": v, "FN": F_N, "T_bulk": T_bulk})
            self.fmu.exitInitializationMode()
        except (FMICallException, Exception) as e:
            if self._instantiated:
                try:
                    self.fmu.freeInstance()
                except Exception:  # noqa: BLE001 - the original error matters
                    pass
            if isinstance(e, DrivetrainError):
                raise
            log = "; ".join(self.log_lines[-3:]) or str(e)
            raise FMUError(f"contact FMU {Path(fmu_path).name} ({name}, model {model!r}, preset {preset!r}) "
                           f"refused the set-up: {log}") from None
        # hot path: fmpy's public FMI functions (status checked by fmpy) with fixed arrays
        self._c = self.fmu.component
        self._setReal, self._getReal, self._doStep = self.fmu.fmi2SetReal, self.fmu.fmi2GetReal, self.fmu.fmi2DoStep
        self._vr_in = (ctypes.c_uint * 1)(self.vr("cx"))
        self._val_in = (ctypes.c_double * 1)()
        out_names = ["Fx", "f"] + [n for n in EXTRA_OUTPUTS if n in self.vars]
        self._out_names = out_names
        self._vr_out = (ctypes.c_uint * len(out_names))(*[self.vr(n) for n in out_names])
        self._val_out = (ctypes.c_double * len(out_names))()
        self.f = 0.0

    MAX_LOG_LINES = 3

    def _make_callbacks(self):
        """FMU logger that prints the first MAX_LOG_LINES messages per status and counts the rest."""
        from fmpy.fmi2 import (fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                               fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
        from fmpy import calloc, free

        status_names = {0: "OK", 1: "WARNING", 2: "DISCARD", 3: "ERROR", 4: "FATAL", 5: "PENDING"}

        def logger(env, instance, status, category, message):
            key = status_names.get(status, str(status))
            if status >= 2 and len(self.log_lines) < 20:
                self.log_lines.append(message.decode("utf-8", "replace") if message else "")
            n = self.log_counts.get(key, 0) + 1
            self.log_counts[key] = n
            if n <= self.MAX_LOG_LINES:
                msg = message.decode("utf-8", "replace") if message else ""
                print(f"[{self.name} {key}] {msg}", file=sys.stderr, flush=True)
            elif n == self.MAX_LOG_LINES + 1:
                print(f"[{self.name} {key}] further messages counted, not printed", file=sys.stderr, flush=True)

        cb = fmi2CallbackFunctions()
        cb.logger = fmi2CallbackLoggerTYPE(logger)
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self._logger_ref = cb.logger
        return cb

    def vr(self, name):
        try:
            return self.vars[name].valueReference
        except KeyError:
            raise FMUError(f"FMU has no variable '{name}' (has: {', '.join(sorted(self.vars))})") from None

    def _set_real(self, d):
        self.fmu.setReal([self.vr(k) for k in d], list(d.values()))

    def _set_parameters(self, model, preset, grid, transient, params):
        fmu = self.fmu
        if "model" in self.vars:
            fmu.setString([self.vr("model")], [model])
        if preset and "preset" in self.vars:
            fmu.setString([self.vr("preset")], [preset])
        tname = next((n for n in ("transient", "effect_transient") if n in self.vars), None)
        if tname:
            fmu.setBoolean([self.vr(tname)], [bool(transient)])
        elif not transient:
            raise FMUError("FMU has no `transient` parameter; cannot switch the transient model off")
        if grid:
            names = grid_variable_names(self.vars)
            if not names:
                raise FMUError("FMU exposes no grid-size parameter; drop --grid")
            fmu.setInteger([self.vr(names[0]), self.vr(names[1])], [int(grid[0]), int(grid[1])])
        for k, val in params.items():
            sv = self.vars.get(k)
            if sv is None or sv.causality != "parameter":
                names = sorted(n for n, x in self.vars.items() if x.causality == "parameter")
                raise ConfigError(f"--fmu-param {k}: the FMU has no parameter '{k}' (parameters: {', '.join(names)})")
            try:
                if sv.type == "Real":
                    fmu.setReal([sv.valueReference], [float(val)])
                elif sv.type == "Integer":
                    fmu.setInteger([sv.valueReference], [int(val)])
                elif sv.type == "Boolean":
                    fmu.setBoolean([sv.valueReference], [_to_bool(k, val)])
                else:
                    fmu.setString([sv.valueReference], [str(val)])
            except ValueError:
                raise ConfigError(f"--fmu-param {k}={val}: expected a {sv.type} value") from None

    def step(self, t, h, cx):
        self._val_in[0] = cx
        try:
            self._setReal(self._c, self._vr_in, 1, self._val_in)
            self._doStep(self._c, t, h, 1)
            self._getReal(self._c, self._vr_out, len(self._out_names), self._val_out)
        except Exception as e:  # fmpy's FMICallException (status > fmi2Warning)
            log = "; ".join(self.log_lines[-3:])
            raise FMUError(f"contact FMU ({self.name}) failed at t = {t:.6g} s, cx = {cx:.6g}: {e}"
                           + (f" ({log})" if log else "")) from None
        self.f = self._val_out[1]
        return self._val_out[0], self._val_out[1]

    def extra(self):
        return {n: self._val_out[i] for i, n in enumerate(self._out_names) if i >= 2}

    def close(self):
        try:
            self.fmu.terminate()
        finally:
            self.fmu.freeInstance()
        extra = {k: n - self.MAX_LOG_LINES for k, n in self.log_counts.items() if n > self.MAX_LOG_LINES}
        if extra:
            print(f"[{self.name}] FMU messages not printed: {extra}", file=sys.stderr, flush=True)


def grid_variable_names(vars_):
    """(nx, ny) integer parameter names of the FMU's grid size, or None."""
    ints = [n for n, sv in vars_.items() if sv.type == "Integer"]
    if "nx" in ints and "ny" in ints:
        return "nx", "ny"
    nx = [n for n in ints if "nx" in n.lower()]
    ny = [n for n in ints if "ny" in n.lower()]
    return (nx[0], ny[0]) if nx and ny else None


def steady_curve_fmu(fmu_path, cx, model="ecf", v=5.0, F_N=110e3, T_bulk=20.0, preset=None, grid=None,
                     params=None):
    """Steady f(cx) from the FMU: one instance with transient off, one long step per creepage."""
    c = FMUContact(fmu_path, model=model, v=v, F_N=F_N, T_bulk=T_bulk, preset=preset, grid=grid,
                   transient=False, params=params, name="steady")
    try:
        out = []
        t = 0.0
        for x in np.atleast_1d(cx):
            _, f = c.step(t, 1e-3, float(x))
            t += 1e-3
            out.append(f)
        return np.array(out)
    finally:
        c.close()


def make_contact(kind, fmu_path=None, **kw):
    if kind == "curve":
        return CurveContact(**kw)
    if kind == "fmu":
        return FMUContact(fmu_path, **kw)
    raise ConfigError(f"--contact {kind}: unknown (accepted: fmu, curve)")


def _to_bool(name, val):
    if isinstance(val, bool):
        return val
    t = str(val).strip().lower()
    if t in ("1", "true", "yes", "on"):
        return True
    if t in ("0", "false", "no", "off"):
        return False
    raise ConfigError(f"--fmu-param {name}={val}: expected a Boolean (true/false/1/0)")
