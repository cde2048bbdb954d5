//! fmi2GetTypesPlatform, fmi2GetVersion, fmi2Instantiate, fmi2FreeInstance, fmi2SetDebugLogging and the life cycle (fmi2SetupExperiment to fmi2Reset; FMI 2.0 sec. 2.1.5, 2.1.6).

use super::*;

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: f::fmi2String,
    fmuType: f::fmi2Type,
    fmuGUID: f::fmi2String,
    fmuResourceLocation: f::fmi2String,
    functions: *const f::fmi2CallbackFunctions,
    _visible: f::fmi2Boolean,
    loggingOn: f::fmi2Boolean,
) -> f::fmi2Component {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: a non-null fmi2CallbackFunctions is the importer's, valid during
        // fmi2Instantiate (FMI 2.0 sec. 2.1.5); null is handled.
        let (logger, env) = match unsafe { functions.as_ref() } {
            Some(cb) => (cb.logger, cb.componentEnvironment),
            None => (None, std::ptr::null_mut()),
        };
        // SAFETY: fmi2Instantiate receives instanceName as a NUL-terminated string or null
        // (FMI 2.0 sec. 2.1.5); `cstr` checks null.
        let name = unsafe { cstr(instanceName) }
            .unwrap_or(MODEL_IDENTIFIER)
            .to_string();
        let cname = escape_percent(&name);
        let fail = |text: String| {
            let m = LogMsg {
                status: Status::Error,
                category: "logStatusError",
                text,
            };
            // SAFETY: logger and env come from this fmi2Instantiate call's
            // fmi2CallbackFunctions, valid while it runs (FMI 2.0 sec. 2.1.5).
            unsafe { emit(Logger::Fmi2(logger, env), &cname, &m) };
            std::ptr::null_mut()
        };
        if fmuType != f::fmi2Type_fmi2CoSimulation {
            return fail(format!("fmi2Instantiate: {MODEL_IDENTIFIER} supports Co-Simulation only (fmuType = {fmuType})"));
        }
        let want = guid();
        // SAFETY: fmuGUID is a NUL-terminated string or null (FMI 2.0 sec. 2.1.5); `cstr`
        // checks null.
        match unsafe { cstr(fmuGUID) } {
            Some(g) if g == want => {}
            g => return fail(format!("fmi2Instantiate: GUID {g:?} does not match this binary's {want} (modelDescription.xml and binary from different builds)")),
        }
        // SAFETY: fmuResourceLocation is a NUL-terminated URI or null (FMI 2.0 sec. 2.1.5);
        // `cstr` checks null.
        let res = unsafe { cstr(fmuResourceLocation) };
        let inst = Instance::new(&name, res, loggingOn != 0);
        let mut comp = Box::new(Component {
            inst,
            logger: Logger::Fmi2(logger, env),
            name: cname,
            strings: Vec::new(),
            v3: None,
        });
        flush(&mut comp);
        register(comp)
    }));
    r.unwrap_or(std::ptr::null_mut())
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: f::fmi2Component) {
    free_instance(c, "fmi2FreeInstance");
}

/// Frees the instance behind `c` and its FMU states (fmi2FreeInstance, fmi3FreeInstance).
pub(super) fn free_instance(c: *mut std::ffi::c_void, func: &str) {
    let h = c as usize;
    if h == 0 {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        let (ptr, states) = {
            let mut r = registry();
            let ptr = r.comps.remove(&h);
            // the instance's FMU states go with it
            let owned: Vec<usize> = r
                .states
                .iter()
                .filter(|(_, b)| b.owner == h)
                .map(|(k, _)| *k)
                .collect();
            let states: Vec<StateBox> = if ptr.is_some() {
                owned.iter().filter_map(|k| r.states.remove(k)).collect()
            } else {
                Vec::new()
            };
            r.release_when_idle();
            (ptr, states)
        };
        drop(states);
        match ptr {
            // SAFETY: the address came from Box::into_raw in fmi2Instantiate and was just
            // removed from the registry, so it is freed exactly once; fmi2FreeInstance is the
            // instance's last call (FMI 2.0 sec. 2.1.5), and later calls with `c` are refused.
            Some(p) => drop(unsafe { Box::from_raw(p as *mut Component) }),
            None => unknown_handle(func, "instance", h),
        }
    }));
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: f::fmi2Component,
    loggingOn: f::fmi2Boolean,
    nCategories: usize,
    categories: *const f::fmi2String,
) -> S {
    // SAFETY: as `set_debug_logging`.
    status(unsafe {
        set_debug_logging(
            c,
            "fmi2SetDebugLogging",
            loggingOn != 0,
            nCategories,
            categories,
        )
    })
}

/// The body of fmi2SetDebugLogging and fmi3SetDebugLogging (`func`: the function's name).
pub(super) unsafe fn set_debug_logging(
    c: *mut std::ffi::c_void,
    func: &str,
    on: bool,
    nCategories: usize,
    categories: *const *const c_char,
) -> Status {
    // SAFETY: `c` as in `with`; fmi2SetDebugLogging and fmi3SetDebugLogging pass categories
    // as an array of nCategories NUL-terminated strings (FMI 2.0 sec. 2.1.5, FMI 3.0 sec.
    // 2.3.1): `slice` checks the array for null, `cstr` each string.
    unsafe {
        with_status(c, func, |comp| {
            let Some(cats) = slice(categories, nCategories) else {
                return null_arg(&mut comp.inst, func, "categories");
            };
            let names: Vec<String> = cats
                .iter()
                .map(|p| cstr(*p).unwrap_or("<null>").to_string())
                .collect();
            comp.inst.set_debug_logging(on, &names)
        })
    }
}

// ---------------------------------------------------------------------------------------
// Life cycle

#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: f::fmi2Component,
    _toleranceDefined: f::fmi2Boolean,
    _tolerance: f::fmi2Real,
    startTime: f::fmi2Real,
    _stopTimeDefined: f::fmi2Boolean,
    _stopTime: f::fmi2Real,
) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe {
        with(c, "fmi2SetupExperiment", |comp| {
            comp.inst.setup_experiment(startTime)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: f::fmi2Component) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe {
        with(c, "fmi2EnterInitializationMode", |comp| {
            comp.inst.enter_initialization()
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: f::fmi2Component) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe {
        with(c, "fmi2ExitInitializationMode", |comp| {
            comp.inst.exit_initialization()
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: f::fmi2Component) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe { with(c, "fmi2Terminate", |comp| comp.inst.terminate()) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: f::fmi2Component) -> S {
    // SAFETY: `with` dereferences `c` only if it is a live instance of the registry, and the
    // importer calls one instance from one thread at a time (an FMI 2.0 rule); no other
    // pointer is read.
    unsafe { with(c, "fmi2Reset", |comp| comp.inst.reset()) }
}
