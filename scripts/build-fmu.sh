#!/usr/bin/env bash
# Builds the ecf_contact FMU in release mode for glibc >= 2.17 (cargo-zigbuild) and packs dist/ecf_contact.fmu; the last line of output is its path.
#
# Checks on the binary: no glibc symbol version newer than 2.17 (objdump -T), only
# base-system libraries (ldd), and exactly the fmi2* functions exported (nm -D).
# Needs: cargo, the Python venv of scripts/setup-venv.sh (ziglang, cargo-zigbuild, fmpy),
# libclang (bindgen of fmi-sys), binutils. Set ECF_FMU_NATIVE=1 to link with the host's
# toolchain instead of zig (no glibc-2.17 guarantee; for quick local iterations).
#
# Binaries for other platforms, built elsewhere (docs/fmu.md, "Windows and macOS"), are packed
# beside linux64: `--binary win64=PATH/ecf_contact.dll`, `--binary darwin64=PATH/libecf_contact.dylib`
# (repeatable; also ECF_FMU_EXTRA_BINARIES="win64=... darwin64=..."). Each is checked for the
# platform's file format (PE / Mach-O) and stored as binaries/<platform>/ecf_contact.<ext>.
# ECF_FMU_OUT=PATH writes the FMU elsewhere than dist/ecf_contact.fmu.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
ID=ecf_contact
TARGET=x86_64-unknown-linux-gnu
GLIBC_MAX=2.17
OUT="${ECF_FMU_OUT:-$ROOT/dist/$ID.fmu}"

EXTRA=()
for b in ${ECF_FMU_EXTRA_BINARIES:-}; do EXTRA+=("$b"); done
while [ $# -gt 0 ]; do
  case "$1" in
    --binary) [ $# -ge 2 ] || { echo "build-fmu: --binary needs PLATFORM=PATH" >&2; exit 2; }
              EXTRA+=("$2"); shift 2 ;;
    --binary=*) EXTRA+=("${1#--binary=}"); shift ;;
    *) echo "build-fmu: unknown argument '$1' (accepted: --binary PLATFORM=PATH)" >&2; exit 2 ;;
  esac
done
# check every extra binary before building anything
for b in ${EXTRA[@]+"${EXTRA[@]}"}; do
  plat=${b%%=*}; path=${b#*=}
  case "$plat" in
    win64|win32) ext=dll; magic=4d5a ;;                       # "MZ" (PE)
    darwin64) ext=dylib; magic='cffaedfe|cafebabe' ;;          # Mach-O 64-bit / universal
    linux32) ext=so; magic=7f454c46 ;;                         # ELF
    *) echo "build-fmu: --binary $b: platform '$plat' (accepted: win64, win32, darwin64, linux32)" >&2; exit 2 ;;
  esac
  [ "$b" != "$plat" ] && [ -f "$path" ] || { echo "build-fmu: --binary $b: '$path' is not a file" >&2; exit 2; }
  head4=$(head -c 4 "$path" | od -An -tx1 | tr -d ' \n')
  if ! echo "$head4" | grep -Eq "^($magic)"; then
    echo "build-fmu: --binary $b: not a $plat shared library ($ext; first bytes $head4)" >&2; exit 2
  fi
done

bash scripts/setup-venv.sh >&2
export PATH="$ROOT/.venv/bin:$PATH"

if [ "${ECF_FMU_NATIVE:-0}" = 1 ]; then
  cargo build --release -p ecf-fmu --lib --target "$TARGET" >&2
else
  # fmi-sys runs bindgen for the target; cargo-zigbuild hands it zig's include paths relative
  # to the working directory, which bindgen (run in fmi-sys's directory) cannot find. Give
  # the same headers with absolute paths (this variable takes precedence over zigbuild's).
  Z=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "lib"))')
  env "BINDGEN_EXTRA_CLANG_ARGS_$TARGET=-nostdinc -isystem $Z/include -isystem $Z/libc/include/x86-linux-gnu -isystem $Z/libc/include/generic-glibc -isystem $Z/libc/include/x86-linux-any -isystem $Z/libc/include/any-linux-any" \
    cargo zigbuild --release -p ecf-fmu --lib --target "$TARGET.$GLIBC_MAX" >&2
fi
SO="target/$TARGET/release/lib$ID.so"
[ -f "$SO" ] || { echo "build-fmu: $SO not found" >&2; exit 1; }

# --- binary checks -----------------------------------------------------------------------
newest=$(objdump -T "$SO" | grep -o 'GLIBC_[0-9][0-9.]*' | sed 's/GLIBC_//' | sort -V | tail -1)
echo "build-fmu: newest glibc symbol version required: ${newest:-none}" >&2
if [ "${ECF_FMU_NATIVE:-0}" != 1 ] && [ -n "$newest" ] && \
   [ "$(printf '%s\n%s\n' "$newest" "$GLIBC_MAX" | sort -V | tail -1)" != "$GLIBC_MAX" ]; then
  echo "build-fmu: $SO needs GLIBC_$newest > $GLIBC_MAX" >&2
  objdump -T "$SO" | grep "GLIBC_$newest" >&2
  exit 1
fi
allowed='^(linux-vdso\.so\.1|libc\.so\.6|libm\.so\.6|libdl\.so\.2|libpthread\.so\.0|librt\.so\.1|libgcc_s\.so\.1|/lib64/ld-linux-x86-64\.so\.2|ld-linux-x86-64\.so\.2)$'
bad=$(ldd "$SO" | awk '{print $1}' | grep -Ev "$allowed" || true)
if [ -n "$bad" ]; then
  echo "build-fmu: $SO links libraries outside the base system: $bad" >&2
  exit 1
fi
echo "build-fmu: ldd: $(ldd "$SO" | awk '{print $1}' | tr '\n' ' ')" >&2
extra=$(nm -D --defined-only "$SO" | awk '{print $3}' | grep -v '^fmi2' || true)
nexp=$(nm -D --defined-only "$SO" | awk '{print $3}' | grep -c '^fmi2' || true)
if [ -n "$extra" ] || [ "$nexp" != 44 ]; then
  echo "build-fmu: exports: $nexp fmi2* functions (want 44), others: $extra" >&2
  exit 1
fi

# --- pack ----------------------------------------------------------------------------------
STAGE="$ROOT/target/fmu-stage/$ID"
rm -rf "$STAGE"
mkdir -p "$STAGE/binaries/linux64" "$STAGE/resources/presets" "$STAGE/documentation" "$(dirname "$OUT")"
cp modelDescription/modelDescription.xml "$STAGE/"
cp "$SO" "$STAGE/binaries/linux64/$ID.so"
cp creep-core/presets/*.json "$STAGE/resources/presets/"
cp fmu-crate/assets/model.png "$STAGE/model.png"
for b in ${EXTRA[@]+"${EXTRA[@]}"}; do
  plat=${b%%=*}; path=${b#*=}
  case "$plat" in win*) ext=dll ;; darwin*) ext=dylib ;; *) ext=so ;; esac
  mkdir -p "$STAGE/binaries/$plat"
  cp "$path" "$STAGE/binaries/$plat/$ID.$ext"
  echo "build-fmu: packed $path as binaries/$plat/$ID.$ext" >&2
done
# documentation/index.html: docs/fmu.md rendered to HTML (pulldown-cmark), the markdown beside it
cp docs/fmu.md "$STAGE/documentation/"
cargo run -q --release -p ecf-fmu --example render_doc -- docs/fmu.md "$STAGE/documentation/index.html" >&2
rm -f "$OUT"
python3 - "$STAGE" "$OUT" <<'PY'
import os, sys, zipfile
stage, out = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
    for base, dirs, files in sorted(os.walk(stage)):
        dirs.sort()
        for f in sorted(files):
            p = os.path.join(base, f)
            z.write(p, os.path.relpath(p, stage))
PY

# --- smoke test: the binary accepts the packed modelDescription.xml (same GUID) -------------
python3 - "$OUT" <<'PY' >&2
import sys
from fmpy import read_model_description, extract
from fmpy.fmi2 import FMU2Slave
fmu = sys.argv[1]
md = read_model_description(fmu)
d = extract(fmu)
s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="smoke")
try:
    s.instantiate()
except Exception as e:
    sys.exit(f"build-fmu: the binary refuses modelDescription.xml ({e}); regenerate it: "
             "ECF_FMU_WRITE_MD=1 cargo test -p ecf-fmu --test model_description")
s.freeInstance()
print("build-fmu: smoke test ok (instantiate with the packed GUID)")
PY
echo "$OUT"
