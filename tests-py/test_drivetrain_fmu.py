"""Drive-train co-simulation with the contact FMU (one FMU2Slave instance per wheel).

CI settings (documented in docs/drivetrain.md): the demo's bristle grid scenarios.DEFAULT_GRID, 14x7
(FMU parameters nx, ny; the FMU's default scheme),
communication step h = 0.25 ms, step scenario of T_STEP simulated seconds, transient ECF.
Every check compares simulation output with a physical expectation or with the linear
analysis; nothing here is a stored result.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "drivetrain-demo"))

from drivetrain_demo import params, scenarios  # noqa: E402

GRID = scenarios.DEFAULT_GRID
H = 2.5e-4
T_STEP = 2.5  # s: at 5 m/s the limit cycle is reached ~1.7 s after the step
T_STEP_10 = 3.5  # s: at 10 m/s the growth rate is ~1/6 of that at 5 m/s; limit cycle after ~2.5 s


@pytest.fixture(scope="session")
def contact_fmu(fmu_path):
    """The packed contact FMU from the shared conftest fixture (built once per session, or $ECF_FMU_PATH)."""
    return Path(fmu_path)


_cache = {}


def run(contact_fmu, scenario="step", model="ecf", v=5.0, h=H, t_end=T_STEP, grid=GRID, p=None, key=None, **kw):
    key = key or (scenario, model, v, h, t_end, grid)
    if key not in _cache:
        cfg = scenarios.RunConfig(scenario=scenario, model=model, v=v, h=h, t_end=t_end, grid=grid, contact="fmu",
                                  fmu=str(contact_fmu), progress=False, **kw)
        _cache[key] = scenarios.run(cfg, p or params.load(), write=False, plot=False)
    return _cache[key]


def test_step_ecf_sustained_oscillation_53_Hz(contact_fmu):
    """CI regression of the oscillation frequency: ECF, step 0 -> 15 % at 5 m/s."""
    s, _ = run(contact_fmu)
    assert 50.0 <= s["dominant_frequency_hz"] <= 56.0, s["dominant_frequency_hz"]
    # sustained: a large oscillation of the long-axle creepage that does not decay
    assert s["oscillation_amplitude"] > 0.02, s["oscillation_amplitude"]
    assert s["pp_last_0.25s"] > 0.8 * s["pp_prev_0.25s"], (s["pp_last_0.25s"], s["pp_prev_0.25s"])


def test_step_fastsim_oscillation_decays(contact_fmu):
    s, _ = run(contact_fmu, model="fastsim")
    e, _ = run(contact_fmu)
    assert s["oscillation_amplitude"] < 0.05 * e["oscillation_amplitude"], (s["oscillation_amplitude"],
                                                                             e["oscillation_amplitude"])
    # the step excites the ~54 Hz mode and its amplitude decays by orders of magnitude
    # (ECF: it grows); what is left in c_x,L is broadband numerical noise of ~1e-5
    assert s["mode_amplitude_late"] < 1e-2 * s["mode_amplitude_early"], (s["mode_amplitude_early"],
                                                                         s["mode_amplitude_late"])
    assert e["mode_amplitude_late"] > 100 * e["mode_amplitude_early"]
    assert s["sustained_oscillation"] is False and e["sustained_oscillation"] is True
    assert s["transient_frequency_hz"] == pytest.approx(s["predicted_frequency_hz"], rel=0.05)
    assert abs(s["mean_cx_L_last_0.5s"] - 0.15) < 0.005  # the controller holds 15 %


def test_linear_analysis_predicts_simulation(contact_fmu):
    e, _ = run(contact_fmu)
    f, _ = run(contact_fmu, model="fastsim")
    assert e["predicted_unstable"] is True
    assert f["predicted_unstable"] is False
    assert e["predicted_frequency_hz"] == pytest.approx(e["dominant_frequency_hz"], rel=0.05)


def test_stiffness_change_moves_frequency_as_predicted(contact_fmu):
    """Softer long axle (C_L x 0.7): the simulated frequency shift matches the linear analysis."""
    p0 = params.load()
    p1 = p0.with_drivetrain(C_L=0.7 * p0.drivetrain.C_L)
    a, _ = run(contact_fmu)
    b, _ = run(contact_fmu, p=p1, key="soft")
    sim_ratio = b["dominant_frequency_hz"] / a["dominant_frequency_hz"]
    lin_ratio = b["predicted_frequency_hz"] / a["predicted_frequency_hz"]
    assert sim_ratio < 0.95  # it moved, clearly
    assert sim_ratio == pytest.approx(lin_ratio, rel=0.02), (sim_ratio, lin_ratio)
    assert b["predicted_unstable"] and b["oscillation_amplitude"] > 0.02


def test_amplitude_lower_at_10_than_at_5_mps(contact_fmu):
    """Seed Sec. 3.1.2: the oscillation amplitude falls with vehicle speed (limit cycles compared)."""
    a, _ = run(contact_fmu)
    b, _ = run(contact_fmu, v=10.0, t_end=T_STEP_10)
    assert a["pp_last_0.25s"] == pytest.approx(a["pp_prev_0.25s"], rel=0.15)  # 5 m/s has settled
    assert b["oscillation_amplitude"] < a["oscillation_amplitude"], (a["oscillation_amplitude"],
                                                                     b["oscillation_amplitude"])
    assert b["pp_last_0.25s"] == pytest.approx(b["pp_prev_0.25s"], rel=0.15)  # 10 m/s has settled too


def test_communication_step_halved_frequency_within_1_percent(contact_fmu):
    a, _ = run(contact_fmu)
    b, _ = run(contact_fmu, h=H / 2)
    assert b["dominant_frequency_hz"] == pytest.approx(a["dominant_frequency_hz"], rel=0.01)


def test_frequency_insensitive_to_bristle_grid(contact_fmu):
    """The CI grid (14x7) against 10x5 (and, in docs/drivetrain.md, up to 80x21): frequency within 1 %."""
    a, _ = run(contact_fmu)
    b, _ = run(contact_fmu, grid=(10, 5))
    assert b["dominant_frequency_hz"] == pytest.approx(a["dominant_frequency_hz"], rel=0.01)


def test_sine_hysteresis_encircles_steady_curve(contact_fmu):
    """Fig. 6.6: with transient ECF the f(c_x) loop has an area; quasi-steady ECF retraces the curve."""
    tr, _ = run(contact_fmu, scenario="sine", t_end=10 / 53.0)
    qs, _ = run(contact_fmu, scenario="sine", t_end=10 / 53.0, transient=False, key="sine-qs")
    assert abs(tr["hysteresis_loop_area"]) > 10 * abs(qs["hysteresis_loop_area"])
    assert qs["cv_rmse_vs_steady_percent"] < 1.0
    assert tr["cv_rmse_vs_steady_percent"] > 10 * qs["cv_rmse_vs_steady_percent"]
