"""PNG plots: creepage time series (seed Fig. 6.4/6.5), spectrum, f over c_x hysteresis (Fig. 6.6), ECF vs FASTSIM."""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def _osc_text(s):
    if s.get("sustained_oscillation", True):
        return f"f_dom = {s['dominant_frequency_hz']:.1f} Hz"
    if s["scenario"] == "ramp":
        return "no oscillation (p-p < 1 %)"
    return f"no sustained oscillation (response {s['transient_frequency_hz']:.1f} Hz decays)"


def _title(s):
    return (f"{s['scenario']} | {s['model'].upper()} | v = {s['v_mps']:g} m/s | {_osc_text(s)} | "
            f"pred. {s['predicted_frequency_hz']:.1f} Hz ({'unstable' if s['predicted_unstable'] else 'stable'})")


def _timeseries(ax, res, zoom=None):
    t = res["t_s"]
    m = np.ones_like(t, bool) if zoom is None else (t >= zoom[0]) & (t <= zoom[1])
    ax.plot(t[m], 100 * res["cx_L"][m], lw=0.8, label="$c_{x,L}$ (long axle)")
    ax.plot(t[m], 100 * res["cx_S"][m], lw=0.8, label="$c_{x,S}$ (short axle)")
    ax.plot(t[m], 100 * res["cx_M"][m], lw=0.8, label="$c_{x,M}$ (motor, Eq. 6.3)")
    ax.plot(t[m], 100 * res["cx_des"][m], "k--", lw=0.8, label="$c_{x,des}$")
    ax.set_xlabel("t / s")
    ax.set_ylabel("$c_x$ / %")
    ax.grid(alpha=0.3)


def _spectrum(ax, s, results):
    sustained = s.get("sustained_oscillation", True)
    freqs, spec = results["spectrum"] if sustained else results["spectrum_transient"]
    if len(freqs):
        m = freqs <= 300
        ax.semilogy(freqs[m], np.maximum(spec[m], 1e-12), lw=0.8)
    if s.get("predicted_frequency_hz"):
        ax.axvline(s["predicted_frequency_hz"], color="r", ls="--", lw=0.8, label="linear prediction")
    fd = s.get("dominant_frequency_hz") if sustained else s.get("transient_frequency_hz")
    if fd:
        ax.axvline(fd, color="k", ls=":", lw=0.8, label="dominant")
    ax.set_xlabel("frequency / Hz")
    ax.set_ylabel("|C_x,L| (amplitude)")
    w = s.get("settled_window_s") if sustained else [0.2, min(1.0, s["t_end_s"])]
    ax.set_title(f"spectrum of $c_{{x,L}}$" + (f", {w[0]:.2f}-{w[1]:.2f} s" if w else ""), fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)


def _fc(ax, res, curve, t_from=None):
    t = res["t_s"]
    m = np.ones_like(t, bool) if t_from is None else t >= t_from
    ax.plot(100 * res["cx_L"][m], res["f_L"][m], lw=0.6, label="$f_L$ over $c_{x,L}$ (simulation)")
    ax.plot(100 * curve[0], curve[1], "k", lw=1.2, label="steady characteristic")
    ax.set_xlabel("$c_{x,L}$ / %")
    ax.set_ylabel("$f_L$")
    ax.set_xlim(min(0.0, 100 * np.nanmin(res["cx_L"][m]) - 1), max(60, 100 * np.nanmax(res["cx_L"][m]) + 2))
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)


def plot_run(path: Path, s: dict, results: dict) -> Path:
    res = results["res"]
    t_end = res["t_s"][-1]
    fig, axs = plt.subplots(2, 2, figsize=(12, 8))
    _timeseries(axs[0, 0], res)
    axs[0, 0].legend(fontsize=7)
    axs[0, 0].set_title("creepages (seed Fig. 6.4/6.5)", fontsize=9)
    z = s.get("zoom_window_s") or [t_end - 0.1, t_end]
    _timeseries(axs[0, 1], res, zoom=tuple(z))
    axs[0, 1].set_title(f"zoom {z[0]:.2f}-{z[1]:.2f} s" + (" (largest oscillation)" if s["scenario"] == "ramp" else ""),
                        fontsize=9)
    _spectrum(axs[1, 0], s, results)
    _fc(axs[1, 1], res, results["curve"], t_from=s["settled_window_s"][0])
    axs[1, 1].set_title("traction over creepage, settled window (seed Fig. 6.6)", fontsize=9)
    fig.suptitle(_title(s), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_sine(path: Path, s: dict, results: dict) -> Path:
    r = results["res"]
    c_grid, f_grid = results["curve"]
    t = r["t_s"]
    period = 1.0 / s["frequency_prescribed_hz"]
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.8))
    axs[0].plot(t * 1e3, 100 * r["cx"], lw=0.8, label="$c_x$ / %")
    ax2 = axs[0].twinx()
    ax2.plot(t * 1e3, r["f"], "r", lw=0.8, label="f")
    axs[0].set_xlabel("t / ms")
    axs[0].set_ylabel("$c_x$ / %")
    ax2.set_ylabel("f", color="r")
    axs[0].grid(alpha=0.3)
    last = t >= t[-1] - period - 1e-12
    axs[1].plot(100 * r["cx"][last], r["f"][last], "r", lw=1.2, label="transient, last period")
    axs[1].plot(100 * r["cx"], r["f"], "r", lw=0.3, alpha=0.4, label="transient, all periods")
    axs[1].plot(100 * c_grid, f_grid, "k", lw=1.2, label="steady characteristic")
    axs[1].set_xlim(0, 100 * (s["cx_mean"] + s["cx_amplitude"]) + 5)
    axs[1].set_xlabel("$c_x$ / %")
    axs[1].set_ylabel("f")
    axs[1].legend(fontsize=8)
    axs[1].grid(alpha=0.3)
    axs[1].set_title(f"hysteresis (seed Fig. 6.6): CV(RMSE) vs steady {s['cv_rmse_vs_steady_percent']:.1f} %, "
                     f"loop area {s['hysteresis_loop_area']:.2e}", fontsize=9)
    fig.suptitle(f"sine | {s['model'].upper()} | v = {s['v_mps']:g} m/s | c_m = {100 * s['cx_mean']:g} %, "
                 f"c_A = {100 * s['cx_amplitude']:g} %, {s['frequency_prescribed_hz']:g} Hz", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_compare(path: Path, runs: list) -> Path:
    """Side by side: one column per (summary, results) run, e.g. ECF and FASTSIM."""
    n = len(runs)
    fig, axs = plt.subplots(3, n, figsize=(6 * n, 11), squeeze=False)
    for j, (s, results) in enumerate(runs):
        res = results["res"]
        if s["scenario"] == "sine":
            c_grid, f_grid = results["curve"]
            axs[0, j].plot(res["t_s"], 100 * res["cx"], lw=0.8)
            axs[1, j].plot(res["t_s"], res["f"], lw=0.8)
            axs[2, j].plot(100 * res["cx"], res["f"], "r", lw=0.8)
            axs[2, j].plot(100 * c_grid, f_grid, "k")
            axs[0, j].set_title(f"{s['model'].upper()}: sine", fontsize=10)
            continue
        _timeseries(axs[0, j], res)
        axs[0, j].legend(fontsize=7)
        axs[0, j].set_title(f"{s['model'].upper()}: {_osc_text(s)},\n"
                            f"p-p(last 0.5 s) = {100 * s['oscillation_amplitude']:.2f} %", fontsize=10)
        _spectrum(axs[1, j], s, results)
        _fc(axs[2, j], res, results["curve"], t_from=s["settled_window_s"][0])
    ylims = [ax.get_ylim() for ax in axs[0]]
    for ax in axs[0]:
        ax.set_ylim(min(y[0] for y in ylims), max(y[1] for y in ylims))
    s0 = runs[0][0]
    fig.suptitle(f"{s0['scenario']} at v = {s0['v_mps']:g} m/s: " + " vs ".join(s['model'].upper() for s, _ in runs),
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _num(v):
    try:
        x = float(v)
    except (TypeError, ValueError):
        return float("nan")
    return x


def plot_stability_map(path, rows, x="v_mps", y="preset", title=""):
    """Stability map of a sweep: x (numeric, e.g. speed) against y (e.g. condition), one panel per
    combination of the other varying inputs. Simulated cases are coloured by the oscillation
    amplitude (p-p of c_x,L, log scale; circle: sustained oscillation, square: none, grey x: failed).
    The linear analysis's stability boundary (predicted damping ratio = 0, interpolated linearly in x
    between swept values, from modal rows where present, else from simulate rows) is drawn as a
    black bar in each y row; the predicted-unstable x ranges are shaded."""
    from matplotlib.colors import LogNorm

    ignore = {x, y, "case_id", "status", "error", "t_end_s", "trace_file", "summary_file", "fmu_content_sha256",
              "project_version", "analysis", "scenario"}
    inputs = ["model", "preset", "v_mps", "FN_kN", "cx_target", "h_ms", "grid"] + \
        sorted({k for r in rows for k in r if k.startswith(("set.", "fmu_param."))})
    varying = [k for k in inputs if k not in ignore and len({str(r.get(k)) for r in rows}) > 1]

    def pkey(r):
        return tuple(str(r.get(k)) for k in varying)

    panels = sorted({pkey(r) for r in rows})[:12]
    ylabels = []
    for r in rows:
        if str(r.get(y)) not in ylabels:
            ylabels.append(str(r.get(y)))
    ncol = min(3, max(1, len(panels)))
    nrow = math.ceil(len(panels) / ncol) if panels else 1
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.2 * ncol + 1.2, 0.55 * len(ylabels) * nrow + 2.2 * nrow),
                             squeeze=False, constrained_layout=True)
    norm = LogNorm(vmin=1e-4, vmax=1.0)
    sc = None
    for i, pk in enumerate(panels):
        ax = axes[i // ncol][i % ncol]
        sel = [r for r in rows if pkey(r) == pk]
        for j, yl in enumerate(ylabels):
            ry = [r for r in sel if str(r.get(y)) == yl]
            sim = [r for r in ry if r.get("analysis") == "simulate"]
            ok = [r for r in sim if r.get("status") == "ok"]
            bad = [r for r in sim if r.get("status") != "ok"]
            for marker, grp in (("o", [r for r in ok if str(r.get("sustained_oscillation")) == "True"]),
                                ("s", [r for r in ok if str(r.get("sustained_oscillation")) != "True"])):
                if grp:
                    amp = np.clip([_num(r["oscillation_pp_cx_L"]) for r in grp], 1e-4, 1.0)
                    sc = ax.scatter([_num(r[x]) for r in grp], [j] * len(grp), c=amp, norm=norm, cmap="viridis",
                                    marker=marker, s=110, edgecolors="k", linewidths=0.6, zorder=3)
            if bad:
                ax.scatter([_num(r[x]) for r in bad], [j] * len(bad), marker="x", c="0.5", s=80, zorder=3)
            # linear boundary from the predicted damping ratio over x
            lin = [r for r in ry if r.get("analysis") == "modal" and r.get("status") == "ok"] or ok
            pts = sorted((_num(r[x]), _num(r["predicted_damping_ratio"])) for r in lin
                         if math.isfinite(_num(r.get("predicted_damping_ratio"))))
            for (x0, z0), (x1, z1) in zip(pts[:-1], pts[1:]):
                if z0 < 0 and z1 < 0:
                    ax.fill_between([x0, x1], j - 0.35, j + 0.35, color="tab:red", alpha=0.12, lw=0)
                if z0 * z1 < 0 and x1 > x0:
                    xb = x0 + (x1 - x0) * (-z0) / (z1 - z0)
                    ax.plot([xb, xb], [j - 0.42, j + 0.42], "k-", lw=2.2, zorder=4)
                    lo, hi = (x0, xb) if z0 < 0 else (xb, x1)
                    ax.fill_between([lo, hi], j - 0.35, j + 0.35, color="tab:red", alpha=0.12, lw=0)
            if len(pts) == 1 and pts[0][1] < 0:
                ax.fill_between([pts[0][0] - 0.3, pts[0][0] + 0.3], j - 0.35, j + 0.35, color="tab:red", alpha=0.12,
                                lw=0)
        ax.set_yticks(range(len(ylabels)))
        ax.set_yticklabels(ylabels)
        ax.set_ylim(-0.6, len(ylabels) - 0.4)
        ax.set_xlabel({"v_mps": "v / (m/s)", "FN_kN": "F_N / kN", "cx_target": "c_x target / -"}.get(x, x))
        ax.set_ylabel(y)
        ax.grid(alpha=0.3)
        ax.set_title(", ".join(f"{k} = {v}" for k, v in zip(varying, pk)) or "all cases", fontsize=9)
    for k in range(len(panels), nrow * ncol):
        axes[k // ncol][k % ncol].axis("off")
    if sc is not None:
        cb = fig.colorbar(sc, ax=axes.ravel().tolist(), shrink=0.9)
        cb.set_label("p-p of $c_{x,L}$, last 0.5 s (dimensionless)")
    fig.suptitle(f"stability map {title}: o sustained oscillation, \u25a1 none, x failed; "
                 "red band / black bar: linear analysis unstable / boundary (\u03b6 = 0)", fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
