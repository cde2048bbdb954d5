//! fmi3GetVersion, fmi3SetDebugLogging, fmi3InstantiateCoSimulation, fmi3FreeInstance, the modes (configuration, initialization, step, terminated), fmi3DoStep and the FMU state functions (FMI 3.0 sec. 2.3, 4.2).

use super::*;

#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    instance: f3::fmi3Instance,
    loggingOn: f3::fmi3Boolean,
    nCategories: usize,
    categories: *const f3::fmi3String,
) -> St {
    // SAFETY: as `set_debug_logging` (the same arguments in FMI 3.0, sec. 2.3.1).
    status3(unsafe {
        set_debug_logging(
            instance,
            "fmi3SetDebugLogging",
            loggingOn,
            nCategories,
            categories,
        )
    })
}

/// Logs an instantiation failure through the importer's callback and returns NULL.
unsafe fn refuse(
    log: f3::fmi3LogMessageCallback,
    env: f3::fmi3InstanceEnvironment,
    text: String,
) -> f3::fmi3Instance {
    let m = LogMsg {
        status: Status::Error,
        category: "logStatusError",
        text,
    };
    // SAFETY: log and env come from the instantiation call, valid while it runs (FMI 3.0
    // sec. 2.3.1).
    unsafe { emit(Logger::Fmi3(log, env), c"", &m) };
    std::ptr::null_mut()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instanceName: f3::fmi3String,
    instantiationToken: f3::fmi3String,
    resourcePath: f3::fmi3String,
    _visible: f3::fmi3Boolean,
    loggingOn: f3::fmi3Boolean,
    eventModeUsed: f3::fmi3Boolean,
    _earlyReturnAllowed: f3::fmi3Boolean,
    _requiredIntermediateVariables: *const f3::fmi3ValueReference,
    _nRequiredIntermediateVariables: usize,
    instanceEnvironment: f3::fmi3InstanceEnvironment,
    logMessage: f3::fmi3LogMessageCallback,
    _intermediateUpdate: f3::fmi3IntermediateUpdateCallback,
) -> f3::fmi3Instance {
    const F: &str = "fmi3InstantiateCoSimulation";
    let (log, env) = (logMessage, instanceEnvironment);
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: instanceName, instantiationToken and resourcePath are NUL-terminated
        // strings or null (FMI 3.0 sec. 2.3.1); `cstr` checks null.
        let (name, token, res) = unsafe {
            (
                cstr(instanceName),
                cstr(instantiationToken),
                cstr(resourcePath),
            )
        };
        let name = name.unwrap_or(MODEL_IDENTIFIER).to_string();
        if eventModeUsed {
            // SAFETY: the callback of this call (see `refuse`).
            return unsafe {
                refuse(log, env, format!("{F}: eventModeUsed = true, but {MODEL_IDENTIFIER} has no event mode (hasEventMode = false)"))
            };
        }
        let want = crate::model_description3::instantiation_token();
        if token != Some(want.as_str()) {
            // SAFETY: the callback of this call (see `refuse`).
            return unsafe {
                refuse(log, env, format!("{F}: instantiationToken {token:?} does not match this binary's {want} (modelDescription.xml and binary from different builds)"))
            };
        }
        let mut comp = Box::new(Component {
            inst: Instance::new_with_resource_dir(&name, res, loggingOn),
            logger: Logger::Fmi3(log, env),
            name: escape_percent(&name),
            strings: Vec::new(),
            v3: Some(Part::new()),
        });
        flush(&mut comp);
        register(comp)
    }));
    r.unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    _instanceName: f3::fmi3String,
    _instantiationToken: f3::fmi3String,
    _resourcePath: f3::fmi3String,
    _visible: f3::fmi3Boolean,
    _loggingOn: f3::fmi3Boolean,
    instanceEnvironment: f3::fmi3InstanceEnvironment,
    logMessage: f3::fmi3LogMessageCallback,
) -> f3::fmi3Instance {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: the callback of this call (see `refuse`).
        unsafe {
            refuse(logMessage, instanceEnvironment, format!("fmi3InstantiateModelExchange: not supported by {MODEL_IDENTIFIER} (the FMU is Co-Simulation only)"))
        }
    }));
    r.unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    _instanceName: f3::fmi3String,
    _instantiationToken: f3::fmi3String,
    _resourcePath: f3::fmi3String,
    _visible: f3::fmi3Boolean,
    _loggingOn: f3::fmi3Boolean,
    instanceEnvironment: f3::fmi3InstanceEnvironment,
    logMessage: f3::fmi3LogMessageCallback,
    _clockUpdate: f3::fmi3ClockUpdateCallback,
    _lockPreemption: f3::fmi3LockPreemptionCallback,
    _unlockPreemption: f3::fmi3UnlockPreemptionCallback,
) -> f3::fmi3Instance {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: the callback of this call (see `refuse`).
        unsafe {
            refuse(logMessage, instanceEnvironment, format!("fmi3InstantiateScheduledExecution: not supported by {MODEL_IDENTIFIER} (the FMU is Co-Simulation only)"))
        }
    }));
    r.unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeInstance(instance: f3::fmi3Instance) {
    free_instance(instance, "fmi3FreeInstance");
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterConfigurationMode(instance: f3::fmi3Instance) -> St {
    const F: &str = "fmi3EnterConfigurationMode";
    // SAFETY: `with3` dereferences `instance` only if it is a live instance of the registry,
    // and the importer calls one instance from one thread at a time (an FMI 3.0 rule).
    unsafe {
        with3(instance, F, |comp, part| {
            if part.configuring {
                return comp
                    .inst
                    .error(format!("{F}: already in ConfigurationMode"));
            }
            if comp.inst.phase() != Phase::Instantiated {
                return comp.inst.error(format!(
                    "{F}: allowed in Instantiated only, not in {} (n_field is fixed: there is no ReconfigurationMode)",
                    comp.inst.phase().name()
                ));
            }
            part.configuring = true;
            Status::Ok
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3ExitConfigurationMode(instance: f3::fmi3Instance) -> St {
    const F: &str = "fmi3ExitConfigurationMode";
    // SAFETY: `with3` dereferences `instance` only if it is a live instance of the registry,
    // and the importer calls one instance from one thread at a time (an FMI 3.0 rule).
    unsafe {
        with3(instance, F, |comp, part| {
            if !part.configuring {
                return comp.inst.error(format!("{F}: not in ConfigurationMode"));
            }
            part.configuring = false;
            Status::Ok
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    instance: f3::fmi3Instance,
    _toleranceDefined: f3::fmi3Boolean,
    _tolerance: f3::fmi3Float64,
    startTime: f3::fmi3Float64,
    _stopTimeDefined: f3::fmi3Boolean,
    _stopTime: f3::fmi3Float64,
) -> St {
    const F: &str = "fmi3EnterInitializationMode";
    // SAFETY: `with3` dereferences `instance` only if it is a live instance of the registry,
    // and the importer calls one instance from one thread at a time (an FMI 3.0 rule).
    unsafe {
        with3(instance, F, |comp, part| {
            if let Err(s) = not_configuring(comp, part, F) {
                return s;
            }
            match comp.inst.setup_experiment(startTime) {
                Status::Error => Status::Error,
                st => st.max(comp.inst.enter_initialization()),
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: f3::fmi3Instance) -> St {
    // SAFETY: `with3` dereferences `instance` only if it is a live instance of the registry,
    // and the importer calls one instance from one thread at a time (an FMI 3.0 rule).
    unsafe {
        with3(instance, "fmi3ExitInitializationMode", |comp, _| {
            comp.inst.exit_initialization()
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Terminate(instance: f3::fmi3Instance) -> St {
    // SAFETY: `with3` dereferences `instance` only if it is a live instance of the registry,
    // and the importer calls one instance from one thread at a time (an FMI 3.0 rule).
    unsafe { with3(instance, "fmi3Terminate", |comp, _| comp.inst.terminate()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Reset(instance: f3::fmi3Instance) -> St {
    // SAFETY: `with3` dereferences `instance` only if it is a live instance of the registry,
    // and the importer calls one instance from one thread at a time (an FMI 3.0 rule).
    unsafe {
        with3(instance, "fmi3Reset", |comp, part| {
            *part = Part::new();
            comp.inst.reset()
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3DoStep(
    instance: f3::fmi3Instance,
    currentCommunicationPoint: f3::fmi3Float64,
    communicationStepSize: f3::fmi3Float64,
    _noSetFMUStatePriorToCurrentPoint: f3::fmi3Boolean,
    eventHandlingNeeded: *mut f3::fmi3Boolean,
    terminateSimulation: *mut f3::fmi3Boolean,
    earlyReturn: *mut f3::fmi3Boolean,
    lastSuccessfulTime: *mut f3::fmi3Float64,
) -> St {
    // SAFETY: `instance` as in `with3`; the four out-arguments point to the importer's
    // variables (FMI 3.0 sec. 4.2.1, fmi3DoStep), each written only if not null.
    unsafe {
        with3(instance, "fmi3DoStep", |comp, _| {
            let st = comp
                .inst
                .do_step(currentCommunicationPoint, communicationStepSize);
            for p in [eventHandlingNeeded, terminateSimulation, earlyReturn] {
                if let Some(b) = p.as_mut() {
                    *b = false;
                }
            }
            if let Some(t) = lastSuccessfulTime.as_mut() {
                *t = comp.inst.last_successful_time();
            }
            st
        })
    }
}

// ---------------------------------------------------------------------------------------
// FMU states: the bodies of the FMI 2.0 functions, in the FMI 3.0 FMU's serialized format

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(
    instance: f3::fmi3Instance,
    FMUState: *mut f3::fmi3FMUState,
) -> St {
    // SAFETY: as `get_fmu_state` (the same arguments in FMI 3.0, sec. 2.3.6).
    status3(unsafe { fmu_state::get_fmu_state(instance, "fmi3GetFMUState", FMUState) })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(
    instance: f3::fmi3Instance,
    FMUState: f3::fmi3FMUState,
) -> St {
    const F: &str = "fmi3SetFMUState";
    // SAFETY: as `set_fmu_state`.
    let st = unsafe { fmu_state::set_fmu_state(instance, F, FMUState) };
    if st != Status::Error {
        // the state's mode replaces configuration mode, as every other mode
        // SAFETY: `with3` dereferences `instance` only if it is live.
        unsafe {
            with3(instance, F, |_, part| {
                part.configuring = false;
                Status::Ok
            })
        };
    }
    status3(st)
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(
    instance: f3::fmi3Instance,
    FMUState: *mut f3::fmi3FMUState,
) -> St {
    // SAFETY: as `free_fmu_state`.
    status3(unsafe { fmu_state::free_fmu_state(instance, "fmi3FreeFMUState", FMUState) })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    instance: f3::fmi3Instance,
    FMUState: f3::fmi3FMUState,
    size: *mut usize,
) -> St {
    // SAFETY: as `serialized_size`.
    status3(unsafe {
        fmu_state::serialized_size(instance, "fmi3SerializedFMUStateSize", FMUState, size)
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializeFMUState(
    instance: f3::fmi3Instance,
    FMUState: f3::fmi3FMUState,
    serializedState: *mut f3::fmi3Byte,
    size: usize,
) -> St {
    // SAFETY: as `serialize_fmu_state`.
    status3(unsafe {
        fmu_state::serialize_fmu_state(
            instance,
            "fmi3SerializeFMUState",
            FMUState,
            serializedState,
            size,
        )
    })
}

#[no_mangle]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    instance: f3::fmi3Instance,
    serializedState: *const f3::fmi3Byte,
    size: usize,
    FMUState: *mut f3::fmi3FMUState,
) -> St {
    // SAFETY: as `deserialize_fmu_state`.
    status3(unsafe {
        fmu_state::deserialize_fmu_state(
            instance,
            "fmi3DeserializeFMUState",
            serializedState,
            size,
            FMUState,
        )
    })
}
