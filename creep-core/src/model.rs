//! One front for all models: `Model` wraps the bristle engine (ECF, FASTSIM) and the closed-form Polach model.

use crate::config::{Config, ModelKind};
use crate::engine::{Contact, FieldPoint, Inputs, Outputs};
use crate::error::Result;
use crate::polach::polach;

/// A stateful creep force model of one wheel-rail contact.
#[derive(Clone, Debug)]
pub enum Model {
    /// Bristle engine (ECF or FASTSIM).
    Bristle(Box<Contact>),
    /// Polach's closed form (stateless; keeps the last inputs).
    Polach {
        /// Configuration.
        cfg: Box<Config>,
        /// Last inputs.
        inputs: Inputs,
        /// Last outputs.
        out: Outputs,
        /// Simulated time, s.
        time: f64,
    },
}

impl Model {
    /// A model for a configuration.
    pub fn new(cfg: &Config) -> Result<Self> {
        Ok(match cfg.model {
            ModelKind::Polach => Model::Polach {
                cfg: Box::new(cfg.clone()),
                inputs: Inputs::default(),
                out: Outputs::default(),
                time: 0.0,
            },
            _ => Model::Bristle(Box::new(Contact::new(cfg)?)),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &Config {
        match self {
            Model::Bristle(c) => c.config(),
            Model::Polach { cfg, .. } => cfg,
        }
    }

    /// Advances by `dt` seconds (transient bristle grid; Polach is quasi-steady).
    pub fn step(&mut self, dt: f64, inputs: &Inputs) -> Result<Outputs> {
        match self {
            Model::Bristle(c) => c.step(dt, inputs),
            Model::Polach {
                cfg,
                inputs: last,
                out,
                time,
            } => {
                crate::error::check_range("dt", dt, 0.0, 1e3, "s")?;
                *out = polach(cfg, inputs)?;
                *last = *inputs;
                *time += dt;
                Ok(*out)
            }
        }
    }

    /// Steady state of constant inputs (sets the bristle grid to it).
    pub fn steady(&mut self, inputs: &Inputs) -> Result<Outputs> {
        match self {
            Model::Bristle(c) => c.steady(inputs),
            Model::Polach {
                cfg,
                inputs: last,
                out,
                ..
            } => {
                *out = polach(cfg, inputs)?;
                *last = *inputs;
                Ok(*out)
            }
        }
    }

    /// Last outputs.
    pub fn outputs(&self) -> Outputs {
        match self {
            Model::Bristle(c) => c.outputs(),
            Model::Polach { out, .. } => *out,
        }
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        match self {
            Model::Bristle(c) => c.time(),
            Model::Polach { time, .. } => *time,
        }
    }

    /// Fields along y = 0 (bristle models only).
    pub fn field_y0(&self) -> Option<Vec<FieldPoint>> {
        match self {
            Model::Bristle(c) => Some(c.field_y0()),
            Model::Polach { .. } => None,
        }
    }

    /// Sets the values of extra (data) columns used by formula effects (ignored by Polach).
    pub fn set_extra(&mut self, values: &[(String, f64)]) -> Result<()> {
        match self {
            Model::Bristle(c) => c.set_extra(values),
            Model::Polach { .. } => Ok(()),
        }
    }

    /// Threads that advance the bristle strips (1: the calling thread; results do not
    /// depend on it). Polach has no strips.
    pub fn set_threads(&mut self, threads: usize) -> Result<()> {
        match self {
            Model::Bristle(c) if c.threads() != threads.max(1) => c.set_threads(threads),
            _ => Ok(()),
        }
    }

    /// How a step advances the bristles (see [`crate::scheme::Scheme`]; Polach has none).
    pub fn set_scheme(&mut self, scheme: crate::scheme::Scheme) {
        if let Model::Bristle(c) = self {
            c.set_scheme(scheme);
        }
    }

    /// How the local temperature of a bristle move is solved (see
    /// [`crate::thermal::TemperatureSolve`]; Polach has none).
    pub fn set_temperature_solve(&mut self, solve: crate::thermal::TemperatureSolve) {
        if let Model::Bristle(c) = self {
            c.set_temperature_solve(solve);
        }
    }

    /// How a step advances the bristles now (None for Polach, which has none).
    pub fn scheme(&self) -> Option<crate::scheme::Scheme> {
        match self {
            Model::Bristle(c) => Some(c.scheme()),
            Model::Polach { .. } => None,
        }
    }

    /// Warnings since the last call (drained).
    pub fn take_warnings(&mut self) -> Vec<String> {
        match self {
            Model::Bristle(c) => c.take_warnings(),
            Model::Polach { .. } => Vec::new(),
        }
    }
}
