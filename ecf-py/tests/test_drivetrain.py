"""The drive-train demo's steady-curve contact takes its curve from the package when it is
installed, and the curve is the one the `ecf curve` CLI gives it (its other path)."""

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def contact_module(monkeypatch):
    pytest.importorskip("scipy")
    pytest.importorskip("matplotlib")
    monkeypatch.syspath_prepend(str(ROOT / "drivetrain-demo"))
    from drivetrain_demo import contact

    return contact


def test_curve_contact_from_the_package_is_the_cli_curve(contact_module, monkeypatch):
    from test_ecf import _ecf_bin

    kw = dict(model="ecf", v=5.0, F_N=90e3, T_bulk=25.0, preset="dry", grid=(20, 5))
    via_package = contact_module.CurveContact(**kw)
    # without the package, the same stand-in runs the CLI
    monkeypatch.setitem(sys.modules, "ecf", None)
    monkeypatch.setattr(contact_module, "ECF_CLI", Path(_ecf_bin()))
    via_cli = contact_module.CurveContact(**kw)
    assert len(via_package._f) == 441
    assert np.array_equal(via_package._f, via_cli._f)
    assert via_package.steady_f(np.array([-0.01, 0.003])).tolist() == via_cli.steady_f(np.array([-0.01, 0.003])).tolist()
