"""Signal analysis of the simulated creepages: dominant frequency, oscillation amplitude, envelope."""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize_scalar


def _window(t, y, t0, t1):
    m = (t >= t0) & (t <= t1) & np.isfinite(y)
    return t[m], y[m]


def _detrend(t, y):
    if len(y) < 3:
        return y - np.mean(y)
    k = np.polyfit(t - t[0], y, 1)
    return y - np.polyval(k, t - t[0])


def dominant_frequency(t, y, t0, t1, fmin=5.0, fmax=500.0):
    """Frequency (Hz) of the largest spectral peak of y over [t0, t1] in [fmin, fmax].

    Linear trend removed, Hann window; the peak of a 16x zero-padded FFT is refined by
    maximizing the windowed DFT magnitude over frequency (resolution far below 1/T).
    Returns (frequency, (freqs, amplitude spectrum)) for plotting."""
    tw, yw = _window(t, y, t0, t1)
    if len(yw) < 16:
        return float("nan"), (np.array([]), np.array([]))
    dt = float(np.median(np.diff(tw)))
    x = _detrend(tw, yw)
    w = np.hanning(len(x))
    nfft = 16 * len(x)
    spec = np.abs(np.fft.rfft(x * w, nfft)) * 2 / w.sum()
    freqs = np.fft.rfftfreq(nfft, dt)
    band = (freqs >= fmin) & (freqs <= min(fmax, 0.5 / dt))
    if not band.any() or np.max(spec[band]) == 0:
        return float("nan"), (freqs, spec)
    i = np.flatnonzero(band)[np.argmax(spec[band])]
    df = freqs[1] - freqs[0]
    tt = tw - tw[0]

    def neg(f):
        return -abs(np.sum(x * w * np.exp(-2j * np.pi * f * tt)))

    r = minimize_scalar(neg, bounds=(freqs[i] - df, freqs[i] + df), method="bounded",
                        options={"xatol": 1e-6 * freqs[i]})
    return float(r.x), (freqs, spec)


def peak_to_peak(t, y, t0, t1, detrend=True):
    """Peak-to-peak of y over [t0, t1] (linear trend removed when detrend)."""
    tw, yw = _window(t, y, t0, t1)
    if len(yw) < 2:
        return float("nan")
    x = _detrend(tw, yw) if detrend else yw
    return float(np.max(x) - np.min(x))


def oscillation_part(t, y, period):
    """y minus its moving average over one period (removes trends such as a ramp)."""
    dt = float(np.median(np.diff(t)))
    n = max(1, int(round(period / dt)))
    k = np.ones(n) / n
    ma = np.convolve(y, k, mode="same")
    out = y - ma
    out[: n // 2 + 1] = np.nan
    out[-(n // 2 + 1):] = np.nan
    return out


def envelope(t, y, period, win=0.1):
    """Peak-to-peak of the oscillation part of y in consecutive windows of length win: (t_mid, pp)."""
    osc = oscillation_part(t, y, period)
    edges = np.arange(t[0], t[-1] + 1e-12, win)
    mids, pps = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        m = (t >= a) & (t < b) & np.isfinite(osc)
        if m.sum() > 3:
            mids.append(0.5 * (a + b))
            pps.append(float(np.max(osc[m]) - np.min(osc[m])))
    return np.array(mids), np.array(pps)


def cv_rmse(meas, ref):
    """Eq. 2.8-2.9: CV(RMSE) in percent of ref's mean."""
    meas, ref = np.asarray(meas), np.asarray(ref)
    return float(100 * np.sqrt(np.mean((meas - ref) ** 2)) / np.mean(ref))


def loop_area(c, f):
    """Signed area of the closed curve (c, f) (trapezoid, closes the loop): > 0 counter-clockwise."""
    c = np.append(c, c[0])
    f = np.append(f, f[0])
    return float(0.5 * np.sum(c[:-1] * f[1:] - c[1:] * f[:-1]))


def tone_amplitude(t, y, f, t0, t1):
    """Amplitude of the component of y at frequency f over [t0, t1] (Hann-windowed DFT, trend removed)."""
    tw, yw = _window(t, y, t0, t1)
    if len(yw) < 16 or not np.isfinite(f):
        return float("nan")
    x = _detrend(tw, yw)
    w = np.hanning(len(x))
    return float(2 * abs(np.sum(x * w * np.exp(-2j * np.pi * f * (tw - tw[0])))) / w.sum())
