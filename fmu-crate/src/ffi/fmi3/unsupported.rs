//! The FMI 3.0 functions this FMU does not support (Model Exchange, Scheduled Execution, event mode, clocks, derivatives, dependency queries): each logs a message and returns fmi3Error.

use super::*;

/// Exports each unsupported function (its arguments after the instance, and why it is not
/// supported): it logs the reason and returns fmi3Error.
macro_rules! unsupported3 {
    ($($name:ident($($arg:ident: $ty:ty),*) => $why:expr;)*) => {
        $(
            #[no_mangle]
            pub unsafe extern "C" fn $name(instance: f3::fmi3Instance, $($arg: $ty),*) -> St {
                const F: &str = stringify!($name);
                // SAFETY: `with3` dereferences `instance` only if it is a live instance of
                // the registry, and the importer calls one instance from one thread at a time
                // (an FMI 3.0 rule); no other pointer is read.
                unsafe {
                    with3(instance, F, |comp, _| {
                        comp.inst.error(format!("{F}: not supported by {MODEL_IDENTIFIER} ({})", $why))
                    })
                }
            }
        )*
    };
}

const ME: &str = "the FMU is Co-Simulation only";
const EVENTS: &str = "hasEventMode = false: the FMU has no event mode";
const CLOCKS: &str = "the FMU has no clocks";
const DERIVATIVES: &str = "providesDirectionalDerivatives = providesAdjointDerivatives = false: at a communication point the outputs are those of the completed step and do not depend on inputs set since; for the Jacobian of a step take finite differences with fmi3GetFMUState/fmi3SetFMUState, see docs/fmu.md";
const DEPENDENCIES: &str = "the dependencies are those of modelDescription.xml: at a communication point no output depends on an input (dependencies=\"\")";

unsupported3! {
    fmi3EnterEventMode() => EVENTS;
    fmi3EvaluateDiscreteStates() => EVENTS;
    fmi3UpdateDiscreteStates(
        _discreteStatesNeedUpdate: *mut f3::fmi3Boolean,
        _terminateSimulation: *mut f3::fmi3Boolean,
        _nominalsOfContinuousStatesChanged: *mut f3::fmi3Boolean,
        _valuesOfContinuousStatesChanged: *mut f3::fmi3Boolean,
        _nextEventTimeDefined: *mut f3::fmi3Boolean,
        _nextEventTime: *mut f3::fmi3Float64
    ) => EVENTS;
    fmi3EnterStepMode() => EVENTS;
    fmi3GetNumberOfVariableDependencies(
        _valueReference: f3::fmi3ValueReference,
        _nDependencies: *mut usize
    ) => DEPENDENCIES;
    fmi3GetVariableDependencies(
        _dependent: f3::fmi3ValueReference,
        _elementIndicesOfDependent: *mut usize,
        _independents: *mut f3::fmi3ValueReference,
        _elementIndicesOfIndependents: *mut usize,
        _dependencyKinds: *mut f3::fmi3DependencyKind,
        _nDependencies: usize
    ) => DEPENDENCIES;
    fmi3GetDirectionalDerivative(
        _unknowns: *const f3::fmi3ValueReference,
        _nUnknowns: usize,
        _knowns: *const f3::fmi3ValueReference,
        _nKnowns: usize,
        _seed: *const f3::fmi3Float64,
        _nSeed: usize,
        _sensitivity: *mut f3::fmi3Float64,
        _nSensitivity: usize
    ) => DERIVATIVES;
    fmi3GetAdjointDerivative(
        _unknowns: *const f3::fmi3ValueReference,
        _nUnknowns: usize,
        _knowns: *const f3::fmi3ValueReference,
        _nKnowns: usize,
        _seed: *const f3::fmi3Float64,
        _nSeed: usize,
        _sensitivity: *mut f3::fmi3Float64,
        _nSensitivity: usize
    ) => DERIVATIVES;
    fmi3GetOutputDerivatives(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _orders: *const f3::fmi3Int32,
        _values: *mut f3::fmi3Float64,
        _nValues: usize
    ) => "maxOutputDerivativeOrder = 0";
    fmi3GetIntervalDecimal(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _intervals: *mut f3::fmi3Float64,
        _qualifiers: *mut f3::fmi3IntervalQualifier
    ) => CLOCKS;
    fmi3GetIntervalFraction(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _counters: *mut f3::fmi3UInt64,
        _resolutions: *mut f3::fmi3UInt64,
        _qualifiers: *mut f3::fmi3IntervalQualifier
    ) => CLOCKS;
    fmi3GetShiftDecimal(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _shifts: *mut f3::fmi3Float64
    ) => CLOCKS;
    fmi3GetShiftFraction(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _counters: *mut f3::fmi3UInt64,
        _resolutions: *mut f3::fmi3UInt64
    ) => CLOCKS;
    fmi3SetIntervalDecimal(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _intervals: *const f3::fmi3Float64
    ) => CLOCKS;
    fmi3SetIntervalFraction(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _counters: *const f3::fmi3UInt64,
        _resolutions: *const f3::fmi3UInt64
    ) => CLOCKS;
    fmi3SetShiftDecimal(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _shifts: *const f3::fmi3Float64
    ) => CLOCKS;
    fmi3SetShiftFraction(
        _valueReferences: *const f3::fmi3ValueReference,
        _nValueReferences: usize,
        _counters: *const f3::fmi3UInt64,
        _resolutions: *const f3::fmi3UInt64
    ) => CLOCKS;
    fmi3ActivateModelPartition(
        _clockReference: f3::fmi3ValueReference,
        _activationTime: f3::fmi3Float64
    ) => "Scheduled Execution: the FMU is Co-Simulation only";
    fmi3EnterContinuousTimeMode() => ME;
    fmi3CompletedIntegratorStep(
        _noSetFMUStatePriorToCurrentPoint: f3::fmi3Boolean,
        _enterEventMode: *mut f3::fmi3Boolean,
        _terminateSimulation: *mut f3::fmi3Boolean
    ) => ME;
    fmi3SetTime(_time: f3::fmi3Float64) => ME;
    fmi3SetContinuousStates(_continuousStates: *const f3::fmi3Float64, _nContinuousStates: usize) => ME;
    fmi3GetContinuousStateDerivatives(_derivatives: *mut f3::fmi3Float64, _nContinuousStates: usize) => ME;
    fmi3GetEventIndicators(_eventIndicators: *mut f3::fmi3Float64, _nEventIndicators: usize) => ME;
    fmi3GetContinuousStates(_continuousStates: *mut f3::fmi3Float64, _nContinuousStates: usize) => ME;
    fmi3GetNominalsOfContinuousStates(_nominals: *mut f3::fmi3Float64, _nContinuousStates: usize) => ME;
    fmi3GetNumberOfEventIndicators(_nEventIndicators: *mut usize) => ME;
    fmi3GetNumberOfContinuousStates(_nContinuousStates: *mut usize) => ME;
}
