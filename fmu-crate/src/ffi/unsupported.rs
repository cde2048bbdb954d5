//! The functions of the standard this FMU does not support (Model Exchange, derivatives): each returns fmi2Error with a message.

use super::*;

fn unsupported(comp: &mut Component, func: &str, why: &str) -> Status {
    comp.inst.error(format!(
        "{func}: not supported by {MODEL_IDENTIFIER} ({why})"
    ))
}

/// Exports each unsupported function (its arguments after the instance, and why it is not
/// supported): it returns fmi2Error with a message.
macro_rules! unsupported {
    ($($name:ident($($arg:ident: $ty:ty),*) => $why:expr;)*) => {
        $(
            #[no_mangle]
            pub unsafe extern "C" fn $name(c: f::fmi2Component, $($arg: $ty),*) -> S {
                const F: &str = stringify!($name);
                // SAFETY: `with` dereferences `c` only if it is a live instance of the
                // registry, and the importer calls one instance from one thread at a time (an
                // FMI 2.0 rule); no other pointer is read.
                unsafe { with(c, F, |comp| unsupported(comp, F, $why)) }
            }
        )*
    };
}

const ME: &str = "the FMU is Co-Simulation only";

unsupported! {
    fmi2GetDirectionalDerivative(
        _vUnknown_ref: *const f::fmi2ValueReference,
        _nUnknown: usize,
        _vKnown_ref: *const f::fmi2ValueReference,
        _nKnown: usize,
        _dvKnown: *const f::fmi2Real,
        _dvUnknown: *mut f::fmi2Real
    ) => "providesDirectionalDerivative = false: at a communication point the outputs are those of the completed step and do not depend on inputs set since; for the Jacobian of a step take finite differences with fmi2GetFMUstate/fmi2SetFMUstate, see docs/fmu.md";
    fmi2SetRealInputDerivatives(
        _vr: *const f::fmi2ValueReference,
        _nvr: usize,
        _order: *const f::fmi2Integer,
        _value: *const f::fmi2Real
    ) => "canInterpolateInputs = false";
    fmi2GetRealOutputDerivatives(
        _vr: *const f::fmi2ValueReference,
        _nvr: usize,
        _order: *const f::fmi2Integer,
        _value: *mut f::fmi2Real
    ) => "maxOutputDerivativeOrder = 0";
    fmi2EnterEventMode() => ME;
    fmi2NewDiscreteStates(_info: *mut f::fmi2EventInfo) => ME;
    fmi2EnterContinuousTimeMode() => ME;
    fmi2CompletedIntegratorStep(
        _noSetFMUStatePriorToCurrentPoint: f::fmi2Boolean,
        _enterEventMode: *mut f::fmi2Boolean,
        _terminateSimulation: *mut f::fmi2Boolean
    ) => ME;
    fmi2SetTime(_time: f::fmi2Real) => ME;
    fmi2SetContinuousStates(_x: *const f::fmi2Real, _nx: usize) => ME;
    fmi2GetDerivatives(_derivatives: *mut f::fmi2Real, _nx: usize) => ME;
    fmi2GetEventIndicators(_eventIndicators: *mut f::fmi2Real, _ni: usize) => ME;
    fmi2GetContinuousStates(_x: *mut f::fmi2Real, _nx: usize) => ME;
    fmi2GetNominalsOfContinuousStates(_x_nominal: *mut f::fmi2Real, _nx: usize) => ME;
}
