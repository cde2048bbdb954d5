//! The exported FMI 3.0 C API (Co-Simulation): the same instances, registry and state functions as the FMI 2.0 API, with FMI 3.0's signatures, its configuration mode and the field arrays.
//!
//! Every function of fmi3Functions.h is exported. Model Exchange, Scheduled Execution,
//! event mode, clocks, derivatives and dependency queries log a message and return
//! fmi3Error (their instantiation functions return NULL). An FMI 3.0 instance is a
//! [`Component`] with a [`Part`]: the structural parameter `n_field` and whether the
//! instance is in configuration mode. The instance's messages name the FMI 2.0 functions it
//! shares; [`names`] gives them their FMI 3.0 names before they reach the logger. The
//! functions are in `lifecycle` (instantiation, modes, fmi3DoStep, FMU states), `values`
//! (get and set of every type, the arrays) and `unsupported`.
#![allow(non_snake_case)]

use super::*;
use crate::arrays::{self, N_FIELD_MAX};

mod lifecycle;
mod unsupported;
mod values;

pub use lifecycle::*;
pub use unsupported::*;
pub use values::*;

type St = f3::fmi3Status;

/// What only an FMI 3.0 instance has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Part {
    /// Points of the field arrays (the structural parameter `n_field`).
    pub n_field: u64,
    /// In configuration mode (between fmi3EnterConfigurationMode and fmi3ExitConfigurationMode).
    pub configuring: bool,
}

impl Part {
    fn new() -> Self {
        Part {
            n_field: arrays::n_field_start(),
            configuring: false,
        }
    }
}

/// The FMI 3.0 status of a call.
pub(super) fn status3(s: Status) -> St {
    match s {
        Status::Ok => f3::fmi3Status_fmi3OK,
        Status::Warning => f3::fmi3Status_fmi3Warning,
        Status::Discard => f3::fmi3Status_fmi3Discard,
        Status::Error => f3::fmi3Status_fmi3Error,
    }
}

/// The FMI 2.0 names in an instance's message, as FMI 3.0 names them (one table; the rest
/// keep their name with the prefix fmi3).
pub(super) fn names(text: &str) -> String {
    const RENAMED: &[(&str, &str)] = &[
        ("fmi2GetReal", "fmi3GetFloat64"),
        ("fmi2SetReal", "fmi3SetFloat64"),
        ("fmi2GetInteger", "fmi3GetInt32"),
        ("fmi2SetInteger", "fmi3SetInt32"),
        ("fmi2SetupExperiment", "fmi3EnterInitializationMode"),
        ("fmi2Instantiate", "fmi3InstantiateCoSimulation"),
        ("fmi2DeSerializeFMUstate", "fmi3DeserializeFMUState"),
        ("FMUstate", "FMUState"),
        ("fmuResourceLocation", "resourcePath"),
        ("fmi2", "fmi3"),
    ];
    let mut t = text.to_string();
    for (a, b) in RENAMED {
        if t.contains(a) {
            t = t.replace(a, b);
        }
    }
    t
}

/// Runs `body` on the FMI 3.0 instance behind `c` (see [`with_status`]).
unsafe fn with3(
    c: f3::fmi3Instance,
    func: &str,
    body: impl FnOnce(&mut Component, &mut Part) -> Status,
) -> St {
    // SAFETY: as `with_status`.
    status3(unsafe {
        with_status(c, func, |comp| {
            match comp.v3 {
            Some(mut part) => {
                let st = body(comp, &mut part);
                comp.v3 = Some(part);
                st
            }
            None => comp.inst.error(format!(
                "{func}: the instance was made by fmi2Instantiate (an FMI 2.0 instance); call the fmi2 functions"
            )),
        }
        })
    })
}

/// Refuses a call in configuration mode (only structural parameters are set there).
fn not_configuring(comp: &mut Component, part: &Part, func: &str) -> Result<(), Status> {
    if part.configuring {
        Err(comp.inst.error(format!(
            "{func}: not allowed in ConfigurationMode (set n_field there, then call fmi3ExitConfigurationMode)"
        )))
    } else {
        Ok(())
    }
}

/// Checks a value of `n_field`.
fn check_n_field(n: u64) -> Result<usize, String> {
    if (1..=N_FIELD_MAX).contains(&n) {
        Ok(n as usize)
    } else {
        Err(format!("n_field = {n} is outside [1, {N_FIELD_MAX}]"))
    }
}

// ---------------------------------------------------------------------------------------
// Compile-time check of every exported signature against the standard's typedefs.

macro_rules! check_signatures3 {
    ($($name:ident : $ty:ident),* $(,)?) => {
        $(const _: f3::$ty = Some($name);)*
        /// Names of all exported FMI 3.0 functions.
        pub const EXPORTED: &[&str] = &[$(stringify!($name)),*];
    };
}

check_signatures3! {
    fmi3GetVersion: fmi3GetVersionTYPE,
    fmi3SetDebugLogging: fmi3SetDebugLoggingTYPE,
    fmi3InstantiateModelExchange: fmi3InstantiateModelExchangeTYPE,
    fmi3InstantiateCoSimulation: fmi3InstantiateCoSimulationTYPE,
    fmi3InstantiateScheduledExecution: fmi3InstantiateScheduledExecutionTYPE,
    fmi3FreeInstance: fmi3FreeInstanceTYPE,
    fmi3EnterInitializationMode: fmi3EnterInitializationModeTYPE,
    fmi3ExitInitializationMode: fmi3ExitInitializationModeTYPE,
    fmi3EnterEventMode: fmi3EnterEventModeTYPE,
    fmi3Terminate: fmi3TerminateTYPE,
    fmi3Reset: fmi3ResetTYPE,
    fmi3GetFloat32: fmi3GetFloat32TYPE,
    fmi3GetFloat64: fmi3GetFloat64TYPE,
    fmi3GetInt8: fmi3GetInt8TYPE,
    fmi3GetUInt8: fmi3GetUInt8TYPE,
    fmi3GetInt16: fmi3GetInt16TYPE,
    fmi3GetUInt16: fmi3GetUInt16TYPE,
    fmi3GetInt32: fmi3GetInt32TYPE,
    fmi3GetUInt32: fmi3GetUInt32TYPE,
    fmi3GetInt64: fmi3GetInt64TYPE,
    fmi3GetUInt64: fmi3GetUInt64TYPE,
    fmi3GetBoolean: fmi3GetBooleanTYPE,
    fmi3GetString: fmi3GetStringTYPE,
    fmi3GetBinary: fmi3GetBinaryTYPE,
    fmi3GetClock: fmi3GetClockTYPE,
    fmi3SetFloat32: fmi3SetFloat32TYPE,
    fmi3SetFloat64: fmi3SetFloat64TYPE,
    fmi3SetInt8: fmi3SetInt8TYPE,
    fmi3SetUInt8: fmi3SetUInt8TYPE,
    fmi3SetInt16: fmi3SetInt16TYPE,
    fmi3SetUInt16: fmi3SetUInt16TYPE,
    fmi3SetInt32: fmi3SetInt32TYPE,
    fmi3SetUInt32: fmi3SetUInt32TYPE,
    fmi3SetInt64: fmi3SetInt64TYPE,
    fmi3SetUInt64: fmi3SetUInt64TYPE,
    fmi3SetBoolean: fmi3SetBooleanTYPE,
    fmi3SetString: fmi3SetStringTYPE,
    fmi3SetBinary: fmi3SetBinaryTYPE,
    fmi3SetClock: fmi3SetClockTYPE,
    fmi3GetNumberOfVariableDependencies: fmi3GetNumberOfVariableDependenciesTYPE,
    fmi3GetVariableDependencies: fmi3GetVariableDependenciesTYPE,
    fmi3GetFMUState: fmi3GetFMUStateTYPE,
    fmi3SetFMUState: fmi3SetFMUStateTYPE,
    fmi3FreeFMUState: fmi3FreeFMUStateTYPE,
    fmi3SerializedFMUStateSize: fmi3SerializedFMUStateSizeTYPE,
    fmi3SerializeFMUState: fmi3SerializeFMUStateTYPE,
    fmi3DeserializeFMUState: fmi3DeserializeFMUStateTYPE,
    fmi3GetDirectionalDerivative: fmi3GetDirectionalDerivativeTYPE,
    fmi3GetAdjointDerivative: fmi3GetAdjointDerivativeTYPE,
    fmi3EnterConfigurationMode: fmi3EnterConfigurationModeTYPE,
    fmi3ExitConfigurationMode: fmi3ExitConfigurationModeTYPE,
    fmi3GetIntervalDecimal: fmi3GetIntervalDecimalTYPE,
    fmi3GetIntervalFraction: fmi3GetIntervalFractionTYPE,
    fmi3GetShiftDecimal: fmi3GetShiftDecimalTYPE,
    fmi3GetShiftFraction: fmi3GetShiftFractionTYPE,
    fmi3SetIntervalDecimal: fmi3SetIntervalDecimalTYPE,
    fmi3SetIntervalFraction: fmi3SetIntervalFractionTYPE,
    fmi3SetShiftDecimal: fmi3SetShiftDecimalTYPE,
    fmi3SetShiftFraction: fmi3SetShiftFractionTYPE,
    fmi3EvaluateDiscreteStates: fmi3EvaluateDiscreteStatesTYPE,
    fmi3UpdateDiscreteStates: fmi3UpdateDiscreteStatesTYPE,
    fmi3EnterContinuousTimeMode: fmi3EnterContinuousTimeModeTYPE,
    fmi3CompletedIntegratorStep: fmi3CompletedIntegratorStepTYPE,
    fmi3SetTime: fmi3SetTimeTYPE,
    fmi3SetContinuousStates: fmi3SetContinuousStatesTYPE,
    fmi3GetContinuousStateDerivatives: fmi3GetContinuousStateDerivativesTYPE,
    fmi3GetEventIndicators: fmi3GetEventIndicatorsTYPE,
    fmi3GetContinuousStates: fmi3GetContinuousStatesTYPE,
    fmi3GetNominalsOfContinuousStates: fmi3GetNominalsOfContinuousStatesTYPE,
    fmi3GetNumberOfEventIndicators: fmi3GetNumberOfEventIndicatorsTYPE,
    fmi3GetNumberOfContinuousStates: fmi3GetNumberOfContinuousStatesTYPE,
    fmi3EnterStepMode: fmi3EnterStepModeTYPE,
    fmi3GetOutputDerivatives: fmi3GetOutputDerivativesTYPE,
    fmi3DoStep: fmi3DoStepTYPE,
    fmi3ActivateModelPartition: fmi3ActivateModelPartitionTYPE,
}
