#!/usr/bin/env bash
# Installs the Linux wheel of the Python package ecf (dist/wheels, from scripts/build-wheel.sh) into a fresh venv and runs the package's tests (ecf-py/tests) there.
#
# The venv (target/wheel-venv, made anew each run) holds only the wheel and the pinned
# versions from requirements.txt of what the tests use: numpy (the wheel's one dependency),
# pandas, tqdm, matplotlib, scipy (the drive-train demo's test) and pytest. The tests compare
# with the ecf binary: ECF_BIN, else target/release/ecf.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
WHEEL=$(ls "${ECF_WHEEL_OUT:-$ROOT/dist/wheels}"/ecf-*manylinux*x86_64.whl 2>/dev/null | head -1 || true)
[ -n "$WHEEL" ] || { echo "test-wheel: no Linux wheel in dist/wheels: run scripts/build-wheel.sh --linux-only" >&2; exit 1; }
V="$ROOT/target/wheel-venv"
rm -rf "$V"
"${PYTHON:-python3}" -m venv "$V"
pins=$(grep -E '^(numpy|pandas|tqdm|matplotlib|scipy|pytest)==' requirements.txt | awk '{print $1}')
# shellcheck disable=SC2086
"$V/bin/python" -m pip install --quiet $pins "$WHEEL"
# run from outside the source tree: the installed package, not ecf-py/python, is imported
cd "$V"
ECF_BIN="${ECF_BIN:-${CARGO_TARGET_DIR:-$ROOT/target}/release/ecf}" "$V/bin/python" -m pytest -q -p no:cacheprovider "$ROOT/ecf-py/tests"
