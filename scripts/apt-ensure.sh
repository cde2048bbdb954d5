#!/usr/bin/env bash
# Installs the named Debian packages that are missing (apt-get, with sudo when not root); idempotent: nothing runs when all are there.
set -euo pipefail
missing=()
for p in "$@"; do
  # "install ok installed" only: a removed package whose configuration files remain is missing
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "apt-ensure: installing ${missing[*]}" >&2
if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
$SUDO apt-get update -qq >&2
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >&2
