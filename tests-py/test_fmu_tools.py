"""The FMU as commercial tools use it: every start value written before the preset (Dymola, SIMPACK), single material overrides, a fitted configuration with a data column fed from an auxiliary input, and its state restored in a fresh instance."""

import json
import os
import re
import subprocess

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave

PRESETS = ["table4.1", "dry", "wet", "dry_sanded", "wet_sanded", "twin_disc", "fastsim", "polach"]


@pytest.fixture(scope="module")
def md(fmu_path):
    return read_model_description(fmu_path, validate=True)


@pytest.fixture(scope="module")
def unzipdir(fmu_path, tmp_path_factory):
    return extract(fmu_path, unzipdir=str(tmp_path_factory.mktemp("ecf_tools")))


@pytest.fixture(scope="module")
def ecf(repo_root):
    subprocess.run(["cargo", "build", "--release", "-p", "ecf-cli"], cwd=repo_root, check=True,
                   capture_output=True)
    return str(repo_root / "target" / "release" / "ecf")


def vr(md, name):
    return next(v.valueReference for v in md.modelVariables if v.name == name)


def rel_tol_start(md):
    return next(v.start for v in md.modelVariables if v.name == "rel_tol")


def cli_grid(stderr):
    """[nx, ny] of the grid `ecf --tol` reports having chosen."""
    m = re.search(r"grid (\d+)x(\d+)", stderr)
    assert m, stderr
    return [int(m[1]), int(m[2])]


def new(md, unzipdir, name):
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
    s.instantiate()
    return s


def write_start_values(s, md, reverse):
    """What Dymola and SIMPACK do: every parameter and input gets its start value."""
    vs = [v for v in md.modelVariables if v.causality in ("parameter", "input") and v.start is not None]
    for v in (reversed(vs) if reverse else vs):
        if v.type == "Real":
            s.setReal([v.valueReference], [float(v.start)])
        elif v.type == "Integer":
            s.setInteger([v.valueReference], [int(v.start)])
        elif v.type == "Boolean":
            s.setBoolean([v.valueReference], [v.start in (True, "true", "1")])
        else:
            s.setString([v.valueReference], [v.start])


def steady(s, md, cx, v=20.0, fn=110e3):
    s.setReal([vr(md, n) for n in ("cx", "v", "FN")], [cx, v, fn])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.exitInitializationMode()
    return dict(zip(["Fx", "f", "T_max", "P_fric"], s.getReal([vr(md, n) for n in ("Fx", "f", "T_max", "P_fric")])))


@pytest.mark.parametrize("preset", PRESETS)
def test_start_values_then_preset_equal_ecf_curve(md, unzipdir, ecf, preset):
    # the grid: the one the start value of rel_tol chooses (ECF), which --tol gives the CLI
    tol = ["--tol", str(rel_tol_start(md))] if preset not in ("fastsim", "polach") else []
    cli = subprocess.run([ecf, "curve", "--preset", preset, "--v-mps", "20", "--fn-kn", "110",
                          "--cx", "0.003,0.05"] + tol, capture_output=True, text=True, check=True)
    grid = cli_grid(cli.stderr) if tol else None
    rows = [line.split(",") for line in cli.stdout.strip().splitlines()]
    for row in rows[1:]:
        ref = dict(zip(rows[0], row))
        cx = float(ref["cx"])
        for order in ("declaration", "reverse", "preset first"):
            s = new(md, unzipdir, f"{preset}-{order}")
            if order == "preset first":
                s.setString([vr(md, "preset")], [preset])
                write_start_values(s, md, reverse=False)
                # the start values wrote preset = '' again: a tool writes the user's preset last
                s.setString([vr(md, "preset")], [preset])
            else:
                write_start_values(s, md, reverse=(order == "reverse"))
                s.setString([vr(md, "preset")], [preset])
            o = steady(s, md, cx)
            if grid:
                assert s.getInteger([vr(md, "nx"), vr(md, "ny")]) == grid, (preset, order)
            # the CLI prints f with 8 decimals, Fx, T_max and P_fric with 3
            assert abs(o["f"] - float(ref["f"])) <= 0.51e-8, (preset, order, cx, o, ref)
            assert abs(o["Fx"] - float(ref["Fx_N"])) <= 0.51e-3, (preset, order, cx, o["Fx"], ref["Fx_N"])
            assert abs(o["T_max"] - float(ref["T_max_C"])) <= 0.51e-3, (preset, order, cx)
            assert abs(o["P_fric"] - float(ref["P_fric_W"])) <= 0.51e-3, (preset, order, cx)
            s.freeInstance()


def test_single_material_override_beside_start_values(md, unzipdir, ecf):
    # wet with a changed parameter: the start value of rel_tol judges it on every preset's rows
    cli = subprocess.run([ecf, "curve", "--preset", "wet", "--param", "tau_c2_0_GPa=0.5", "--v-mps", "20",
                          "--fn-kn", "110", "--cx", "0.05", "--tol", str(rel_tol_start(md))],
                         capture_output=True, text=True, check=True)
    assert "worst of dry, table4.1, wet" in cli.stderr, cli.stderr
    head, row = [line.split(",") for line in cli.stdout.strip().splitlines()]
    ref = dict(zip(head, row))
    s = new(md, unzipdir, "override")
    write_start_values(s, md, reverse=False)
    s.setString([vr(md, "preset")], ["wet"])
    s.setReal([vr(md, "tau_c2_0_GPa")], [0.5])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    # reading a parameter gives the value in force: the override and the preset's others
    assert s.getReal([vr(md, "tau_c2_0_GPa")]) == [0.5]
    s.freeInstance()
    s = new(md, unzipdir, "override2")
    write_start_values(s, md, reverse=True)
    s.setString([vr(md, "preset")], ["wet"])
    s.setReal([vr(md, "tau_c2_0_GPa")], [0.5])
    o = steady(s, md, 0.05)
    assert abs(o["Fx"] - float(ref["Fx_N"])) <= 0.51e-3, (o, ref)
    s.freeInstance()


def test_preset_fastsim_with_model_ecf_gives_a_clear_message(md, unzipdir):
    s = new(md, unzipdir, "fastsim-ecf")
    s.setString([vr(md, "model")], ["ecf"])
    s.setString([vr(md, "preset")], ["fastsim"])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    with pytest.raises(FMICallException):
        s.exitInitializationMode()
    s.freeInstance()


def fitted_config(ecf, repo_root, tmp_path):
    ex = repo_root / "examples" / "measurements"
    out = tmp_path / "fitted.json"
    subprocess.run([ecf, "fit", str(ex / "humid.csv"), "--config", str(ex / "dry-humid.json"),
                    "--free", "humid.k,tau_c2_0_GPa", "--out", str(out)], check=True, capture_output=True)
    return out


def test_fitted_configuration_with_a_data_column_equals_ecf_compare(md, unzipdir, ecf, repo_root, tmp_path):
    cfg = fitted_config(ecf, repo_root, tmp_path)
    data = repo_root / "examples" / "measurements" / "humid.csv"
    cmp = json.loads(subprocess.run([ecf, "compare", str(data), "--config", str(cfg), "--json"],
                                    capture_output=True, text=True, check=True).stdout)
    lines = data.read_text().strip().splitlines()
    head = lines[0].split(",")
    by_line = {r["line"]: r for r in cmp["rows"]}
    assert len(by_line) == len(lines) - 1
    for i, line in enumerate(lines[1:], start=2):
        row = dict(zip(head, line.split(",")))
        s = new(md, unzipdir, f"humid-{i}")
        write_start_values(s, md, reverse=False)
        s.setString([vr(md, "config_file"), vr(md, "columns")], [str(cfg), "humidity=aux1"])
        s.setReal([vr(md, "aux1"), vr(md, "T_bulk")], [float(row["humidity"]), 20.0])
        o = steady(s, md, float(row["cx"]), float(row["v_mps"]), 1e3 * float(row["fn_kN"]))
        # the same configuration, inputs and column value: the same number, bit for bit
        assert o["f"] == by_line[i]["f_model"], (i, o["f"], by_line[i])
        s.freeInstance()


def test_formula_configuration_state_restores_in_a_fresh_instance(md, unzipdir, ecf, repo_root, tmp_path):
    cfg = fitted_config(ecf, repo_root, tmp_path)

    def start(name):
        s = new(md, unzipdir, name)
        s.setString([vr(md, "config_file"), vr(md, "columns")], [str(cfg), "humidity=aux1"])
        s.setReal([vr(md, "aux1")], [30.0])
        steady(s, md, 0.02, 10.0, 110e3)
        return s

    a = start("formula-a")
    for k in range(3):
        a.setReal([vr(md, "aux1"), vr(md, "cx")], [30.0 + 10 * k, 0.02 + 0.01 * k])
        a.doStep(currentCommunicationPoint=k * 1e-4, communicationStepSize=1e-4)
    st = a.getFMUstate()
    data = a.serializeFMUstate(st)
    a.freeFMUstate(st)
    b = start("formula-b")
    st = b.deSerializeFMUstate(data)
    b.setFMUstate(st)
    b.freeFMUstate(st)
    fx = vr(md, "Fx")
    for k in range(3, 6):
        for s in (a, b):
            s.setReal([vr(md, "aux1"), vr(md, "cx")], [70.0 - 5 * k, 0.05])
            s.doStep(currentCommunicationPoint=k * 1e-4, communicationStepSize=1e-4)
        assert a.getReal([fx]) == b.getReal([fx]), k
    # the humidity acts: another value gives another force
    a.setReal([vr(md, "aux1")], [90.0])
    a.doStep(currentCommunicationPoint=6e-4, communicationStepSize=1e-4)
    b.setReal([vr(md, "aux1")], [20.0])
    b.doStep(currentCommunicationPoint=6e-4, communicationStepSize=1e-4)
    assert a.getReal([fx])[0] < b.getReal([fx])[0]
    a.freeInstance()
    b.freeInstance()


def test_unmapped_column_names_the_parameter(md, unzipdir, repo_root):
    s = new(md, unzipdir, "unmapped")
    s.setString([vr(md, "config_file")], [str(repo_root / "examples" / "measurements" / "dry-humid.json")])
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    with pytest.raises(FMICallException):
        s.exitInitializationMode()
    s.freeInstance()


def test_package_has_icon_html_documentation_and_extra_platform_binaries(fmu_path, repo_root, tmp_path):
    import zipfile
    with zipfile.ZipFile(fmu_path) as z:
        names = z.namelist()
        assert "model.png" in names and z.read("model.png")[:8] == b"\x89PNG\r\n\x1a\n"
        page = z.read("documentation/index.html").decode()
    # real HTML, not the markdown in <pre>: headings, tables
    assert "<h2>Variables</h2>" in page and "<table>" in page and "<pre><code" in page
    # a win64 binary built elsewhere is packed beside linux64 (here a stand-in with the PE magic)
    dll = tmp_path / "ecf_contact.dll"
    dll.write_bytes(b"MZ" + b"\0" * 62)
    out = tmp_path / "multi.fmu"
    env = dict(os.environ, ECF_FMU_OUT=str(out))
    run = subprocess.run(["bash", "scripts/build-fmu.sh", "--binary", f"win64={dll}"], cwd=repo_root,
                         env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-2000:]
    with zipfile.ZipFile(out) as z:
        assert {"binaries/linux64/ecf_contact.so", "binaries/win64/ecf_contact.dll"} <= set(z.namelist())
    # a file of the wrong format is refused before anything is built
    bad = subprocess.run(["bash", "scripts/build-fmu.sh", "--binary", f"darwin64={dll}"], cwd=repo_root,
                         env=env, capture_output=True, text=True)
    assert bad.returncode == 2 and "not a darwin64 shared library" in bad.stderr, bad.stderr
