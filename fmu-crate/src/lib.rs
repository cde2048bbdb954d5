//! ecf_contact: the FMI 2.0 Co-Simulation FMU of one wheel-rail contact, wrapping the stateful creep-core model (transient ECF, FASTSIM, Polach).
//!
//! Layers: [`vars`] declares every variable once and drives get/set in [`instance`] (the
//! FMI state machine around `creep_core::Model`, with its call rules in one table) and
//! modelDescription.xml in [`model_description`]; [`settings`] holds the contact's
//! parameters as set and resolves them to a configuration; [`state`] is the serialized FMU
//! state format; [`ffi`] is the only module with `unsafe`: the exported C functions of the
//! FMI 2.0 standard.
#![deny(unsafe_code)]
#![warn(clippy::too_many_lines)] // at most 150 lines a function (clippy.toml)

pub mod arrays;
#[allow(unsafe_code)]
pub mod ffi;
pub mod instance;
pub mod model_description;
pub mod model_description3;
pub mod settings;
pub mod state;
pub mod vars;
