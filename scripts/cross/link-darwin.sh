#!/usr/bin/env bash
# Linker of the macOS FMU binary (rustc's ld64.lld flavour): LLVM's ld64.lld from Debian, exporting only the FMI functions (_fmi2*, _fmi3*), with a relative install name.
#
# rustc hands its own exported-symbols list, which also names fmi-sys's `callback_log`; the
# list is filtered to _fmi2* (the Mach-O counterpart of fmu-crate/exports.map). zig's linker
# ignores -exported_symbols_list, which is why this is not `zig cc`. ld64.lld signs arm64
# output ad hoc by default (Apple silicon refuses unsigned code).
# libSystem comes from the SDK that rustc names with -syslibroot ($SDKROOT; scripts/build-fmu.sh
# makes a minimal one from zig's stub). Environment: ECF_LD64 (default ld64.lld-22).
set -euo pipefail
args=()
found=0
while [ $# -gt 0 ]; do
  case "$1" in
    -exported_symbols_list)
      [ $# -ge 2 ] || { echo "link-darwin.sh: -exported_symbols_list without a file" >&2; exit 2; }
      grep -E '^_fmi[23][A-Za-z0-9]+$' "$2" > "$2.fmi2" || true
      args+=("$1" "$2.fmi2"); found=1; shift 2 ;;
    -install_name) shift 2 ;;   # replaced below
    -lc|-lm) shift ;;           # both are libSystem on macOS
    -liconv) shift ;;           # the libc crate names it; nothing here calls iconv (a call
                                # would fail the link), and the minimal SDK has no stub
    -flavor) shift 2 ;;         # rustc names the flavour; ld64.lld knows its own
    *) args+=("$1"); shift ;;
  esac
done
[ "$found" = 1 ] || { echo "link-darwin.sh: rustc passed no -exported_symbols_list (not a cdylib link?)" >&2; exit 2; }
exec "${ECF_LD64:-ld64.lld-22}" "${args[@]}" -install_name @rpath/ecf_contact.dylib
