//! FMU states under the importers' call sequences (docs/fmu.md, "FMU state (rollback, restart)"): a state restores the mode it was taken in, every state handed out reloads, none is handed out after a failed initialization.
mod common;

use common::{Fmu, ERROR, N_OUTPUTS, OK};
use ecf_contact::ffi::*;
use fmi_sys::fmi2 as f;

/// A run of `n` steps of 1 ms at c_x = 2 %, 20 m/s: the outputs after each.
fn continue_run(fmu: &mut Fmu, n: usize) -> Vec<[f64; N_OUTPUTS]> {
    (0..n)
        .map(|k| {
            assert_eq!(fmu.set_real("cx", 0.02 + 0.002 * k as f64), OK);
            assert_eq!(fmu.step(1e-3), OK);
            fmu.outputs()
        })
        .collect()
}

#[test]
fn a_state_set_in_a_fresh_instance_continues_without_initialization() {
    let mut a = Fmu::new("modes_a");
    assert_eq!(a.set_string("preset", "dry"), OK);
    a.inputs(0.002, 0.0, 0.0, 20.0, 110e3);
    assert_eq!(a.init(), OK);
    continue_run(&mut a, 5);
    let s = a.get_state();
    let bytes = a.serialize(s);
    a.free_state(s);
    let want = continue_run(&mut a, 5);

    // fmpy's simulate_fmu(fmu_state=...): instantiate, deserialize, set, step
    for how in ["in memory", "serialized"] {
        let mut b = Fmu::new(&format!("modes_b_{}", how.replace(' ', "_")));
        let s = b.deserialize(&bytes).expect("deserialize");
        b.set_state(s);
        b.free_state(s);
        assert!((b.time - 5e-3).abs() < 1e-15, "{how}: time {}", b.time);
        let got = continue_run(&mut b, 5);
        assert_eq!(
            got, want,
            "{how}: the fresh instance continues as the original"
        );
        // the restored mode is StepComplete: initialization is refused, as in the reference FMUs
        assert_eq!(unsafe { fmi2EnterInitializationMode(b.c) }, ERROR);
    }
}

#[test]
fn a_state_taken_before_initialization_restores_that_mode() {
    let mut a = Fmu::new("modes_early");
    let early = a.get_state();
    assert_eq!(a.set_string("preset", "wet"), OK);
    assert_eq!(a.init(), OK);
    assert_eq!(a.step(1e-3), OK);
    // back to Instantiated: parameters may be set again and the instance initialized
    a.set_state(early);
    assert_eq!(a.set_string("preset", "dry"), OK);
    assert_eq!(a.step(1e-3), ERROR, "no doStep before initialization");
    assert_eq!(a.init(), OK);
    assert_eq!(a.get_string("preset"), "dry");
    a.free_state(early);
}

#[test]
fn no_state_is_handed_out_after_a_failed_initialization() {
    let dir = std::env::temp_dir().join(format!("ecf_modes_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cfg = dir.join("col.json");
    // a formula that reads a data column, with `columns` left empty: initialization fails
    std::fs::write(
        &cfg,
        r#"{"preset": "dry", "formula_effects": [{"name": "h", "target": "tau_c2", "factor": "1 - 0.001 * humidity"}]}"#,
    )
    .unwrap();
    let mut a = Fmu::new("modes_failed");
    assert_eq!(a.set_string("config_file", cfg.to_str().unwrap()), OK);
    assert_eq!(a.init(), ERROR);
    let mut s: f::fmi2FMUstate = std::ptr::null_mut();
    assert_eq!(unsafe { fmi2GetFMUstate(a.c, &mut s) }, ERROR);
    assert!(s.is_null());
    assert_eq!(a.step(1e-3), ERROR);
    // still in initialization mode: a second failing exit, then fmi2Reset starts over
    assert_eq!(unsafe { fmi2ExitInitializationMode(a.c) }, ERROR);
    assert_eq!(unsafe { fmi2Reset(a.c) }, OK);
    assert_eq!(a.set_string("preset", "dry"), OK);
    assert_eq!(a.init(), OK);
    assert_eq!(a.step(1e-3), OK);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_state_the_fmu_hands_out_reloads() {
    // a Coulomb layer whose compliance grows with temperature once took an infinite plastic
    // slip (sh = inf), which the state reader refused. Its compliance
    // L_e(T) = L_e_0 exp(0.1 (T - T0)) feeds the release heat back into the temperature
    // without bound: without the trapezoidal dissipation (docs/model.md section 3.4) the steps
    // reported flash temperatures of 1e270 degC, now a step can overflow, and the FMU then
    // refuses it with its non-finite-outputs error. Either way every state it hands out must
    // reload, and after a refused step fmi2SetFMUstate to the state before it makes the
    // instance usable again.
    let mut a = Fmu::new("modes_reload");
    // on the preset's grid (80 x 21), where this runaway was found: the start value of
    // rel_tol would choose 10 x 3 cells, on which its steady state is not finite (NaN)
    assert_eq!(a.set_real("rel_tol", 0.0), OK);
    assert_eq!(a.set_string("preset", "twin_disc"), OK);
    assert_eq!(a.set_bool("effect_coulomb", true), OK);
    assert_eq!(a.set_real("L_e_T_per_C", 0.1), OK);
    a.inputs(0.18, 0.0, 0.0, 20.0, 110e3);
    assert!(a.init() <= common::WARNING);
    let mut refused = 0;
    for k in 0..6 {
        let s = a.get_state();
        let bytes = a.serialize(s);
        let back = a.deserialize(&bytes).unwrap_or_else(|st| {
            panic!(
                "step {k}: the FMU refuses its own state (status {st}): {:?}",
                a.messages()
            )
        });
        a.free_state(back);
        let st = a.step(1e-3);
        if st > common::WARNING {
            let m = a.messages();
            assert!(
                m.iter().any(|(_, t)| t.contains("gave non-finite outputs")),
                "step {k}: refused for another reason: {m:?}"
            );
            refused += 1;
            a.set_state(s);
            assert!(a.get("Fx").is_finite(), "step {k}: the restored state");
        }
        a.free_state(s);
    }
    // at least the first step runs, so that a state after a step (the case above) is among
    // those reloaded
    assert!(refused < 6, "every step refused");
}

#[test]
fn a_state_taken_in_initialization_mode_follows_the_inputs_it_holds() {
    // the state holds the inputs (c_x = 5 %) but the provisional model of c_x = 0.2 %, read
    // by a GetReal before the input changed: its exit must start from 5 %, as the original does
    let init = |name: &str| {
        let f = Fmu::new(name);
        assert_eq!(f.set_string("preset", "dry"), OK);
        f.inputs(0.002, 0.0, 0.0, 20.0, 110e3);
        unsafe {
            assert_eq!(fmi2SetupExperiment(f.c, 0, 0.0, 0.0, 0, 0.0), OK);
            assert_eq!(fmi2EnterInitializationMode(f.c), OK);
        }
        f
    };
    let a = init("modes_init_a");
    let fx_a = a.get("Fx");
    assert_eq!(a.set_real("cx", 0.05), OK);
    let s = a.get_state();
    let bytes = a.serialize(s);
    a.free_state(s);
    assert_eq!(unsafe { fmi2ExitInitializationMode(a.c) }, OK);
    let want = a.get("Fx");
    assert!(
        (want - fx_a).abs() > 1.0,
        "the input change matters: {fx_a} vs {want}"
    );
    let mut b = Fmu::new("modes_init_b");
    let s = b.deserialize(&bytes).expect("deserialize");
    b.set_state(s);
    b.free_state(s);
    assert_eq!(unsafe { fmi2ExitInitializationMode(b.c) }, OK);
    assert_eq!(b.get("Fx"), want);
}
