"""The packed ecf_contact FMU through fmpy: static checks (fmpy, fmutool), simulate_fmu, a hand-written FMU2Slave loop, states, instances, bad input, memory, speed, and agreement with the ecf CLI."""

import ctypes
import math
import os
import shutil
import re
import subprocess
import sys
import time

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
)
from fmpy.validation import validate_fmu

OUTPUTS = ["Fx", "Fy", "Mz", "f", "T_max", "T_mean", "P_fric", "frac_elastic",
           "frac_plastic", "frac_sliding", "a", "b", "p0"]
INPUTS = ["cx", "cy", "spin", "v", "FN", "T_bulk"]


@pytest.fixture(scope="module")
def md(fmu_path):
    return read_model_description(fmu_path, validate=True)


@pytest.fixture(scope="module")
def unzipdir(fmu_path, tmp_path_factory):
    return extract(fmu_path, unzipdir=str(tmp_path_factory.mktemp("ecf_fmu")))


@pytest.fixture(scope="module")
def vr(md):
    return {v.name: v.valueReference for v in md.modelVariables}


class Recorder:
    """A logger callback that records (componentEnvironment, status, category, message)."""

    def __init__(self):
        self.records = []
        self.callbacks = fmi2CallbackFunctions()
        self._logger = fmi2CallbackLoggerTYPE(self._log)
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(lambda n, s: None)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(lambda p: None)
        self.env = ctypes.c_int(4711)
        self.callbacks.componentEnvironment = ctypes.cast(ctypes.pointer(self.env), ctypes.c_void_p)

    def _log(self, env, name, status, category, message):
        self.records.append((env, status, category.decode(), message.decode()))

    def has(self, status, *words):
        return any(r[1] == status and all(w in r[3] for w in words) for r in self.records)


def slave(md, unzipdir, name, recorder=None, grid=None):
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
    s.instantiate(callbacks=recorder.callbacks if recorder else None)
    if grid:
        s.setInteger([s_vr(md, "nx"), s_vr(md, "ny")], list(grid))
    return s


def s_vr(md, name):
    return next(v.valueReference for v in md.modelVariables if v.name == name)


def init(s, md, inputs=(0.01, 0.0, 0.0, 20.0, 110e3, 20.0)):
    s.setReal([s_vr(md, n) for n in INPUTS], list(inputs))
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()


def outputs(s, md):
    return s.getReal([s_vr(md, n) for n in OUTPUTS])


# --- static checks -----------------------------------------------------------------------

def test_fmpy_validate_reports_no_problems(fmu_path):
    problems = validate_fmu(fmu_path)
    assert problems == [], problems


def test_fmutool_check_reports_no_problems(fmu_path):
    exe = shutil.which("fmutool") or os.path.join(os.path.dirname(os.sys.executable), "fmutool")
    run = subprocess.run([exe, "-input", fmu_path, "-check"], capture_output=True, text=True)
    text = run.stdout + run.stderr
    assert run.returncode == 0, text
    assert "compliant with FMI-2.0" in text, text
    assert "No semantic error" in text, text
    assert "ERROR" not in text.replace("ERROR    ", "") or "No semantic error" in text


def test_model_description_variables(md):
    by = {v.name: v for v in md.modelVariables}
    units = {"cx": None, "cy": None, "spin": "1/m", "v": "m/s", "FN": "N", "T_bulk": "degC",
             "Fx": "N", "Fy": "N", "Mz": "N.m", "f": None, "T_max": "degC", "T_mean": "degC",
             "P_fric": "W", "frac_elastic": None, "frac_plastic": None, "frac_sliding": None,
             "a": "m", "b": "m", "p0": "Pa"}
    for n, u in units.items():
        assert n in by, n
        assert by[n].unit == u, (n, by[n].unit)
        assert by[n].description, n
        assert by[n].causality == ("input" if n in INPUTS else "output"), n
    for n in ["model", "preset", "config_file"]:
        assert by[n].type == "String" and by[n].causality == "parameter"
    assert by["effect_transient"].type == "Boolean"
    assert by["nx"].type == "Integer" and by["ny"].type == "Integer"
    assert by["tau_c1_0_GPa"].unit == "GPa" and by["tau_c1_0_GPa"].variability == "fixed"
    assert len({v.valueReference for v in md.modelVariables}) == len(md.modelVariables)
    cs = md.coSimulation
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate
    assert cs.canHandleVariableCommunicationStepSize
    assert not cs.canBeInstantiatedOnlyOncePerProcess


# --- running it ----------------------------------------------------------------------------

def test_simulate_default_experiment(fmu_path, md):
    res = simulate_fmu(fmu_path)
    de = md.defaultExperiment
    assert res["time"][0] == pytest.approx(float(de.startTime))
    assert res["time"][-1] == pytest.approx(float(de.stopTime))
    assert len(res) == round((float(de.stopTime) - float(de.startTime)) / float(de.stepSize)) + 1
    # start values: cx = 0 gives no creep force, a Hertz contact of the default size
    assert np.all(res["Fx"] == 0.0)
    assert res["a"][-1] == pytest.approx(7.63e-3)
    # with a creepage ramp as input the force follows its sign
    t = np.linspace(0.0, 0.05, 11)
    sig = np.array(list(zip(t, 0.02 * np.sin(2 * np.pi * 20 * t))),
                   dtype=[("time", np.float64), ("cx", np.float64)])
    res = simulate_fmu(fmu_path, input=sig, output=["Fx", "f"])
    mid = res[(res["time"] > 0.005) & (res["time"] < 0.02)]
    assert np.all(mid["Fx"] > 0), mid
    late = res[(res["time"] > 0.03) & (res["time"] < 0.045)]
    assert np.all(late["Fx"] < 0), late


def test_hand_written_loop_with_changing_inputs(md, unzipdir):
    s = slave(md, unzipdir, "loop")
    init(s, md)
    t, h = 0.0, 1e-3
    prev_sign = None
    for k in range(40):
        cx = 0.03 * math.sin(2 * math.pi * k / 40)
        v = 20.0 + 0.25 * k
        fn = 110e3 * (1.0 + 0.1 * math.sin(k / 7))
        s.setReal([s_vr(md, "cx"), s_vr(md, "v"), s_vr(md, "FN")], [cx, v, fn])
        s.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        t += h
        o = dict(zip(OUTPUTS, outputs(s, md)))
        assert all(math.isfinite(x) for x in o.values()), o
        assert o["T_max"] >= 20.0 - 1e-9
        assert abs(o["frac_elastic"] + o["frac_plastic"] + o["frac_sliding"] - 1.0) < 1e-9
        if abs(cx) > 0.01:
            sign = math.copysign(1.0, o["Fx"])
            assert sign == math.copysign(1.0, cx), (k, cx, o["Fx"])
            prev_sign = sign
    assert prev_sign is not None
    assert s.getRealStatus(2) == pytest.approx(t)  # fmi2LastSuccessfulTime
    s.terminate()
    s.freeInstance()


def test_steady_state_equals_ecf_curve(md, unzipdir, repo_root):
    exe = repo_root / "target" / "release" / "ecf"
    # always through cargo: a no-op when current, a rebuild when creep-core changed
    subprocess.run(["cargo", "build", "--release", "-p", "ecf-cli"], cwd=repo_root, check=True,
                   capture_output=True)
    # the FMU's grid: the one its start value of rel_tol chooses; the CLI's --tol is the same
    # chooser (for table4.1 at 20 m/s it picks a row of the cell-by-cell scheme, the one the
    # CLI's steady curve takes)
    rel_tol = next(v.start for v in md.modelVariables if v.name == "rel_tol")
    cli = subprocess.run([str(exe), "curve", "--preset", "table4.1", "--v-mps", "20", "--fn-kn", "110",
                          "--cx", "0.01,0.05", "--tol", str(rel_tol)],
                         capture_output=True, text=True, check=True)
    assert "grid " in cli.stderr, cli.stderr
    rows = [line.split(",") for line in cli.stdout.strip().splitlines()]
    head = rows[0]
    for row in rows[1:]:
        ref = dict(zip(head, row))
        cx = float(ref["cx"])
        for transient in (False, True):
            s = slave(md, unzipdir, f"steady-{cx}-{transient}")
            s.setString([s_vr(md, "preset")], ["table4.1"])
            s.setBoolean([s_vr(md, "effect_transient")], [transient])
            init(s, md, (cx, 0.0, 0.0, 20.0, 110e3, 20.0))
            if not transient:
                # quasi-steady: every step returns the steady state of its inputs
                for k in range(3):
                    s.doStep(currentCommunicationPoint=k * 1e-3, communicationStepSize=1e-3)
            # transient: initialization sets the bristle grid to the steady state (later
            # steps with constant inputs stay within the sub-step discretization error of
            # it, about 0.1 % at the default grid, which shrinks as the grid is refined)
            o = dict(zip(OUTPUTS, outputs(s, md)))
            grid = re.search(r"grid (\d+)x(\d+)", cli.stderr)
            assert s.getInteger([s_vr(md, "nx"), s_vr(md, "ny")]) == [int(grid[1]), int(grid[2])]
            # the CLI prints f with 8 decimals, Fx with 3 and T_max with 3
            assert abs(o["f"] - float(ref["f"])) <= 0.51e-8, (cx, transient, o["f"], ref["f"])
            assert abs(o["Fx"] - float(ref["Fx_N"])) <= 0.51e-3, (cx, transient, o["Fx"], ref["Fx_N"])
            assert abs(o["T_max"] - float(ref["T_max_C"])) <= 0.51e-3, (cx, transient)
            assert abs(o["P_fric"] - float(ref["P_fric_W"])) <= 0.51e-3, (cx, transient)
            s.freeInstance()


# --- state, instances ----------------------------------------------------------------------

def test_state_rollback_and_serialization(md, unzipdir):
    a = slave(md, unzipdir, "state-a", grid=(40, 11))
    init(a, md, (0.005, 0.0, 0.0, 20.0, 110e3, 20.0))
    a.setReal([s_vr(md, "cx")], [0.04])
    a.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    st = a.getFMUstate()
    a.doStep(currentCommunicationPoint=1e-3, communicationStepSize=1e-3)
    ref = outputs(a, md)
    a.setFMUstate(st)
    a.doStep(currentCommunicationPoint=1e-3, communicationStepSize=1e-3)
    assert outputs(a, md) == ref  # bit for bit
    blob = a.serializeFMUstate(st)
    b = slave(md, unzipdir, "state-b")
    init(b, md)
    st_b = b.deSerializeFMUstate(blob)
    b.setFMUstate(st_b)
    b.doStep(currentCommunicationPoint=1e-3, communicationStepSize=1e-3)
    assert outputs(b, md) == ref
    a.freeFMUstate(st)
    b.freeFMUstate(st_b)
    a.freeInstance()
    b.freeInstance()


def test_two_instances_in_one_process_are_independent(md, unzipdir):
    def run(s, cx, fn, steps):
        out = []
        for k in range(steps):
            s.setReal([s_vr(md, "cx"), s_vr(md, "FN")], [cx * (1 + 0.1 * k), fn])
            s.doStep(currentCommunicationPoint=k * 1e-3, communicationStepSize=1e-3)
            out.append(outputs(s, md))
        return out

    a = slave(md, unzipdir, "pair-a", grid=(30, 9))
    b = slave(md, unzipdir, "pair-b", grid=(30, 9))
    init(a, md)
    init(b, md, (-0.02, 0.0, 0.0, 30.0, 80e3, 10.0))
    got_a, got_b = [], []
    for k in range(5):  # interleaved
        got_a += run_one(a, md, 0.01 * (1 + 0.1 * k), 110e3, k)
        got_b += run_one(b, md, -0.02 * (1 + 0.1 * k), 80e3, k)
    a.freeInstance()
    b.freeInstance()
    solo = slave(md, unzipdir, "solo-a", grid=(30, 9))
    init(solo, md)
    want_a = run(solo, 0.01, 110e3, 5)
    solo.freeInstance()
    assert got_a == want_a
    assert all(o[0] < 0 for o in got_b) and all(o[0] > 0 for o in got_a)


def run_one(s, md, cx, fn, k):
    s.setReal([s_vr(md, "cx"), s_vr(md, "FN")], [cx, fn])
    s.doStep(currentCommunicationPoint=k * 1e-3, communicationStepSize=1e-3)
    return [outputs(s, md)]


# --- bad input -----------------------------------------------------------------------------

def test_bad_input_statuses_messages_and_component_environment(md, unzipdir):
    rec = Recorder()
    s = slave(md, unzipdir, "bad", recorder=rec, grid=(20, 7))
    # doStep before initialization: error, logged with the reason
    with pytest.raises(FMICallException):
        s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    assert rec.has(3, "fmi2DoStep", "Instantiated")
    # a missing and a malformed configuration file
    with pytest.raises(FMICallException):
        s.setString([s_vr(md, "config_file")], ["no/such.json"])
    assert rec.has(3, "config_file", "no/such.json", "cannot read")
    bad = os.path.join(unzipdir, "resources", "broken.json")
    with open(bad, "w") as fh:
        fh.write('{"preset": "dry", "params": {"mu": 0.3,}}')
    with pytest.raises(FMICallException):
        s.setString([s_vr(md, "config_file")], ["broken.json"])
    assert rec.has(3, "broken.json", "line 1")
    # a shipped preset file resolves against resources/
    s.setString([s_vr(md, "config_file")], ["presets/wet.json"])
    init(s, md)
    # NaN and infinite inputs: error, value kept
    for name, x in [("cx", float("nan")), ("v", float("inf")), ("FN", float("-inf"))]:
        before = s.getReal([s_vr(md, name)])[0]
        with pytest.raises(FMICallException):
            s.setReal([s_vr(md, name)], [x])
        assert s.getReal([s_vr(md, name)])[0] == before
        assert rec.has(3, "fmi2SetReal", name, "finite"), rec.records[-3:]
    # |cx| > 1: warning (fmpy does not raise), computed anyway; the '%' arrives escaped
    s.setReal([s_vr(md, "cx")], [1.2])
    assert rec.has(1, "cx = 1.2", "|cx| > 1", "120 %%")
    s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    # lift-off: warning and zero forces
    s.setReal([s_vr(md, "FN")], [-10.0])
    assert rec.has(1, "FN = -10", "lifted off")
    s.doStep(currentCommunicationPoint=1e-3, communicationStepSize=1e-3)
    o = dict(zip(OUTPUTS, outputs(s, md)))
    assert o["Fx"] == 0.0 and o["Fy"] == 0.0 and o["Mz"] == 0.0
    # standstill
    s.setReal([s_vr(md, "FN"), s_vr(md, "v"), s_vr(md, "cx")], [110e3, 0.0, 0.01])
    s.doStep(currentCommunicationPoint=2e-3, communicationStepSize=1e-3)
    assert all(math.isfinite(x) for x in outputs(s, md))
    # fixed parameter after initialization, unknown value reference
    with pytest.raises(FMICallException):
        s.setReal([s_vr(md, "mu")], [0.3])
    assert rec.has(3, "mu", "fixed parameter")
    with pytest.raises(FMICallException):
        s.setReal([99999], [1.0])
    assert rec.has(3, "unknown value reference 99999")
    # every message carried the importer's componentEnvironment; all '%' were escaped
    envs = {r[0] for r in rec.records}
    assert envs == {ctypes.addressof(rec.env)}, envs
    for r in rec.records:
        assert "%" not in r[3].replace("%%", ""), r
    s.freeInstance()


def test_null_logger_is_tolerated(md, unzipdir):
    cb = fmi2CallbackFunctions()  # all NULL
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier="ecf_contact", instanceName="quiet")
    s.instantiate(callbacks=cb)
    with pytest.raises(FMICallException):
        s.setReal([s_vr(md, "cx")], [float("nan")])
    with pytest.raises(FMICallException):
        s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    s.freeInstance()


# --- memory and speed ----------------------------------------------------------------------

def rss_kib():
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS")


def test_instantiate_free_cycles_do_not_grow_memory(md, unzipdir, capsys):
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier="ecf_contact", instanceName="cycle")
    vrs = [s_vr(md, n) for n in INPUTS]

    def cycle():
        s.instantiate()
        s.setReal(vrs, [0.02, 0.0, 0.0, 20.0, 110e3, 20.0])
        # the presets' 80x21 grid, given explicitly (the start value of rel_tol would choose
        # 10x3): a large grid makes a leak of any part of it show
        s.setInteger([s_vr(md, "nx"), s_vr(md, "ny")], [80, 21])
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.exitInitializationMode()  # builds the 80x21-cell model
        s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-4)
        st = s.getFMUstate()
        s.serializeFMUstate(st)
        s.freeFMUstate(st)
        s.fmi2FreeInstance(s.component)

    for _ in range(50):
        cycle()
    before = rss_kib()
    n = 1000
    for _ in range(n):
        cycle()
    after = rss_kib()
    s.freeLibrary()
    # one initialized instance holds its bristle grid and heat histories: a leak of even a
    # small part of it per cycle would add many MiB over 1000 cycles
    # (per bristle: its state, 8 x 8 bytes, and 30 heat-kernel accumulators, each also held
    # at its last lattice node for the whole-cell commit)
    grid_kib = 81 * 21 * 2 * (8 * 8 + 30 * 8) / 1024
    with capsys.disabled():
        print(f"\n[fmu memory] {n} instantiate/init/step/state/free cycles: RSS {before} -> {after} KiB "
              f"({after - before:+d} KiB; one grid ~{grid_kib:.0f} KiB)")
    assert after - before < 2048, (before, after)


UNLOAD_SCRIPT = """
import glob, os, sys, time
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
fmu, threads, fresh = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "fresh"
md = read_model_description(fmu)
vr = {v.name: v.valueReference for v in md.modelVariables}
def copies():
    with open("/proc/self/maps") as fh:
        return len({l.split()[-1] for l in fh if l.rstrip().endswith("ecf_contact.so")})
base = len(os.listdir("/proc/self/task"))
once = extract(fmu)
for i in range(4):
    s = FMU2Slave(guid=md.guid, unzipDirectory=extract(fmu) if fresh else once,
                  modelIdentifier="ecf_contact", instanceName=f"c{i}")
    s.instantiate()
    s.setInteger([vr["threads"]], [threads])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    for k in range(20):
        s.doStep(currentCommunicationPoint=k * 1e-4, communicationStepSize=1e-4)
    s.freeInstance()  # fmi2FreeInstance, then dlclose
    extra = len(os.listdir("/proc/self/task")) - base
    for _ in range(200):  # the workers end once they see the pool dropped
        if extra == 0:
            break
        time.sleep(0.01)
        extra = len(os.listdir("/proc/self/task")) - base
    print(copies(), extra)
"""


@pytest.mark.skipif(not os.path.exists("/proc/self/maps"), reason="reads /proc/self/maps (Linux)")
def test_library_unloads_at_free_and_two_threads_keep_one_copy(fmu_path):
    """With one thread the library leaves the process at freeInstance; with two, the pool's
    thread-local state on the importer's thread keeps it loaded (glibc holds a library whose
    thread-local destructors are pending) and the workers end: a run from the same extracted
    copy reuses it, a run from a new copy adds one (docs/fmu.md, threads)."""
    def run(threads, fresh):
        out = subprocess.run([sys.executable, "-c", UNLOAD_SCRIPT, fmu_path, str(threads),
                              "fresh" if fresh else "same"],
                             capture_output=True, text=True, timeout=300)
        assert out.returncode == 0, out.stderr[-3000:]
        return [tuple(int(x) for x in line.split()) for line in out.stdout.split("\n") if line]

    # (library copies mapped, threads above the start) after each of four runs
    assert run(1, fresh=True) == [(0, 0)] * 4
    assert run(2, fresh=False) == [(1, 0)] * 4
    assert run(2, fresh=True) == [(1, 0), (2, 0), (3, 0), (4, 0)]


HEAP_SCRIPT = """
import ctypes, sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
class MallInfo2(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in
                "arena ordblks smblks hblks hblkhd usmblks fsmblks uordblks fordblks keepcost".split()]
libc = ctypes.CDLL(None)
libc.mallinfo2.restype = MallInfo2
fmu = sys.argv[1]
md = read_model_description(fmu)
vr = {v.name: v.valueReference for v in md.modelVariables}
folder = extract(fmu)
used = []
for i in range(40):
    # each instance loads the library anew and its freeInstance unloads it (dlclose)
    s = FMU2Slave(guid=md.guid, unzipDirectory=folder, modelIdentifier="ecf_contact", instanceName="c")
    s.instantiate(loggingOn=False)
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()  # rel_tol's start value: the grid from the accuracy table
    for k in range(5):
        s.doStep(currentCommunicationPoint=k * 1e-4, communicationStepSize=1e-4)
    st = s.getFMUstate()
    st2 = s.deSerializeFMUstate(s.serializeFMUstate(st))
    s.setFMUstate(st2)
    s.freeFMUstate(st)
    s.freeFMUstate(st2)
    s.freeInstance()
    used.append(libc.mallinfo2().uordblks)
print((used[-1] - used[9]) / 30)
"""


@pytest.mark.skipif(not os.path.exists("/proc/self/maps"), reason="glibc's mallinfo2 (Linux)")
def test_unloading_the_library_leaves_no_heap_behind(fmu_path, capsys):
    """An importer that loads and unloads the library for each run (fmpy's simulate_fmu does)
    gets back the heap the library took: nothing it allocates outlives its last instance
    (a static's heap would stay allocated after the unload: the accuracy table the start
    value of rel_tol reads took 84 kB per load, the states' parameter list 40 kB)."""
    out = subprocess.run([sys.executable, "-c", HEAP_SCRIPT, fmu_path],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    per_run = float(out.stdout.split()[-1])
    with capsys.disabled():
        print(f"\n[fmu unload] heap in use after each load, run and unload: {per_run / 1024:+.1f} kB per run")
    # fmpy's own objects take about 1 kB per run
    assert per_run < 8 * 1024, per_run


def test_speed_of_one_do_step(md, unzipdir, capsys):
    s = slave(md, unzipdir, "bench")
    init(s, md, (0.02, 0.0, 0.0, 20.0, 110e3, 20.0))
    vcx = s_vr(md, "cx")
    h, n = 1e-3, 200
    t = 0.0
    for k in range(10):  # warm-up
        s.setReal([vcx], [0.02 + 0.01 * math.sin(k / 5)])
        s.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        t += h
    start = time.perf_counter()
    for k in range(n):
        s.setReal([vcx], [0.02 + 0.01 * math.sin(k / 5)])
        s.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        t += h
    cost = (time.perf_counter() - start) / n
    nx = s.getInteger([s_vr(md, "nx")])[0]
    ny = s.getInteger([s_vr(md, "ny")])[0]
    s.freeInstance()
    with capsys.disabled():
        print(f"\n[fmu speed] one doStep(1 ms), transient ECF, default grid {nx}x{ny}, v = 20 m/s: "
              f"{cost * 1e6:.0f} us (incl. setReal), {cost / h:.3f} x real time (wall / simulated)")
    assert 0 < cost < 1.0
