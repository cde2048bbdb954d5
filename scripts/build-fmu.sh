#!/usr/bin/env bash
# Builds the ecf_contact FMUs, FMI 2.0 (dist/ecf_contact.fmu: linux64, win64, darwin64) and FMI 3.0
# (dist/ecf_contact_fmi3.fmu: x86_64-linux, x86_64-windows, x86_64-darwin, aarch64-darwin,
# aarch64-linux), from one library per platform that exports both APIs; the last two lines of
# output are the paths of the FMI 3.0 and the FMI 2.0 FMU (the last).
#
# binaries/linux64/ecf_contact.so     x86_64 Linux, glibc >= 2.17 (cargo-zigbuild)
# binaries/win64/ecf_contact.dll      x86_64 Windows (MinGW-w64), no MinGW runtime DLL needed
# binaries/darwin64/ecf_contact.dylib macOS >= 11, universal (x86_64 + arm64, arm64 signed ad hoc)
# The FMI 3.0 FMU holds the same libraries in its platform-tuple folders (the darwin64 slices
# each in its own: x86_64-darwin, aarch64-darwin), plus binaries/aarch64-linux/ecf_contact.so
# (ARM64 Linux, glibc >= 2.17, cargo-zigbuild with the standard library built from source).
# `--linux-only` (or ECF_FMU_LINUX_ONLY=1) builds and packs (x86_64) linux alone, for a user in a hurry.
#
# Windows and macOS are cross-built here with Debian's Rust (rustc-web), which builds their
# standard library from source (-Zbuild-std, once per target: target/cross/) because rustup's
# targets cannot be downloaded; scripts/cross/ holds the two linker wrappers and says why.
# Checks on each binary: exactly the 44 fmi2* and 75 fmi3* functions exported (nm / objdump /
# llvm-nm); linux64 and aarch64-linux: no glibc symbol version newer than 2.17; linux64: only
# base-system libraries (ldd);
# win64: PE32+ x86-64, imports only Windows system DLLs; darwin64: both architectures, only
# /usr/lib/libSystem linked, minimum macOS 11.0, install name @rpath/ecf_contact.dylib, the arm64
# slice signed. Needs: cargo, the apt packages of scripts/setup.sh (installed here when missing),
# the Python venv of scripts/setup-venv.sh (ziglang, cargo-zigbuild, fmpy). Set ECF_FMU_NATIVE=1
# to link linux64 with the host's toolchain instead of zig (no glibc-2.17 guarantee).
#
# Binaries for further platforms, built elsewhere, are packed beside them: `--binary
# win32=PATH/ecf_contact.dll` (repeatable; also ECF_FMU_EXTRA_BINARIES="win32=..."); a win64 or
# darwin64 given so replaces the one built here. Each is checked for the platform's file format
# (PE / Mach-O / ELF) and stored as binaries/<platform>/ecf_contact.<ext> of the FMI 2.0 FMU.
# ECF_FMU_OUT=PATH writes the FMI 2.0 FMU elsewhere than dist/ecf_contact.fmu, the FMI 3.0 FMU
# beside it (ecf_contact_fmi3.fmu in the same folder).
#
# Your own Rust effects, without forking the project: `--effects PATH/TO/CRATE` links a crate
# that registers effects with creep_core::register_effect! (example: examples/user-effect)
# into the FMU (every platform above) and into an `ecf` binary. Both go to
# dist/with-<lib name>/ (ecf_contact.fmu, ecf); the wrapper crates that link them are generated
# in target/with-effects/<lib name>/.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
ID=ecf_contact
TARGET=x86_64-unknown-linux-gnu
GLIBC_MAX=2.17
OUT="${ECF_FMU_OUT:-$ROOT/dist/$ID.fmu}"
# the number of functions of each API the libraries export (fmi2Functions.h, fmi3Functions.h)
N_FMI2=44
N_FMI3=75

EXTRA=()
EFFECTS=""
LINUX_ONLY=${ECF_FMU_LINUX_ONLY:-0}
for b in ${ECF_FMU_EXTRA_BINARIES:-}; do EXTRA+=("$b"); done
while [ $# -gt 0 ]; do
  case "$1" in
    --binary) [ $# -ge 2 ] || { echo "build-fmu: --binary needs PLATFORM=PATH" >&2; exit 2; }
              EXTRA+=("$2"); shift 2 ;;
    --binary=*) EXTRA+=("${1#--binary=}"); shift ;;
    --effects) [ $# -ge 2 ] || { echo "build-fmu: --effects needs the path of a crate" >&2; exit 2; }
               EFFECTS="$2"; shift 2 ;;
    --effects=*) EFFECTS="${1#--effects=}"; shift ;;
    --linux-only) LINUX_ONLY=1; shift ;;
    *) echo "build-fmu: unknown argument '$1' (accepted: --linux-only, --binary PLATFORM=PATH, --effects PATH)" >&2; exit 2 ;;
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

# --- --effects: a workspace of two wrapper crates that link the user's crate -----------------
MAN=()
PKG=(-p ecf-fmu --lib)
LIBNAME=$ID
if [ -n "$EFFECTS" ]; then
  [ -f "$EFFECTS/Cargo.toml" ] || { echo "build-fmu: --effects $EFFECTS: no Cargo.toml there (give the folder of your effect crate)" >&2; exit 2; }
  EFF=$(cd "$EFFECTS" && pwd)
  meta=$(cargo metadata -q --no-deps --format-version 1 --manifest-path "$EFF/Cargo.toml") || {
    echo "build-fmu: --effects $EFFECTS: cargo cannot read $EFF/Cargo.toml" >&2; exit 2; }
  names=$(python3 -c '
import json, sys
m = json.loads(sys.stdin.read())
p = [p for p in m["packages"] if p["manifest_path"] == sys.argv[1]][0]
lib = [t for t in p["targets"] if "lib" in t["kind"] or "rlib" in t["kind"]]
if not lib:
    sys.exit("build-fmu: --effects: the crate has no library target")
if not any(d["name"] == "creep-core" for d in p["dependencies"]):
    sys.exit("build-fmu: --effects: the crate does not depend on creep-core (it registers effects with creep_core::register_effect!)")
print(p["name"], lib[0]["name"].replace("-", "_"))' "$EFF/Cargo.toml" <<<"$meta")
  read -r EPKG ELIB <<<"$names"
  W="$ROOT/target/with-effects/$ELIB"
  mkdir -p "$W/fmu/src" "$W/cli/src"
  cat > "$W/Cargo.toml" <<TOML
# generated by scripts/build-fmu.sh --effects $EFFECTS: the FMU and the ecf binary with $EPKG linked
[workspace]
resolver = "2"
members = ["fmu", "cli"]

$(sed -n '/^\[profile\.release\]/,/^$/p' "$ROOT/Cargo.toml")
TOML
  cat > "$W/fmu/Cargo.toml" <<TOML
[package]
name = "ecf-fmu-with-effects"
version = "0.1.0"
edition = "2021"
publish = false

[lib]
name = "ecf_contact_with_effects"
crate-type = ["cdylib"]

[dependencies]
ecf_fmu = { package = "ecf-fmu", path = "$ROOT/fmu-crate" }
user_effects = { package = "$EPKG", path = "$EFF" }
TOML
  cat > "$W/fmu/src/lib.rs" <<'RS'
//! The contact FMU with a user's effect crate linked in (generated by scripts/build-fmu.sh --effects).
extern crate ecf_fmu;
extern crate user_effects;
RS
  cat > "$W/cli/Cargo.toml" <<TOML
[package]
name = "ecf-with-effects"
version = "0.1.0"
edition = "2021"
publish = false

[[bin]]
name = "ecf-with-$ELIB"
path = "src/main.rs"

[dependencies]
ecf-cli = { path = "$ROOT/ecf-cli" }
user_effects = { package = "$EPKG", path = "$EFF" }
TOML
  cat > "$W/cli/src/main.rs" <<'RS'
//! The `ecf` binary with a user's effect crate linked in (generated by scripts/build-fmu.sh --effects).
extern crate user_effects;

fn main() -> std::process::ExitCode {
    ecf_cli::main()
}
RS
  # start from the project's lock file: the same versions of every shared dependency
  [ -f "$W/Cargo.lock" ] || cp Cargo.lock "$W/Cargo.lock"
  MAN=(--manifest-path "$W/Cargo.toml")
  PKG=(-p ecf-fmu-with-effects --lib)
  LIBNAME=ecf_contact_with_effects
  DEST="$ROOT/dist/with-$ELIB"
  OUT="${ECF_FMU_OUT:-$DEST/$ID.fmu}"
  export CARGO_TARGET_DIR="$ROOT/target"
fi

bash scripts/setup-venv.sh >&2
if [ "$LINUX_ONLY" != 1 ]; then
  # the apt packages of the cross builds (scripts/setup.sh says what each is for); Debian 12
  # has them, other distributions may not: then say so and build linux64 alone
  source scripts/cross/packages.sh
  if ! bash scripts/apt-ensure.sh libclang-dev binutils "${CROSS_PACKAGES[@]}"; then
    echo "build-fmu: WARNING: the Windows and macOS binaries need the Debian 12 packages ${CROSS_PACKAGES[*]}, which could not be installed here: building linux64 only (--linux-only silences this)" >&2
    LINUX_ONLY=1
  fi
fi
export PATH="$ROOT/.venv/bin:$PATH"

if [ "${ECF_FMU_NATIVE:-0}" = 1 ]; then
  cargo build --release ${MAN[@]+"${MAN[@]}"} "${PKG[@]}" --target "$TARGET" >&2
else
  # fmi-sys runs bindgen for the target; cargo-zigbuild hands it zig's include paths relative
  # to the working directory, which bindgen (run in fmi-sys's directory) cannot find. Give
  # the same headers with absolute paths (this variable takes precedence over zigbuild's).
  Z=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "lib"))')
  env "BINDGEN_EXTRA_CLANG_ARGS_$TARGET=-nostdinc -isystem $Z/include -isystem $Z/libc/include/x86-linux-gnu -isystem $Z/libc/include/generic-glibc -isystem $Z/libc/include/x86-linux-any -isystem $Z/libc/include/any-linux-any" \
    cargo zigbuild --release ${MAN[@]+"${MAN[@]}"} "${PKG[@]}" --target "$TARGET.$GLIBC_MAX" >&2
fi
# where cargo wrote it: $CARGO_TARGET_DIR when set (relative to the root, where cargo ran), else
# target/ (packing target/ under a set CARGO_TARGET_DIR would pack a stale library)
SO="${CARGO_TARGET_DIR:-target}/$TARGET/release/lib$LIBNAME.so"
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
# exports(LIST, WHAT): the exported names (one a line, macOS's leading _ removed) are exactly
# the N_FMI2 fmi2* and N_FMI3 fmi3* functions
exports() {
  local names n2 n3 other
  names=$(sed 's/^_//' <<<"$1")
  n2=$(grep -c '^fmi2' <<<"$names" || true)
  n3=$(grep -c '^fmi3' <<<"$names" || true)
  other=$(grep -Ev '^fmi[23]' <<<"$names" | head -5 | xargs || true)
  if [ "$n2" != "$N_FMI2" ] || [ "$n3" != "$N_FMI3" ] || [ -n "$other" ]; then
    echo "build-fmu: $2 exports $n2 fmi2* (want $N_FMI2) and $n3 fmi3* (want $N_FMI3) functions, others: $other" >&2
    exit 1
  fi
}
exports "$(nm -D --defined-only "$SO" | awk '{print $3}')" "linux64"

# --- win64 and darwin64: cross builds with Debian's Rust and -Zbuild-std -----------------
WIN_DLL=""
MAC_DYLIB=""
for b in ${EXTRA[@]+"${EXTRA[@]}"}; do
  case "${b%%=*}" in win64|darwin64) echo "build-fmu: ${b%%=*} given by --binary replaces the one built here" >&2 ;; esac
done
if [ "$LINUX_ONLY" != 1 ]; then
  XDIR="$ROOT/target/cross"
  # bindgen (fmi-sys) runs the host's libclang for each target: its own resource headers
  # (stddef.h, mm_malloc.h) and, for macOS, zig's libc headers of Darwin
  LIBCLANG=$(ls /usr/lib/llvm-*/lib/libclang.so* 2>/dev/null | sort -V | tail -1 || true)
  CLANG_RES=$(ls -d "$(dirname "${LIBCLANG:-/none}")"/clang/*/include 2>/dev/null | sort -V | tail -1 || true)
  [ -f "$CLANG_RES/stddef.h" ] || { echo "build-fmu: no resource headers of libclang ($LIBCLANG) found" >&2; exit 1; }
  Z=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "lib"))')
  # A minimal macOS SDK for rustc (-syslibroot) and zig (headers): zig's libSystem stub, with
  # the arm64e.x1 architecture names that LLVM's TAPI reader refuses renamed to arm64 (the stub
  # lists arm64e, which ld64.lld does not take for arm64), and zig's Darwin libc headers
  SDK="$XDIR/MacOSX.sdk"
  mkdir -p "$SDK/usr/lib"
  sed 's/arm64e\.x1-/arm64-/g' "$Z/libc/darwin/libSystem.tbd" > "$SDK/usr/lib/libSystem.tbd.new"
  mv "$SDK/usr/lib/libSystem.tbd.new" "$SDK/usr/lib/libSystem.tbd"
  ln -sfn "$Z/libc/include/any-darwin-any" "$SDK/usr/include"
  cross() {  # cross TARGET: builds the FMU library for TARGET into $XDIR/TARGET/release
    local t=$1 u
    u=$(echo "${t//-/_}" | tr '[:lower:]' '[:upper:]')
    local -a e=(PATH="$ROOT/.venv/bin:/usr/bin:$PATH" RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR="$XDIR")
    local -a c=(--release ${MAN[@]+"${MAN[@]}"} "${PKG[@]}" --target "$t" -Zbuild-std=std,panic_unwind)
    echo "build-fmu: $t (Debian's rustc $(/usr/bin/rustc --version | cut -d' ' -f2), standard library from source)" >&2
    case "$t" in
      *-windows-gnu)
        env "${e[@]}" "CARGO_TARGET_${u}_LINKER=$ROOT/scripts/cross/link-mingw.sh" \
          "BINDGEN_EXTRA_CLANG_ARGS_$t=-I$CLANG_RES" /usr/bin/cargo build "${c[@]}" >&2 ;;
      aarch64-unknown-linux-gnu)
        # zig's glibc headers of the target for bindgen (fmi-sys), as for linux64 above
        env "${e[@]}" "BINDGEN_EXTRA_CLANG_ARGS_$t=-nostdinc -isystem $CLANG_RES -isystem $Z/libc/include/aarch64-linux-gnu -isystem $Z/libc/include/generic-glibc -isystem $Z/libc/include/aarch64-linux-any -isystem $Z/libc/include/any-linux-any" \
          /usr/bin/cargo zigbuild --release ${MAN[@]+"${MAN[@]}"} "${PKG[@]}" --target "$t.$GLIBC_MAX" -Zbuild-std=std,panic_unwind >&2 ;;
      *-apple-darwin)
        env "${e[@]}" "CARGO_TARGET_${u}_LINKER=$ROOT/scripts/cross/link-darwin.sh" \
          "CARGO_TARGET_${u}_RUSTFLAGS=-C linker-flavor=ld64.lld" SDKROOT="$SDK" \
          MACOSX_DEPLOYMENT_TARGET=11.0 "BINDGEN_EXTRA_CLANG_ARGS_$t=-I$CLANG_RES -isystem $Z/libc/include/any-darwin-any" \
          /usr/bin/cargo zigbuild "${c[@]}" >&2 ;;
    esac
  }
  cross x86_64-pc-windows-gnu
  WIN_DLL="$XDIR/x86_64-pc-windows-gnu/release/$LIBNAME.dll"
  [ -f "$WIN_DLL" ] || { echo "build-fmu: $WIN_DLL not found" >&2; exit 1; }
  fmt=$(x86_64-w64-mingw32-objdump -f "$WIN_DLL" | sed -n 's/.*file format //p')
  [ "$fmt" = pei-x86-64 ] || { echo "build-fmu: $WIN_DLL is '$fmt', not PE32+ x86-64" >&2; exit 1; }
  wexp=$(x86_64-w64-mingw32-objdump -p "$WIN_DLL" | sed -n '/\[Ordinal\/Name Pointer\] Table/,/^$/p' | awk '/^[[:space:]]*\[ *[0-9]+\]/ {print $NF}')
  exports "$wexp" "win64 ($WIN_DLL)"
  wimp=$(x86_64-w64-mingw32-objdump -p "$WIN_DLL" | sed -n 's/^\s*DLL Name: //p' | sort -fu)
  # Windows system DLLs only: no libgcc_s_seh, libwinpthread or libstdc++ beside the FMU
  wbad=$(echo "$wimp" | grep -Eiv '^(kernel32|msvcrt|ntdll|userenv|ws2_32|bcryptprimitives|advapi32|api-ms-win-[a-z0-9-]+)\.dll$' || true)
  [ -z "$wbad" ] || { echo "build-fmu: $WIN_DLL imports DLLs outside the Windows system: $wbad" >&2; exit 1; }
  echo "build-fmu: win64: PE32+ x86-64, $N_FMI2 fmi2* and $N_FMI3 fmi3* exports, imports $(echo $wimp)" >&2

  cross x86_64-apple-darwin
  cross aarch64-apple-darwin
  MAC_DYLIB="$XDIR/darwin64/$LIBNAME.dylib"
  mkdir -p "$XDIR/darwin64"
  llvm-lipo-22 -create -output "$MAC_DYLIB" \
    "$XDIR/x86_64-apple-darwin/release/lib$LIBNAME.dylib" "$XDIR/aarch64-apple-darwin/release/lib$LIBNAME.dylib"
  archs=$(llvm-lipo-22 -archs "$MAC_DYLIB" | xargs)
  [ "$archs" = "x86_64 arm64" ] || { echo "build-fmu: $MAC_DYLIB holds '$archs', want 'x86_64 arm64'" >&2; exit 1; }
  for arch in x86_64 arm64; do
    slice="$XDIR/darwin64/$arch.dylib"
    llvm-lipo-22 -thin "$arch" -output "$slice" "$MAC_DYLIB"
    exports "$(llvm-nm-22 -gU --defined-only "$slice" | awk '{print $NF}')" "darwin64 $arch"
    load=$(llvm-otool-22 -L "$slice" | tail -n +2 | awk '{print $1}')
    [ "$load" = "$(printf '@rpath/ecf_contact.dylib\n/usr/lib/libSystem.B.dylib')" ] || {
      echo "build-fmu: darwin64 $arch: install name and libraries: $(echo $load) (want @rpath/ecf_contact.dylib /usr/lib/libSystem.B.dylib)" >&2; exit 1; }
    # the load commands read once (a reader that stops early would cut the pipe under pipefail)
    cmds=$(llvm-otool-22 -l "$slice")
    minos=$(awk '/LC_BUILD_VERSION/ {b = 1} b && $1 == "minos" {print $2; exit}' <<<"$cmds")
    [ "$minos" = 11.0 ] || { echo "build-fmu: darwin64 $arch: minimum macOS '$minos', want 11.0" >&2; exit 1; }
    if [ "$arch" = arm64 ] && ! grep -q LC_CODE_SIGNATURE <<<"$cmds"; then
      echo "build-fmu: darwin64 arm64 slice is not signed (Apple silicon refuses it)" >&2; exit 1
    fi
  done
  echo "build-fmu: darwin64: universal ($archs), $N_FMI2 _fmi2* and $N_FMI3 _fmi3* exports each, only libSystem, macOS >= $minos, arm64 signed ad hoc" >&2

  # aarch64-linux (FMI 3.0 only: FMI 2.0 names no ARM platform)
  cross aarch64-unknown-linux-gnu
  ARM_SO="$XDIR/aarch64-unknown-linux-gnu/release/lib$LIBNAME.so"
  [ -f "$ARM_SO" ] || { echo "build-fmu: $ARM_SO not found" >&2; exit 1; }
  afmt=$(llvm-objdump-22 -f "$ARM_SO" | sed -n 's/.*file format //p')
  [ "$afmt" = elf64-littleaarch64 ] || { echo "build-fmu: $ARM_SO is '$afmt', not elf64-littleaarch64" >&2; exit 1; }
  exports "$(llvm-nm-22 -D --defined-only "$ARM_SO" | awk '{print $NF}')" "aarch64-linux"
  anewest=$(llvm-objdump-22 -T "$ARM_SO" | grep -o 'GLIBC_[0-9][0-9.]*' | sed 's/GLIBC_//' | sort -V | tail -1)
  if [ -n "$anewest" ] && [ "$(printf '%s\n%s\n' "$anewest" "$GLIBC_MAX" | sort -V | tail -1)" != "$GLIBC_MAX" ]; then
    echo "build-fmu: $ARM_SO needs GLIBC_$anewest > $GLIBC_MAX" >&2; exit 1
  fi
  aneeded=$(llvm-readelf-22 -d "$ARM_SO" | sed -n 's/.*Shared library: \[\(.*\)\]/\1/p' | xargs)
  abad=$(tr ' ' '\n' <<<"$aneeded" | grep -Ev '^(libc\.so\.6|libm\.so\.6|libdl\.so\.2|libpthread\.so\.0|librt\.so\.1|libgcc_s\.so\.1|ld-linux-aarch64\.so\.1)$' || true)
  [ -z "$abad" ] || { echo "build-fmu: $ARM_SO needs libraries outside the base system: $abad" >&2; exit 1; }
  echo "build-fmu: aarch64-linux: ELF aarch64, $N_FMI2 fmi2* and $N_FMI3 fmi3* exports, glibc >= ${anewest:-any}, needs $aneeded" >&2
fi

# --- pack ----------------------------------------------------------------------------------
OUT3="$(dirname "$OUT")/${ID}_fmi3.fmu"
STAGE="$ROOT/target/fmu-stage/$ID"
STAGE3="$ROOT/target/fmu-stage/${ID}_fmi3"
rm -rf "$STAGE" "$STAGE3"
mkdir -p "$STAGE/binaries/linux64" "$STAGE/resources/presets" "$STAGE/documentation" "$(dirname "$OUT")"
mkdir -p "$STAGE3/binaries/x86_64-linux" "$STAGE3/resources/presets" "$STAGE3/documentation" "$STAGE3/terminalsAndIcons"
cp modelDescription/modelDescription.xml "$STAGE/"
cp modelDescription/fmi3/modelDescription.xml "$STAGE3/"
cp "$SO" "$STAGE/binaries/linux64/$ID.so"
cp "$SO" "$STAGE3/binaries/x86_64-linux/$ID.so"
if [ -n "$WIN_DLL" ]; then
  mkdir -p "$STAGE/binaries/win64" "$STAGE3/binaries/x86_64-windows"
  cp "$WIN_DLL" "$STAGE/binaries/win64/$ID.dll"
  cp "$WIN_DLL" "$STAGE3/binaries/x86_64-windows/$ID.dll"
fi
if [ -n "$MAC_DYLIB" ]; then
  mkdir -p "$STAGE/binaries/darwin64" "$STAGE3/binaries/x86_64-darwin" "$STAGE3/binaries/aarch64-darwin"
  cp "$MAC_DYLIB" "$STAGE/binaries/darwin64/$ID.dylib"
  # FMI 3.0 has a folder per architecture: the universal library's slices
  cp "$XDIR/darwin64/x86_64.dylib" "$STAGE3/binaries/x86_64-darwin/$ID.dylib"
  cp "$XDIR/darwin64/arm64.dylib" "$STAGE3/binaries/aarch64-darwin/$ID.dylib"
fi
if [ -n "${ARM_SO:-}" ]; then mkdir -p "$STAGE3/binaries/aarch64-linux"; cp "$ARM_SO" "$STAGE3/binaries/aarch64-linux/$ID.so"; fi
cp creep-core/presets/*.json "$STAGE/resources/presets/"
cp creep-core/presets/*.json "$STAGE3/resources/presets/"
cp fmu-crate/assets/model.png "$STAGE/model.png"
cp fmu-crate/assets/model.png "$STAGE3/terminalsAndIcons/icon.png"
for b in ${EXTRA[@]+"${EXTRA[@]}"}; do
  plat=${b%%=*}; path=${b#*=}
  case "$plat" in win*) ext=dll ;; darwin*) ext=dylib ;; *) ext=so ;; esac
  mkdir -p "$STAGE/binaries/$plat"
  cp "$path" "$STAGE/binaries/$plat/$ID.$ext"
  echo "build-fmu: packed $path as binaries/$plat/$ID.$ext (FMI 2.0 FMU)" >&2
done
# documentation/index.html: docs/fmu.md rendered to HTML (pulldown-cmark), the markdown beside it
cp docs/fmu.md "$STAGE/documentation/"
cargo run -q --release -p ecf-fmu --example render_doc -- docs/fmu.md "$STAGE/documentation/index.html" >&2
cp "$STAGE/documentation/"* "$STAGE3/documentation/"
rm -f "$OUT" "$OUT3"
for pair in "$STAGE=$OUT" "$STAGE3=$OUT3"; do
python3 - "${pair%%=*}" "${pair#*=}" <<'PY'
import os, sys, zipfile
stage, out = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
    for base, dirs, files in sorted(os.walk(stage)):
        dirs.sort()
        for f in sorted(files):
            p = os.path.join(base, f)
            z.write(p, os.path.relpath(p, stage))
PY
done

# --- smoke test: the binary accepts the packed model descriptions (GUID, token) -------------
python3 - "$OUT" "$OUT3" <<'PY' >&2
import sys
from fmpy import read_model_description, extract
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
for fmu, cls, what in ((sys.argv[1], FMU2Slave, "GUID"), (sys.argv[2], FMU3Slave, "instantiationToken")):
    md = read_model_description(fmu)
    d = extract(fmu)
    token = md.guid if cls is FMU2Slave else md.instantiationToken
    s = cls(guid=token, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="smoke")
    try:
        s.instantiate()
    except Exception as e:
        sys.exit(f"build-fmu: the binary refuses the modelDescription.xml of {fmu} ({e}); regenerate it: "
                 "ECF_FMU_WRITE_MD=1 cargo test -p ecf-fmu --test model_description --test model_description3")
    s.freeInstance()
    print(f"build-fmu: smoke test ok ({md.fmiVersion}: instantiate with the packed {what})")
PY
if [ -n "$EFFECTS" ]; then
  # the ecf binary with the same effects (built for this machine, beside the project's own
  # target/release/ecf, whose compiled dependencies it shares)
  cargo build --release "${MAN[@]}" -p ecf-with-effects >&2
  mkdir -p "$DEST"
  cp "target/release/ecf-with-$ELIB" "$DEST/ecf"
  echo "build-fmu: with $EPKG: $DEST/ecf, $OUT and $OUT3" >&2
fi
echo "$OUT3"
echo "$OUT"
