"""Wheel-rail creep forces (ECF, FASTSIM, Polach) and the measurement loop, with NumPy arrays.

The model runs (`curve`, `step_response`, `sine_response`, `field`, `Contact`) and the
measurement loop (`compare`, `diagnose`, `fit`) call the same Rust functions as the `ecf`
command line: the numbers are the command line's to the last bit, with its column names
and units (``cx``, ``f``, ``Fx_N``, ..., ``p0_MPa``) and its error messages (`EcfError`, a
`ValueError`). Long calls release the GIL and stop at Ctrl-C.
"""

from __future__ import annotations

import json
import os
import re
import sys
import warnings as _warnings
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _ecf
from ._ecf import EcfError, __version__

__all__ = [
    "Contact",
    "CompareResult",
    "DiagnoseResult",
    "EcfError",
    "EcfWarning",
    "FitResult",
    "Table",
    "compare",
    "curve",
    "diagnose",
    "field",
    "fit",
    "info",
    "sine_response",
    "step_response",
]


class EcfWarning(UserWarning):
    """A warning of the model (e.g. inputs outside a law's calibrated range)."""


# --- model set-up ------------------------------------------------------------------------


def _config_keys(config: Any) -> Dict[str, Optional[str]]:
    """`config` as a file path or JSON text (a dict, e.g. a fit's `config`, or JSON text)."""
    if config is None:
        return {"config_path": None, "config_json": None}
    if isinstance(config, Mapping):
        return {"config_path": None, "config_json": json.dumps(config)}
    if isinstance(config, (str, os.PathLike)):
        text = os.fspath(config)
        if text.lstrip().startswith("{"):
            return {"config_path": None, "config_json": text}
        return {"config_path": text, "config_json": None}
    raise TypeError(f"config: a file path, a dict or JSON text, not {type(config).__name__}")


def _name_values(what: str, values: Optional[Mapping[str, float]]) -> List[str]:
    """A dict of NAME: VALUE as the command line's NAME=VALUE texts (repr: the same bits)."""
    if values is None:
        return []
    if not isinstance(values, Mapping):
        raise TypeError(f"{what}: a dict of name: value, not {type(values).__name__}")
    return [f"{k}={float(v)!r}" for k, v in values.items()]


def _setup(
    *,
    preset: Optional[str] = None,
    config: Any = None,
    model: str = "ecf",
    v_mps: float = 20.0,
    fn_kN: float = 110.0,
    a_mm: Optional[float] = None,
    b_mm: Optional[float] = None,
    cy: float = 0.0,
    spin: float = 0.0,
    t_bulk_C: float = 20.0,
    mu: Optional[float] = None,
    grid: Optional[str] = None,
    tol: Optional[float] = None,
    scheme: Optional[str] = None,
    params: Optional[Mapping[str, float]] = None,
    extra: Optional[Mapping[str, float]] = None,
) -> Dict[str, Any]:
    d: Dict[str, Any] = {
        "model": str(model),
        "preset": preset,
        "mu": None if mu is None else float(mu),
        "v_mps": float(v_mps),
        "fn_kn": float(fn_kN),
        "a_mm": None if a_mm is None else float(a_mm),
        "b_mm": None if b_mm is None else float(b_mm),
        "grid": grid,
        "tol": None if tol is None else float(tol),
        "cy": float(cy),
        "spin": float(spin),
        "t_bulk_c": float(t_bulk_C),
        "params": _name_values("params", params),
        "extra": _name_values("extra", extra),
        "scheme": scheme,
    }
    d.update(_config_keys(config))
    return d


def _warn(note: Optional[str], warnings: Sequence[str]) -> None:
    if note is not None and note.startswith("warning:"):
        _warnings.warn(note[len("warning: "):], EcfWarning, stacklevel=3)
    for w in warnings:
        _warnings.warn(w, EcfWarning, stacklevel=3)


# --- tables ------------------------------------------------------------------------------


class Table(dict):
    """Columns by name (the command line's CSV header, units in the names), each a float64
    array; `note` is the grid and scheme that `tol` chose, `warnings` the model's."""

    note: Optional[str]
    warnings: List[str]

    def __init__(self, columns: Sequence[str], values: bytes, note=None, warnings=()):
        a = np.frombuffer(values, dtype=np.float64).reshape(-1, len(columns))
        super().__init__((c, a[:, k].copy()) for k, c in enumerate(columns))
        self.note = note
        self.warnings = list(warnings)

    def to_frame(self):
        """The table as a pandas DataFrame (needs pandas)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("as_frame=True / to_frame() need pandas: pip install pandas") from e
        df = pd.DataFrame(dict(self))
        df.attrs["note"] = self.note
        df.attrs["warnings"] = list(self.warnings)
        return df

    def __repr__(self) -> str:
        n = len(next(iter(self.values()))) if self else 0
        return f"<ecf.Table {n} rows: {', '.join(self)}>"


def _table(r, as_frame: bool):
    cols, values, note, warnings = r
    _warn(note, warnings)
    t = Table(cols, values, note, warnings)
    return t.to_frame() if as_frame else t


def curve(*, cx: Union[Sequence[float], np.ndarray], as_frame: bool = False, **model: Any):
    """The steady creep curve at each creepage of `cx` (dimensionless, 0.01 = 1 %), as
    `ecf curve`: columns ``cx, f, Fx_N, Fy_N, Mz_Nm, T_max_C, T_mean_C, P_fric_W,
    frac_elastic, frac_plastic, frac_sliding, a_mm, b_mm, p0_MPa``.

    Model keywords: preset, config (path or dict), model ("ecf", "fastsim", "polach"), v_mps
    (20), fn_kN (110), a_mm and b_mm, cy (0), spin (1/m, 0), t_bulk_C (20), mu, grid
    ("NXxNY"), tol (relative F_x tolerance, ECF), scheme ("cells", "cells-ho"), params and
    extra (dicts of name: value)."""
    x = np.ascontiguousarray(np.atleast_1d(np.asarray(cx, dtype=np.float64)))
    if x.ndim != 1:
        raise EcfError("cx: expected a 1-D sequence of creepages")
    return _table(_ecf.curve(_setup(**model), x.tobytes()), as_frame)


def step_response(
    *,
    cx_from: float,
    cx_to: float,
    duration_ms: float = 5.0,
    dt_ms: float = 0.01,
    as_frame: bool = False,
    **model: Any,
):
    """The response to a creepage step at t = 0 from the steady state at `cx_from` to
    `cx_to`, as `ecf step`: columns ``t_s, cx`` and the outputs of `curve`. Model keywords
    as `curve`; scheme may also be "continuous"."""
    r = _ecf.step_series(_setup(**model), float(cx_from), float(cx_to), float(duration_ms), float(dt_ms))
    return _table(r, as_frame)


def sine_response(
    *,
    cm: float,
    ca: float,
    freq_hz: float,
    cycles: int = 3,
    steps_per_cycle: int = 200,
    as_frame: bool = False,
    **model: Any,
):
    """Periodic creepage cx = cm + ca sin(2 pi freq_hz t) from the steady state at `cm`, as
    `ecf sine`: columns ``t_s, cx`` and the outputs of `curve`."""
    r = _ecf.sine(_setup(**model), float(cm), float(ca), float(freq_hz), int(cycles), int(steps_per_cycle))
    return _table(r, as_frame)


def field(*, cx: float, as_frame: bool = False, **model: Any):
    """The steady fields along y = 0 at creepage `cx`, as `ecf field`: ``x_mm, tau_Pa,
    tau_x_Pa, tau_c1_Pa, tau_c2_Pa, p_Pa, T_C, regime`` (a strength without limit is inf
    here, -1 in the command line's CSV; regime 0 elastic, 1 plastic, 2 sliding)."""
    return _table(_ecf.field(_setup(**model), float(cx)), as_frame)


_OUTPUTS: Optional[List[str]] = None


def _output_names() -> List[str]:
    global _OUTPUTS
    if _OUTPUTS is None:
        _OUTPUTS = [o["column"] for o in json.loads(_ecf.info_json())["outputs"]]
    return _OUTPUTS


class Contact:
    """One stateful contact: `steady()`, `step(dt_s)`, `field()`, `state()`/`restore()`.

    Keywords as `curve` (the operating point is the initial input); `cx` the initial
    creepage. `steady` and `step` take new inputs (cx, cy, spin in 1/m, v_mps, fn_kN,
    t_bulk_C; those not given stay) and return the outputs as a dict with `curve`'s names.
    """

    def __init__(self, *, cx: float = 0.0, **model: Any):
        self._c = _ecf.Contact(_setup(**model), float(cx))
        if self._c.note is not None and self._c.note.startswith("warning:"):
            _warn(self._c.note, [])

    @staticmethod
    def _inputs(cx, cy, spin, v_mps, fn_kN, t_bulk_C) -> Dict[str, Optional[float]]:
        f = lambda v: None if v is None else float(v)  # noqa: E731
        return {"cx": f(cx), "cy": f(cy), "spin": f(spin), "v_mps": f(v_mps), "fn_kn": f(fn_kN), "t_bulk_c": f(t_bulk_C)}

    def _out(self, values: List[float]) -> Dict[str, float]:
        _warn(None, self._c.take_warnings())
        return dict(zip(_output_names(), values))

    def steady(self, *, cx=None, cy=None, spin=None, v_mps=None, fn_kN=None, t_bulk_C=None) -> Dict[str, float]:
        """Sets the contact to the steady state of its inputs; returns the outputs."""
        return self._out(self._c.steady(self._inputs(cx, cy, spin, v_mps, fn_kN, t_bulk_C)))

    def step(self, dt_s: float, *, cx=None, cy=None, spin=None, v_mps=None, fn_kN=None, t_bulk_C=None) -> Dict[str, float]:
        """Advances by `dt_s` seconds with the inputs held over the step; returns the outputs."""
        return self._out(self._c.step(float(dt_s), self._inputs(cx, cy, spin, v_mps, fn_kN, t_bulk_C)))

    def field(self, as_frame: bool = False):
        """The fields along y = 0 now (columns as `ecf.field`)."""
        cols, values = self._c.field()
        t = Table(cols, values)
        return t.to_frame() if as_frame else t

    def state(self) -> bytes:
        """The complete state as bytes (with the configuration; see `restore`)."""
        return self._c.state()

    def restore(self, state: bytes) -> None:
        """Restores a state from `state()` of a contact with the same configuration."""
        self._c.restore(bytes(state))

    @property
    def time_s(self) -> float:
        """Simulated time, s."""
        return self._c.time_s

    @property
    def inputs(self) -> Dict[str, float]:
        """The current inputs (cx, cy, spin, v_mps, fn_kN, t_bulk_C)."""
        return dict(self._c.inputs)

    @property
    def config(self) -> Dict[str, Any]:
        """The configuration (as a configuration JSON file holds it)."""
        return json.loads(self._c.config_json)

    @property
    def scheme(self) -> Optional[str]:
        """How a step advances the bristles (None for Polach)."""
        return self._c.scheme

    @property
    def note(self) -> Optional[str]:
        """The grid and scheme that `tol` chose (None without `tol`)."""
        return self._c.note

    def __repr__(self) -> str:
        return f"<ecf.Contact t = {self.time_s} s, inputs {self.inputs}>"


# --- the measurement loop ----------------------------------------------------------------


def _data_keys(data: Any, config: Any, preset, grid, threads, v_mps, fn_kN, cx_unit) -> Dict[str, Any]:
    d: Dict[str, Any] = {
        "data_path": None,
        "data_text": None,
        "data_name": "DataFrame",
        "preset": preset,
        "grid": grid,
        "threads": None if threads is None else int(threads),
        "v_mps": None if v_mps is None else float(v_mps),
        "fn_kn": None if fn_kN is None else float(fn_kN),
        "cx_unit": cx_unit,
    }
    d.update(_config_keys(config))
    if isinstance(data, (str, os.PathLike)):
        d["data_path"] = os.fspath(data)
    elif hasattr(data, "to_csv"):
        # the DataFrame as CSV text: the file reader maps its columns (names with units)
        # exactly as for a file; floats written by repr keep their bits
        d["data_text"] = data.to_csv(index=False)
    else:
        raise TypeError(f"data: a file path or a pandas DataFrame, not {type(data).__name__}")
    return d


_COUNTED = re.compile(r"^(.*) \[(\d+)/(\d+)\]$")


class _Progress:
    """A progress bar for the loop's stages: tqdm (tqdm.auto: a widget in a notebook) when
    installed, else a line of text on stderr. A stage ending in "[done/total]" shows a bar."""

    def __init__(self, title: str):
        self.title = title
        self.bar = None
        self.last = ""
        try:
            from tqdm.auto import tqdm

            self.tqdm = tqdm
        except ImportError:
            self.tqdm = None

    def __call__(self, text: str) -> None:
        m = _COUNTED.match(text)
        msg, done, total = (m.group(1), int(m.group(2)), int(m.group(3))) if m else (text, None, None)
        if self.tqdm is not None:
            if self.bar is None or (total is not None and self.bar.total != total):
                if self.bar is not None:
                    self.bar.close()
                self.bar = self.tqdm(total=total, desc=self.title, leave=False)
            self.bar.set_postfix_str(msg[:60], refresh=False)
            if done is not None:
                self.bar.n = done
            self.bar.refresh()
            return
        if done is not None and total:
            k = int(20 * done / total)
            line = f"{self.title}: {msg[:50]} [{'#' * k}{'.' * (20 - k)}] {done}/{total}"
        else:
            line = f"{self.title}: {msg[:70]}"
        sys.stderr.write("\r" + line.ljust(len(self.last)))
        sys.stderr.flush()
        self.last = line

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.last:
            sys.stderr.write("\r" + " " * len(self.last) + "\r")
            sys.stderr.flush()


def _progress(progress: Union[bool, Callable[[str], None]], title: str):
    if progress is True:
        return _Progress(title)
    if callable(progress):
        return progress
    return None


class _Result:
    """A result with the fields of the command line's JSON as attributes (and items)."""

    def __init__(self, doc: Dict[str, Any]):
        self._doc = doc

    def __getattr__(self, name: str) -> Any:
        try:
            return self.__dict__["_doc"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __getitem__(self, name: str) -> Any:
        return self._doc[name]

    def keys(self):
        return self._doc.keys()

    def to_dict(self) -> Dict[str, Any]:
        """The command line's JSON document as a dict."""
        return self._doc

    def __dir__(self) -> Iterable[str]:
        return list(super().__dir__()) + list(self._doc)


def _plt():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("plot() needs matplotlib: pip install matplotlib") from e
    return plt


class CompareResult(_Result):
    """`ecf compare --json`: cv_rmse_pct, groups, rows (each measured and model value), ..."""

    def frame(self):
        """The rows (line, series, cx, f, f_model, residual, T_max_C, slip_velocity_mps) as
        a DataFrame."""
        import pandas as pd

        return pd.DataFrame(self._doc.get("rows", []))

    def plot(self, ax=None):
        """Measured (points) and model (lines) traction coefficient over creepage per series."""
        plt = _plt()
        if ax is None:
            _, ax = plt.subplots()
        rows = self._doc.get("rows", [])
        for s in dict.fromkeys(r["series"] for r in rows):
            rs = sorted((r for r in rows if r["series"] == s), key=lambda r: r["cx"])
            cx = [100 * r["cx"] for r in rs]
            p = ax.plot(cx, [r["f"] for r in rs], "o", ms=3, label=f"{s} measured")
            ax.plot(cx, [r["f_model"] for r in rs], "-", color=p[0].get_color(), label=f"{s} model")
        ax.set_xlabel("creepage c_x (%)")
        ax.set_ylabel("traction coefficient f (-)")
        ax.set_title(f"CV(RMSE) {self._doc['cv_rmse_pct']:.2f} %")
        ax.legend(fontsize="small")
        return ax

    def __repr__(self) -> str:
        return f"<ecf.CompareResult CV(RMSE) {self._doc.get('cv_rmse_pct'):.3f} %, {self._doc.get('n')} rows>"


class DiagnoseResult(_Result):
    """`ecf diagnose --json`: baseline_cv_rmse_pct, candidates, correlations, search, verdict,
    ...; `proposed_config` is the configuration with the proposed formula effect (or None)."""

    def __init__(self, doc: Dict[str, Any], proposed: Optional[str]):
        super().__init__(doc)
        self.__dict__["proposed_config"] = None if proposed is None else json.loads(proposed)

    def plot(self, ax=None):
        """Held-out CV(RMSE) of each candidate effect against the configuration as given."""
        plt = _plt()
        if ax is None:
            _, ax = plt.subplots()
        c = self._doc.get("candidates", [])
        names = ["as given"] + [x["effect"] for x in c]
        vals = [self._doc["baseline_heldout_cv_rmse_pct"]] + [x["heldout_cv_rmse_pct"] for x in c]
        ax.barh(names[::-1], vals[::-1])
        ax.set_xlabel("held-out CV(RMSE) (%)")
        ax.set_title(self._doc.get("verdict", "")[:80], fontsize="small")
        return ax

    def __repr__(self) -> str:
        return f"<ecf.DiagnoseResult baseline {self._doc.get('baseline_cv_rmse_pct'):.3f} %: {self._doc.get('verdict', '')[:80]}>"


class FitResult(_Result):
    """`ecf fit --json`: cv_rmse_pct_before/after, params, stderr, status, correlation, ...;
    `config` is the fitted configuration (with its "fit" record) as `--out` writes it."""

    def __init__(self, doc: Dict[str, Any], config_text: str, data: Any, loop: Dict[str, Any]):
        super().__init__(doc)
        self.__dict__["config_text"] = config_text
        self.__dict__["config"] = json.loads(config_text)
        self.__dict__["_data"] = data
        self.__dict__["_loop"] = loop

    def save(self, path: Union[str, os.PathLike]) -> None:
        """Writes the fitted configuration as `ecf fit --out` does (the same bytes)."""
        with open(path, "w", encoding="utf-8", newline="") as f:
            f.write(self.config_text)

    def plot(self, ax=None):
        """The data against the fitted configuration (see `CompareResult.plot`)."""
        return compare(self._data, config=self.config, **self._loop).plot(ax)

    def __repr__(self) -> str:
        return (
            f"<ecf.FitResult CV(RMSE) {self._doc.get('cv_rmse_pct_before'):.3f} % -> "
            f"{self._doc.get('cv_rmse_pct_after'):.3f} %, {self._doc.get('params')}>"
        )


def compare(
    data: Any,
    *,
    config: Any = None,
    preset: Optional[str] = None,
    grid: Optional[str] = None,
    threads: Optional[int] = None,
    v_mps: Optional[float] = None,
    fn_kN: Optional[float] = None,
    cx_unit: Optional[str] = None,
) -> CompareResult:
    """Compares a configuration (exactly one of `config` and `preset`) with a measurement
    file or DataFrame, as `ecf compare --json`. `v_mps`/`fn_kN`: speed and load of every row
    for data without those columns; `cx_unit`: "1" or "percent" for creepage columns whose
    name gives no unit; `threads`: worker threads (default: every core; results do not
    depend on it)."""
    d = _data_keys(data, config, preset, grid, threads, v_mps, fn_kN, cx_unit)
    return CompareResult(json.loads(_ecf.compare(d)))


def diagnose(
    data: Any,
    *,
    config: Any = None,
    preset: Optional[str] = None,
    grid: Optional[str] = None,
    threads: Optional[int] = None,
    v_mps: Optional[float] = None,
    fn_kN: Optional[float] = None,
    cx_unit: Optional[str] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    progress: Union[bool, Callable[[str], None]] = True,
) -> DiagnoseResult:
    """Which physical effect is missing, as `ecf diagnose --json` (keywords as `compare`).
    `out`: where to write the configuration with the proposed formula effect, if one is
    proposed. `progress`: a progress bar (True), none (False) or a callable of the stage."""
    d = _data_keys(data, config, preset, grid, threads, v_mps, fn_kN, cx_unit)
    bar = _progress(progress, "diagnose")
    try:
        text, proposed = _ecf.diagnose(d, bar)
    finally:
        if isinstance(bar, _Progress):
            bar.close()
    if out is not None and proposed is not None:
        with open(out, "w", encoding="utf-8", newline="") as f:
            f.write(proposed)
    return DiagnoseResult(json.loads(text), proposed)


def fit(
    data: Any,
    *,
    config: Any = None,
    preset: Optional[str] = None,
    free: Optional[Union[str, Sequence[str]]] = None,
    bounds: Optional[Union[Mapping[str, Sequence[float]], Sequence[str]]] = None,
    grid: Optional[str] = None,
    threads: Optional[int] = None,
    v_mps: Optional[float] = None,
    fn_kN: Optional[float] = None,
    cx_unit: Optional[str] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    progress: Union[bool, Callable[[str], None]] = True,
) -> FitResult:
    """Fits parameters to the data, as `ecf fit --json` (keywords as `compare`). `free`:
    names of the parameters (default: the layer strengths and hardening scale); `bounds`:
    {name: (min, max)} or ["NAME=MIN:MAX", ...] narrowing them; `out`: where to write the
    fitted configuration (also `FitResult.save`)."""
    d = _data_keys(data, config, preset, grid, threads, v_mps, fn_kN, cx_unit)
    if free is not None and not isinstance(free, str):
        free = ",".join(free)
    if bounds is None:
        b: List[str] = []
    elif isinstance(bounds, Mapping):
        b = [f"{k}={float(lo)!r}:{float(hi)!r}" for k, (lo, hi) in bounds.items()]
    else:
        b = [str(x) for x in bounds]
    bar = _progress(progress, "fit")
    try:
        text, doc = _ecf.fit(d, free, b, None if out is None else os.fspath(out), bar)
    finally:
        if isinstance(bar, _Progress):
            bar.close()
    if out is not None:
        with open(out, "w", encoding="utf-8", newline="") as f:
            f.write(doc)
    loop = {"grid": grid, "threads": threads, "v_mps": v_mps, "fn_kN": fn_kN, "cx_unit": cx_unit}
    return FitResult(json.loads(text), doc, data, loop)


class Info(dict):
    """`ecf info` as a dict (presets, effects, inputs, outputs with their CSV column, scale
    and decimals, params); printed, the command line's text."""

    text: str

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return self.text


def info() -> Info:
    """Presets, effects, inputs, outputs and parameters with units, defaults and bounds."""
    i = Info(json.loads(_ecf.info_json()))
    i.text = _ecf.info_text()
    return i
