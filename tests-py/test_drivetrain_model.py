"""Drive-train equations, energy conservation of the integrator, modal analysis, CLI errors (no FMU needed)."""

import dataclasses
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "drivetrain-demo"))

from drivetrain_demo import model, params, stability  # noqa: E402

P = params.load()


def _rhs_spec(dt, x, u, tau_f):
    """Model-spec §10 written out term by term (independent of the matrix assembly)."""
    pL, pS, pM, pG, wL, wS, wM, wG, wf = x
    FL, FS, TM = u
    j = dt.j_G
    aL = (dt.C_L * (pG - pL) + dt.D_L * (wG - wL) - FL * dt.R) / dt.J_L
    aS = (dt.C_S * (pG - pS) + dt.D_S * (wG - wS) - FS * dt.R) / dt.J_S
    aM = (dt.C_M * (j * pG - pM) + dt.D_M * (j * wG - wM) + TM) / dt.J_M
    aG = (dt.C_L * (pL - pG) + dt.C_S * (pS - pG) + j * dt.C_M * (pM - j * pG)
          + dt.D_L * (wL - wG) + dt.D_S * (wS - wG) + j * dt.D_M * (wM - j * wG)) / dt.J_G
    return np.array([wL, wS, wM, wG, aL, aS, aM, aG, (wM - wf) / tau_f])


def test_state_space_matches_model_spec_equations():
    rng = np.random.default_rng(1)
    A, B = model.state_space(P.drivetrain, P.controller.tau_f)
    for _ in range(5):
        x = rng.normal(size=9) * np.array([1e-3] * 4 + [10] * 5)
        u = rng.normal(size=3) * np.array([3e4, 3e4, 5e3])
        np.testing.assert_allclose(A @ x + B @ u, _rhs_spec(P.drivetrain, x, u, P.controller.tau_f),
                                   rtol=1e-10, atol=1e-9)


def test_energy_conserved_undamped_no_torque_no_contact():
    """D = 0, T_M = 0, F = 0: the exact (matrix-exponential) step conserves E to round-off.

    Step h = 0.25 ms (the default communication step), 40 000 steps (10 s) from a random
    state with twisted shafts; tolerance |E - E0|/E0 < 1e-10 (measured 7e-13)."""
    dt = dataclasses.replace(P.drivetrain, D_L=0.0, D_S=0.0, D_M=0.0)
    st = model.Stepper(dt, P.controller.tau_f, 2.5e-4)
    rng = np.random.default_rng(7)
    x = model.rolling_state(dt, 5.0, 0.1)
    x[:4] += rng.normal(scale=2e-3, size=4)
    x[4:8] += rng.normal(scale=0.5, size=4)
    E0 = model.energy(dt, x)
    Es = []
    for k in range(40000):
        x = st.step(x, (0.0, 0.0, 0.0))
        if k % 1000 == 0:
            Es.append(model.energy(dt, x))
    Es.append(model.energy(dt, x))
    drift = np.max(np.abs(np.array(Es) - E0)) / E0
    assert drift < 1e-10, drift
    # the shafts really oscillated (energy moved between kinetic and elastic parts)
    assert abs(dt.C_L * (x[3] - x[0])) > 0


def test_energy_balance_with_damping_and_inputs():
    """E(t) - E(0) = work of T_M and the contact forces - dissipation (trapezoid in time, h = 0.05 ms)."""
    dt = P.drivetrain
    h = 5e-5
    st = model.Stepper(dt, P.controller.tau_f, h)
    x = model.rolling_state(dt, 5.0, 0.0)
    x[4] += 0.3
    D = model.damping_matrix(dt)
    u = np.array([2e4, 1e4, 3e3])
    E0 = model.energy(dt, x)
    work = 0.0
    for _ in range(4000):
        w0 = x[4:8].copy()
        x1 = st.step(x, u)
        w1 = x1[4:8]
        p0 = -u[0] * dt.R * w0[0] - u[1] * dt.R * w0[1] + u[2] * w0[2] - w0 @ D @ w0
        p1 = -u[0] * dt.R * w1[0] - u[1] * dt.R * w1[1] + u[2] * w1[2] - w1 @ D @ w1
        work += 0.5 * h * (p0 + p1)
        x = x1
    dE = model.energy(dt, x) - E0
    assert abs(dE - work) < 1e-4 * abs(work), (dE, work)


def test_modal_analysis_wheel_on_long_axle_mode_near_53_Hz():
    """The frequencies come from the parameter file: one torsional mode lies in 50-57 Hz and it
    is the mode of the wheel on the long axle against the motor."""
    modes = stability.undamped_modes(P)
    assert abs(modes[0].frequency_hz) < 1e-3  # rigid rotation
    m53 = [m for m in modes if 50.0 < m.frequency_hz < 57.0]
    assert len(m53) == 1
    shape = m53[0].shape  # wheel L, wheel S, motor/j_G, gear
    assert shape[0] == pytest.approx(1.0)
    assert shape[2] > 0.25 and m53[0].phase_deg[2] == 180.0


def test_stiffness_moves_mode_as_sqrt_of_stiffness_when_dominant():
    """Softening the long axle lowers the ~54 Hz mode; rigid motor coupling check of monotonicity."""
    f0 = [m.frequency_hz for m in stability.undamped_modes(P)][1]
    f1 = [m.frequency_hz for m in stability.undamped_modes(P.with_drivetrain(C_L=0.8 * P.drivetrain.C_L))][1]
    assert f1 < f0
    assert np.sqrt(0.8) * f0 < f1  # the mode is not a pure C_L/J_L oscillator: shift below sqrt scaling


def test_contact_damping_sign_eq_6_4():
    """A falling characteristic (f' < 0) is negative damping and destabilizes the ~54 Hz mode; f' = 0 leaves it stable."""
    falling = stability.analyse(P, 5.0, 0.15, 0.33, -0.56)
    flat = stability.analyse(P, 5.0, 0.15, 0.25, 0.0)
    assert falling["D_C_Ns_per_m"] > 0 and falling["wheel_damping_Nms_per_rad"] < 0
    assert falling["predicted_unstable"] and not flat["predicted_unstable"]
    assert 50 < falling["predicted_frequency_hz"] < 58


def _cli(*args):
    env = dict(os.environ, PYTHONPATH=str(ROOT / "drivetrain-demo"))
    return subprocess.run([sys.executable, "-m", "drivetrain_demo", *args], capture_output=True, text=True, env=env,
                          cwd=ROOT)


@pytest.mark.parametrize("args, msg", [
    (["step", "--v-mps", "-5"], "--v-mps must be > 0"),
    (["step", "--grid", "16by9"], "expected NXxNY"),
    (["bogus"], "invalid choice"),
    (["step", "--model", "kalker"], "invalid choice"),
    (["step", "--set", "C_X=1"], "unknown"),
    (["step", "--cx", "15"], "creepage must be in [0, 1]"),
])
def test_cli_rejects_bad_input_with_clear_message(args, msg):
    r = _cli(*args)
    assert r.returncode != 0
    assert msg in r.stderr


def test_cli_json_summary_keys_with_stand_in_contact(tmp_path):
    if not (ROOT / "target" / "release" / "ecf").is_file():
        pytest.skip("ecf CLI not built")
    r = _cli("step", "--model", "fastsim", "--contact", "curve", "--t-end", "0.8", "--out", str(tmp_path), "--json",
             "--quiet")
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    for k in ("dominant_frequency_hz", "oscillation_amplitude", "predicted_frequency_hz", "predicted_unstable",
              "real_time_factor"):
        assert k in s
    assert (tmp_path / "step_fastsim_default_v5.csv").is_file() and (tmp_path / "step_fastsim_default_v5.png").is_file()
