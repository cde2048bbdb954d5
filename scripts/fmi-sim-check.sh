#!/usr/bin/env bash
# Opt-in check of the FMU in a third importer: fmi-sim, the command-line FMI simulator of the
# rust-fmi project (crates.io `fmi-sim`), beside fmpy (tests-py) and rust-fmi's library
# (fmu-crate/tests/rust_fmi_import.rs). Not part of scripts/test-all.sh: installing fmi-sim
# compiles ~340 crates (arrow, ...), about 10 min of CPU (22 min wall on a busy 2-core machine).
#
#   bash scripts/fmi-sim-check.sh     # installs fmi-sim into .tools/ once, then runs the check
#
# Runs dist/ecf_contact.fmu (or $ECF_FMU_PATH; built by scripts/build-fmu.sh if missing) for
# 0.1 s in Co-Simulation with 1 ms communication steps and an input file with c_x = +0.002
# (traction) up to 0.05 s and -0.002 (braking) after, v = 20 m/s, FN = 110 kN (the change lies
# between two communication points, so every importer sets exactly these values), twice: with the default
# parameters (preset table4.1) and with the String parameter preset = wet plus nx = 40 set as
# start values. Checks: the output columns are time and the FMU's 13 outputs, 101 rows, every
# value finite, Fx has the sign of c_x (traction > 0 at the start, braking < 0 at the end),
# f = Fx/FN, the area fractions sum to 1, and the wet run has a smaller |Fx| than the dry one
# (the String start value reached the FMU), and the FMU logged no error (fmi-sim ignores a
# refused start value and exits 0; RUST_LOG=warn shows the FMU's log, `-v` does not).
# With the project's venv (fmpy) present, both runs are also compared with fmpy's
# simulate_fmu on the same input (relative difference < 1e-9; measured ~1e-11. Not on
# a ramp: a 1-ulp difference of an interpolated c_x changes Fx by up to ~1e-5 relative, the
# tolerance of the model's iterations, and importers interpolate differently in the last bit).
#
# Environment: ECF_TOOLS_DIR (install root, default .tools), FMI_SIM (an fmi-sim binary to
# use instead of installing one), ECF_FMU_PATH (the FMU to check).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
VERSION=0.7.0
TOOLS=${ECF_TOOLS_DIR:-$ROOT/.tools}
SIM=${FMI_SIM:-$TOOLS/bin/fmi-sim}

if [ -z "${FMI_SIM:-}" ] && ! { [ -x "$SIM" ] && cargo install --list --root "$TOOLS" | grep -q "^fmi-sim v$VERSION:"; }; then
  echo "fmi-sim-check: installing fmi-sim $VERSION into $TOOLS (cargo install --locked; takes minutes)" >&2
  cargo install fmi-sim --version "=$VERSION" --locked --root "$TOOLS" >&2
fi
[ -x "$SIM" ] || { echo "fmi-sim-check: $SIM is not an executable" >&2; exit 1; }

FMU=${ECF_FMU_PATH:-$ROOT/dist/ecf_contact.fmu}
if [ ! -f "$FMU" ]; then
  [ -z "${ECF_FMU_PATH:-}" ] || { echo "fmi-sim-check: ECF_FMU_PATH=$FMU does not exist" >&2; exit 1; }
  FMU=$(bash scripts/build-fmu.sh | tail -1)
fi

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# fmi-sim interpolates linearly between rows; inputs not in the file (cy, spin, T_bulk, aux*)
# keep their start values.
cat > "$WORK/input.csv" <<'CSV'
time,cx,v,FN
0.0,0.002,20.0,110000.0
0.0502,0.002,20.0,110000.0
0.0508,-0.002,20.0,110000.0
0.1,-0.002,20.0,110000.0
CSV

run() { # name, then extra fmi-sim co-simulation options
  local name=$1; shift
  # fmi-sim prints a line per recorded step on stdout: keep it in a log
  if ! RUST_LOG=warn "$SIM" --model "$FMU" -i "$WORK/input.csv" -o "$WORK/$name.csv" co-simulation \
      -s 0 -f 0.1 --output-interval 0.001 "$@" > "$WORK/$name.log" 2>&1; then
    echo "fmi-sim-check: fmi-sim failed on $FMU ($name):" >&2
    tail -20 "$WORK/$name.log" >&2
    exit 1
  fi
  if grep -q '^ERROR' "$WORK/$name.log"; then
    echo "fmi-sim-check: the FMU logged errors ($name):" >&2
    grep '^ERROR' "$WORK/$name.log" | head -5 >&2
    exit 1
  fi
}
run dry
run wet --init-values preset=wet --init-values nx=40

PY=python3
[ -x "$ROOT/.venv/bin/python" ] && PY=$ROOT/.venv/bin/python
"$PY" - "$WORK" "$FMU" <<'PY'
import csv, math, sys

work, fmu = sys.argv[1], sys.argv[2]
OUT = ["Fx", "Fy", "Mz", "f", "T_max", "T_mean", "P_fric", "frac_elastic", "frac_plastic",
       "frac_sliding", "a", "b", "p0"]
FN = 110e3
bad = []


def check(name):
    with open(f"{work}/{name}.csv", newline="") as fh:
        r = csv.reader(fh)
        header = next(r)
        rows = [[float(x) for x in row] for row in r]
    if header != ["time"] + OUT:
        bad.append(f"{name}: columns {header}, want time + {OUT}")
        return None
    cols = {h: [row[i] for row in rows] for i, h in enumerate(header)}
    if len(rows) != 101 or abs(cols["time"][0]) > 1e-12 or abs(cols["time"][-1] - 0.1) > 1e-9:
        bad.append(f"{name}: {len(rows)} rows from t = {cols['time'][0]} to {cols['time'][-1]}, want 101 from 0 to 0.1")
    for h, xs in cols.items():
        nonfinite = [t for t, x in zip(cols["time"], xs) if not math.isfinite(x)]
        if nonfinite:
            bad.append(f"{name}: {h} not finite at t = {nonfinite[:5]}")
    for t, fx, f, fe, fp, fs in zip(cols["time"], cols["Fx"], cols["f"], cols["frac_elastic"],
                                    cols["frac_plastic"], cols["frac_sliding"]):
        # row t holds the outputs of the step from t - 1 ms, which ran with c_x(t - 1 ms)
        cx = 0.002 if t < 0.0515 else -0.002
        if fx * cx <= 0:
            bad.append(f"{name}: t = {t:.3f} s: Fx = {fx:.6g} N has not the sign of c_x = {cx:.6g}")
        if abs(f - fx / FN) > 1e-9 * max(1.0, abs(f)):
            bad.append(f"{name}: t = {t:.3f} s: f = {f} != Fx/FN = {fx / FN}")
        if abs(fe + fp + fs - 1) > 1e-9:
            bad.append(f"{name}: t = {t:.3f} s: area fractions sum to {fe + fp + fs}")
    return cols


dry, wet = check("dry"), check("wet")
if dry and wet:
    print(f"fmi-sim-check: dry (table4.1): Fx = {dry['Fx'][0]:.1f} N at t = 0 (c_x = +0.002), "
          f"{dry['Fx'][-1]:.1f} N at t = 0.1 s (c_x = -0.002)")
    print(f"fmi-sim-check: preset = wet, nx = 40: Fx = {wet['Fx'][0]:.1f} N at t = 0, {wet['Fx'][-1]:.1f} N at t = 0.1 s")
    if not abs(wet["Fx"][0]) < abs(dry["Fx"][0]):
        bad.append(f"wet: |Fx| = {abs(wet['Fx'][0])} N not below dry's {abs(dry['Fx'][0])} N: was preset = wet applied?")
    try:
        import numpy as np
        from fmpy import read_model_description, simulate_fmu
    except ImportError:
        print("fmi-sim-check: fmpy not available, no comparison with fmpy")
    else:
        # every input in the table (fmpy warns of missing ones): those fmi-sim had not at their start
        given = {"cx": [0.002, 0.002, -0.002, -0.002], "v": [20.0] * 4, "FN": [FN] * 4}
        ins = [v for v in read_model_description(fmu).modelVariables if v.causality == "input"]
        inp = np.array([tuple([t] + [given[v.name][k] if v.name in given else float(v.start) for v in ins])
                        for k, t in enumerate([0.0, 0.0502, 0.0508, 0.1])],
                       dtype=[("time", float)] + [(v.name, float) for v in ins])
        for name, cols, start in [("dry", dry, {}), ("wet", wet, {"preset": "wet", "nx": 40})]:
            ref = simulate_fmu(fmu, start_time=0.0, stop_time=0.1, output_interval=1e-3,
                               step_size=1e-3, input=inp, start_values=start, output=OUT)
            # relative to the column's largest value; Fy, Mz (zero up to rounding here) to |Fx|
            fx_scale = max(abs(x) for x in cols["Fx"])
            worst = max(max(abs(a - b) for a, b in zip(cols[h], ref[h])) /
                        max(max(abs(x) for x in ref[h]),
                            fx_scale if h in ("Fx", "Fy", "Mz") else 0.0, 1e-12)
                        for h in OUT)
            if len(ref) != len(cols["Fx"]) or worst > 1e-9:
                bad.append(f"{name}: differs from fmpy (relative {worst:.3g}, rows {len(ref)})")
            else:
                print(f"fmi-sim-check: {name}: equals fmpy's simulate_fmu (largest relative difference {worst:.2g})")
if bad:
    sys.exit("fmi-sim-check: FAILED\n  " + "\n  ".join(bad[:20]))
print("fmi-sim-check: ok")
PY
