#!/usr/bin/env bash
# Linker of the macOS Python extension (ecf._ecf, rustc's ld64.lld flavour): LLVM's ld64.lld from Debian, with rustc's own export list (PyInit__ecf) and Python's symbols left to the interpreter.
#
# The FMU's link-darwin.sh filters the export list to _fmi2*; the extension keeps rustc's list
# as it is. pyo3 asks for `-undefined dynamic_lookup` (the interpreter provides Python's
# symbols at load time), which ld64.lld takes; maturin's `-Wl,-install_name,...` is unwrapped. libSystem comes from the SDK that rustc names
# with -syslibroot ($SDKROOT; scripts/build-wheel.sh makes the same minimal one as
# scripts/build-fmu.sh). Environment: ECF_LD64 (default ld64.lld-22).
set -euo pipefail
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    -lc|-lm) shift ;;           # both are libSystem on macOS
    -liconv) shift ;;           # std names it, uses none of it; the minimal SDK has no stub
    -flavor) shift 2 ;;         # rustc names the flavour; ld64.lld knows its own
    -Wl,*)                      # a compiler driver's form (maturin's install name): unwrapped
      IFS=, read -r -a parts <<<"${1#-Wl,}"; args+=("${parts[@]}"); shift ;;
    *) args+=("$1"); shift ;;
  esac
done
exec "${ECF_LD64:-ld64.lld-22}" "${args[@]}"
