"""The FMI 3.0 FMU through fmpy: validation, the variables of the FMI 2.0 FMU, outputs bit for bit equal to the FMI 2.0 FMU's, the field arrays in simulate_fmu and by hand, n_field, and states restored into fresh instances (refused across the two FMUs)."""

import os
import shutil
import subprocess

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

OUTPUTS = ["Fx", "Fy", "Mz", "f", "T_max", "T_mean", "P_fric", "frac_elastic",
           "frac_plastic", "frac_sliding", "a", "b", "p0"]
FIELDS = ["field_x", "field_p", "field_tau_x", "field_tau_c2", "field_T"]


@pytest.fixture(scope="module")
def md3(fmu3_path):
    return read_model_description(fmu3_path, validate=True)


@pytest.fixture(scope="module")
def md2(fmu_path):
    return read_model_description(fmu_path)


@pytest.fixture(scope="module")
def dirs(fmu_path, fmu3_path, tmp_path_factory):
    return (extract(fmu_path, unzipdir=str(tmp_path_factory.mktemp("fmu2"))),
            extract(fmu3_path, unzipdir=str(tmp_path_factory.mktemp("fmu3"))))


def vrs(md, *names):
    by = {v.name: v.valueReference for v in md.modelVariables}
    return [by[n] for n in names]


def slave3(md3, d, name="fmi3"):
    s = FMU3Slave(guid=md3.instantiationToken, unzipDirectory=d,
                  modelIdentifier=md3.coSimulation.modelIdentifier, instanceName=name)
    s.instantiate()
    return s


def test_fmpy_validate_reports_no_problems(fmu3_path, md3):
    assert validate_fmu(fmu3_path) == []
    assert md3.fmiVersion == "3.0"
    assert md3.modelExchange is None and md3.coSimulation.canGetAndSetFMUstate


def test_fmutool_check_reports_no_problems(fmu3_path):
    exe = shutil.which("fmutool") or os.path.join(os.path.dirname(os.sys.executable), "fmutool")
    run = subprocess.run([exe, "-input", fmu3_path, "-check"], capture_output=True, text=True)
    text = run.stdout + run.stderr
    assert run.returncode == 0, text
    assert "compliant with FMI-3.0" in text and "No semantic error against the FMI-3 standard" in text, text


def test_every_variable_of_the_fmi2_fmu_with_its_name_unit_range_start_and_description(md2, md3):
    v3 = {v.name: v for v in md3.modelVariables}
    types = {"Real": "Float64", "Integer": "Int32", "Boolean": "Boolean", "String": "String"}
    for v in md2.modelVariables:
        w = v3[v.name]
        assert (w.valueReference, w.type, w.causality, w.variability) == \
            (v.valueReference, types[v.type], v.causality, v.variability), v.name
        assert (w.unit, w.min, w.max, w.description) == (v.unit, v.min, v.max, v.description), v.name
        assert str(w.start) == str(v.start), v.name
    extra = set(v3) - {v.name for v in md2.modelVariables}
    assert extra == {"time", "n_field", *FIELDS, "field_regime"}
    for n in FIELDS + ["field_regime"]:
        assert [d.valueReference for d in v3[n].dimensions] == [v3["n_field"].valueReference]
    assert v3["n_field"].causality == "structuralParameter" and v3["n_field"].start == "80"
    # no output depends on an input at a communication point, in either FMU
    assert all(u.dependencies == [] for u in md3.outputs) and len(md3.outputs) == 19
    assert all(u.dependencies == [] for u in md2.outputs) and len(md2.outputs) == 13


def test_outputs_equal_the_fmi2_fmus_bit_for_bit(md2, md3, dirs):
    s2 = FMU2Slave(guid=md2.guid, unzipDirectory=dirs[0],
                   modelIdentifier=md2.coSimulation.modelIdentifier, instanceName="fmi2")
    s2.instantiate()
    s3 = slave3(md3, dirs[1])
    inputs = ["cx", "cy", "spin", "v", "FN"]
    for s, md in ((s2, md2), (s3, md3)):
        setr = s.setReal if s is s2 else s.setFloat64
        setr(vrs(md, *inputs), [0.002, 0.0, 0.0, 20.0, 110e3])
        if s is s2:
            s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.exitInitializationMode()
    h = 1e-3
    for k in range(20):
        u = [0.002 + 0.002 * k, 0.001, 0.05 * (k % 3), 20.0 + k, 110e3 - 1e3 * k]
        s2.setReal(vrs(md2, *inputs), u)
        s3.setFloat64(vrs(md3, *inputs), u)
        s2.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
        s3.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
        a = np.array(s2.getReal(vrs(md2, *OUTPUTS)))
        b = np.array(s3.getFloat64(vrs(md3, *OUTPUTS)))
        assert a.tobytes() == b.tobytes(), (k, a, b)
    assert a[0] > 0
    for s in (s2, s3):
        s.terminate()
        s.freeInstance()


def test_simulate_fmu_records_the_field_arrays_of_a_creepage_step(fmu3_path):
    # fmpy 0.3.32 sizes the recorded arrays by the start value of n_field (80): kept here
    n = 80
    res = simulate_fmu(fmu3_path, start_time=0.0, stop_time=0.02, output_interval=1e-3,
                       start_values={"cx": 0.001, "v": 20.0},
                       input=np.array([(0.0, 0.001), (0.005, 0.001), (0.005, 0.03), (0.02, 0.03)],
                                      dtype=[("time", float), ("cx", float)]),
                       output=["Fx", "field_x", "field_p", "field_tau_x", "field_tau_c2", "field_T", "field_regime"])
    assert res["field_p"].shape == (len(res), n)
    x, tau, t, reg = res["field_x"], res["field_tau_x"], res["field_T"], res["field_regime"]
    # leading edge (+a) first; the pressure is positive inside, the strength bounds the traction
    assert np.all(np.diff(x[-1]) < 0) and x[-1][0] > 0 > x[-1][-1]
    assert np.all(res["field_p"][-1][1:-1] > 0)
    assert np.all(np.abs(tau[-1]) <= res["field_tau_c2"][-1] * (1 + 1e-12) + 1e-6)
    # the creepage step: the traction grows, the trailing part heats up and yields
    before, after = res[res["time"] < 0.005][-1], res[-1]
    assert after["Fx"] > 1.5 * before["Fx"]
    assert np.abs(after["field_tau_x"]).max() > np.abs(before["field_tau_x"]).max()
    assert after["field_T"].max() > before["field_T"].max() + 1.0
    assert (reg[-1] > 0).sum() > (reg[0] > 0).sum() and set(np.unique(reg)) <= {0, 1, 2}
    assert t.shape == (len(res), n)


def test_n_field_is_structural_and_the_arrays_follow_it(md3, dirs):
    s = slave3(md3, dirs[1], "n_field")
    nf = vrs(md3, "n_field")
    s.enterConfigurationMode()
    s.setUInt64(nf, [7])
    s.exitConfigurationMode()
    s.enterInitializationMode()
    s.exitInitializationMode()
    s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    x = s.getFloat64(vrs(md3, "field_x"), nValues=7)
    assert len(x) == 7 and x[0] > x[-1]
    with pytest.raises(FMICallException):
        s.getFloat64(vrs(md3, "field_x"), nValues=8)
    with pytest.raises(FMICallException):
        s.setUInt64(nf, [9])
    s.terminate()
    s.freeInstance()


def test_a_state_continues_in_a_fresh_instance_and_the_fmi2_fmu_refuses_it(fmu3_path, md2, md3, dirs):
    s = slave3(md3, dirs[1], "original")
    s.setString(vrs(md3, "preset"), ["dry"])
    s.setFloat64(vrs(md3, "cx", "v", "FN"), [0.002, 20.0, 110e3])
    s.enterInitializationMode()
    s.exitInitializationMode()
    h = 1e-3
    s.setFloat64(vrs(md3, "cx"), [0.03])
    for k in range(3):
        s.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
    state = s.getFMUState()
    saved = s.serializeFMUState(state)
    s.freeFMUState(state)
    want = []
    for k in range(3, 8):
        s.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
        want.append(s.getFloat64(vrs(md3, "Fx", "T_max")) + s.getFloat64(vrs(md3, "field_T"), nValues=80))
    s.terminate()
    s.freeInstance()
    # a fresh instance by hand: deserialize, set, step (no initialization)
    f = slave3(md3, dirs[1], "fresh")
    f.setFMUState(f.deserializeFMUState(saved))
    got = []
    for k in range(3, 8):
        f.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
        got.append(f.getFloat64(vrs(md3, "Fx", "T_max")) + f.getFloat64(vrs(md3, "field_T"), nValues=80))
    assert np.array(got).tobytes() == np.array(want).tobytes()
    f.freeInstance()
    # simulate_fmu into a fresh instance
    res = simulate_fmu(fmu3_path, start_time=3 * h, stop_time=8 * h, output_interval=h,
                       fmu_state=saved, output=["Fx", "T_max"])
    assert [r["Fx"] for r in res if r["time"] > 3.5 * h] == [w[0] for w in want]
    # the FMI 2.0 FMU refuses the FMI 3.0 FMU's state, naming it
    messages = []
    cb = fmi2CallbackFunctions()
    cb.logger = fmi2CallbackLoggerTYPE(lambda env, name, st, cat, msg: messages.append(msg.decode()))
    cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(lambda n, size: None)
    cb.freeMemory = fmi2CallbackFreeMemoryTYPE(lambda p: None)
    s2 = FMU2Slave(guid=md2.guid, unzipDirectory=dirs[0],
                   modelIdentifier=md2.coSimulation.modelIdentifier, instanceName="fmi2")
    s2.instantiate(callbacks=cb)
    with pytest.raises(FMICallException):
        s2.deSerializeFMUstate(saved)
    assert any("serialized by the FMI 3.0 FMU" in m for m in messages), messages
    s2.freeInstance()
