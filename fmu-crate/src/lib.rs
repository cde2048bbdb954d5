//! ecf_contact: the FMI 2.0 Co-Simulation FMU of one wheel-rail contact, wrapping the stateful creep-core model (transient ECF, FASTSIM, Polach).
//!
//! Layers: [`vars`] is the one table of variables, which drives get/set in [`instance`]
//! (a safe state machine around `creep_core::Model`) and generates modelDescription.xml
//! in [`model_description`]; [`state`] is the serialized FMU state format; [`ffi`] is the
//! only module with `unsafe`: the exported C functions of the FMI 2.0 standard.
#![deny(unsafe_code)]

#[allow(unsafe_code)]
pub mod ffi;
pub mod instance;
pub mod model_description;
pub mod state;
pub mod vars;
