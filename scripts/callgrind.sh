#!/usr/bin/env bash
# Instruction counts (valgrind --tool=callgrind; repeatable, unlike wall times on a shared
# machine) of the cases the release profile and the bench's guard are chosen by:
#   steady FASTSIM, steady ECF dry (the steady table's 40x21 calls: 4 creepages) and the C
#   FASTSIM's calls for the same case (the ratios' reference), inside `ecf-bench count`'s
#   measured region;
#   the transient cells-ho run (table4.1, 20x3, 50 steps of 0.1 ms at 20 m/s, measured region);
#   `ecf step` of the same run and the FMU's do_step bench (10 steps of 1 ms per speed), whole
#   programs; the transient run and `ecf step` once more with the local temperature's
#   predictor-corrector (`--temperature-solve predictor`, docs/model.md section 6) beside the
#   exact solve.
#   bash scripts/callgrind.sh            builds the release binaries, prints one table row
#   CARGO_PROFILE_RELEASE_LTO=thin CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1 bash scripts/callgrind.sh
#                                        the same under another profile (cargo's environment
#                                        overrides; CARGO_TARGET_DIR keeps builds apart)
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "callgrind.sh: valgrind is missing" >&2; exit 2; }
target=${CARGO_TARGET_DIR:-target}
cargo build --release -q -p ecf-cli -p ecf-bench
cargo build --release -q -p ecf-fmu --bench do_step
bench_bin=$(ls -t "$target"/release/deps/do_step-* | grep -v '\.d$' | head -1)
# instructions of a command: inside `ecf-bench count`'s measured region, or all of them
count() {
  local out
  out=$(mktemp)
  valgrind --tool=callgrind --callgrind-out-file="$out" "$@" >/dev/null 2>"$out.log" ||
    { cat "$out.log" >&2; exit 1; }
  awk '/^(summary|totals):/ {print $2; exit}' "$out"
  rm -f "$out" "$out.log"
}
region=(--toggle-collect='*measured_region*' "$target/release/ecf-bench" count)
c=$(count "${region[@]}" c 40x21)
fs=$(count "${region[@]}" fastsim 40x21)
dry=$(count "${region[@]}" dry 40x21)
ho=$(count "${region[@]}" cells-ho 20x3 --temperature-solve exact)
ho_pc=$(count "${region[@]}" cells-ho 20x3 --temperature-solve predictor)
step_args=(step --preset table4.1 --v-mps 20 --cx-from 0.002 --cx-to 0.05 --dt-ms 0.1 --grid 20x3
  --scheme cells-ho)
step=$(count "$target/release/ecf" "${step_args[@]}" --temperature-solve exact)
step_pc=$(count "$target/release/ecf" "${step_args[@]}" --temperature-solve predictor)
fmu=$(ECF_BENCH_STEPS=10 count "$bench_bin")
printf '%-22s %12s %12s %9s %12s %9s %12s %12s %14s %14s %14s\n' profile C_40x21 FASTSIM FS/C \
  dry dry/C cells-ho cells-ho_pc ecf_step ecf_step_pc FMU_do_step
printf '%-22s %12d %12d %9.2f %12d %9.2f %12d %12d %14d %14d %14d\n' \
  "lto=${CARGO_PROFILE_RELEASE_LTO:-toml},cgu=${CARGO_PROFILE_RELEASE_CODEGEN_UNITS:-toml}" \
  "$c" "$fs" "$(awk "BEGIN {print $fs / $c}")" "$dry" "$(awk "BEGIN {print $dry / $c}")" \
  "$ho" "$ho_pc" "$step" "$step_pc" "$fmu"
