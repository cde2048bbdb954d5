"""Runs the project's own programs and reads their CSV output.

* ``ecf`` (ecf-cli): steady curves, creepage steps, periodic creepage, steady fields and
  the fields during a step (``ecf step --field-at-ms``).
* ``python -m drivetrain_demo`` (drivetrain-demo): drive-train co-simulation with the FMU.

Every ECF/FASTSIM/Polach run is described by a configuration JSON (the format of
``ecf --config``, README "Models, effects and configurations"), written to a scratch
directory, so the exact configuration of every figure is on disk and in numbers.json.
"""
from __future__ import annotations

import csv
import hashlib
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
ECF = Path(os.environ.get("ECF_BIN", ROOT / "target" / "release" / "ecf"))
SCRATCH = Path(os.environ.get("ECF_GALLERY_SCRATCH", ROOT / "out" / "gallery-scratch"))

# Operating point of the seed's Tab. 4.1/4.2 (Vectron wheel).
VECTRON = {"a_mm": 7.63, "b_mm": 7.88, "fn_ref_kN": 110.0}


class RunError(RuntimeError):
    pass


def read_csv(text: str) -> dict[str, np.ndarray]:
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        raise RunError("empty CSV")
    head, body = rows[0], [r for r in rows[1:] if r]
    cols = list(zip(*body)) if body else [[] for _ in head]
    return {h: np.array([float(x) for x in c]) for h, c in zip(head, cols)}


def config(preset: str | None = None, model: str | None = None, params: dict | None = None,
           effects: list[str] | None = None, grid: tuple[int, int] | None = None,
           geometry: dict | None = None) -> dict:
    """A configuration dict in the format of `ecf --config` (keys left out when unused)."""
    c: dict = {}
    if model:
        c["model"] = model
    if preset:
        c["preset"] = preset
    if effects:
        c["effects"] = list(effects)
    if params:
        c["params"] = {k: ("inf" if v == float("inf") else v) for k, v in params.items()}
    if grid:
        c["grid"] = {"nx": int(grid[0]), "ny": int(grid[1])}
    if geometry is not None:
        c["geometry"] = dict(geometry)
    elif (model or "") != "polach" and preset not in ("twin_disc", "polach"):
        c["geometry"] = dict(VECTRON)
    return c


def _config_file(cfg: dict) -> Path:
    text = json.dumps(cfg, sort_keys=True)
    SCRATCH.mkdir(parents=True, exist_ok=True)
    p = SCRATCH / f"cfg_{hashlib.sha1(text.encode()).hexdigest()[:12]}.json"
    if not p.exists():
        tmp = p.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(text)
        tmp.replace(p)
    return p


def _run(argv: list[str]) -> str:
    r = subprocess.run([str(a) for a in argv], capture_output=True, text=True)
    if r.returncode != 0:
        raise RunError(f"{' '.join(map(str, argv))}\nexit {r.returncode}: {r.stderr.strip()}")
    return r.stdout


def _common(cfg: dict, v: float, fn_kN: float) -> list[str]:
    return ["--config", str(_config_file(cfg)), "--v-mps", repr(float(v)), "--fn-kN", repr(float(fn_kN))]


def curve(cfg: dict, cx, v: float = 20.0, fn_kN: float = 110.0) -> dict[str, np.ndarray]:
    """Steady characteristic: `ecf curve` at the creepages `cx` (dimensionless)."""
    cxs = ",".join(repr(float(c)) for c in cx)
    return read_csv(_run([ECF, "curve", *_common(cfg, v, fn_kN), "--cx", cxs]))


def step(cfg: dict, cx_from: float, cx_to: float, v: float = 5.0, fn_kN: float = 110.0,
         duration_ms: float = 5.0, dt_ms: float = 0.01) -> dict[str, np.ndarray]:
    """Creepage step (Eq. 4.36): `ecf step`."""
    return read_csv(_run([ECF, "step", *_common(cfg, v, fn_kN), "--cx-from", repr(cx_from),
                          "--cx-to", repr(cx_to), "--duration-ms", repr(duration_ms),
                          "--dt-ms", repr(dt_ms)]))


def sine(cfg: dict, cm: float, ca: float, freq_hz: float, v: float = 5.0, fn_kN: float = 110.0,
         cycles: int = 3, steps_per_cycle: int = 200) -> dict[str, np.ndarray]:
    """Periodic creepage (Eq. 4.37): `ecf sine`."""
    return read_csv(_run([ECF, "sine", *_common(cfg, v, fn_kN), "--cm", repr(cm), "--ca", repr(ca),
                          "--freq-hz", repr(freq_hz), "--cycles", str(cycles),
                          "--steps-per-cycle", str(steps_per_cycle)]))


def field(cfg: dict, cx: float, v: float = 20.0, fn_kN: float = 110.0) -> dict[str, np.ndarray]:
    """Steady fields along y = 0: `ecf field`."""
    return read_csv(_run([ECF, "field", *_common(cfg, v, fn_kN), "--cx", repr(cx)]))


def step_fields(cfg: dict, cx_from: float, cx_to: float, at_ms, v: float = 5.0, fn_kN: float = 110.0,
                dt_ms: float = 0.01) -> dict[float, dict[str, np.ndarray]]:
    """Fields along y = 0 at the instants `at_ms` after a creepage step: `ecf step --field-at-ms`."""
    text = _run([ECF, "step", *_common(cfg, v, fn_kN), "--cx-from", repr(cx_from), "--cx-to", repr(cx_to),
                 "--dt-ms", repr(dt_ms), "--field-at-ms", ",".join(repr(float(t)) for t in at_ms)])
    d = read_csv(text)
    out = {}
    for t in at_ms:
        m = np.isclose(d["t_ms"], float(t))
        out[float(t)] = {k: v_[m] for k, v_ in d.items()}
    return out


def drivetrain(scenario: str, model: str, outdir: Path, args: list[str]) -> dict:
    """Runs `python -m drivetrain_demo SCENARIO --model MODEL --out OUTDIR --json ARGS`;
    returns its JSON summary and the path of its time-series CSV."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "drivetrain-demo") + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    outdir.mkdir(parents=True, exist_ok=True)
    argv = [sys.executable, "-m", "drivetrain_demo", scenario, "--model", model, "--out", str(outdir),
            "--json", "--quiet", *args]
    r = subprocess.run(argv, capture_output=True, text=True, env=env, cwd=ROOT)
    if r.returncode != 0:
        raise RunError(f"{' '.join(argv)}\nexit {r.returncode}: {r.stderr.strip()[-2000:]}")
    s = json.loads(r.stdout)
    if model in s and isinstance(s[model], dict):
        s = s[model]
    return s


def git_describe() -> str:
    try:
        r = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT)
        return r.stdout.strip()
    except OSError:
        return "unknown"
