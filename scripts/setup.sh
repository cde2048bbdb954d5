#!/usr/bin/env bash
# Installs what the project needs on a fresh Debian machine: apt packages, the Rust crates
# (cargo fetch) and the Python venv from the pinned requirements.txt. Idempotent; apt runs only
# when something is missing. `--tests` adds what only the tests need (Wine, to run the Windows
# FMU binary; qemu-user and an ARM64 C compiler, to run the aarch64-linux one).
#
# apt packages and why:
#   libclang-dev, binutils        bindgen of fmi-sys; objdump/nm checks of the linux64 binary
#   rustc-web cargo-web           Debian's Rust with the source of its standard library
#   rust-web-src                  (-Zbuild-std): the Windows and macOS standard libraries are
#                                 built from it, as rustup's cannot be downloaded here
#   gcc-mingw-w64-x86-64          MinGW-w64: linker and C compiler of the win64 binary
#   lld-22, llvm-22               ld64.lld (links the darwin64 binary with its export list),
#                                 llvm-lipo/-nm/-otool/-objdump/-readelf (universal binary,
#                                 aarch64-linux binary and their checks)
#   wine64 (--tests)              runs the win64 binary under test
#   qemu-user (--tests)           runs the aarch64-linux binary under test (qemu-aarch64)
#   gcc-aarch64-linux-gnu (--tests)  builds the C test driver for aarch64-linux (with its glibc)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/apt-ensure.sh libclang-dev binutils
# the cross-build and Wine packages are Debian 12's; elsewhere build-fmu.sh builds linux64
# alone (with a warning) and the Windows test fails, saying Wine is missing
source scripts/cross/packages.sh
if [ "${1:-}" = --tests ]; then CROSS_PACKAGES+=(wine64 qemu-user gcc-aarch64-linux-gnu); fi
bash scripts/apt-ensure.sh "${CROSS_PACKAGES[@]}" || echo "setup: WARNING: could not install ${CROSS_PACKAGES[*]} (Debian 12 packages): the FMU will carry linux64 only" >&2
command -v cargo >/dev/null || { echo "setup: cargo (stable Rust) is required: https://rustup.rs" >&2; exit 1; }
cargo fetch --locked -q >&2 || cargo fetch -q >&2
bash scripts/setup-venv.sh
