#!/usr/bin/env bash
# Sets everything up and runs every test: formatting, clippy, the Rust tests (physics,
# CLI, the FMI 2.0 and 3.0 FMUs through their exported functions and through the rust-fmi
# importer) and the Python tests (the Python package ecf from its wheel, both FMUs through
# fmpy and fmutool, the C driver natively, under Wine and under qemu-user, drive-train demo).
set -euo pipefail
cd "$(dirname "$0")/.."
# Each phase prints its wall time (s) so a slow CI run shows where the time went.
t_phase=$SECONDS
phase() {
  echo "   (previous phase: $((SECONDS - t_phase)) s; total $SECONDS s)" >&2
  t_phase=$SECONDS
  echo "== $1" >&2
}
echo "== setup (scripts/setup.sh --tests)" >&2
bash scripts/setup.sh --tests
phase "commit subjects (scripts/check-commits.sh: at most 72 characters)"
bash scripts/check-commits.sh
phase "cargo fmt --check"
cargo fmt --all --check
phase "cargo clippy -D warnings"
cargo clippy -q --workspace --all-targets -- -D warnings
phase "build the FMUs (dist/ecf_contact.fmu: FMI 2.0, dist/ecf_contact_fmi3.fmu: FMI 3.0)"
bash scripts/build-fmu.sh >/dev/null
phase "cargo test (release)"
cargo test -q --release --workspace
phase "benchmark smoke run and cost guard (scripts/bench.sh --quick; fails when an in-run cost ratio passes its limit)"
bash scripts/bench.sh --quick
phase "Python package ecf: the Linux wheel (scripts/build-wheel.sh --linux-only) in a fresh venv, its tests against the CLI"
bash scripts/build-wheel.sh --linux-only >/dev/null
bash scripts/test-wheel.sh
phase "pytest tests-py"
.venv/bin/python -m pytest -q --durations=15 tests-py
phase "drive-train frequency regression (python -m drivetrain_demo regress drivetrain-demo/baselines/ci.json)"
PYTHONPATH=drivetrain-demo .venv/bin/python -m drivetrain_demo regress drivetrain-demo/baselines/ci.json --quiet
phase "done"
