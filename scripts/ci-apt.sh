#!/usr/bin/env bash
# Debian packages the FMU build needs: libclang (bindgen in fmi-sys), binutils (objdump, nm; ldd comes with libc-bin).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq libclang-dev binutils >/dev/null
