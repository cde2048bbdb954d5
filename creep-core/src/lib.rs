//! creep-core: wheel-rail creep force models — the Extended Creep Force (ECF) model, FASTSIM and Polach — in safe Rust.
//!
//! The ECF model (elasto-plastic third body layer with Voce hardening, pressure- and
//! temperature-dependent material laws and a flash-temperature sub-model, fully time
//! dependent) and FASTSIM are named configurations of one bristle engine
//! ([`engine::Contact`]) with switchable [`effects`]; Polach's model is a closed form.
//! Equation numbers refer to the seed dissertation ("A new Wheel-Rail Creep Force Model
//! based on Elasto-Plastic Third Body Layers"); `docs/model.md` lists every reading of it.
//!
//! ```
//! use creep_core::{Config, Inputs, Model};
//! let cfg = Config::preset("table4.1").unwrap();
//! let mut m = Model::new(&cfg).unwrap();
//! let out = m.steady(&Inputs { cx: 0.01, v: 20.0, fn_n: 110e3, ..Inputs::default() }).unwrap();
//! assert!(out.f > 0.1 && out.f < 0.6);
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]
#![warn(clippy::too_many_lines)] // at most 150 lines a function (clippy.toml)

pub mod bristle;
pub mod bytes;
pub mod commands;
pub mod config;
pub mod custom;
pub mod effects;
pub mod engine;
pub mod error;
pub(crate) mod fastexp;
pub mod formula;
pub mod hertz;
pub mod kalker;
pub mod material;
pub mod model;
pub mod modifier;
pub mod params;
pub mod polach;
pub mod scheme;
pub mod state;
pub mod thermal;
pub mod tolerance;

#[doc(hidden)]
pub use inventory;

pub use config::AnyModifier;
pub use config::{Bound, Config, Geometry, Grid, ModelKind};
pub use effects::Effect;
pub use engine::io::{InputId, InputSpec, OutputSpec, INPUTS, OUTPUTS};
pub use engine::{Contact, FieldPoint, Inputs, Outputs};
pub use error::{CreepError, Result};
pub use model::Model;
pub use modifier::Modifier;
pub use scheme::Scheme;
