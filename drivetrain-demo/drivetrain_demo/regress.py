"""Frequency regression for users' own CI: baselines written by `--save-baseline FILE`, re-run and
compared by `python -m drivetrain_demo regress BASELINE.json [--tolerance-hz 0.5]`.

A baseline is self-contained: every run's options and the full resolved drive-train parameter set
(so a changed parameter file shows up as a regression, not as a silently different baseline), the
expected results and the FMU identity it was made with. Compared per run:
  * sustained_oscillation (simulated) and predicted_unstable (linear analysis): must be equal;
  * dominant_frequency_hz (when the baseline oscillates) or transient_frequency_hz (when it decays),
    and predicted_frequency_hz: |difference| <= tolerance_hz;
  * oscillation_amplitude (p-p of c_x,L, when the baseline oscillates): relative difference
    <= tolerance_amplitude.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

from . import __version__, api, contact, io_util
from .errors import ConfigError

FORMAT = "ecf-drivetrain-baseline/1"
EXPECTED = ("dominant_frequency_hz", "transient_frequency_hz", "predicted_frequency_hz", "oscillation_amplitude",
            "sustained_oscillation", "predicted_unstable", "predicted_damping_ratio")


def entry(cfg, p, summary) -> dict:
    """Baseline entry of one run (cfg: scenarios.RunConfig, p: Params actually used, summary: its JSON summary)."""
    params = {**dataclasses.asdict(p.drivetrain), **dataclasses.asdict(p.controller), **dataclasses.asdict(p.contact)}
    run = {"scenario": cfg.scenario, "contact": cfg.model, "preset": cfg.preset, "v_mps": cfg.v,
           "t_end_s": summary["t_end_s"], "h_ms": cfg.h * 1e3, "grid": list(cfg.grid) if cfg.grid else None,
           "transient": cfg.transient, "cx": cfg.c_target, "fmu_params": dict(cfg.fmu_params), "params": params}
    if cfg.scenario == "sine":
        run["sine"] = [cfg.sine["cm"], cfg.sine["ca"], cfg.sine["f0"]]
    return {"name": cfg.tag, "run": run, "expected": {k: summary.get(k) for k in EXPECTED},
            "provenance": summary.get("provenance")}


def save(path, entries: list):
    """Writes a baseline file (atomically)."""
    io_util.write_json(path, {"format": FORMAT, "project_version": __version__, "runs": entries})
    return Path(path)


def load(path) -> dict:
    path = Path(path)
    try:
        b = json.loads(path.read_text())
    except FileNotFoundError:
        raise ConfigError(f"baseline {path} not found (write one with --save-baseline {path})") from None
    except json.JSONDecodeError as e:
        raise ConfigError(f"baseline {path}: not JSON ({e})") from None
    if not isinstance(b, dict) or b.get("format") != FORMAT or not isinstance(b.get("runs"), list) or not b["runs"]:
        raise ConfigError(f"baseline {path}: expected a file written by --save-baseline (format {FORMAT!r} "
                          "with a non-empty list `runs`)")
    for i, e in enumerate(b["runs"]):
        if not isinstance(e, dict) or not {"run", "expected"} <= set(e):
            raise ConfigError(f"baseline {path}: runs[{i}] needs `run` and `expected`")
    return b


def rerun(e: dict, fmu=None, progress=False) -> dict:
    """Runs a baseline entry again; returns the new summary."""
    r = e["run"]
    try:
        res = api.simulate(r["scenario"], r["contact"], overrides=r["params"], preset=r.get("preset"),
                           v_mps=r["v_mps"], t_end_s=r["t_end_s"], h_ms=r["h_ms"],
                           grid=tuple(r["grid"]) if r.get("grid") else None, fmu=fmu,
                           fmu_params=r.get("fmu_params") or {}, transient=r.get("transient", True), cx=r.get("cx"),
                           sine=r.get("sine"), progress=progress)
    except KeyError as k:
        raise ConfigError(f"baseline entry {e.get('name')}: `run` lacks {k}") from None
    return res.summary


def _f(x):
    return float("nan") if x is None else float(x)


def compare(e: dict, new: dict, tolerance_hz=0.5, tolerance_amplitude=0.1) -> list:
    """List of (quantity, baseline, now, verdict text, ok) for one entry."""
    exp = e["expected"]
    out = []
    for k in ("sustained_oscillation", "predicted_unstable"):
        if exp.get(k) is not None:
            out.append((k, exp[k], new.get(k), "equal", exp[k] == new.get(k)))
    fkeys = ["predicted_frequency_hz"]
    if exp.get("sustained_oscillation"):
        fkeys.insert(0, "dominant_frequency_hz")
    elif exp.get("transient_frequency_hz") is not None:
        fkeys.insert(0, "transient_frequency_hz")
    for k in fkeys:
        a, b = _f(exp.get(k)), _f(new.get(k))
        if math.isnan(a) and math.isnan(b):
            continue
        d = b - a
        out.append((k, a, b, f"diff {d:+.3f} Hz (tolerance {tolerance_hz:g})", abs(d) <= tolerance_hz))
    if exp.get("sustained_oscillation"):
        a, b = _f(exp.get("oscillation_amplitude")), _f(new.get("oscillation_amplitude"))
        rel = (b - a) / a if a else float("inf")
        out.append(("oscillation_amplitude", a, b, f"diff {100 * rel:+.1f} % (tolerance {100 * tolerance_amplitude:g} %)",
                    abs(rel) <= tolerance_amplitude))
    return out


def regress(path, tolerance_hz=0.5, tolerance_amplitude=0.1, fmu=None, progress=False):
    """Re-runs every entry of a baseline; returns (all_ok, report text)."""
    if not tolerance_hz >= 0:
        raise ConfigError(f"--tolerance-hz {tolerance_hz}: must be >= 0")
    if not tolerance_amplitude >= 0:
        raise ConfigError(f"--tolerance-amplitude {tolerance_amplitude}: must be >= 0")
    b = load(path)
    lines = [f"regress {path}: {len(b['runs'])} run(s), frequency tolerance {tolerance_hz:g} Hz, "
             f"amplitude tolerance {100 * tolerance_amplitude:g} %"]
    fmu_now = contact.find_fmu(fmu)
    bad = 0
    for e in b["runs"]:
        new = rerun(e, fmu=fmu, progress=progress)
        rows = compare(e, new, tolerance_hz, tolerance_amplitude)
        moved = [r for r in rows if not r[4]]
        bad += bool(moved)
        lines.append(f"{'FAIL' if moved else 'ok  '} {e.get('name', e['run']['scenario'])}")
        for q, a, n, txt, ok in rows:
            fa = f"{a:.4g}" if isinstance(a, float) else str(a)
            fn = f"{n:.4g}" if isinstance(n, float) else str(n)
            lines.append(f"     {'  ' if ok else '!!'} {q:24s} baseline {fa:>10s}  now {fn:>10s}  {txt}")
        old_sha = ((e.get("provenance") or {}).get("fmu_identity") or {}).get("sha256")
        if moved and old_sha and fmu_now and contact.fmu_identity(fmu_now)["sha256"] != old_sha:
            lines.append(f"     note: the baseline was made with FMU sha256 {old_sha[:12]}, now "
                         f"{contact.fmu_identity(fmu_now)['sha256'][:12]}")
    lines.append(f"{'REGRESSION' if bad else 'OK'}: {bad} of {len(b['runs'])} run(s) moved")
    return bad == 0, "\n".join(lines)
