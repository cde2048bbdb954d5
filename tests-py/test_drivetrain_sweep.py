"""Sweeps on Dask (docs/drivetrain.md): the same tiny sweep serially, on a LocalCluster and on a real
`dask scheduler` with two `dask worker` processes started here on localhost; the three tables
must be equal (timing columns aside), failures recorded, resume skips finished cases.

Tiny on purpose (CI budget): ECF and FASTSIM at 5 and 20 m/s, step of 0.8 s on the 10x5 grid,
simulate + modal, and an invalid J_L = 0 axis value that must fail without stopping the sweep."""

import csv
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "drivetrain-demo"))

from drivetrain_demo import ConfigError, sweep  # noqa: E402

TINY = """
description = "CI sweep"
scenario = "step"
analysis = "both"
t_end_s = 0.8
grid = "10x5"
save_every = 20
[axes]
model = ["ecf", "fastsim"]
v_mps = [5, 20]
[axes.set]
J_L = [120.0, 0.0]
[set]
K_p = 1000.0
"""
N_CASES = 2 * 2 * 2 * 2
N_FAILED = 8  # every J_L = 0 case


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    p = tmp_path_factory.mktemp("sweepfile") / "tiny.toml"
    p.write_text(TINY)
    return p


@pytest.fixture(scope="module")
def serial(sweep_file, fmu_path, tmp_path_factory):
    out = tmp_path_factory.mktemp("serial")
    return sweep.run_sweep(sweep_file, out, scheduler="serial", fmu=fmu_path, progress=False), out


def _table(out):
    with open(out / "sweep.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    return [{k: v for k, v in r.items() if k not in sweep.TIMING_COLUMNS} for r in rows]


def test_serial_sweep_records_results_and_failures(serial):
    r, out = serial
    rows = _table(out)
    assert r["ran"] == N_CASES and r["skipped"] == 0 and r["failed"] == N_FAILED
    assert len(rows) == N_CASES
    for row in rows:
        if row["set.J_L"] == "0":
            assert row["status"] == "failed" and "J_L" in row["error"], row
        else:
            assert row["status"] == "ok" and row["error"] == "", row
            assert 50 < float(row["predicted_frequency_hz"]) < 58
    sim = [r for r in rows if r["status"] == "ok" and r["analysis"] == "simulate"]
    assert len(sim) == 4
    # ECF at 5 m/s is predicted unstable, FASTSIM stable (the linear analysis in the table)
    pred = {(r["model"], r["v_mps"]): r["predicted_unstable"] for r in sim}
    assert pred[("ecf", "5")] == "True" and pred[("fastsim", "5")] == "False"
    for r_ in sim:
        trace = out / r_["trace_file"]
        lines = trace.read_text().splitlines()
        assert len(lines) - 1 == 3200 // 20 + 1  # --save-every 20 of 3201 rows
        assert lines[0].startswith("t_s,")
    png = (out / "stability_map.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_parquet_table_equals_csv(serial):
    pq = pytest.importorskip("pyarrow.parquet")
    _, out = serial
    t = pq.read_table(out / "sweep.parquet").to_pylist()
    rows = _table(out)
    assert [r["case_id"] for r in t] == [r["case_id"] for r in rows]
    assert [r["status"] for r in t] == [r["status"] for r in rows]


def test_resume_skips_finished_cases(serial, sweep_file, fmu_path):
    r0, out = serial
    ok_rec = next((out / "cases").glob("*.json"))
    before = {p.name: p.stat().st_mtime_ns for p in (out / "cases").glob("*.json")}
    r = sweep.run_sweep(sweep_file, out, scheduler="serial", fmu=fmu_path, progress=False, plot=False)
    assert r["skipped"] == N_CASES - N_FAILED and r["ran"] == N_FAILED  # failed cases run again
    after = {p.name: p.stat().st_mtime_ns for p in (out / "cases").glob("*.json")}
    ok_ids = {row["case_id"] for row in _table(out) if row["status"] == "ok"}
    assert all(before[f"{i}.json"] == after[f"{i}.json"] for i in ok_ids)
    assert ok_rec.is_file()


def test_local_cluster_equals_serial(serial, sweep_file, fmu_path, tmp_path):
    _, sout = serial
    r = sweep.run_sweep(sweep_file, tmp_path, scheduler="local", workers=2, fmu=fmu_path, progress=False)
    assert r["ran"] == N_CASES
    assert _table(tmp_path) == _table(sout)
    # the traces are bit-identical too
    for row in _table(sout):
        if row["trace_file"]:
            assert (tmp_path / row["trace_file"]).read_bytes() == (sout / row["trace_file"]).read_bytes()


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_real_scheduler_and_two_workers_equal_serial(serial, sweep_file, fmu_path, tmp_path):
    """`dask scheduler` + 2 x `dask worker` as separate processes on localhost; the FMU is sent to
    the workers by the client (no shared path needed)."""
    from dask.distributed import Client
    _, sout = serial
    dask_cli = str(Path(sys.executable).parent / "dask")
    port = _free_port()
    addr = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, PYTHONPATH=str(ROOT / "drivetrain-demo"))
    env.pop("ECF_FMU_PATH", None)
    env.pop("ECF_CONTACT_FMU", None)
    procs = [subprocess.Popen([dask_cli, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        for _ in range(2):
            procs.append(subprocess.Popen([dask_cli, "worker", addr, "--nworkers", "1", "--nthreads", "1",
                                           "--no-dashboard", "--local-directory", str(tmp_path / "dask-worker")],
                                          env=env, cwd=tmp_path, stdout=subprocess.DEVNULL,
                                          stderr=subprocess.DEVNULL))
        deadline = time.time() + 60
        while True:
            try:
                with Client(addr, timeout="5s") as c:
                    c.wait_for_workers(2, timeout=60)
                    break
            except OSError:
                if time.time() > deadline:
                    raise
                time.sleep(0.5)
        out = tmp_path / "dist"
        r = sweep.run_sweep(sweep_file, out, scheduler=addr, fmu=fmu_path, progress=False)
        assert r["ran"] == N_CASES
        assert _table(out) == _table(sout)
    finally:
        for p in procs[::-1]:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


def test_sweep_file_errors_name_file_and_key(tmp_path):
    cases = [
        ("speed = [5]\n", "unknown key(s) speed"),
        ("[axes]\npreset = ['humid']\n", "axes.preset 'humid'"),
        ("[axes.set]\nC_X = [1.0]\n", "[axes.set] C_X: unknown"),
        ("[axes]\nv_mps = [-5]\n", "axes.v_mps value -5"),
        ("analysis = 'eigen'\n", "analysis = 'eigen'"),
        ("[axes]\nwind = [1]\n", "[axes] wind: unknown axis"),
    ]
    for i, (text, msg) in enumerate(cases):
        p = tmp_path / f"s{i}.toml"
        p.write_text(text)
        with pytest.raises(ConfigError) as e:
            sweep.load_sweep(p)
        assert str(p) in str(e.value) and msg in str(e.value), str(e.value)


def test_example_sweep_file_loads():
    spec = sweep.load_sweep(ROOT / "drivetrain-demo" / "examples" / "sweep.toml")
    cases = sweep.expand(spec)
    assert len([c for c in cases if c["analysis"] == "simulate"]) == 20


def test_unknown_fmu_parameter_axis_refused_before_running(tmp_path, fmu_path):
    p = tmp_path / "s.toml"
    p.write_text("[axes.fmu_param]\nfriction = [0.2, 0.3]\n")
    with pytest.raises(ConfigError, match="FMU parameter 'friction' unknown"):
        sweep.run_sweep(p, tmp_path / "out", scheduler="serial", fmu=fmu_path, progress=False)
    assert not (tmp_path / "out" / "sweep.csv").exists()
