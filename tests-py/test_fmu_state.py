"""FMU states across instances through fmpy: simulate_fmu(fmu_state=...) continues a serialized state in a fresh instance (docs/fmu.md, "FMU state")."""

from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Slave


def test_simulate_fmu_continues_a_serialized_state_as_the_original_instance(fmu_path):
    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(fmu_path),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="original")
    fmu.instantiate()
    fmu.setString([vr["preset"]], ["dry"])
    fmu.setReal([vr["cx"], vr["v"], vr["FN"]], [0.002, 20.0, 110e3])
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    h, t = 1e-3, 0.0
    fmu.setReal([vr["cx"]], [0.03])  # a creepage step: the grid is far from steady when saved
    for k in range(3):
        fmu.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
    t = 3 * h
    state = fmu.getFMUState()
    saved = fmu.serializeFMUState(state)
    fmu.freeFMUState(state)
    want = []
    for k in range(3, 8):
        fmu.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
        want.append(fmu.getReal([vr["Fx"], vr["T_max"]]))
    fmu.terminate()
    fmu.freeInstance()

    # a fresh instance: instantiate, deserialize, set the state, step (no initialization)
    res = simulate_fmu(fmu_path, start_time=t, stop_time=8 * h, output_interval=h,
                       fmu_state=saved, output=["Fx", "T_max"])
    got = [(r["Fx"], r["T_max"]) for r in res if r["time"] > t + h / 2]
    assert len(got) == len(want) == 5
    for (fx, tm), (wfx, wtm) in zip(got, want):
        assert abs(fx - wfx) <= 1e-12 * abs(wfx) and abs(tm - wtm) <= 1e-12 * abs(wtm), (got, want)
    # and the continuation is not the state it started from: the step response goes on
    assert abs(got[-1][1] - got[0][1]) > 1e-3
