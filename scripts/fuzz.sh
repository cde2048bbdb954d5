#!/usr/bin/env bash
# Fuzz runs of the FMU and the CLI (docs/fmu.md, "Fuzzing").
#   bash scripts/fuzz.sh           the bounded runs of the normal tests (seconds)
#   bash scripts/fuzz.sh --long    long runs: 200,000 legal FMI calls (fuzz.rs), 2,000 widened
#                                  FMU cases in child processes (fuzz_wide.rs), 2,000 CLI runs
#                                  (fuzz_cli.rs); about 30-60 minutes on one core
#   ECF_FUZZ_SEED=N                another seed (default: the tests' own)
# Each prints its counts (signals, hangs, failed checks, states restored, corruptions
# refused/accepted); a nonzero exit means a check failed.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == "--long" ]]; then
  export ECF_FUZZ_CALLS="${ECF_FUZZ_CALLS:-200000}"
  export ECF_FUZZ_CASES="${ECF_FUZZ_CASES:-2000}"
  export ECF_FUZZ_CLI_RUNS="${ECF_FUZZ_CLI_RUNS:-2000}"
elif [[ -n "${1:-}" ]]; then
  echo "usage: bash scripts/fuzz.sh [--long]" >&2
  exit 2
fi
cargo test -q --release -p ecf-fmu --test fuzz --test fuzz_wide -- --nocapture --test-threads=1
cargo test -q --release -p ecf-cli --test fuzz_cli -- --nocapture
