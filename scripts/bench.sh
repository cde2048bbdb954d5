#!/usr/bin/env bash
# Prints the measured cost ratio (steady ECF with temperature) / FASTSIM on the same grid, one run, medians.
# Criterion benches: cargo bench -p creep-core
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run --quiet --release -p creep-core --example ratio
