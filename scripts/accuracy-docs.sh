#!/usr/bin/env bash
# Regenerates what is derived from the accuracy table creep-core/data/accuracy.csv (written by
# `bash scripts/bench.sh --only accuracy`, which calls this script at its end):
#   - docs/img/accuracy/pareto_*.png: one Pareto PNG per case (scripts/accuracy_pareto.py,
#     matplotlib from .venv, or the Python named by $PYTHON);
#   - the tolerance table of docs/fmu.md, between the markers <!-- tolerance-table:begin -->
#     and <!-- tolerance-table:end -->, printed by
#     `cargo run --release -q -p creep-core --example tolerance_table` (creep_core::tolerance
#     itself, so the table is what --tol and rel_tol choose);
#   - the accuracy summary of docs/model.md section 9.2, between the markers
#     <!-- accuracy-summary:begin --> and <!-- accuracy-summary:end -->, printed by
#     scripts/accuracy_summary.py (python3, no packages).
#   bash scripts/accuracy-docs.sh            both
#   bash scripts/accuracy-docs.sh --no-plots the docs tables only
set -euo pipefail
cd "$(dirname "$0")/.."
plots=1
for a in "$@"; do
  case "$a" in
    --no-plots) plots=0 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "accuracy-docs.sh: unknown option $a" >&2; exit 2 ;;
  esac
done
if [ "$plots" = 1 ]; then
  PY=${PYTHON:-.venv/bin/python}
  if [ ! -x "$PY" ] && ! command -v "$PY" >/dev/null 2>&1; then
    bash scripts/setup-venv.sh
    PY=.venv/bin/python
  fi
  "$PY" scripts/accuracy_pareto.py creep-core/data/accuracy.csv docs/img/accuracy >/dev/null
  echo "== accuracy-docs: Pareto PNGs -> docs/img/accuracy/" >&2
fi
table=$(cargo run --release -q -p creep-core --example tolerance_table)
summary=$(python3 scripts/accuracy_summary.py creep-core/data/accuracy.csv)
# replace_block FILE NAME TEXT: the text between <!-- NAME:begin --> and <!-- NAME:end -->
replace_block() {
  BLOCK="$3" python3 - "$1" "$2" <<'EOF'
import os, sys
path, name = sys.argv[1], sys.argv[2]
text = open(path).read()
begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
i, j = text.find(begin), text.find(end)
if i < 0 or j < i:
    sys.exit(f"accuracy-docs: {path} has no {begin} ... {end} block")
new = text[: i + len(begin)] + "\n" + os.environ["BLOCK"].strip() + "\n" + text[j:]
if new != text:
    open(path, "w").write(new)
EOF
}
replace_block docs/fmu.md tolerance-table "$table"
echo "== accuracy-docs: tolerance table -> docs/fmu.md" >&2
replace_block docs/model.md accuracy-summary "$summary"
echo "== accuracy-docs: accuracy summary -> docs/model.md" >&2
