"""Four-inertia locomotive drive-train (seed Eq. 3.4, model-spec §10) coupled to the ECF contact FMU.

Public API (see api.py): simulate, modal, Result, ModalResult, find_fmu, load_params; errors
DrivetrainError, ConfigError, FMUNotFoundError, FMUError; sweeps: drivetrain_demo.sweep.run_sweep;
frequency regression: drivetrain_demo.regress.

Modules: params (parameter file), model (equations, energy, exact step), contact (FMU2Slave
wrapper and steady-curve stand-in), stability (linear analysis with the contact damping of Eq.
6.4), simulate (co-simulation loop), analysis (spectrum, amplitude), scenarios (step/ramp/sine),
plots, sweep (Dask), regress (baselines), cli.
"""

__version__ = "0.2.0"

from .errors import ConfigError, DrivetrainError, FMUError, FMUNotFoundError  # noqa: E402
from .api import ModalResult, Result, find_fmu, load_params, modal, simulate  # noqa: E402

__all__ = ["simulate", "modal", "Result", "ModalResult", "find_fmu", "load_params", "DrivetrainError",
           "ConfigError", "FMUNotFoundError", "FMUError", "__version__"]
