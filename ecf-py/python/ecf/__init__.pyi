"""Type stubs of the Python package ecf: keyword names and units for editors."""

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str
__all__: List[str]

_Path = Union[str, "os.PathLike[str]"]
_Config = Union[_Path, Mapping[str, Any], None]
_Progress = Union[bool, Callable[[str], None]]

class EcfError(ValueError):
    """Bad input or a model that cannot run at it; the message is the `ecf` command line's."""

class EcfWarning(UserWarning): ...

class Table(Dict[str, npt.NDArray[np.float64]]):
    """Columns by name (units in the names), each a float64 array."""
    note: Optional[str]
    warnings: List[str]
    def to_frame(self) -> Any: ...

def curve(
    *,
    cx: Union[Sequence[float], npt.ArrayLike],
    as_frame: bool = ...,
    preset: Optional[str] = ...,
    config: _Config = ...,
    model: str = ...,
    v_mps: float = ...,
    fn_kN: float = ...,
    a_mm: Optional[float] = ...,
    b_mm: Optional[float] = ...,
    cy: float = ...,
    spin: float = ...,
    t_bulk_C: float = ...,
    mu: Optional[float] = ...,
    grid: Optional[str] = ...,
    tol: Optional[float] = ...,
    scheme: Optional[str] = ...,
    params: Optional[Mapping[str, float]] = ...,
    extra: Optional[Mapping[str, float]] = ...,
) -> Any: ...
def step_response(
    *,
    cx_from: float,
    cx_to: float,
    duration_ms: float = ...,
    dt_ms: float = ...,
    as_frame: bool = ...,
    preset: Optional[str] = ...,
    config: _Config = ...,
    model: str = ...,
    v_mps: float = ...,
    fn_kN: float = ...,
    a_mm: Optional[float] = ...,
    b_mm: Optional[float] = ...,
    cy: float = ...,
    spin: float = ...,
    t_bulk_C: float = ...,
    mu: Optional[float] = ...,
    grid: Optional[str] = ...,
    tol: Optional[float] = ...,
    scheme: Optional[str] = ...,
    params: Optional[Mapping[str, float]] = ...,
    extra: Optional[Mapping[str, float]] = ...,
) -> Any: ...
def sine_response(
    *,
    cm: float,
    ca: float,
    freq_hz: float,
    cycles: int = ...,
    steps_per_cycle: int = ...,
    as_frame: bool = ...,
    preset: Optional[str] = ...,
    config: _Config = ...,
    model: str = ...,
    v_mps: float = ...,
    fn_kN: float = ...,
    a_mm: Optional[float] = ...,
    b_mm: Optional[float] = ...,
    cy: float = ...,
    spin: float = ...,
    t_bulk_C: float = ...,
    mu: Optional[float] = ...,
    grid: Optional[str] = ...,
    tol: Optional[float] = ...,
    scheme: Optional[str] = ...,
    params: Optional[Mapping[str, float]] = ...,
    extra: Optional[Mapping[str, float]] = ...,
) -> Any: ...
def field(
    *,
    cx: float,
    as_frame: bool = ...,
    preset: Optional[str] = ...,
    config: _Config = ...,
    model: str = ...,
    v_mps: float = ...,
    fn_kN: float = ...,
    a_mm: Optional[float] = ...,
    b_mm: Optional[float] = ...,
    cy: float = ...,
    spin: float = ...,
    t_bulk_C: float = ...,
    mu: Optional[float] = ...,
    grid: Optional[str] = ...,
    tol: Optional[float] = ...,
    scheme: Optional[str] = ...,
    params: Optional[Mapping[str, float]] = ...,
    extra: Optional[Mapping[str, float]] = ...,
) -> Any: ...

class Contact:
    def __init__(
        self,
        *,
        cx: float = ...,
        preset: Optional[str] = ...,
        config: _Config = ...,
        model: str = ...,
        v_mps: float = ...,
        fn_kN: float = ...,
        a_mm: Optional[float] = ...,
        b_mm: Optional[float] = ...,
        cy: float = ...,
        spin: float = ...,
        t_bulk_C: float = ...,
        mu: Optional[float] = ...,
        grid: Optional[str] = ...,
        tol: Optional[float] = ...,
        scheme: Optional[str] = ...,
        params: Optional[Mapping[str, float]] = ...,
        extra: Optional[Mapping[str, float]] = ...,
    ) -> None: ...
    def steady(
        self,
        *,
        cx: Optional[float] = ...,
        cy: Optional[float] = ...,
        spin: Optional[float] = ...,
        v_mps: Optional[float] = ...,
        fn_kN: Optional[float] = ...,
        t_bulk_C: Optional[float] = ...,
    ) -> Dict[str, float]: ...
    def step(
        self,
        dt_s: float,
        *,
        cx: Optional[float] = ...,
        cy: Optional[float] = ...,
        spin: Optional[float] = ...,
        v_mps: Optional[float] = ...,
        fn_kN: Optional[float] = ...,
        t_bulk_C: Optional[float] = ...,
    ) -> Dict[str, float]: ...
    def field(self, as_frame: bool = ...) -> Any: ...
    def state(self) -> bytes: ...
    def restore(self, state: bytes) -> None: ...
    @property
    def time_s(self) -> float: ...
    @property
    def inputs(self) -> Dict[str, float]: ...
    @property
    def config(self) -> Dict[str, Any]: ...
    @property
    def scheme(self) -> Optional[str]: ...
    @property
    def note(self) -> Optional[str]: ...

class _Result:
    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, name: str) -> Any: ...
    def keys(self) -> Any: ...
    def to_dict(self) -> Dict[str, Any]: ...

class CompareResult(_Result):
    cv_rmse_pct: float
    n: int
    groups: List[Dict[str, Any]]
    rows: List[Dict[str, Any]]
    data: str
    config: Dict[str, Any]
    warnings: List[Any]
    def frame(self) -> Any: ...
    def plot(self, ax: Any = ...) -> Any: ...

class DiagnoseResult(_Result):
    baseline_cv_rmse_pct: float
    baseline_heldout_cv_rmse_pct: float
    candidates: List[Dict[str, Any]]
    correlations: List[Dict[str, Any]]
    verdict: str
    proposed_config: Optional[Dict[str, Any]]
    def plot(self, ax: Any = ...) -> Any: ...

class FitResult(_Result):
    cv_rmse_pct_before: float
    cv_rmse_pct_after: float
    params: Dict[str, Any]
    stderr: Dict[str, Any]
    status: Dict[str, Any]
    free: List[str]
    correlation: List[List[Any]]
    evaluations: int
    config: Dict[str, Any]
    config_text: str
    def save(self, path: _Path) -> None: ...
    def plot(self, ax: Any = ...) -> Any: ...

def compare(
    data: Any,
    *,
    config: _Config = ...,
    preset: Optional[str] = ...,
    grid: Optional[str] = ...,
    threads: Optional[int] = ...,
    v_mps: Optional[float] = ...,
    fn_kN: Optional[float] = ...,
    cx_unit: Optional[str] = ...,
) -> CompareResult: ...
def diagnose(
    data: Any,
    *,
    config: _Config = ...,
    preset: Optional[str] = ...,
    grid: Optional[str] = ...,
    threads: Optional[int] = ...,
    v_mps: Optional[float] = ...,
    fn_kN: Optional[float] = ...,
    cx_unit: Optional[str] = ...,
    out: Optional[_Path] = ...,
    progress: _Progress = ...,
) -> DiagnoseResult: ...
def fit(
    data: Any,
    *,
    config: _Config = ...,
    preset: Optional[str] = ...,
    free: Optional[Union[str, Sequence[str]]] = ...,
    bounds: Optional[Union[Mapping[str, Sequence[float]], Sequence[str]]] = ...,
    grid: Optional[str] = ...,
    threads: Optional[int] = ...,
    v_mps: Optional[float] = ...,
    fn_kN: Optional[float] = ...,
    cx_unit: Optional[str] = ...,
    out: Optional[_Path] = ...,
    progress: _Progress = ...,
) -> FitResult: ...

class Info(Dict[str, Any]):
    text: str

def info() -> Info: ...
