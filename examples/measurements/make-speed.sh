#!/usr/bin/env bash
# Regenerates speed.csv: steady curves of speed-truth.json (the dry preset, 20x7 bristles, with
# tau_c1 falling with speed as 1/(1 + 1.5 (v - 5)/15), a form no catalogue effect has) at 5, 10,
# 15, 20, 25 m/s, 110 kN, 20 creepages each (100 rows), with +-0.005 uniform noise (sd 0.0029)
# from a fixed seed (awk srand).
set -euo pipefail
cd "$(dirname "$0")"
ECF=${ECF:-../../target/release/ecf}
echo "cx,f,series,v_mps,fn_kN" > speed.csv
for v in 5 10 15 20 25; do
  "$ECF" curve --config speed-truth.json --v-mps $v --fn-kN 110 --cx 0.0015:0.25:20 \
    | awk -F, -v v=$v 'NR==1{srand(v)} NR>1{printf "%s,%.6f,v%s,%s,110\n", $1, $2 + 0.01*(rand()-0.5), v, v}' >> speed.csv
done
