"""Exceptions of the drive-train package. Library code raises these; only the command line turns
them into a one-line `error: ...` message and exit code 2."""

from __future__ import annotations


class DrivetrainError(Exception):
    """Base class of every error the package raises on purpose (bad input, missing FMU, FMU failure)."""


class ConfigError(DrivetrainError, ValueError):
    """An option, parameter file, sweep file or baseline file is invalid; the message names it and
    the accepted values."""


class FMUNotFoundError(DrivetrainError, FileNotFoundError):
    """The contact FMU was not found at the given path, $ECF_FMU_PATH, $ECF_CONTACT_FMU or dist/."""


class FMUError(DrivetrainError, RuntimeError):
    """The contact FMU refused a parameter or failed during a step (message includes its log)."""
