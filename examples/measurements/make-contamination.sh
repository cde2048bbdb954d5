#!/usr/bin/env bash
# Regenerates contamination.csv: steady curves of contamination-truth.json (the dry preset on
# 80x21 cells with the higher-order rules, both layer strengths falling with a contaminant
# deposit as 1 - 0.35 (1 - exp(-m / 2 mg)), a form no catalogue effect has) at 5, 10, 15, 20,
# 25 m/s and 70, 130 kN, 14 creepages from 0.15 % to 25 % each (140 rows). Each curve has its
# own deposit m (column contamination_mg) and rail head temperature (column rail_C, which the
# truth does not read). The measured f carries normal noise of sd 2 % of f plus 0.003, from a
# fixed seed (awk srand).
set -euo pipefail
cd "$(dirname "$0")"
ECF=${ECF:-../../target/release/ecf}
echo "cx,f,series,v_mps,fn_kN,contamination_mg,rail_C" > contamination.csv
m=(0.4 3.1 1.2 5.6 0.0 2.2 4.3 0.8 3.7 5.0)
r=(18 31 24 12 27 35 21 15 29 22)
k=0
for v in 5 10 15 20 25; do
  for fn in 70 130; do
    "$ECF" curve --config contamination-truth.json --v-mps $v --fn-kN $fn \
      --cx 0.0015,0.0022,0.0033,0.0049,0.0073,0.011,0.016,0.024,0.035,0.052,0.077,0.11,0.17,0.25 \
      --extra contamination_mg=${m[$k]} \
      | awk -F, -v v=$v -v fn=$fn -v m=${m[$k]} -v r=${r[$k]} -v s=$((k + 1)) '
          NR == 1 { srand(s) }
          NR > 1 {
            u = rand(); if (u < 1e-12) u = 1e-12
            z = sqrt(-2 * log(u)) * cos(6.283185307179586 * rand())
            printf "%s,%.6f,v%sF%s,%s,%s,%s,%s\n", $1, $2 + (0.02 * $2 + 0.003) * z, v, fn, v, fn, m, r
          }' >> contamination.csv
    k=$((k + 1))
  done
done
