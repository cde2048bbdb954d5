"""The Python package ecf against the `ecf` command line: the same numbers to the last bit (each
value printed with the CLI's decimals is the CLI's text; JSON documents equal), the same error
messages, the state round trip, and calls that release the GIL and stop at Ctrl-C.

The CLI is ECF_BIN, else target/release/ecf of the repository (CARGO_TARGET_DIR honoured).
"""

import json
import os
import re
import signal
import subprocess
import threading
from pathlib import Path

import numpy as np
import pytest

import ecf

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "examples" / "measurements" / "speed.csv"


def _ecf_bin() -> str:
    if os.environ.get("ECF_BIN"):
        return os.environ["ECF_BIN"]
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    exe = target / "release" / "ecf"
    if not exe.exists():
        pytest.skip(f"no ecf binary at {exe} (set ECF_BIN or build with cargo build --release -p ecf-cli)")
    return str(exe)


def cli(*args, ok=True):
    p = subprocess.run([_ecf_bin(), *map(str, args)], capture_output=True, text=True)
    if ok:
        assert p.returncode == 0, p.stderr
    return p


def csv_rows(text):
    lines = text.strip().splitlines()
    return lines[0].split(","), [l.split(",") for l in lines[1:]]


DECIMALS = {o["column"]: o["decimals"] for o in ecf.info()["outputs"]}


def assert_outputs_equal(table, header, rows, skip=()):
    """Every output column of `table` printed with the CLI's decimals is the CLI's text."""
    assert list(table) == header
    n = len(rows)
    for k, name in enumerate(header):
        col = table[name]
        assert len(col) == n
        if name in skip:
            continue
        d = DECIMALS[name]
        got = [f"{x:.{d}f}" for x in col]
        want = [r[k] for r in rows]
        assert got == want, name


MODEL_CASES = [
    (dict(preset="table4.1", grid="20x5"), ["--preset", "table4.1", "--grid", "20x5"]),
    (
        dict(model="fastsim", cy=0.001, spin=0.1, v_mps=-10.0),
        ["--model", "fastsim", "--cy", "0.001", "--spin", "0.1", "--v-mps", "-10"],
    ),
    (dict(model="polach", fn_kN=80.0), ["--model", "polach", "--fn-kN", "80"]),
    (
        dict(preset="dry", a_mm=6.0, b_mm=5.0, grid="16x3", t_bulk_C=40.0, params={"mu": 0.4}),
        ["--preset", "dry", "--a-mm", "6", "--b-mm", "5", "--grid", "16x3", "--t-bulk-c", "40", "--param", "mu=0.4"],
    ),
    (dict(preset="dry", tol=0.05, v_mps=10.0), ["--preset", "dry", "--tol", "0.05", "--v-mps", "10"]),
]


@pytest.mark.parametrize("kw,flags", MODEL_CASES)
def test_curve_is_the_cli_curve_to_the_last_digit(kw, flags):
    cx = [-0.02, 0.0005, 0.001, 0.003, 0.01, 0.05, 0.2]
    t = ecf.curve(cx=np.array(cx), **kw)
    header, rows = csv_rows(cli("curve", *flags, "--cx", ",".join(map(repr, cx))).stdout)
    assert [float(r[0]) for r in rows] == list(t["cx"])
    assert_outputs_equal(t, header, rows, skip=("cx",))
    # a range as the CLI's start:stop:n, through the same numbers
    t2 = ecf.curve(cx=np.linspace(0.001, 0.3, 7), **kw)
    header, rows = csv_rows(cli("curve", *flags, "--cx", "0.001:0.3:7").stdout)
    assert_outputs_equal(t2, header, rows, skip=("cx",))


def test_curve_as_frame_has_the_cli_columns():
    pd = pytest.importorskip("pandas")
    df = ecf.curve(cx=[0.01, 0.02], preset="dry", grid="10x3", as_frame=True)
    assert isinstance(df, pd.DataFrame)
    header, _ = csv_rows(cli("curve", "--preset", "dry", "--grid", "10x3", "--cx", "0.01").stdout)
    assert list(df.columns) == header
    assert df["f"].iloc[1] > df["f"].iloc[0] > 0


def test_tol_note_is_the_clis():
    t = ecf.curve(cx=[0.01], preset="dry", tol=0.05, v_mps=10.0)
    err = cli("curve", "--preset", "dry", "--tol", "0.05", "--v-mps", "10", "--cx", "0.01").stderr
    assert t.note is not None and t.note in err


def test_step_and_sine_are_the_cli_runs():
    kw = dict(preset="table4.1", v_mps=5.0, grid="20x7")
    flags = ["--preset", "table4.1", "--v-mps", "5", "--grid", "20x7"]
    t = ecf.step_response(cx_from=0.001, cx_to=0.01, duration_ms=1.0, dt_ms=0.1, **kw)
    header, rows = csv_rows(
        cli("step", *flags, "--cx-from", "0.001", "--cx-to", "0.01", "--duration-ms", "1", "--dt-ms", "0.1").stdout
    )
    assert len(rows) == 11
    assert [f"{x:.8f}" for x in t["t_s"][1:]] == [r[0] for r in rows[1:]]
    assert [float(r[1]) for r in rows] == list(t["cx"])
    assert_outputs_equal(t, header, rows, skip=("t_s", "cx"))
    for scheme in ["cells", "continuous", "cells-ho"]:
        s = ecf.step_response(cx_from=0.001, cx_to=0.01, duration_ms=0.5, dt_ms=0.1, scheme=scheme, **kw)
        h, r = csv_rows(
            cli("step", *flags, "--cx-from", "0.001", "--cx-to", "0.01", "--duration-ms", "0.5", "--dt-ms", "0.1", "--scheme", scheme).stdout
        )
        assert_outputs_equal(s, h, r, skip=("t_s", "cx"))

    t = ecf.sine_response(cm=0.005, ca=0.002, freq_hz=100.0, cycles=1, steps_per_cycle=20, **kw)
    header, rows = csv_rows(
        cli("sine", *flags, "--cm", "0.005", "--ca", "0.002", "--freq-hz", "100", "--cycles", "1", "--steps-per-cycle", "20").stdout
    )
    assert len(rows) == 21
    assert [f"{x:.8f}" for x in t["cx"][1:]] == [r[1] for r in rows[1:]]
    assert [f"{x:.8f}" for x in t["t_s"][1:]] == [r[0] for r in rows[1:]]
    assert_outputs_equal(t, header, rows, skip=("t_s", "cx"))


def field_text(t):
    def lim(x):
        return -1.0 if np.isinf(x) else x

    return [
        [f"{x:.5f}", f"{a:.1f}", f"{b:.1f}", f"{lim(c):.1f}", f"{lim(d):.1f}", f"{p:.1f}", f"{T:.3f}", f"{int(g)}"]
        for x, a, b, c, d, p, T, g in zip(*t.values())
    ]


def test_field_and_contact_field_are_the_cli_field():
    t = ecf.field(cx=0.01, preset="dry", grid="20x5")
    header, rows = csv_rows(cli("field", "--preset", "dry", "--grid", "20x5", "--cx", "0.01").stdout)
    assert list(t) == header
    assert field_text(t) == rows
    c = ecf.Contact(preset="dry", grid="20x5", cx=0.01)
    c.steady()
    assert field_text(c.field()) == rows


def test_contact_steps_are_the_step_response_and_the_state_round_trips():
    kw = dict(preset="table4.1", v_mps=5.0, grid="20x7")
    ref = ecf.step_response(cx_from=0.001, cx_to=0.01, duration_ms=1.0, dt_ms=0.1, **kw)
    c = ecf.Contact(cx=0.001, **kw)
    first = c.steady()
    assert first["f"] == ref["f"][0]
    saved = None
    for k in range(1, 11):
        o = c.step(1e-4, cx=0.01)
        assert [o[n] for n in DECIMALS] == [ref[n][k] for n in DECIMALS]
        if k == 4:
            saved, at = c.state(), c.time_s
    assert isinstance(saved, bytes)
    # restored, the next steps are the same bits as the first time
    c.restore(saved)
    assert c.time_s == at and c.inputs["cx"] == 0.01
    o = c.step(1e-4)
    assert o["f"] == ref["f"][5] and o["T_max_C"] == ref["T_max_C"][5]
    # a fresh contact of the same configuration takes the state too
    d = ecf.Contact(cx=0.0, **kw)
    d.restore(saved)
    assert d.step(1e-4)["Fx_N"] == ref["Fx_N"][5]
    with pytest.raises(ValueError):
        d.restore(b"not a state")
    other = ecf.Contact(cx=0.0, preset="dry", grid="20x7")
    with pytest.raises(ecf.EcfError):
        other.restore(saved)


@pytest.mark.parametrize(
    "call,flags",
    [
        (lambda: ecf.curve(cx=[0.01], preset="dry", v_mps=5000), ["curve", "--preset", "dry", "--v-mps", "5000", "--cx", "0.01"]),
        (lambda: ecf.curve(cx=[0.01], preset="moist"), ["curve", "--preset", "moist", "--cx", "0.01"]),
        (lambda: ecf.curve(cx=[0.01], preset="dry", a_mm=1e300, b_mm=1.0), ["curve", "--preset", "dry", "--a-mm", "1e300", "--b-mm", "1", "--cx", "0.01"]),
        (lambda: ecf.curve(cx=[0.01], preset="dry", params={"nu": 0.9}), ["curve", "--preset", "dry", "--param", "nu=0.9", "--cx", "0.01"]),
        (lambda: ecf.curve(cx=[0.01], model="polach", tol=0.01), ["curve", "--model", "polach", "--tol", "0.01", "--cx", "0.01"]),
        (
            lambda: ecf.step_response(cx_from=0.001, cx_to=0.01, dt_ms=0.0, preset="dry"),
            ["step", "--preset", "dry", "--cx-from", "0.001", "--cx-to", "0.01", "--dt-ms", "0"],
        ),
        (
            lambda: ecf.sine_response(cm=0.005, ca=-1.0, freq_hz=100.0, preset="dry"),
            ["sine", "--preset", "dry", "--cm", "0.005", "--ca=-1", "--freq-hz", "100"],
        ),
        (lambda: ecf.field(cx=0.01, model="polach"), ["field", "--model", "polach", "--cx", "0.01"]),
        (lambda: ecf.compare(DATA), ["compare", str(DATA)]),
        (lambda: ecf.compare(DATA, preset="dry", fn_kN=-3), ["compare", str(DATA), "--preset", "dry", "--fn-kN=-3"]),
        (lambda: ecf.compare("/no/such.csv", preset="dry"), ["compare", "/no/such.csv", "--preset", "dry"]),
    ],
)
def test_bad_input_raises_valueerror_with_the_cli_message(call, flags):
    with pytest.raises(ValueError) as e:
        call()
    p = cli(*flags, ok=False)
    assert p.returncode == 2
    assert f"error: {e.value}\n" in p.stderr


def without_timings(v):
    """The diagnosis without its cost record (measured times, and evaluation counts that
    depend on which thread fills the shared memo first: two CLI runs differ there too) and
    the seconds in its verdict."""
    if isinstance(v, dict):
        return {k: without_timings(x) for k, x in v.items() if k not in ("cost", "seconds")}
    if isinstance(v, list):
        return [without_timings(x) for x in v]
    if isinstance(v, str):
        return re.sub(r"in \d+ s\b", "in N s", v)
    return v


def test_compare_is_the_cli_json_from_a_file_and_a_dataframe():
    r = ecf.compare(DATA, preset="dry", grid="20x5")
    want = json.loads(cli("compare", DATA, "--preset", "dry", "--grid", "20x5", "--json", "--quiet").stdout)
    assert r.to_dict() == want
    assert r.cv_rmse_pct == want["cv_rmse_pct"] and r["groups"] == want["groups"]
    pd = pytest.importorskip("pandas")
    df = pd.read_csv(DATA)
    rd = ecf.compare(df, preset="dry", grid="20x5")
    assert rd.data == "DataFrame"
    assert rd.cv_rmse_pct == want["cv_rmse_pct"] and rd.groups == want["groups"] and rd.rows == want["rows"]
    assert list(rd.frame()["f_model"]) == [x["f_model"] for x in want["rows"]]


def test_fit_is_the_cli_fit_and_writes_the_same_file(tmp_path):
    out_cli, out_py = tmp_path / "cli.json", tmp_path / "py.json"
    want = json.loads(
        cli("fit", DATA, "--preset", "dry", "--grid", "10x3", "--json", "--quiet", "--out", out_cli, "--bound", "tau_c2_0_GPa=0.2:2").stdout
    )
    stages = []
    r = ecf.fit(DATA, preset="dry", grid="10x3", out=out_py, bounds={"tau_c2_0_GPa": (0.2, 2)}, progress=stages.append)
    got = r.to_dict()
    assert got.pop("out") == str(out_py) and want.pop("out") == str(out_cli)
    assert got == want
    assert out_py.read_bytes() == out_cli.read_bytes()
    assert r.config["fit"]["cv_rmse_pct_after"] == want["cv_rmse_pct_after"]
    assert stages and all("model evaluations" in s for s in stages)
    # the fitted configuration goes back in as a dict, as the file goes back into the CLI
    again = ecf.compare(DATA, config=r.config, grid="10x3")
    back = json.loads(cli("compare", DATA, "--config", out_cli, "--grid", "10x3", "--json", "--quiet").stdout)
    assert again.cv_rmse_pct == back["cv_rmse_pct"]
    assert abs(again.cv_rmse_pct - want["cv_rmse_pct_after"]) < 1e-6


def test_diagnose_is_the_cli_diagnosis(tmp_path):
    want = json.loads(cli("diagnose", DATA, "--preset", "dry", "--grid", "10x3", "--json", "--quiet").stdout)
    stages = []
    r = ecf.diagnose(DATA, preset="dry", grid="10x3", progress=stages.append)
    assert without_timings(r.to_dict()) == without_timings(want)
    assert r.baseline_cv_rmse_pct == want["baseline_cv_rmse_pct"]
    assert len(stages) > 3


def test_a_raising_progress_callback_stops_the_loop():
    class Stop(Exception):
        pass

    def stop(_):
        raise Stop

    with pytest.raises(Stop):
        ecf.fit(DATA, preset="dry", grid="10x3", progress=stop)
    # the worker of the stopped fit leaves the next call alone
    assert ecf.compare(DATA, preset="dry", grid="10x3").n == 100


def test_text_progress_bar_without_tqdm(monkeypatch, capsys):
    import builtins

    real = builtins.__import__

    def no_tqdm(name, *a, **k):
        if name.startswith("tqdm"):
            raise ImportError(name)
        return real(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", no_tqdm)
    bar = ecf._Progress("diagnose")
    bar("held-out folds [3/10]")
    bar.close()
    err = capsys.readouterr().err
    assert "diagnose: held-out folds [######" in err and "3/10" in err


def test_ctrl_c_stops_a_long_curve():
    # a curve of many points on a fine grid; SIGINT arrives while it runs without the GIL.
    # Python's own Ctrl-C handler is set here: a process started as a background job of a
    # shell inherits SIGINT ignored, and Python then installs none
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            ecf.curve(cx=np.linspace(0.001, 0.3, 100000), preset="dry", grid="80x21")
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)


def test_long_calls_release_the_gil():
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.001)

    th = threading.Thread(target=count)
    th.start()
    before = len(ticks)
    ecf.curve(cx=np.linspace(0.001, 0.3, 200), preset="dry", grid="40x11")
    during = len(ticks) - before
    done.set()
    th.join()
    # the other thread ran while the curve was computed
    assert during > 5


def test_info_is_the_cli_info():
    i = ecf.info()
    assert str(i) == cli("info").stdout
    assert "dry" in i["presets"]
    assert [o["column"] for o in i["outputs"]][:3] == ["f", "Fx_N", "Fy_N"]
