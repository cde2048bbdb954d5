//! Bad input never crashes the host: each case returns the status a master expects and logs a message naming the variable and the reason.

mod common;
use common::*;
use ecf_contact::ffi::*;
use fmi_sys::fmi2 as f;
use std::ffi::CString;

fn has(fmu: &Fmu, level: log::Level, words: &[&str]) -> bool {
    fmu.messages()
        .iter()
        .any(|(l, m)| *l == level && words.iter().all(|w| m.contains(w)))
}

fn ready(name: &str) -> Fmu {
    let mut f = Fmu::new(name);
    assert_eq!(f.set_int("nx", 16), OK);
    assert_eq!(f.set_int("ny", 5), OK);
    f.inputs(0.01, 0.0, 0.0, 20.0, 110e3);
    assert_eq!(f.init(), OK);
    f
}

#[test]
fn non_finite_inputs_are_rejected_and_the_old_value_kept() {
    let mut f = ready("nan");
    for (n, x) in [
        ("cx", f64::NAN),
        ("v", f64::INFINITY),
        ("FN", f64::NEG_INFINITY),
        ("T_bulk", f64::NAN),
    ] {
        let before = f.get(n);
        assert_eq!(f.set_real(n, x), ERROR, "{n} = {x}");
        assert_eq!(f.get(n).to_bits(), before.to_bits(), "{n} unchanged");
        assert!(
            has(&f, log::Level::Error, &["fmi2SetReal", n, "finite"]),
            "{n}: {:?}",
            f.messages()
        );
    }
    assert_eq!(f.step(1e-3), OK);
    assert!(f.outputs().iter().all(|x| x.is_finite()));
}

#[test]
fn lift_off_gives_zero_forces_with_a_warning() {
    let mut f = ready("liftoff");
    assert!(f.get("Fx") > 0.0);
    assert_eq!(f.set_real("FN", -1500.0), WARNING);
    assert!(
        has(&f, log::Level::Warn, &["FN = -1500", "lifted off"]),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.step(1e-3), OK);
    for n in ["Fx", "Fy", "Mz", "f", "P_fric"] {
        assert_eq!(f.get(n), 0.0, "{n}");
    }
    assert_eq!(f.set_real("FN", 0.0), OK);
    assert_eq!(f.step(1e-3), OK);
    assert_eq!(f.get("Fx"), 0.0);
    // touch-down again: forces come back
    assert_eq!(f.set_real("FN", 110e3), OK);
    for _ in 0..5 {
        assert_eq!(f.step(1e-3), OK);
    }
    assert!(f.get("Fx") > 0.0);
}

#[test]
fn standstill_and_large_creepage() {
    let mut f = ready("standstill");
    assert_eq!(f.set_real("v", 0.0), OK);
    assert_eq!(f.step(1e-3), OK);
    assert!(
        f.outputs().iter().all(|x| x.is_finite()),
        "{:?}",
        f.outputs()
    );
    assert_eq!(f.get("P_fric"), 0.0, "no frictional power at standstill");
    assert_eq!(f.set_real("v", 20.0), OK);
    assert_eq!(f.set_real("cx", 1.5), WARNING);
    // the message is formatted by the FMU with a '%' that survives printf-style logging
    assert!(
        has(&f, log::Level::Warn, &["cx = 1.5", "|cx| > 1", "150 %"]),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.step(1e-3), OK);
    assert!(f.get("Fx") > 0.0 && f.get("f") < 1.0);
    assert_eq!(f.set_real("cx", -12.0), ERROR);
    assert!(
        has(&f, log::Level::Error, &["cx = -12", "[-10, 10]"]),
        "{:?}",
        f.messages()
    );
    // negative speeds roll backwards (docs/fmu.md); beyond 1000 m/s is refused
    assert_eq!(f.set_real("v", -3000.0), ERROR);
    assert!(
        has(&f, log::Level::Error, &["v = -3000"]),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.set_real("cx", 0.01), OK);
    assert_eq!(f.set_real("v", -3.0), OK);
    assert_eq!(f.step(1e-3), OK);
    assert!(
        f.get("Fx") > 0.0,
        "traction while rolling backwards: Fx has the sign of cx"
    );
}

#[test]
fn wrong_call_sequence_unknown_references_and_fixed_parameters() {
    let mut f = Fmu::new("sequence");
    assert_eq!(f.step(1e-3), ERROR);
    assert!(
        has(
            &f,
            log::Level::Error,
            &["fmi2DoStep", "not allowed in state Instantiated"]
        ),
        "{:?}",
        f.messages()
    );
    let mut x = 0.0;
    assert_eq!(unsafe { fmi2GetReal(f.c, &vr("Fx"), 1, &mut x) }, ERROR);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, ERROR);
    assert_eq!(f.set_int("nx", 16), OK);
    assert_eq!(f.set_int("ny", 5), OK);
    assert_eq!(f.init(), OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, ERROR);
    assert_eq!(f.set_real("tau_c1_0_GPa", 0.4), ERROR);
    assert!(
        has(
            &f,
            log::Level::Error,
            &["tau_c1_0_GPa", "fixed parameter", "StepComplete"]
        ),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.set_int("nx", 30), ERROR);
    assert_eq!(f.set_string("preset", "wet"), ERROR);
    assert_eq!(f.set_real("Fx", 1.0), ERROR);
    assert!(
        has(&f, log::Level::Error, &["cannot set Fx", "output"]),
        "{:?}",
        f.messages()
    );
    let bad = 4242u32;
    assert_eq!(unsafe { fmi2SetReal(f.c, &bad, 1, &1.0) }, ERROR);
    assert_eq!(unsafe { fmi2GetReal(f.c, &bad, 1, &mut x) }, ERROR);
    assert!(
        has(&f, log::Level::Error, &["unknown value reference 4242"]),
        "{:?}",
        f.messages()
    );
    // a Real read as Integer
    let mut i = 0;
    assert_eq!(unsafe { fmi2GetInteger(f.c, &vr("cx"), 1, &mut i) }, ERROR);
    assert!(
        has(&f, log::Level::Error, &["cx", "Real, not Integer"]),
        "{:?}",
        f.messages()
    );
    // unsupported functions answer with an error and a message
    assert_eq!(unsafe { fmi2CancelStep(f.c) }, ERROR);
    assert_eq!(
        unsafe { fmi2GetDirectionalDerivative(f.c, &bad, 1, &bad, 1, &x, &mut x) },
        ERROR
    );
    assert!(
        has(
            &f,
            log::Level::Error,
            &["fmi2GetDirectionalDerivative", "not supported"]
        ),
        "{:?}",
        f.messages()
    );
    // the instance still works after all of this
    assert_eq!(f.step(1e-3), OK);
    // a time that does not match: an error of fmi2DoStep, so the error state (see
    // a_failed_step_leaves_only_diagnosis_restore_reset_and_free)
    assert_eq!(unsafe { fmi2DoStep(f.c, 5.0, 1e-3, 1) }, ERROR);
    assert!(
        has(
            &f,
            log::Level::Error,
            &["currentCommunicationPoint = 5", "error state"]
        ),
        "{:?}",
        f.messages()
    );
    assert_eq!(unsafe { fmi2Terminate(f.c) }, ERROR);
    assert_eq!(unsafe { fmi2Reset(f.c) }, OK);
    f.time = 0.0;
    assert_eq!(f.init(), OK);
    assert_eq!(f.step(1e-3), OK);
    assert_eq!(unsafe { fmi2Terminate(f.c) }, OK);
    assert_eq!(f.step(1e-3), ERROR);
    assert_eq!(unsafe { fmi2Reset(f.c) }, OK);
    f.time = 0.0;
    assert_eq!(f.init(), OK);
    assert_eq!(f.step(1e-3), OK);
}

#[test]
fn null_component_and_null_arguments() {
    let n = std::ptr::null_mut();
    let mut x = 0.0;
    let v = 1u32;
    unsafe {
        assert_eq!(fmi2DoStep(n, 0.0, 1e-3, 1), ERROR);
        assert_eq!(fmi2SetReal(n, &v, 1, &x), ERROR);
        assert_eq!(fmi2GetReal(n, &v, 1, &mut x), ERROR);
        assert_eq!(fmi2EnterInitializationMode(n), ERROR);
        assert_eq!(fmi2ExitInitializationMode(n), ERROR);
        assert_eq!(fmi2SetupExperiment(n, 0, 0.0, 0.0, 0, 0.0), ERROR);
        assert_eq!(fmi2Terminate(n), ERROR);
        assert_eq!(fmi2Reset(n), ERROR);
        assert_eq!(fmi2SetFMUstate(n, n), ERROR);
        assert_eq!(fmi2CancelStep(n), ERROR);
        fmi2FreeInstance(n);
    }
    let f = ready("nullargs");
    unsafe {
        assert_eq!(fmi2GetReal(f.c, std::ptr::null(), 1, &mut x), ERROR);
        assert_eq!(fmi2SetReal(f.c, &v, 1, std::ptr::null()), ERROR);
        assert_eq!(
            fmi2GetReal(f.c, std::ptr::null(), 0, std::ptr::null_mut()),
            OK
        );
        assert_eq!(fmi2GetFMUstate(f.c, std::ptr::null_mut()), ERROR);
        assert_eq!(fmi2SetFMUstate(f.c, std::ptr::null_mut()), ERROR);
        let p: f::fmi2String = std::ptr::null();
        assert_eq!(fmi2SetString(f.c, &vr("config_file"), 1, &p), ERROR);
    }
    assert!(
        has(&f, log::Level::Error, &["fmi2GetReal", "null pointer"]),
        "{:?}",
        f.messages()
    );
}

#[test]
fn instantiate_refuses_wrong_guid_and_model_exchange_and_tolerates_a_null_logger() {
    let cb = callbacks();
    let name = CString::new("guid-check").unwrap();
    let wrong = CString::new("{00000000-0000-0000-0000-000000000000}").unwrap();
    let good = CString::new(ecf_contact::model_description::guid()).unwrap();
    unsafe {
        let c = fmi2Instantiate(
            name.as_ptr(),
            f::fmi2Type_fmi2CoSimulation,
            wrong.as_ptr(),
            std::ptr::null(),
            &*cb,
            0,
            0,
        );
        assert!(c.is_null());
        let c = fmi2Instantiate(
            name.as_ptr(),
            f::fmi2Type_fmi2ModelExchange,
            good.as_ptr(),
            std::ptr::null(),
            &*cb,
            0,
            0,
        );
        assert!(c.is_null());
    }
    let m = messages("guid-check");
    assert!(m.iter().any(|(_, t)| t.contains("GUID")), "{m:?}");
    assert!(
        m.iter().any(|(_, t)| t.contains("Co-Simulation only")),
        "{m:?}"
    );
    // a null logger and a null callback struct: errors are still returned, nothing crashes
    let silent = f::fmi2CallbackFunctions {
        logger: None,
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: std::ptr::null_mut(),
    };
    for cbp in [&silent as *const _, std::ptr::null()] {
        unsafe {
            let c = fmi2Instantiate(
                name.as_ptr(),
                f::fmi2Type_fmi2CoSimulation,
                good.as_ptr(),
                std::ptr::null(),
                cbp,
                0,
                1,
            );
            assert!(!c.is_null());
            assert_eq!(fmi2SetReal(c, &vr("cx"), 1, &f64::NAN), ERROR);
            assert_eq!(fmi2DoStep(c, 0.0, 1e-3, 1), ERROR);
            fmi2FreeInstance(c);
        }
    }
}

#[test]
fn configuration_files_missing_malformed_conflicting_and_good() {
    let dir = std::env::temp_dir().join(format!("ecf-fmu-test-{}", std::process::id()));
    let res = dir.join("resources");
    std::fs::create_dir_all(&res).unwrap();
    std::fs::write(
        res.join("bad.json"),
        "{\"model\": \"ecf\",\n \"params\": {\"mu\": }}",
    )
    .unwrap();
    std::fs::write(
        res.join("wet_mu.json"),
        "{\"preset\": \"wet\", \"params\": {\"mu\": 0.2}, \"grid\": {\"nx\": 12, \"ny\": 5}}",
    )
    .unwrap();
    let uri = format!("file://{}/", res.display());
    let f = Fmu::with_resources("config", Some(&uri));
    assert_eq!(f.set_string("config_file", "missing.json"), ERROR);
    assert!(
        has(
            &f,
            log::Level::Error,
            &["config_file = 'missing.json'", "cannot read"]
        ),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.set_string("config_file", "bad.json"), ERROR);
    assert!(
        has(
            &f,
            log::Level::Error,
            &["config_file = 'bad.json'", "line 2"]
        ),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.set_string("model", "brush"), ERROR);
    assert!(
        has(
            &f,
            log::Level::Error,
            &["model = 'brush'", "ecf, fastsim, polach"]
        ),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.set_string("preset", "moist"), ERROR);
    assert_eq!(
        f.get_string_safe("config_file"),
        None,
        "not gettable before initialization"
    );
    assert_eq!(f.set_string("config_file", "wet_mu.json"), OK);
    assert_eq!(f.set_string("model", "fastsim"), OK);
    unsafe {
        assert_eq!(fmi2SetupExperiment(f.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(f.c), OK);
        assert_eq!(fmi2ExitInitializationMode(f.c), ERROR);
    }
    assert!(
        has(
            &f,
            log::Level::Error,
            &["model = 'fastsim'", "wet_mu.json", "'ecf'"]
        ),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.set_string("model", "ecf"), OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, OK);
    assert_eq!(f.get("mu"), 0.2);
    let wet = creep_core::Config::preset("wet").unwrap();
    assert_eq!(
        f.get("tau_c2_0_GPa"),
        wet.params.get(creep_core::params::P::Tc20)
    );
    let mut nx = 0;
    assert_eq!(unsafe { fmi2GetInteger(f.c, &vr("nx"), 1, &mut nx) }, OK);
    assert_eq!(nx, 12);
    // a relative file without a resource location
    let g = Fmu::new("config-nores");
    assert_eq!(g.set_string("config_file", "wet_mu.json"), ERROR);
    assert!(
        has(&g, log::Level::Error, &["relative", "fmuResourceLocation"]),
        "{:?}",
        g.messages()
    );
    // an absolute path works without one
    let abs = res.join("wet_mu.json");
    assert_eq!(g.set_string("config_file", abs.to_str().unwrap()), OK);
    let _ = std::fs::remove_dir_all(&dir);
}

trait GetStringSafe {
    fn get_string_safe(&self, name: &str) -> Option<String>;
}
impl GetStringSafe for Fmu {
    fn get_string_safe(&self, name: &str) -> Option<String> {
        let mut p: f::fmi2String = std::ptr::null();
        let st = unsafe { fmi2GetString(self.c, &vr(name), 1, &mut p) };
        (st == OK).then(|| {
            unsafe { std::ffi::CStr::from_ptr(p) }
                .to_string_lossy()
                .into_owned()
        })
    }
}

#[test]
fn a_formula_nested_ten_thousand_deep_is_refused_on_a_small_thread() {
    // nesting is capped (docs/measurements.md section 4, "Add it"), so a deep formula
    // cannot overflow the stack of the importer's thread
    let dir = std::env::temp_dir().join(format!("ecf_deep_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cfg = dir.join("deep.json");
    let factor = format!("{}1{}", "(".repeat(10_000), ")".repeat(10_000));
    std::fs::write(
        &cfg,
        format!(r#"{{"preset": "dry", "formula_effects": [{{"name": "d", "target": "mu", "factor": "{factor}"}}]}}"#),
    )
    .unwrap();
    let path = cfg.to_str().unwrap().to_string();
    let (st, msgs) = std::thread::Builder::new()
        // 256 KiB for the release build CI tests (an unoptimized build's frames are larger)
        .stack_size(if cfg!(debug_assertions) { 2048 } else { 256 } * 1024)
        .spawn(move || {
            let f = Fmu::new("deep_formula");
            let st = f.set_string("config_file", &path);
            (st, f.messages())
        })
        .unwrap()
        .join()
        .expect("no crash on a 256 KiB thread");
    assert_eq!(st, ERROR);
    assert!(
        msgs.iter()
            .any(|(_, m)| m.contains("nests deeper than 50 levels")),
        "{msgs:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_normal_force_message_says_what_is_done_with_a_negative_force() {
    let mut f = Fmu::new("fn_message");
    assert_eq!(f.init(), OK);
    assert_eq!(f.set_real("FN", 2e8), ERROR);
    assert!(
        f.messages()
            .iter()
            .any(|(_, m)| m.contains("1e8 N") && m.contains("FN <= 0 is accepted: lift-off")),
        "{:?}",
        f.messages()
    );
    // and it is: a negative force is lift-off, not an error
    assert!(f.set_real("FN", -5.0) <= WARNING);
    assert!(f.step(1e-3) <= WARNING);
    assert_eq!(f.get("Fx"), 0.0);
}

/// Each way fmi2DoStep can fail in StepComplete: the model refusing the step (a step over
/// 1000 s), a step size that is not finite or negative, a communication point that does not
/// match. Each puts the instance in the error state (FMI 2.0, fmi2Error: "the simulation
/// cannot be continued with this FMU instance"), where only diagnosis (fmi2Get* of inputs
/// and parameters, fmi2GetStatus, fmi2GetRealStatus), fmi2SetFMUstate of an earlier state,
/// fmi2Reset and fmi2FreeInstance are accepted; both ways back continue as a fresh run does.
#[test]
fn a_failed_step_leaves_only_diagnosis_restore_reset_and_free() {
    let cases: [(&str, f64, f64, &str); 4] = [
        ("model", 0.0, 2000.0, "dt = 2000"),
        ("nan", 0.0, f64::NAN, "communicationStepSize = NaN"),
        ("negative", 0.0, -1e-3, "communicationStepSize = -0.001"),
        ("time", 5.0, 1e-3, "currentCommunicationPoint = 5"),
    ];
    // the reference: two steps of 1 ms after one step of 1 ms
    let mut r = ready("failed-step-reference");
    assert_eq!(r.step(1e-3), OK);
    assert_eq!(r.step(1e-3), OK);
    let fx_reference = r.get("Fx");
    for (what, dt_point, h, words) in cases {
        let name = format!("failed-step-{what}");
        let mut f = ready(&name);
        assert_eq!(f.step(1e-3), OK);
        let saved = f.get_state();
        let t_before = f.time;
        let st = unsafe { fmi2DoStep(f.c, f.time + dt_point, h, 1) };
        assert_eq!(st, ERROR, "{what}");
        assert!(
            has(&f, log::Level::Error, &["fmi2DoStep", words, "error state"]),
            "{what}: {:?}",
            f.messages()
        );
        // refused in the error state, with the mode named
        let mut x = 0.0;
        let mut s: f::fmi2FMUstate = std::ptr::null_mut();
        unsafe {
            assert_eq!(fmi2DoStep(f.c, t_before, 1e-3, 1), ERROR, "{what}: step");
            assert!(
                has(
                    &f,
                    log::Level::Error,
                    &["fmi2DoStep: not allowed in state Error"]
                ),
                "{what}: {:?}",
                f.messages()
            );
            assert_eq!(fmi2Terminate(f.c), ERROR, "{what}: terminate");
            assert_eq!(fmi2SetupExperiment(f.c, 0, 0.0, 0.0, 0, 0.0), ERROR);
            assert_eq!(fmi2EnterInitializationMode(f.c), ERROR, "{what}: enter");
            assert_eq!(fmi2ExitInitializationMode(f.c), ERROR, "{what}: exit");
            assert_eq!(fmi2GetFMUstate(f.c, &mut s), ERROR, "{what}: get state");
            assert!(s.is_null());
            // an output of a step that did not complete is not handed out
            assert_eq!(fmi2GetReal(f.c, &vr("Fx"), 1, &mut x), ERROR, "{what}: Fx");
        }
        assert_eq!(f.set_real("cx", 0.02), ERROR, "{what}: set an input");
        assert_eq!(f.set_int("nx", 20), ERROR, "{what}: set a parameter");
        // diagnosis: inputs and parameters as they were, the status, the last good time
        assert_eq!(f.get("cx"), 0.01, "{what}");
        let mut nx = 0;
        assert_eq!(unsafe { fmi2GetInteger(f.c, &vr("nx"), 1, &mut nx) }, OK);
        assert_eq!(nx, 16, "{what}: nx");
        let mut ds = OK;
        let mut last = f64::NAN;
        unsafe {
            assert_eq!(
                fmi2GetStatus(f.c, f::fmi2StatusKind_fmi2DoStepStatus, &mut ds),
                OK
            );
            assert_eq!(
                fmi2GetRealStatus(f.c, f::fmi2StatusKind_fmi2LastSuccessfulTime, &mut last),
                OK
            );
        }
        assert_eq!(ds, ERROR, "{what}: fmi2DoStepStatus");
        assert_eq!(last, t_before, "{what}: last successful time");
        // back by an earlier state: continues as if the failed step had not been called
        f.set_state(saved);
        assert_eq!(f.step(1e-3), OK, "{what}: step after the restore");
        assert_eq!(f.get("Fx"), fx_reference, "{what}: restored run");
        // fail again, then back by fmi2Reset and a new initialization
        assert_eq!(unsafe { fmi2DoStep(f.c, f.time + dt_point, h, 1) }, ERROR);
        assert_eq!(unsafe { fmi2Reset(f.c) }, OK, "{what}: reset");
        f.time = 0.0;
        assert_eq!(f.set_int("nx", 16), OK);
        assert_eq!(f.set_int("ny", 5), OK);
        f.inputs(0.01, 0.0, 0.0, 20.0, 110e3);
        assert_eq!(f.init(), OK, "{what}: init after reset");
        assert_eq!(f.step(1e-3), OK);
        assert_eq!(f.step(1e-3), OK);
        assert_eq!(f.get("Fx"), fx_reference, "{what}: run after the reset");
        f.free_state(saved);
        assert_eq!(unsafe { fmi2Terminate(f.c) }, OK);
    }
    let mut e = ready("failed-step-free");
    assert_eq!(e.step(f64::NAN), ERROR);
    drop(e); // fmi2FreeInstance in the error state
}
