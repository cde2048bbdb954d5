"""Parameter sweeps on Dask: python -m drivetrain_demo sweep SWEEP.toml --out DIR.

The sweep file (TOML; example: drivetrain-demo/examples/sweep.toml, format in docs/drivetrain.md)
lists axes; every combination is one case, every case one Dask task. By default an in-process
LocalCluster with one single-threaded worker process per core runs them; `--scheduler
tcp://HOST:8786` uses an existing dask.distributed cluster (the FMU file is sent to the workers,
so they need no shared file system, but they need this package installed); `--scheduler serial`
runs the cases one after the other in this process (no Dask).

Output in DIR:
  cases/<case_id>.json   one record per finished case (inputs, results or error), written
                         atomically when the case finishes; a re-run skips cases recorded "ok"
                         (resume) and runs failed ones again;
  traces/<case_id>_<scenario>_<model>_<condition>_v<v>.csv   time series (every --save-every-th row);
  sweep.csv, sweep.parquet (when pyarrow is installed)   the tidy table, one row per case;
  stability_map.png      amplitude over x (speed) and y (condition) per panel, with the linear
                         analysis's stability boundary.
The case id is a hash of the case's inputs, the FMU's content hash and the project version: a
different FMU or version never resumes from old results (an identical rebuild does).
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
import sys
import tempfile
import time
import tomllib
import traceback
from pathlib import Path

import numpy as np

from . import __version__, contact, io_util, scenarios
from .errors import ConfigError, DrivetrainError, FMUNotFoundError
from .params import override_names

TOP_KEYS = {"scenario", "analysis", "t_end_s", "h_ms", "grid", "cx", "save_every", "contact_threads", "transient",
            "axes", "set", "fmu_param", "map", "description"}
AXIS_KEYS = ("model", "preset", "FN_kN", "v_mps", "cx")
ANALYSES = ("simulate", "modal")

# the tidy table: column -> meaning (with unit); docs/drivetrain.md repeats this list
COLUMNS = {
    "case_id": "hash of the case's inputs, FMU content hash and project version",
    "status": "ok | failed",
    "error": "exception type and message of a failed case",
    "analysis": "simulate (co-simulation + linear analysis) | modal (linear analysis only)",
    "scenario": "step | ramp | sine",
    "model": "contact model: ecf | fastsim | polach",
    "preset": "contact condition (preset), default = the model's own",
    "v_mps": "vehicle speed, m/s",
    "FN_kN": "wheel normal load, kN",
    "cx_target": "desired creepage of the step / operating point of the modal analysis, dimensionless",
    "t_end_s": "simulated time, s",
    "h_ms": "communication step, ms",
    "grid": "bristle grid NXxNY of the FMU",
    "fastsim_mu": "friction coefficient FASTSIM ran with (condition-matched or given), - ; empty for ECF",
    "dominant_frequency_hz": "dominant frequency of c_x,L over the settled window, Hz",
    "predicted_frequency_hz": "least damped torsional mode of the linear analysis, Hz",
    "predicted_damping_ratio": "its damping ratio (< 0: unstable), dimensionless",
    "predicted_unstable": "linear analysis: an eigenvalue with positive real part",
    "oscillation_pp_cx_L": "peak-to-peak of c_x,L over the last 0.5 s, dimensionless (0.28 = 28 % creepage)",
    "sustained_oscillation": "simulation: oscillation_pp_cx_L above 0.1 % (step), envelope above 1 % (ramp)",
    "stable": "simulate: not sustained_oscillation; modal: not predicted_unstable",
    "real_time_factor": "wall-clock time of the co-simulation loop / simulated time",
    "wall_s": "wall-clock time of the whole case on its worker, s",
    "trace_file": "time-series CSV, relative to the output directory",
    "summary_file": "case record (inputs, full JSON summary), relative to the output directory",
    "fmu_content_sha256": "sha256 of the contact FMU's content (members' names and bytes)",
    "project_version": "drivetrain_demo version",
}
# columns that differ between identical runs (timing): left out when tables are compared
TIMING_COLUMNS = ("real_time_factor", "wall_s")


def _err(path, msg):
    return ConfigError(f"sweep file {path}: {msg}")


def _as_list(path, key, v):
    vals = v if isinstance(v, list) else [v]
    if not vals:
        raise _err(path, f"{key}: empty list")
    return vals


def load_sweep(path) -> dict:
    """Reads and checks a sweep file; returns the normalized spec. Raises ConfigError naming the
    file, the key and the accepted values."""
    path = Path(path)
    try:
        raw = tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise ConfigError(f"sweep file {path} not found") from None
    except IsADirectoryError:
        raise ConfigError(f"sweep file {path} is a directory") from None
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"sweep file {path}: {e}") from None
    unknown = set(raw) - TOP_KEYS
    if unknown:
        raise _err(path, f"unknown key(s) {', '.join(sorted(unknown))} (accepted: {', '.join(sorted(TOP_KEYS))})")
    spec = {"file": str(path), "description": str(raw.get("description", ""))}
    spec["scenario"] = raw.get("scenario", "step")
    if spec["scenario"] not in ("step", "ramp"):
        raise _err(path, f"scenario = {spec['scenario']!r}: accepted step, ramp")
    an = raw.get("analysis", ["simulate"])
    an = [an] if isinstance(an, str) else list(an)
    if an == ["both"]:
        an = list(ANALYSES)
    bad = [a for a in an if a not in ANALYSES]
    if bad or not an:
        raise _err(path, f"analysis = {raw.get('analysis')!r}: accepted \"simulate\", \"modal\", \"both\" or a list of them")
    spec["analysis"] = an
    for key, default, kind in (("t_end_s", None, float), ("h_ms", 0.25, float), ("cx", scenarios.STEP_TARGET, float),
                               ("save_every", 1, int), ("contact_threads", False, bool), ("transient", True, bool),
                               ("grid", scenarios.DEFAULT_GRID_TEXT, str)):
        v = raw.get(key, default)
        if v is not None and not isinstance(v, kind) and not (kind is float and isinstance(v, int)):
            raise _err(path, f"{key} = {v!r}: expected a {kind.__name__}")
        spec[key] = kind(v) if v is not None else None
    if spec["save_every"] < 1:
        raise _err(path, f"save_every = {spec['save_every']}: must be >= 1")
    axes = raw.get("axes", {})
    if not isinstance(axes, dict):
        raise _err(path, "[axes] must be a table")
    names = override_names()
    known_set = set(sum(names.values(), []))
    ax = {}
    for k, v in axes.items():
        if k in ("set", "fmu_param"):
            if not isinstance(v, dict):
                raise _err(path, f"[axes.{k}] must be a table")
            for n, vals in v.items():
                if k == "set" and n not in known_set:
                    raise _err(path, f"[axes.set] {n}: unknown (accepted: {', '.join(sorted(known_set))})")
                ax[f"{k}.{n}"] = _as_list(path, f"axes.{k}.{n}", vals)
        elif k in AXIS_KEYS:
            ax[k] = _as_list(path, f"axes.{k}", v)
        else:
            raise _err(path, f"[axes] {k}: unknown axis (accepted: {', '.join(AXIS_KEYS)}, set.NAME, fmu_param.NAME)")
    for m in ax.get("model", []):
        if m not in scenarios.MODELS:
            raise _err(path, f"axes.model {m!r}: accepted {', '.join(scenarios.MODELS)}")
    for pr in ax.get("preset", []):
        if pr != "default" and pr not in scenarios.CONDITIONS:
            raise _err(path, f"axes.preset {pr!r}: accepted default, {', '.join(scenarios.CONDITIONS)}")
    for k in ("v_mps", "FN_kN", "cx"):
        for x in ax.get(k, []):
            if not isinstance(x, (int, float)) or not x > 0 or not math.isfinite(x):
                raise _err(path, f"axes.{k} value {x!r}: expected a number > 0")
    spec["axes"] = ax
    for sec in ("set", "fmu_param"):
        fixed = raw.get(sec, {})
        if not isinstance(fixed, dict):
            raise _err(path, f"[{sec}] must be a table of NAME = VALUE")
        if sec == "set":
            for n in fixed:
                if n not in known_set:
                    raise _err(path, f"[set] {n}: unknown (accepted: {', '.join(sorted(known_set))})")
        spec[sec] = dict(fixed)
    mp = raw.get("map", {})
    spec["map"] = {"x": mp.get("x", "v_mps"), "y": mp.get("y", "preset")}
    return spec


def expand(spec) -> list:
    """The cases of a sweep spec, in a fixed order: analysis x model x preset x FN_kN x v_mps x cx x set.* x fmu_param.*"""
    ax = spec["axes"]
    order = [k for k in AXIS_KEYS if k in ax] + sorted(k for k in ax if "." in k)
    cases = []
    for an in spec["analysis"]:
        for combo in itertools.product(*[ax[k] for k in order]):
            d = dict(zip(order, combo))
            preset = d.get("preset", "default")
            case = {
                "analysis": an,
                "scenario": spec["scenario"] if an == "simulate" else "modal",
                "model": d.get("model", "ecf"),
                "preset": preset,
                "v_mps": float(d.get("v_mps", 5.0)),
                "FN_kN": float(d["FN_kN"]) if "FN_kN" in d else None,
                "cx_target": float(d.get("cx", spec["cx"])),
                "t_end_s": spec["t_end_s"] if an == "simulate" else None,
                "h_ms": spec["h_ms"],
                "grid": spec["grid"],
                "transient": spec["transient"],
                "contact_threads": spec["contact_threads"],
                "set": {**spec["set"], **{k[4:]: v for k, v in d.items() if k.startswith("set.")}},
                "fmu_param": {**spec["fmu_param"], **{k[10:]: v for k, v in d.items() if k.startswith("fmu_param.")}},
            }
            cases.append(case)
    return cases


def case_id(case, fmu_sha) -> str:
    key = json.dumps({"case": case, "fmu": fmu_sha, "version": __version__}, sort_keys=True, default=str)
    return hashlib.sha256(key.encode()).hexdigest()[:12]


_FMU_CACHE = {}


def _fmu_on_worker(fmu):
    """The FMU path on this worker: a path as given, or (bytes, sha) written once to a temp file."""
    if isinstance(fmu, (str, os.PathLike)):
        return str(fmu)
    data, sha = fmu
    if sha not in _FMU_CACHE:
        p = Path(tempfile.gettempdir()) / f"ecf_contact_{sha[:16]}.fmu"
        if not p.is_file() or hashlib.sha256(p.read_bytes()).hexdigest() != sha:
            with io_util.atomic_path(p) as tmp:
                Path(tmp).write_bytes(data)
        _FMU_CACHE[sha] = str(p)
    return _FMU_CACHE[sha]


def run_case(case: dict, fmu, save_every: int = 1) -> dict:
    """Runs one case (on a Dask worker or in-process). Never raises: a failure is returned as a
    record with status "failed" and the error. Returns the record with `_traces` (decimated arrays)."""
    from . import api

    t0 = time.perf_counter()
    rec = {"inputs": case, "status": "ok", "error": None}
    try:
        fmu_path = _fmu_on_worker(fmu)
        overrides = dict(case["set"])
        if case["FN_kN"] is not None:
            overrides["F_N"] = case["FN_kN"] * 1e3
        preset = None if case["preset"] == "default" else case["preset"]
        common = dict(params=None, overrides=overrides, preset=preset, v_mps=case["v_mps"], grid=case["grid"],
                      fmu=fmu_path, fmu_params=case["fmu_param"])
        if case["analysis"] == "modal":
            m = api.modal(case["model"], cx=case["cx_target"], **common)
            rec["summary"] = {"linear_analysis": m.linear_analysis, "provenance": m.provenance}
            rec["results"] = {"predicted_frequency_hz": m.predicted_frequency_hz,
                              "predicted_damping_ratio": m.predicted_damping_ratio,
                              "predicted_unstable": m.predicted_unstable,
                              "fastsim_mu": m.provenance["fmu_params"].get("mu") if case["model"] == "fastsim" else None}
        else:
            r = api.simulate(case["scenario"], case["model"], t_end_s=case["t_end_s"], h_ms=case["h_ms"],
                             cx=case["cx_target"], transient=case["transient"],
                             contact_threads=case["contact_threads"], **common)
            s = r.summary
            rec["summary"] = s
            rec["results"] = {k: s.get(k) for k in ("dominant_frequency_hz", "predicted_frequency_hz",
                                                     "predicted_damping_ratio", "predicted_unstable",
                                                     "sustained_oscillation", "real_time_factor")}
            rec["results"]["oscillation_pp_cx_L"] = s["oscillation_amplitude"]
            rec["results"]["fastsim_mu"] = s["provenance"]["fmu_params"].get("mu") if case["model"] == "fastsim" \
                else None
            every = max(1, int(save_every))
            rec["_traces"] = {k: np.asarray(v)[::every] if every > 1 else np.asarray(v) for k, v in r.traces.items()}
            if every > 1 and len(r.traces["t_s"]) % every != 1:
                for k, v in r.traces.items():  # keep the last row as well
                    rec["_traces"][k] = np.append(rec["_traces"][k], np.asarray(v)[-1])
    except Exception as e:  # noqa: BLE001 - recorded, the sweep goes on
        rec["status"] = "failed"
        msg = str(e).splitlines()[0] if str(e) else ""
        rec["error"] = f"{type(e).__name__}: {msg}"
        if not isinstance(e, DrivetrainError):
            rec["traceback"] = traceback.format_exc(limit=6)
    rec["wall_s"] = time.perf_counter() - t0
    return rec


def _trace_name(cid, case):
    cond = case["preset"]
    return f"traces/{cid}_{case['scenario']}_{case['model']}_{cond}_v{case['v_mps']:g}.csv"


def _store(out: Path, cid: str, case: dict, rec: dict, fmu_sha: str):
    """Writes the traces and the case record (atomically; the record last, so it means 'done')."""
    traces = rec.pop("_traces", None)
    rec["case_id"] = cid
    rec["fmu_content_sha256"] = fmu_sha
    rec["project_version"] = __version__
    rec["trace_file"] = None
    if traces is not None:
        rel = _trace_name(cid, case)
        io_util.write_csv(out / rel, traces)
        rec["trace_file"] = rel
    io_util.write_json(out / "cases" / f"{cid}.json", scenarios._json_clean(rec))
    return rec


def _row(cid, case, rec):
    res = rec.get("results") or {}
    row = {
        "case_id": cid, "status": rec["status"], "error": rec.get("error") or "", "analysis": case["analysis"],
        "scenario": case["scenario"], "model": case["model"], "preset": case["preset"], "v_mps": case["v_mps"],
        "FN_kN": case["FN_kN"] if case["FN_kN"] is not None else None, "cx_target": case["cx_target"],
        "t_end_s": (rec.get("summary") or {}).get("t_end_s", case["t_end_s"]), "h_ms": case["h_ms"],
        "grid": case["grid"],
    }
    for k, v in sorted(case["set"].items()):
        row[f"set.{k}"] = float(v)
    for k, v in sorted(case["fmu_param"].items()):
        row[f"fmu_param.{k}"] = v
    row["fastsim_mu"] = res.get("fastsim_mu")
    for k in ("dominant_frequency_hz", "predicted_frequency_hz", "predicted_damping_ratio", "predicted_unstable",
              "oscillation_pp_cx_L", "sustained_oscillation"):
        row[k] = res.get(k)
    if rec["status"] != "ok":
        row["stable"] = None
    elif case["analysis"] == "modal":
        row["stable"] = not res.get("predicted_unstable")
    else:
        row["stable"] = not res.get("sustained_oscillation")
    row["real_time_factor"] = res.get("real_time_factor")
    row["wall_s"] = rec.get("wall_s")
    row["trace_file"] = rec.get("trace_file") or ""
    row["summary_file"] = f"cases/{cid}.json"
    row["fmu_content_sha256"] = rec.get("fmu_content_sha256")
    row["project_version"] = rec.get("project_version")
    return row


def _fn_kN_default():
    from . import params
    return params.load().contact.F_N / 1e3


def write_table(out: Path, rows: list):
    """sweep.csv (always) and sweep.parquet (when pyarrow is installed); returns the written paths."""
    import csv
    cols = []
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    files = []
    with io_util.atomic_path(out / "sweep.csv") as tmp:
        with open(tmp, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=cols)
            w.writeheader()
            for r in rows:
                w.writerow({k: _fmt(r.get(k)) for k in cols})
    files.append(out / "sweep.csv")
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        return files
    table = pa.table({k: [r.get(k) for r in rows] for k in cols})
    with io_util.atomic_path(out / "sweep.parquet") as tmp:
        pq.write_table(table, tmp)
    files.append(out / "sweep.parquet")
    return files


def _fmt(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return "" if not math.isfinite(v) else f"{v:.10g}"
    return v


def read_table(path) -> list:
    """sweep.csv as a list of dicts (strings as written)."""
    import csv
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def run_sweep(sweep_file, out, scheduler: str | None = None, workers: int | None = None, save_every: int | None = None,
              fmu=None, progress: bool = True, plot: bool = True) -> dict:
    """Runs (or resumes) a sweep; returns {"table": path, "rows": [...], "ran": n, "skipped": n, "failed": n,
    "wall_s": s, "files": [...]}. scheduler: None/"local" (LocalCluster, `workers` processes,
    default all cores), "serial" (no Dask), or a scheduler address such as tcp://HOST:8786."""
    spec = load_sweep(sweep_file)
    if save_every is not None:
        if save_every < 1:
            raise ConfigError(f"--save-every {save_every}: must be an integer >= 1")
        spec["save_every"] = save_every
    fmu_path = contact.find_fmu(fmu)
    if fmu_path is None:
        raise FMUNotFoundError("sweep needs the contact FMU (scripts/build-fmu.sh, --fmu or $ECF_FMU_PATH)")
    ident = contact.fmu_identity(fmu_path)
    fmu_sha = ident["content_sha256"]
    from fmpy import read_model_description
    fmu_params = sorted(v.name for v in read_model_description(str(fmu_path)).modelVariables
                        if v.causality == "parameter")
    asked = set(spec["fmu_param"]) | {k[10:] for k in spec["axes"] if k.startswith("fmu_param.")}
    for n in sorted(asked - set(fmu_params)):
        raise ConfigError(f"sweep file {sweep_file}: FMU parameter {n!r} unknown (the FMU's parameters: "
                          f"{', '.join(fmu_params)})")
    out = Path(out)
    (out / "cases").mkdir(parents=True, exist_ok=True)
    cases = expand(spec)
    fn_default = _fn_kN_default()
    for c in cases:
        if c["FN_kN"] is None:
            c["FN_kN"] = fn_default
    ids = [case_id(c, fmu_sha) for c in cases]
    if len(set(ids)) != len(ids):
        raise ConfigError(f"sweep file {sweep_file}: the axes contain duplicate values (two cases are identical)")
    done = {}
    for cid in ids:
        p = out / "cases" / f"{cid}.json"
        if p.is_file():
            try:
                rec = json.loads(p.read_text())
            except json.JSONDecodeError:
                continue
            if rec.get("status") == "ok":
                done[cid] = rec
    todo = [(cid, c) for cid, c in zip(ids, cases) if cid not in done]
    log = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    log(f"sweep {sweep_file}: {len(cases)} cases, {len(done)} already in {out} (skipped), {len(todo)} to run")
    t0 = time.perf_counter()
    recs = dict(done)
    bar = _bar(len(todo), progress)
    try:
        if scheduler == "serial":
            for cid, c in todo:
                rec = run_case(c, str(fmu_path), spec["save_every"])
                recs[cid] = _store(out, cid, c, rec, fmu_sha)
                bar.update(1)
        elif todo:
            _run_dask(todo, spec, fmu_path, fmu_sha, out, scheduler, workers, recs, bar)
    finally:
        bar.close()
    wall = time.perf_counter() - t0
    rows = [_row(cid, c, recs[cid]) for cid, c in zip(ids, cases) if cid in recs]
    files = write_table(out, rows)
    if plot:
        from . import plots
        with io_util.atomic_path(out / "stability_map.png") as tmp:
            plots.plot_stability_map(tmp, rows, spec["map"]["x"], spec["map"]["y"], title=Path(sweep_file).name)
        files.append(out / "stability_map.png")
    failed = [r for r in rows if r["status"] != "ok"]
    for r in failed:
        log(f"  failed {r['case_id']} ({r['model']}, {r['preset']}, v = {r['v_mps']:g} m/s): {r['error']}")
    log(f"sweep done: {len(todo)} run in {wall:.1f} s, {len(done)} skipped, {len(failed)} failed; table {out / 'sweep.csv'}")
    return {"table": out / "sweep.csv", "rows": rows, "ran": len(todo), "skipped": len(done), "failed": len(failed),
            "wall_s": wall, "files": files}


class _NoBar:
    def update(self, n):
        pass

    def close(self):
        pass


def _bar(total, progress):
    if not progress:
        return _NoBar()
    from tqdm import tqdm
    return tqdm(total=total, unit="case", file=sys.stderr, desc="sweep", dynamic_ncols=True)


def _run_dask(todo, spec, fmu_path, fmu_sha, out, scheduler, workers, recs, bar):
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler in (None, "local"):
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                               silence_logs=40)
        client = Client(cluster)
        fmu_arg = str(fmu_path)
    else:
        if not scheduler.startswith(("tcp://", "tls://", "inproc://", "ucx://", "ws://", "wss://")):
            raise ConfigError(f"--scheduler {scheduler}: expected local, serial or an address such as tcp://HOST:8786")
        try:
            client = Client(scheduler, timeout="20s")
        except OSError as e:
            raise ConfigError(f"--scheduler {scheduler}: cannot connect ({e})") from None
        # workers may run on other machines: send the FMU's bytes once to every worker
        fmu_arg = client.scatter([(Path(fmu_path).read_bytes(), fmu_sha)], broadcast=True)[0]
    try:
        if not todo:
            return
        futs = {}
        for cid, c in todo:
            f = client.submit(run_case, c, fmu_arg, spec["save_every"], key=f"ecf-case-{cid}", pure=False)
            futs[f] = (cid, c)
        for f in as_completed(list(futs)):
            cid, c = futs[f]
            try:
                rec = f.result()
            except Exception as e:  # noqa: BLE001 - e.g. a worker died (KilledWorker)
                rec = {"inputs": c, "status": "failed", "error": f"{type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''}",
                       "wall_s": None}
            recs[cid] = _store(out, cid, c, rec, fmu_sha)
            bar.update(1)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
