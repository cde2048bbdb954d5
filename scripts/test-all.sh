#!/usr/bin/env bash
# Sets everything up and runs every test: formatting, clippy, the Rust tests (physics,
# CLI, FMU through its exported functions and through the rust-fmi importer) and the Python
# tests (FMU through fmpy and fmutool, drive-train demo).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --tests
echo "== cargo fmt --check" >&2
cargo fmt --all --check
echo "== cargo clippy -D warnings" >&2
cargo clippy -q --workspace --all-targets -- -D warnings
echo "== build the FMU (dist/ecf_contact.fmu)" >&2
bash scripts/build-fmu.sh >/dev/null
echo "== cargo test (release)" >&2
cargo test -q --release --workspace
echo "== benchmark smoke run (scripts/bench.sh --quick; figures only, no assertions)" >&2
bash scripts/bench.sh --quick
echo "== pytest tests-py" >&2
.venv/bin/python -m pytest -q tests-py
echo "== drive-train frequency regression (python -m drivetrain_demo regress drivetrain-demo/baselines/ci.json)" >&2
PYTHONPATH=drivetrain-demo .venv/bin/python -m drivetrain_demo regress drivetrain-demo/baselines/ci.json --quiet
