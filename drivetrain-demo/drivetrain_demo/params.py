"""Parameter file of the drive-train, controller and contact operating point (TOML, SI units)."""

from __future__ import annotations

import dataclasses
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .errors import ConfigError

DEFAULT_FILE = Path(__file__).with_name("data") / "locomotive.toml"


@dataclass(frozen=True)
class Drivetrain:
    """Four-inertia drive-train (seed Eq. 3.4). All SI: kg m^2, N m/rad, N m s/rad, m."""

    J_L: float  # wheel on the long axle, kg m^2
    J_S: float  # wheel on the short axle, kg m^2
    J_G: float  # gear wheel, kg m^2
    J_M: float  # motor rotor (motor side), kg m^2
    j_G: float  # gear ratio omega_M/omega_G, -
    R: float  # wheel radius, m
    C_L: float  # long axle torsional stiffness, N m/rad
    C_S: float  # short axle torsional stiffness, N m/rad
    C_M: float  # motor shaft + mesh stiffness (motor side), N m/rad
    D_L: float  # long axle damping, N m s/rad
    D_S: float  # short axle damping, N m s/rad
    D_M: float  # motor shaft damping (motor side), N m s/rad


@dataclass(frozen=True)
class Controller:
    """PI speed controller on the filtered motor speed (seed Eq. 6.1/6.2)."""

    K_p: float  # N m s/rad
    T_i: float  # s
    tau_f: float  # s
    T_max: float  # N m


@dataclass(frozen=True)
class ContactPoint:
    """Operating point handed to each wheel's contact."""

    F_N: float  # N
    T_bulk: float  # degC


@dataclass(frozen=True)
class Params:
    drivetrain: Drivetrain
    controller: Controller
    contact: ContactPoint
    source: str = ""
    docs: dict = field(default_factory=dict, compare=False, repr=False)

    def with_drivetrain(self, **kw) -> "Params":
        """Copy with some drive-train values replaced (e.g. C_L=...)."""
        return dataclasses.replace(self, drivetrain=dataclasses.replace(self.drivetrain, **kw))

    def with_controller(self, **kw) -> "Params":
        return dataclasses.replace(self, controller=dataclasses.replace(self.controller, **kw))


def load(path: str | Path | None = None) -> Params:
    """Reads a parameter file; every value must carry value/unit/meaning (clear error otherwise)."""
    path = Path(path) if path else DEFAULT_FILE
    try:
        raw = tomllib.loads(path.read_text())
    except IsADirectoryError:
        raise ConfigError(f"parameter file {path} is a directory") from None
    except FileNotFoundError:
        raise ConfigError(f"parameter file {path} not found") from None
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"parameter file {path}: {e}") from None
    docs = {}
    out = {}
    for section, cls in (("drivetrain", Drivetrain), ("controller", Controller), ("contact", ContactPoint)):
        sec = raw.get(section, {})
        vals = {}
        for f in dataclasses.fields(cls):
            if f.name not in sec:
                raise ConfigError(f"parameter file {path}: missing [{section}.{f.name}]")
            entry = sec[f.name]
            if not isinstance(entry, dict) or "value" not in entry or "unit" not in entry:
                raise ConfigError(f"parameter file {path}: [{section}.{f.name}] needs value and unit")
            v = float(entry["value"])
            if section != "contact" and not v >= 0.0:
                raise ConfigError(f"parameter file {path}: {section}.{f.name} = {v} must be >= 0")
            vals[f.name] = v
            docs[f"{section}.{f.name}"] = entry
        out[section] = cls(**vals)
    for k in ("J_L", "J_S", "J_G", "J_M", "j_G", "R"):
        if getattr(out["drivetrain"], k) <= 0:
            raise ConfigError(f"parameter file {path}: drivetrain.{k} must be > 0")
    return Params(out["drivetrain"], out["controller"], out["contact"], str(path), docs)


def override_names() -> dict:
    """Names accepted by `with_overrides` (and `--set`), by section."""
    return {"drivetrain": [f.name for f in dataclasses.fields(Drivetrain)],
            "controller": [f.name for f in dataclasses.fields(Controller)],
            "contact": [f.name for f in dataclasses.fields(ContactPoint)]}


def with_overrides(p: Params, overrides) -> Params:
    """Copy of `p` with values replaced: `overrides` is a mapping (or NAME=VALUE pairs) of field
    names of [drivetrain], [controller] or [contact] (e.g. {"C_L": 1e7, "K_p": 1500, "F_N": 9e4}),
    SI units as in the parameter file. Raises ConfigError naming the option (`--set NAME`) for an
    unknown name, a non-number or a value out of range."""
    items = overrides.items() if hasattr(overrides, "items") else overrides
    names = override_names()
    for k, v in items:
        try:
            x = float(v)
        except (TypeError, ValueError):
            raise ConfigError(f"--set {k}={v}: value is not a number") from None
        if x != x or x in (float("inf"), float("-inf")):
            raise ConfigError(f"--set {k}={v}: value must be finite")
        if k in names["drivetrain"]:
            if x < 0 or (x == 0 and k in ("J_L", "J_S", "J_G", "J_M", "j_G", "R")):
                raise ConfigError(f"--set {k}={v}: must be {'> 0' if k in ('J_L', 'J_S', 'J_G', 'J_M', 'j_G', 'R') else '>= 0'}")
            p = p.with_drivetrain(**{k: x})
        elif k in names["controller"]:
            if x < 0:
                raise ConfigError(f"--set {k}={v}: must be >= 0")
            p = p.with_controller(**{k: x})
        elif k in names["contact"]:
            if k == "F_N" and not x > 0:
                raise ConfigError(f"--set F_N={v}: the normal load must be > 0 N")
            p = dataclasses.replace(p, contact=dataclasses.replace(p.contact, **{k: x}))
        else:
            raise ConfigError(f"--set {k}: unknown (drive-train: {', '.join(sorted(names['drivetrain']))}; "
                              f"controller: {', '.join(sorted(names['controller']))}; "
                              f"contact: {', '.join(names['contact'])})")
    return p
