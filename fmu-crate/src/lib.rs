//! ecf_contact: the FMI 2.0 and FMI 3.0 Co-Simulation FMUs of one wheel-rail contact, wrapping the stateful creep-core model (transient ECF, FASTSIM, Polach).
//!
//! Layers: [`vars`] declares every variable once and drives get/set in [`instance`] (the
//! FMI state machine around `creep_core::Model`, with its call rules in one table) and
//! modelDescription.xml in [`model_description`] (FMI 2.0) and [`model_description3`] (FMI
//! 3.0, with the field arrays of [`arrays`]); [`settings`] holds the contact's
//! parameters as set and resolves them to a configuration; [`state`] is the serialized FMU
//! state format; [`ffi`] is the only module with `unsafe`: the exported C functions of the
//! FMI 2.0 standard and, in [`ffi::fmi3`], of FMI 3.0, both over the same instances.
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
