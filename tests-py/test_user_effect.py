"""A user's own Rust effect without forking: examples/user-effect (oil_film) is linked by
`scripts/build-fmu.sh --effects`, fitted by that `ecf`, and run by that FMU through fmpy;
the project's own `ecf` and FMU do not know it."""

import csv
import io
import json
import os
import subprocess

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave

H0_TRUE = 0.5  # um, the film thickness scale the "measurements" are made with
FILMS = [0.0, 0.25, 0.5, 1.0, 2.0]  # um
CXS = [0.002, 0.01, 0.03, 0.1]


@pytest.fixture(scope="module")
def built(repo_root, fmu_path):
    """(ecf, fmu) with examples/user-effect linked in (fmu_path first: the shared build).
    Linux only: these tests run the FMU through fmpy here; the Windows and macOS builds of
    `--effects` go through the same cross() of scripts/build-fmu.sh as the shipped FMU, which
    the session's fmu_path builds and tests-py/test_platforms.py checks (this saves CI about a
    minute of three cross links)."""
    r = subprocess.run(["bash", "scripts/build-fmu.sh", "--linux-only", "--effects", "examples/user-effect"],
                       cwd=repo_root, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-4000:]
    fmu = r.stdout.strip().splitlines()[-1]
    ecf = repo_root / "dist" / "with-user_effect_example" / "ecf"
    assert os.path.isfile(fmu) and ecf.is_file(), (fmu, ecf)
    return str(ecf), fmu


def config(tmp_path, h0, name):
    p = tmp_path / name
    p.write_text(json.dumps({"preset": "dry", "grid": {"nx": 20, "ny": 7},
                             "custom_effects": [{"name": "oil_film", "params": {"h0_um": h0}}]}))
    return p


def test_only_the_build_with_effects_knows_the_effect(built, repo_root):
    ecf, _ = built
    assert "oil_film (scales tau_c2)" in subprocess.run([ecf, "info"], capture_output=True, text=True,
                                                        check=True).stdout
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "ecf-cli"], cwd=repo_root, check=True)
    plain = subprocess.run([str(repo_root / "target" / "release" / "ecf"), "info"], capture_output=True,
                           text=True, check=True).stdout
    assert "humidity_softening" in plain and "oil_film" not in plain


def test_fit_recovers_the_film_scale_from_files_made_with_it(built, tmp_path):
    ecf, _ = built
    truth = config(tmp_path, H0_TRUE, "truth.json")
    rows = []
    for h in FILMS:
        out = subprocess.run([ecf, "curve", "--config", str(truth), "--v-mps", "10", "--fn-kN", "110",
                              "--extra", f"oil_um={h}", "--cx", ",".join(map(str, CXS))],
                             capture_output=True, text=True, check=True).stdout
        for r in csv.DictReader(io.StringIO(out)):
            rows.append((r["cx"], r["f"], h))
    data = tmp_path / "oil.csv"
    data.write_text("cx,f,v_mps,fn_kN,oil_um\n" + "".join(f"{c},{f},10,110,{h}\n" for c, f, h in rows))
    # the film lowers the traction: the effect acts through the data column
    f_dry = [float(f) for c, f, h in rows if h == 0.0]
    f_oil = [float(f) for c, f, h in rows if h == 2.0]
    assert all(o < 0.9 * d for o, d in zip(f_oil[1:], f_dry[1:])), (f_dry, f_oil)
    start = config(tmp_path, 2.0, "start.json")
    fitted = tmp_path / "fitted.json"
    r = subprocess.run([ecf, "fit", str(data), "--config", str(start), "--free", "oil_film.h0_um",
                        "--out", str(fitted), "--json"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    got = json.loads(fitted.read_text())["custom_effects"][0]["params"]["h0_um"]
    assert abs(got / H0_TRUE - 1) < 1e-3, got


def test_fmu_with_effects_runs_it_and_the_shipped_fmu_refuses_it(built, fmu_path, tmp_path):
    _, fmu = built

    def fx(path, film, instance):
        md = read_model_description(path, validate=True)
        d = extract(path, unzipdir=str(tmp_path / instance))
        vr = {v.name: v.valueReference for v in md.modelVariables}
        s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                      instanceName=instance)
        s.instantiate()
        try:
            s.setString([vr["config_file"], vr["columns"]],
                        [str(config(tmp_path, H0_TRUE, "fmu.json")), "oil_um=aux1"])
            s.setReal([vr["aux1"], vr["cx"], vr["v"], vr["FN"]], [film, 0.03, 10.0, 110e3])
            s.setupExperiment(startTime=0.0)
            s.enterInitializationMode()
            s.exitInitializationMode()
            s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
            return s.getReal([vr["Fx"]])[0]
        finally:
            s.freeInstance()

    dry, oily = fx(fmu, 0.0, "dry"), fx(fmu, 2.0, "oily")
    assert 0 < oily < 0.9 * dry, (dry, oily)
    with pytest.raises(FMICallException):
        fx(fmu_path, 0.0, "shipped")
