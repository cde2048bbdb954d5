"""Four-inertia locomotive drive-train (seed Eq. 3.4, model-spec §10) coupled to the ECF contact FMU.

Modules: params (parameter file), model (equations, energy, exact step), controller
(Eq. 6.1/6.2), contact (FMU2Slave wrapper and steady-curve stand-in), stability (linear
analysis with the contact damping of Eq. 6.4), simulate (co-simulation loop), analysis
(spectrum, amplitude), scenarios (step/ramp/sine), plots, cli.
"""

__version__ = "0.1.0"
