"""The dip of the dry curve at 30 m/s between c_x = 0.4 % and 0.8 % (docs/model.md section 6):
three grids and the same set with the temperature effect off.

    .venv/bin/python docs/figures/dip_dry_30mps.py   (builds nothing: needs target/release/ecf)
writes docs/figures/dip_dry_30mps.png.
"""
import csv
import io
import pathlib
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
ECF = ROOT / "target" / "release" / "ecf"
CX = "0.001:0.02:39"


def curve(args):
    out = subprocess.run([str(ECF), "curve", "--v-mps", "30", "--cx", CX, *args],
                         check=True, capture_output=True, text=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    return [100 * float(r["cx"]) for r in rows], [float(r["f"]) for r in rows], [float(r["T_max_C"]) for r in rows]


def main():
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for grid, style in [("80x21", ":"), ("160x41", "--"), ("320x81", "-")]:
        x, f, t = curve(["--preset", "dry", "--grid", grid])
        ax.plot(x, f, style, label=f"dry, {grid}")
        bx.plot(x, t, style, label=f"dry, {grid}")
    cfg = ROOT / "target" / "dip_notemp.json"
    cfg.write_text('{"preset": "dry", "effects": ["-temperature"]}')
    x, f, _ = curve(["--config", str(cfg), "--grid", "160x41"])
    ax.plot(x, f, "k-", lw=0.8, label="dry without temperature, 160x41")
    ax.axvspan(0.4, 0.8, color="0.9")
    ax.set_xlabel("longitudinal creepage c_x (%)")
    ax.set_ylabel("traction coefficient f = F_x / F_N (-)")
    ax.set_title("dry preset, v = 30 m/s, F_N = 110 kN")
    ax.set_ylim(0.22, 0.34)
    ax.legend(fontsize=8)
    bx.set_xlabel("longitudinal creepage c_x (%)")
    bx.set_ylabel("peak flash temperature T_max (degC)")
    bx.legend(fontsize=8)
    fig.savefig(ROOT / "docs" / "figures" / "dip_dry_30mps.png", dpi=110)


if __name__ == "__main__":
    main()
