#!/usr/bin/env bash
# Linker of the Windows FMU binary: MinGW-w64's gcc, exporting only the FMI functions (fmi2*, fmi3*).
#
# rustc writes the DLL's exports as a module-definition file (list.def) that also names
# fmi-sys's `callback_log`; the file is filtered to the fmi2* and fmi3* names (the PE counterpart of
# fmu-crate/exports.map). libgcc and libwinpthread are linked statically (rustc's
# windows-gnu default), so the DLL needs no MinGW runtime DLL beside it.
# Environment: ECF_MINGW_GCC (default x86_64-w64-mingw32-gcc).
set -euo pipefail
args=()
found=0
for a in "$@"; do
  case "$a" in
    *.def)
      def=${a#-Wl,}
      [ -f "$def" ] || { echo "link-mingw.sh: $def not found" >&2; exit 2; }
      awk '/^EXPORTS/ || /^[[:space:]]*"?fmi[23][A-Za-z0-9]+"?[[:space:]]*$/' "$def" > "$def.fmi2.def"
      args+=("${a%.def}.def.fmi2.def"); found=1 ;;
    *) args+=("$a") ;;
  esac
done
[ "$found" = 1 ] || { echo "link-mingw.sh: rustc passed no .def file (not a cdylib link?)" >&2; exit 2; }
exec "${ECF_MINGW_GCC:-x86_64-w64-mingw32-gcc}" "${args[@]}"
