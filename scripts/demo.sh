#!/usr/bin/env bash
# Main job of the project: set everything up and reproduce the drive-train oscillation result.
#  1. scripts/setup.sh (apt packages if missing, cargo fetch, Python venv from the pinned
#     requirements) and the release build of the ecf CLI, 2. the contact FMU (scripts/build-fmu.sh),
#  3. the Python venv check (scripts/setup-venv.sh),
#  4. the `step` scenario (desired creepage 0 -> 15 % at 5 m/s) with ECF and FASTSIM,
#     printing the two dominant frequencies and where the plots are.
# Environment: OUT (output directory, default out/demo), DEMO_ARGS (extra options for
# python -m drivetrain_demo, e.g. "--t-end 3 --grid 20x11").
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${OUT:-out/demo}

echo "== 1/4 set-up and cargo build --release (ecf CLI)" >&2
if [ -f scripts/setup.sh ]; then bash scripts/setup.sh; fi
cargo build --release -q -p ecf-cli >&2
echo "== 2/4 contact FMU" >&2
FMU=$(bash scripts/build-fmu.sh | tail -n 1)
[ -f "$FMU" ] || { echo "error: scripts/build-fmu.sh did not produce an FMU (last line: '$FMU')" >&2; exit 1; }
echo "   $FMU" >&2
echo "== 3/4 Python venv" >&2
bash scripts/setup-venv.sh
echo "== 4/4 step scenario, ECF and FASTSIM (progress on stderr)" >&2
mkdir -p "$OUT"
# shellcheck disable=SC2086
PYTHONPATH=drivetrain-demo .venv/bin/python -m drivetrain_demo step --model both --contact fmu --fmu "$FMU" \
  --out "$OUT" --json ${DEMO_ARGS:-} > "$OUT/step_summary.json"
.venv/bin/python - "$OUT" <<'PY'
import json, sys, pathlib
out = pathlib.Path(sys.argv[1])
s = json.loads((out / "step_summary.json").read_text())
print()
print("Drive-train step 0 -> 15 % at v = 5 m/s (seed Fig. 6.4)")
for m in ("ecf", "fastsim"):
    r = s[m]
    if r["sustained_oscillation"]:
        osc = f"sustained oscillation, dominant frequency {r['dominant_frequency_hz']:6.2f} Hz"
    else:
        osc = f"no sustained oscillation (the step response at {r['transient_frequency_hz']:.2f} Hz decays)"
    print(f"  {m.upper():8s} {osc}, p-p of c_x,L over the last 0.5 s {100 * r['oscillation_amplitude']:.3f} %")
    print(f"  {'':8s} linear analysis at 15 %: {r['predicted_frequency_hz']:.2f} Hz, "
          f"{'UNSTABLE' if r['predicted_unstable'] else 'stable'} (zeta = {r['predicted_damping_ratio']:+.4f}); "
          f"real-time factor {r['real_time_factor']:.2f}")
print("Plots:")
for p in sorted(out.glob("step_*.png")):
    print(f"  {p}")
print(f"CSV/JSON: {out}/step_*.csv, {out}/step_*.json")
PY
