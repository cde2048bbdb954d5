#!/usr/bin/env bash
# Installs what the project needs on a fresh Debian machine: apt packages (libclang for the
# bindgen of fmi-sys, binutils for the FMU binary checks), the Rust crates (cargo fetch) and
# the Python venv from the pinned requirements.txt. Idempotent; apt runs only when something is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
APT_PACKAGES=(libclang-dev binutils)
missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing apt packages: ${missing[*]}" >&2
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  $SUDO apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >&2
fi
command -v cargo >/dev/null || { echo "setup: cargo (stable Rust) is required: https://rustup.rs" >&2; exit 1; }
cargo fetch --locked -q >&2 || cargo fetch -q >&2
bash scripts/setup-venv.sh
