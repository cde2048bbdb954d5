//! Co-Simulation: fmi2DoStep, fmi2CancelStep and the status inquiries (FMI 2.0 sec. 4.2).

use super::*;

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: f::fmi2Component,
    currentCommunicationPoint: f::fmi2Real,
    communicationStepSize: f::fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: f::fmi2Boolean,
) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe {
        with(c, "fmi2DoStep", |comp| {
            comp.inst
                .do_step(currentCommunicationPoint, communicationStepSize)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: f::fmi2Component) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe {
        with(c, "fmi2CancelStep", |comp| {
            comp.inst.error("fmi2CancelStep: not supported (fmi2DoStep runs synchronously and never returns fmi2Pending)".into())
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(
    c: f::fmi2Component,
    s: f::fmi2StatusKind,
    value: *mut f::fmi2Status,
) -> S {
    const F: &str = "fmi2GetStatus";
    // SAFETY: `c` as in `with`; value points to a writable fmi2Status (FMI 2.0 sec. 4.2.3,
    // fmi2GetStatus), null-checked by `as_mut`.
    unsafe {
        with(c, F, |comp| {
            let Some(v) = value.as_mut() else {
                return null_arg(&mut comp.inst, F, "value");
            };
            if s == f::fmi2StatusKind_fmi2DoStepStatus {
                // no asynchronous step is ever pending
                *v = if comp.inst.phase() == Phase::Error {
                    ERROR
                } else {
                    OK
                };
                Status::Ok
            } else {
                Status::Discard
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: f::fmi2Component,
    s: f::fmi2StatusKind,
    value: *mut f::fmi2Real,
) -> S {
    const F: &str = "fmi2GetRealStatus";
    // SAFETY: `c` as in `with`; value points to a writable fmi2Real (FMI 2.0 sec. 4.2.3),
    // null-checked by `as_mut`.
    unsafe {
        with(c, F, |comp| {
            let Some(v) = value.as_mut() else {
                return null_arg(&mut comp.inst, F, "value");
            };
            if s == f::fmi2StatusKind_fmi2LastSuccessfulTime {
                *v = comp.inst.last_successful_time();
                Status::Ok
            } else {
                Status::Discard
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: f::fmi2Component,
    _s: f::fmi2StatusKind,
    _value: *mut f::fmi2Integer,
) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe { with(c, "fmi2GetIntegerStatus", |_| Status::Discard) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: f::fmi2Component,
    s: f::fmi2StatusKind,
    value: *mut f::fmi2Boolean,
) -> S {
    const F: &str = "fmi2GetBooleanStatus";
    // SAFETY: `c` as in `with`; value points to a writable fmi2Boolean (FMI 2.0 sec. 4.2.3),
    // null-checked by `as_mut`.
    unsafe {
        with(c, F, |comp| {
            let Some(v) = value.as_mut() else {
                return null_arg(&mut comp.inst, F, "value");
            };
            if s == f::fmi2StatusKind_fmi2Terminated {
                *v = 0; // the slave never asks to terminate
                Status::Ok
            } else {
                Status::Discard
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: f::fmi2Component,
    _s: f::fmi2StatusKind,
    _value: *mut f::fmi2String,
) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe { with(c, "fmi2GetStringStatus", |_| Status::Discard) }
}
