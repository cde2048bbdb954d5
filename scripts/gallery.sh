#!/usr/bin/env bash
# Validation gallery: regenerates the seed's results with the project's own code.
#
#   bash scripts/gallery.sh                 full gallery -> docs/validation/ (PNG, README.md, numbers.json)
#   bash scripts/gallery.sh --quick OUTDIR  reduced settings (coarser grids, fewer points, shorter
#                                           drive-train runs): every figure and every assertion (CI)
#   bash scripts/gallery.sh [--quick] [--no-plots] [OUTDIR]
#
# Builds what it needs first: the `ecf` CLI (release), the contact FMU
# (scripts/build-fmu.sh) and the Python venv (scripts/setup-venv.sh). Exit code 1 when a seed
# statement has an unexpected outcome (see the summary printed at the end).
# Environment: GALLERY_JOBS (figures computed in parallel, default 2).
set -euo pipefail
cd "$(dirname "$0")/.."

args=()
out=""
quick=0
for a in "$@"; do
  case "$a" in
    --quick) quick=1; args+=("$a") ;;
    --no-plots) args+=("$a") ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    -*) echo "gallery.sh: unknown option $a" >&2; exit 2 ;;
    *) out="$a" ;;
  esac
done
if [ -z "$out" ]; then
  if [ "$quick" = 1 ]; then out=out/gallery-quick; else out=docs/validation; fi
fi

echo "== gallery: build ecf CLI" >&2
cargo build --release -q -p ecf-cli >&2
echo "== gallery: contact FMUs (the drive-train demo, the FMI 3.0 field arrays)" >&2
bash scripts/build-fmu.sh >/dev/null
bash scripts/setup-venv.sh
echo "== gallery: compute and plot -> $out" >&2
# a full regeneration starts from an empty directory so that no stale figure survives
if [ "$quick" = 0 ] && [ -d "$out" ]; then
  find "$out" -maxdepth 1 \( -name '*.png' -o -name 'README.md' -o -name 'numbers.json' -o -name 'run_info.txt' \) -delete
fi
.venv/bin/python -m gallery "${args[@]}" --jobs "${GALLERY_JOBS:-2}" "$out"
