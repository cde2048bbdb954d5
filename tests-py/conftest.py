"""Shared pytest fixtures: the packed ecf_contact FMU, built once per session by scripts/build-fmu.sh (or taken from $ECF_FMU_PATH)."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def repo_root() -> pathlib.Path:
    """The repository root."""
    return ROOT


@pytest.fixture(scope="session")
def fmu_path() -> str:
    """Path of dist/ecf_contact.fmu, built once per test session."""
    given = os.environ.get("ECF_FMU_PATH")
    if given:
        if not os.path.isfile(given):
            pytest.fail(f"ECF_FMU_PATH={given} does not exist")
        return given
    run = subprocess.run(
        ["bash", str(ROOT / "scripts" / "build-fmu.sh")],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    if run.returncode != 0:
        pytest.fail("scripts/build-fmu.sh failed:\n" + run.stderr[-4000:])
    path = run.stdout.strip().splitlines()[-1]
    assert os.path.isfile(path), path
    return path
