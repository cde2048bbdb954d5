"""Package, public API, provenance of results, option errors, condition-matched FASTSIM, baselines and
the `regress` command (docs/drivetrain.md). Short runs (t_end 0.8 s, small grids) to keep CI fast."""

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "drivetrain-demo"))

import drivetrain_demo as dd  # noqa: E402
from drivetrain_demo import contact, scenarios  # noqa: E402


def _cli(*args, env=None):
    e = dict(os.environ, PYTHONPATH=str(ROOT / "drivetrain-demo"))
    e.update(env or {})
    return subprocess.run([sys.executable, "-m", "drivetrain_demo", *args], capture_output=True, text=True, env=e,
                          cwd=ROOT)


def test_pip_install_and_import_outside_the_source_tree(tmp_path, fmu_path):
    """`pip install ./drivetrain-demo` works; the installed package finds its data and the FMU via $ECF_FMU_PATH."""
    target = tmp_path / "site"
    r = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target", str(target),
                        str(ROOT / "drivetrain-demo")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    code = ("import drivetrain_demo as d, json; m = d.modal('ecf', v_mps=5.0); "
            "print(json.dumps([d.__file__, m.predicted_frequency_hz, m.predicted_unstable, d.find_fmu() is not None]))")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "ECF_CONTACT_FMU")}
    env.update(PYTHONPATH=str(target), ECF_FMU_PATH=str(fmu_path))
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]
    path, f, unstable, found = json.loads(r.stdout)
    assert path.startswith(str(target))
    assert 50 < f < 58 and unstable is True and found is True
    # the package was built from the source tree without leaving build output in it
    for junk in ("build", "drivetrain_demo.egg-info"):
        if (ROOT / "drivetrain-demo" / junk).exists():
            subprocess.run(["rm", "-rf", str(ROOT / "drivetrain-demo" / junk)])


def test_api_raises_exceptions_not_system_exit(fmu_path, tmp_path, monkeypatch):
    with pytest.raises(dd.ConfigError, match="--preset humid: unknown .*wet"):
        dd.simulate("step", preset="humid", fmu=fmu_path)
    with pytest.raises(dd.ConfigError, match="--t-end 0.5: too short"):
        dd.simulate("step", t_end_s=0.5, fmu=fmu_path)
    with pytest.raises(dd.ConfigError, match="--set C_X"):
        dd.simulate("step", overrides={"C_X": 1.0}, fmu=fmu_path)
    with pytest.raises(dd.FMUNotFoundError):
        dd.simulate("step", fmu=tmp_path / "missing.fmu")
    monkeypatch.setenv("ECF_FMU_PATH", str(tmp_path / "nope.fmu"))
    with pytest.raises(dd.FMUNotFoundError, match="ECF_FMU_PATH"):
        dd.find_fmu()
    monkeypatch.setenv("ECF_FMU_PATH", str(fmu_path))
    assert dd.find_fmu() == Path(fmu_path)
    with pytest.raises(dd.ConfigError, match="--fmu-param bogus"):
        dd.simulate("step", contact="fastsim", t_end_s=0.8, grid=(10, 5), fmu_params={"bogus": 1})


def test_api_simulate_result_and_provenance(fmu_path, tmp_path):
    r = dd.simulate("step", contact="fastsim", preset="wet", overrides={"K_p": 1500.0}, t_end_s=0.8, grid=(10, 5),
                    fmu=fmu_path, out=tmp_path, save_every=8)
    s = r.summary
    prov = s["provenance"]
    assert prov["preset"] == "wet" and prov["condition"] == "wet"
    assert prov["overrides"] == {"K_p": 1500.0}
    assert prov["fmu_params"] == {"mu": scenarios.FASTSIM_MU["wet"]}
    assert prov["grid"] == [10, 5] and prov["project_version"] == dd.__version__
    sha = hashlib.sha256(Path(fmu_path).read_bytes()).hexdigest()
    assert prov["fmu_identity"]["sha256"] == sha and prov["fmu_identity"]["version"]
    assert 50 < r.predicted_frequency_hz < 58 and r.predicted_unstable is False
    # files carry the preset; the trace is decimated (3201 rows -> every 8th, last kept)
    names = sorted(p.name for p in r.files)
    assert "step_fastsim_wet_v5.csv" in names and "step_fastsim_wet_v5.json" in names
    rows = (tmp_path / "step_fastsim_wet_v5.csv").read_text().splitlines()
    assert len(rows) - 1 == 3200 // 8 + 1
    assert float(rows[-1].split(",")[0]) == pytest.approx(0.8)
    on_disk = json.loads((tmp_path / "step_fastsim_wet_v5.json").read_text())
    assert on_disk["provenance"]["overrides"] == {"K_p": 1500.0}
    assert not list(tmp_path.glob(".*"))  # no temporary files left behind


def test_condition_matched_fastsim_mu_table_is_what_the_fmu_gives(fmu_path):
    """FASTSIM_MU = 0.25 x max f_ECF,P / max f_ECF,dry, recomputed from the FMU's steady curves."""
    for preset, mu in scenarios.FASTSIM_MU.items():
        assert scenarios.condition_mu(preset, fmu_path) == pytest.approx(mu, abs=0.0015), preset
    assert scenarios.FASTSIM_MU["wet"] < scenarios.FASTSIM_MU["dry"] == 0.25


@pytest.mark.parametrize("args, option", [
    (["step", "--preset", "humid"], "--preset"),
    (["step", "--t-end", "0.1"], "--t-end 0.1"),
    (["step", "--t-end", "0.5"], "--t-end 0.5"),
    (["ramp", "--t-end", "0.9"], "--t-end 0.9"),
    (["step", "--save-every", "0"], "--save-every"),
    (["step", "--model", "polach", "--preset", "wet"], "--preset wet with --model polach"),
    (["regress", "does-not-exist.json"], "baseline does-not-exist.json not found"),
    (["sweep", "missing.toml", "--out", "/tmp/x-never"], "sweep file missing.toml not found"),
])
def test_bad_options_give_one_line_errors(args, option, fmu_path):
    r = _cli(*args, env={"ECF_FMU_PATH": fmu_path})
    assert r.returncode == 2, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert option in lines[0] and "error" in lines[0]
    assert "Traceback" not in r.stderr


def test_preset_humid_lists_accepted_values():
    r = _cli("step", "--preset", "humid")
    for c in scenarios.CONDITIONS:
        assert c in r.stderr


def test_model_both_under_wet_and_dry_into_one_out(fmu_path, tmp_path):
    """--preset wet --model both runs (FASTSIM with the wet mu); a dry run into the same --out keeps the wet files."""
    r = _cli("step", "--model", "both", "--preset", "wet", "--t-end", "0.8", "--grid", "10x5", "--out", str(tmp_path),
             "--json", "--quiet", "--fmu", fmu_path)
    assert r.returncode == 0, r.stderr[-3000:]
    s = json.loads(r.stdout)
    assert s["fastsim"]["provenance"]["fmu_params"]["mu"] == scenarios.FASTSIM_MU["wet"]
    assert s["ecf"]["provenance"]["fmu_preset"] == "wet"
    wet = (tmp_path / "step_fastsim_wet_v5.json").read_text()
    r = _cli("step", "--model", "fastsim", "--preset", "dry", "--t-end", "0.8", "--grid", "10x5", "--out",
             str(tmp_path), "--quiet", "--fmu", fmu_path)
    assert r.returncode == 0, r.stderr[-3000:]
    assert (tmp_path / "step_fastsim_wet_v5.json").read_text() == wet
    dry = json.loads((tmp_path / "step_fastsim_dry_v5.json").read_text())
    assert dry["provenance"]["fmu_params"]["mu"] == 0.25
    assert (tmp_path / "step_compare_wet_v5.png").is_file()


def test_short_run_analysis_window_follows_run_length(fmu_path):
    """The shortest accepted step (0.8 s) analyses 0.3-0.8 s and finds the ~54 Hz step response (not the band edge)."""
    r = dd.simulate("step", contact="fastsim", t_end_s=0.8, grid=(10, 5), fmu=fmu_path)
    assert r.summary["settled_window_s"] == [pytest.approx(0.3), pytest.approx(0.8)]
    assert r.dominant_frequency_hz == pytest.approx(r.predicted_frequency_hz, rel=0.03)


def test_save_baseline_and_regress(fmu_path, tmp_path):
    base = tmp_path / "base.json"
    r = _cli("step", "--model", "fastsim", "--t-end", "0.8", "--grid", "10x5", "--out", str(tmp_path), "--quiet",
             "--set", "K_p=1200", "--save-baseline", str(base), "--fmu", fmu_path)
    assert r.returncode == 0, r.stderr[-3000:]
    b = json.loads(base.read_text())
    assert b["runs"][0]["run"]["params"]["K_p"] == 1200.0
    r = _cli("regress", str(base), "--fmu", fmu_path, "--quiet")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "OK: 0 of 1" in r.stdout
    # a moved frequency and a flipped verdict are reported, exit code 1
    b["runs"][0]["expected"]["predicted_frequency_hz"] += 2.0
    b["runs"][0]["expected"]["predicted_unstable"] = True
    moved = tmp_path / "moved.json"
    moved.write_text(json.dumps(b))
    r = _cli("regress", str(moved), "--fmu", fmu_path, "--quiet")
    assert r.returncode == 1, r.stdout + r.stderr
    assert "REGRESSION: 1 of 1" in r.stdout
    bad = [l for l in r.stdout.splitlines() if "!!" in l]
    assert any("predicted_frequency_hz" in l and "-2.000 Hz" in l for l in bad), r.stdout
    assert any("predicted_unstable" in l for l in bad), r.stdout
    # a larger tolerance accepts the frequency, the verdict still fails
    r = _cli("regress", str(moved), "--fmu", fmu_path, "--quiet", "--tolerance-hz", "2.5")
    assert r.returncode == 1 and "predicted_frequency_hz" not in "".join(l for l in r.stdout.splitlines() if "!!" in l)


def test_shipped_baseline_is_valid():
    """The CI baseline (run by scripts/test-all.sh through `regress`) covers ECF (oscillating) and FASTSIM (decaying)."""
    from drivetrain_demo import regress
    b = regress.load(ROOT / "drivetrain-demo" / "baselines" / "ci.json")
    models = {e["run"]["contact"]: e["expected"] for e in b["runs"]}
    assert models["ecf"]["sustained_oscillation"] is True and models["fastsim"]["sustained_oscillation"] is False
    assert 50 < models["ecf"]["dominant_frequency_hz"] < 56


def test_contact_uses_no_private_fmpy_attributes():
    src = (ROOT / "drivetrain-demo" / "drivetrain_demo" / "contact.py").read_text()
    assert "._functions" not in src and "_fmi2Function" not in src


def test_fmu_content_hash_ignores_zip_time_stamps(fmu_path, tmp_path):
    """Sweep resume keys on the FMU's content: an identical rebuild (new zip time stamps) keeps it, a changed member does not."""
    import zipfile
    src = zipfile.ZipFile(fmu_path)
    same, changed = tmp_path / "same.fmu", tmp_path / "changed.fmu"
    for dst, touch in ((same, None), (changed, "modelDescription.xml")):
        with zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as z:
            for info in src.infolist():
                data = src.read(info.filename)
                if info.filename == touch:
                    data += b"\n"
                z.writestr(zipfile.ZipInfo(info.filename, date_time=(2001, 2, 3, 4, 5, 6)), data)
    a, b, c = (contact.fmu_identity(p) for p in (fmu_path, same, changed))
    assert a["sha256"] != b["sha256"] and a["content_sha256"] == b["content_sha256"]
    assert c["content_sha256"] != a["content_sha256"]


def test_atomic_write_leaves_no_partial_file_and_normal_permissions(tmp_path):
    from drivetrain_demo import io_util
    target = tmp_path / "x.csv"
    with pytest.raises(RuntimeError):
        with io_util.atomic_path(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("interrupted")
    assert not target.exists() and list(tmp_path.iterdir()) == []
    io_util.write_csv(target, {"t_s": [0.0, 1.0]})
    umask = os.umask(0)
    os.umask(umask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~umask
