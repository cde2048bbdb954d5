#!/usr/bin/env bash
# Regenerates humid.csv: steady curves of humidity-truth.json at 30, 50, 70 % humidity, 10 m/s,
# 110 kN, with +-0.002 uniform noise from a fixed seed (awk srand).
set -euo pipefail
cd "$(dirname "$0")"
ECF=${ECF:-../../target/release/ecf}
echo "cx,f,series,v_mps,fn_kN,humidity" > humid.csv
for h in 30 50 70; do
  "$ECF" curve --config humidity-truth.json --extra humidity=$h --v-mps 10 --fn-kN 110 --cx 0.0015:0.25:12 \
    | awk -F, -v h=$h 'NR==1{srand(h)} NR>1{printf "%s,%.6f,h%s,10,110,%s\n", $1, $2 + 0.004*(rand()-0.5), h, h}' >> humid.csv
done
