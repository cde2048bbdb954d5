"""Shared pytest fixtures: the packed ecf_contact FMUs (FMI 2.0 and FMI 3.0), built once per session by scripts/build-fmu.sh (or taken from $ECF_FMU_PATH and $ECF_FMU3_PATH)."""

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
def fmu_paths() -> tuple:
    """Paths of dist/ecf_contact.fmu and dist/ecf_contact_fmi3.fmu, built once per test session."""
    given = os.environ.get("ECF_FMU_PATH")
    if given:
        if not os.path.isfile(given):
            pytest.fail(f"ECF_FMU_PATH={given} does not exist")
        # the FMI 3.0 FMU: $ECF_FMU3_PATH, else the one beside it
        return given, os.environ.get("ECF_FMU3_PATH") or os.path.join(os.path.dirname(given), "ecf_contact_fmi3.fmu")
    run = subprocess.run(
        ["bash", str(ROOT / "scripts" / "build-fmu.sh")],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    if run.returncode != 0:
        pytest.fail("scripts/build-fmu.sh failed:\n" + run.stderr[-4000:])
    path3, path = run.stdout.strip().splitlines()[-2:]
    assert os.path.isfile(path) and os.path.isfile(path3), (path, path3)
    return path, path3


@pytest.fixture(scope="session")
def fmu_path(fmu_paths) -> str:
    """Path of the FMI 2.0 FMU (dist/ecf_contact.fmu)."""
    return fmu_paths[0]


@pytest.fixture(scope="session")
def fmu3_path(fmu_paths) -> str:
    """Path of the FMI 3.0 FMU (dist/ecf_contact_fmi3.fmu)."""
    if not os.path.isfile(fmu_paths[1]):
        pytest.fail(f"{fmu_paths[1]} does not exist (scripts/build-fmu.sh builds it beside the FMI 2.0 FMU; or set ECF_FMU3_PATH)")
    return fmu_paths[1]
