#!/usr/bin/env bash
# Benchmarks (not tests): the project's FASTSIM and steady ECF (dry, table4.1, temperature on)
# against a plain C FASTSIM (gcc -O2, same grid) interleaved in one process (medians of
# per-round ratios), transient wall time / simulated time (dry, 80x21, c_x = 15 %), and
# `ecf diagnose` on the worked example. Pinned to one core where taskset exists.
#   bash scripts/bench.sh            full run (about 2-3 minutes)
#   bash scripts/bench.sh --quick    short run (CI smoke test, < 30 s)
# Every run with the steady table (the default, --quick, --only steady) ends it with a guard
# on in-run ratios to the C FASTSIM (40x21): steady FASTSIM/C <= 1.2, steady ECF dry/C <= 16,
# a transient cells-ho step (table4.1 20x3, 20 m/s, 0.1 ms) / C <= 1.3 x its measured level
# (docs/model.md section 10); it prints them with their limits, measures again (at most three
# times, the lowest counts) while one is over, and exits non-zero when one stays over.
# Instruction counts of the same cases: scripts/callgrind.sh.
#   bash scripts/bench.sh temperature-solve [--quick] [predictor] [REPS]   the predictor-corrector
#       local temperature against the exact solve (differences and cost ratio; about 1-3 minutes)
#   bash scripts/bench.sh --only steady|transient|diagnose
#   bash scripts/bench.sh --only threads   transient on all cores vs one (not pinned)
#   bash scripts/bench.sh --only accuracy [--finest 640]   errors of each grid and scheme against
#       the extrapolated limit of transient responses, beside their cost (about 15-25 minutes under
#       load; 640: longer); also writes creep-core/data/accuracy.csv (ECF_ACCURACY_CSV=path: elsewhere,
#       and nothing else) and then runs scripts/accuracy-docs.sh (the Pareto PNGs in
#       docs/img/accuracy/ and the tolerance table of docs/fmu.md)
#       ECF_ACCURACY_COSTS_FROM=earlier.csv: errors from this run, each row's cost kept from the
#       earlier table (for a change that leaves the costs within their noise; the header says so;
#       a row missing there ends the run before its first case)
#   bash scripts/bench.sh --only consistency   drift of the steady state under transient steps at
#       constant inputs, per preset, speed, grid and communication step (about 10 s)
#   bash scripts/bench.sh --only steady-grid   each grid's largest error of the steady curves
#       (c_x 0.2 ... 30 %) against 640x168, per preset and speed (about 10 s on an idle core)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p ecf-cli -p ecf-bench
if [[ " $* " == *" threads "* ]]; then
  exec target/release/ecf-bench "$@"
fi
# the full accuracy table: then the PNGs and the docs/fmu.md table derived from it
if [[ " $* " == *" accuracy "* && " $* " != *" --quick "* && -z "${ECF_ACCURACY_CSV:-}" ]]; then
  pin=()
  if command -v taskset >/dev/null 2>&1; then pin=(taskset -c 0); fi
  "${pin[@]}" target/release/ecf-bench "$@"
  exec bash scripts/accuracy-docs.sh
fi
if command -v taskset >/dev/null 2>&1; then
  exec taskset -c 0 target/release/ecf-bench "$@"
fi
exec target/release/ecf-bench "$@"
