#!/usr/bin/env bash
# Builds the wheels of the Python package ecf (ecf-py, abi3: CPython >= 3.9) into dist/wheels and checks each; the last lines of output are their paths.
#
# manylinux2014_x86_64  glibc >= 2.17, linked through zig (maturin --zig, as the FMU's linux64)
# win_amd64             MinGW-w64 (as the FMU's win64), python3.dll's import library made by
#                       pyo3 (generate-import-lib), no MinGW runtime DLL needed
# macosx_11_0_universal2 x86_64 + arm64 in one extension (as the FMU's darwin64), arm64 signed;
#                       tagged universal2, arm64 and x86_64 (pip on either Mac takes it)
#
# Windows and macOS are cross-built with Debian's Rust (rustc-web) and -Zbuild-std, in the
# FMU's cross target directory (target/cross), because rustup's targets cannot be downloaded
# (scripts/build-fmu.sh says more). Checks on each wheel: its platform tag; the extension
# ecf/_ecf exports the init function PyInit__ecf; it links only system libraries (Linux: no
# glibc symbol newer than 2.17, no libpython; Windows: system DLLs and python3.dll; macOS:
# libSystem only, Python's symbols looked up at load time, minimum macOS 11.0).
# `--linux-only` (or ECF_WHEEL_LINUX_ONLY=1) builds the Linux wheel alone (CI's tests need
# no more). ECF_WHEEL_OUT=DIR writes the wheels elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
OUT="${ECF_WHEEL_OUT:-$ROOT/dist/wheels}"
LINUX_ONLY=${ECF_WHEEL_LINUX_ONLY:-0}
for a in "$@"; do
  case "$a" in
    --linux-only) LINUX_ONLY=1 ;;
    *) echo "build-wheel: unknown argument '$a' (accepted: --linux-only)" >&2; exit 2 ;;
  esac
done
GLIBC_MAX=2.17
bash scripts/setup-venv.sh >&2
if [ "$LINUX_ONLY" != 1 ]; then
  source scripts/cross/packages.sh
  if ! bash scripts/apt-ensure.sh binutils "${CROSS_PACKAGES[@]}"; then
    echo "build-wheel: WARNING: the Windows and macOS wheels need the Debian 12 packages ${CROSS_PACKAGES[*]}: building the Linux wheel only" >&2
    LINUX_ONLY=1
  fi
fi
export PATH="$ROOT/.venv/bin:$PATH"
mkdir -p "$OUT"
rm -f "$OUT"/ecf-*.whl
MAN=(-m ecf-py/Cargo.toml --release -o "$OUT")
STAGE="$ROOT/target/wheel-check"

# unpack WHEEL into $STAGE/NAME and print its Tag lines, sorted
unpack() {
  local whl=$1 d="$STAGE/$2"
  rm -rf "$d"; mkdir -p "$d"
  python3 -c 'import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])' "$whl" "$d"
  sed -n 's/^Tag: //p' "$d"/ecf-*.dist-info/WHEEL | sort | xargs
}
fail() { echo "build-wheel: $*" >&2; exit 1; }

# --- manylinux2014 x86_64 ----------------------------------------------------------------
maturin build "${MAN[@]}" --zig --compatibility manylinux2014 --target x86_64-unknown-linux-gnu >&2
WL=$(ls "$OUT"/ecf-*manylinux*x86_64.whl)
tags=$(unpack "$WL" linux)
[ "$tags" = "cp39-abi3-manylinux2014_x86_64 cp39-abi3-manylinux_2_17_x86_64" ] || fail "$WL: tags '$tags'"
SO="$STAGE/linux/ecf/_ecf.abi3.so"
[ -f "$SO" ] || fail "$WL holds no ecf/_ecf.abi3.so"
nm -D --defined-only "$SO" | awk '{print $3}' | grep -qx PyInit__ecf || fail "$SO does not export PyInit__ecf"
newest=$(objdump -T "$SO" | grep -o 'GLIBC_[0-9][0-9.]*' | sed 's/GLIBC_//' | sort -V | tail -1)
[ "$(printf '%s\n%s\n' "${newest:-0}" "$GLIBC_MAX" | sort -V | tail -1)" = "$GLIBC_MAX" ] || fail "$SO needs GLIBC_$newest > $GLIBC_MAX"
needed=$(readelf -d "$SO" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | xargs)
for n in $needed; do
  case "$n" in libc.so.6|libm.so.6|libdl.so.2|libpthread.so.0|librt.so.1|libgcc_s.so.1|ld-linux-x86-64.so.2) ;;
    *) fail "$SO links $n (allowed: the base system's libc, libm, libdl, libpthread, librt, libgcc_s)" ;; esac
done
echo "build-wheel: linux: $tags; PyInit__ecf exported; glibc <= ${newest:-none}; needs $needed" >&2

if [ "$LINUX_ONLY" != 1 ]; then
  XDIR="$ROOT/target/cross"
  Z=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "lib"))')
  # Debian's Rust, std from source (as scripts/build-fmu.sh)
  E=(PATH="/usr/bin:$ROOT/.venv/bin:$PATH" RUSTC=/usr/bin/rustc CARGO=/usr/bin/cargo RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR="$XDIR")
  echo "build-wheel: cross builds with Debian's rustc $(/usr/bin/rustc --version | cut -d' ' -f2), standard library from source" >&2

  # --- win_amd64 -------------------------------------------------------------------------
  env "${E[@]}" CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER=x86_64-w64-mingw32-gcc \
    maturin build "${MAN[@]}" --target x86_64-pc-windows-gnu -Zbuild-std=std,panic_unwind >&2
  WW=$(ls "$OUT"/ecf-*win_amd64.whl)
  tags=$(unpack "$WW" win)
  [ "$tags" = "cp39-abi3-win_amd64" ] || fail "$WW: tags '$tags'"
  PYD="$STAGE/win/ecf/_ecf.pyd"
  [ -f "$PYD" ] || fail "$WW holds no ecf/_ecf.pyd"
  fmt=$(x86_64-w64-mingw32-objdump -f "$PYD" | sed -n 's/.*file format //p')
  [ "$fmt" = pei-x86-64 ] || fail "$PYD is '$fmt', not PE32+ x86-64"
  x86_64-w64-mingw32-objdump -p "$PYD" | sed -n '/\[Ordinal\/Name Pointer\] Table/,/^$/p' | grep -qw PyInit__ecf || fail "$PYD does not export PyInit__ecf"
  wimp=$(x86_64-w64-mingw32-objdump -p "$PYD" | sed -n 's/^\s*DLL Name: //p' | sort -fu | xargs)
  for d in $wimp; do
    echo "$d" | grep -Eiq '^(kernel32|msvcrt|ntdll|userenv|ws2_32|bcryptprimitives|advapi32|python3|api-ms-win-[a-z0-9-]+)\.dll$' || fail "$PYD imports $d (outside the Windows system and python3.dll)"
  done
  echo "build-wheel: win: $tags; PE32+ x86-64, PyInit__ecf exported; imports $wimp" >&2

  # --- macosx universal2 -----------------------------------------------------------------
  # the minimal SDK of scripts/build-fmu.sh: zig's libSystem stub (arm64e names renamed)
  SDK="$XDIR/MacOSX.sdk"
  mkdir -p "$SDK/usr/lib"
  sed 's/arm64e\.x1-/arm64-/g' "$Z/libc/darwin/libSystem.tbd" > "$SDK/usr/lib/libSystem.tbd.new"
  mv "$SDK/usr/lib/libSystem.tbd.new" "$SDK/usr/lib/libSystem.tbd"
  ln -sfn "$Z/libc/include/any-darwin-any" "$SDK/usr/include"
  L="$ROOT/scripts/cross/link-darwin-py.sh"
  env "${E[@]}" SDKROOT="$SDK" MACOSX_DEPLOYMENT_TARGET=11.0 \
    CARGO_TARGET_X86_64_APPLE_DARWIN_LINKER="$L" CARGO_TARGET_AARCH64_APPLE_DARWIN_LINKER="$L" \
    CARGO_TARGET_X86_64_APPLE_DARWIN_RUSTFLAGS="-C linker-flavor=ld64.lld" \
    CARGO_TARGET_AARCH64_APPLE_DARWIN_RUSTFLAGS="-C linker-flavor=ld64.lld" \
    maturin build "${MAN[@]}" --target universal2-apple-darwin -Zbuild-std=std,panic_unwind >&2
  WM=$(ls "$OUT"/ecf-*macosx*universal2*.whl)
  tags=$(unpack "$WM" mac)
  [ "$tags" = "cp39-abi3-macosx_11_0_arm64 cp39-abi3-macosx_11_0_universal2 cp39-abi3-macosx_11_0_x86_64" ] || fail "$WM: tags '$tags'"
  MSO="$STAGE/mac/ecf/_ecf.abi3.so"
  [ -f "$MSO" ] || fail "$WM holds no ecf/_ecf.abi3.so"
  archs=$(llvm-lipo-22 -archs "$MSO" | xargs)
  [ "$archs" = "x86_64 arm64" ] || fail "$MSO holds '$archs', want 'x86_64 arm64'"
  for arch in x86_64 arm64; do
    slice="$STAGE/mac/$arch.so"
    llvm-lipo-22 -thin "$arch" -output "$slice" "$MSO"
    llvm-nm-22 -gU --defined-only "$slice" | awk '{print $NF}' | grep -qx _PyInit__ecf || fail "macOS $arch does not export _PyInit__ecf"
    libs=$(llvm-otool-22 -L "$slice" | tail -n +2 | awk '{print $1}' | grep -v '_ecf' | xargs)
    [ "$libs" = /usr/lib/libSystem.B.dylib ] || fail "macOS $arch links '$libs' (want /usr/lib/libSystem.B.dylib only)"
    cmds=$(llvm-otool-22 -l "$slice")
    minos=$(awk '/LC_BUILD_VERSION/ {b = 1} b && $1 == "minos" {print $2; exit}' <<<"$cmds")
    [ "$minos" = 11.0 ] || fail "macOS $arch: minimum macOS '$minos', want 11.0"
    if [ "$arch" = arm64 ] && ! grep -q LC_CODE_SIGNATURE <<<"$cmds"; then fail "macOS arm64 slice is not signed"; fi
  done
  echo "build-wheel: mac: $tags; $archs, _PyInit__ecf exported by each, only libSystem, macOS >= 11.0, arm64 signed" >&2
fi
ls "$OUT"/ecf-*.whl
