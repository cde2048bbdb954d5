#!/usr/bin/env bash
# The measurement loop on files it was never tuned on: every hidden-effect case of
# ecf-measure/tests/measurement/hidden.rs and files with nothing missing, each diagnosed as a
# user would (the preset, no grid), with the held-out error against the file's true noise,
# the variable named and the time. Markdown tables on stdout.
#   bash scripts/loop-sweep.sh [--seeds N] [--nulls N] [--only CASE] [--layout standard|other|sparse|precise|one-load] [--presets dry,table4.1,wet] [--write DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run -q --release -p ecf-measure --example loop_sweep -- "$@"
