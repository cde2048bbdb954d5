#!/usr/bin/env bash
# Builds the ecf_contact FMU in release mode for glibc >= 2.17 (cargo-zigbuild) and packs dist/ecf_contact.fmu; the last line of output is its path.
#
# Checks on the binary: no glibc symbol version newer than 2.17 (objdump -T), only
# base-system libraries (ldd), and exactly the fmi2* functions exported (nm -D).
# Needs: cargo, the Python venv of scripts/setup-venv.sh (ziglang, cargo-zigbuild, fmpy),
# libclang (bindgen of fmi-sys), binutils. Set ECF_FMU_NATIVE=1 to link with the host's
# toolchain instead of zig (no glibc-2.17 guarantee; for quick local iterations).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
ID=ecf_contact
TARGET=x86_64-unknown-linux-gnu
GLIBC_MAX=2.17
OUT="$ROOT/dist/$ID.fmu"

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
mkdir -p "$STAGE/binaries/linux64" "$STAGE/resources/presets" "$STAGE/documentation" "$ROOT/dist"
cp modelDescription/modelDescription.xml "$STAGE/"
cp "$SO" "$STAGE/binaries/linux64/$ID.so"
cp creep-core/presets/*.json "$STAGE/resources/presets/"
if [ -f docs/fmu.md ]; then
  cp docs/fmu.md "$STAGE/documentation/"
  python3 - "$STAGE/documentation" <<'PY'
import html, pathlib, sys
d = pathlib.Path(sys.argv[1])
text = (d / "fmu.md").read_text()
(d / "index.html").write_text(
    "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>ecf_contact FMU</title></head>"
    "<body><pre>" + html.escape(text) + "</pre></body></html>\n")
PY
fi
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
