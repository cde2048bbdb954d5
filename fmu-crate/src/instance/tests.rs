//! The instance's unit tests: threads and state restore, call rules and messages, parameters read back, geometry.

use super::*;
use creep_core::effects::Effect;
use creep_core::params::P;
use creep_core::Geometry;

fn vr(name: &str) -> u32 {
    vars::table()
        .iter()
        .find(|v| v.name == name)
        .map(|v| v.vr)
        .expect(name)
}

fn initialized() -> Instance {
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.set_integer(vr("nx"), 10), Status::Ok);
    assert_eq!(i.set_integer(vr("ny"), 5), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Ok);
    i
}

#[test]
fn threads_give_the_same_steps_and_survive_a_state_restore() {
    let run = |threads: i32| {
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_integer(vr("nx"), 20), Status::Ok);
        assert_eq!(i.set_integer(vr("ny"), 9), Status::Ok);
        assert_eq!(i.set_integer(vr("threads"), threads), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        assert_eq!(i.get_integer(vr("threads")), Ok(threads));
        let mut fx = Vec::new();
        let mut saved = None;
        for k in 0..20 {
            assert_eq!(i.set_real(vr("cx"), 0.002 + 0.01 * k as f64), Status::Ok);
            assert_eq!(i.do_step(k as f64 * 1e-4, 1e-4), Status::Ok);
            fx.push(i.get_real(vr("Fx")).expect("Fx"));
            if k == 10 {
                saved = Some(i.get_state());
            }
        }
        assert_eq!(i.set_state(saved.as_ref().expect("state")), Status::Ok);
        assert_eq!(i.get_integer(vr("threads")), Ok(threads));
        assert_eq!(i.set_real(vr("cx"), 0.002 + 0.01 * 11.0), Status::Ok);
        assert_eq!(i.do_step(11e-4, 1e-4), Status::Ok);
        fx.push(i.get_real(vr("Fx")).expect("Fx"));
        fx
    };
    let one = run(1);
    assert_eq!(one[11], one[20], "a restored state repeats its step");
    assert_eq!(one, run(3));
    // the continuous scheme: close to the reference, not equal to it
    let mut i = Instance::new("t", None, false);
    for (n, x) in [("nx", 20), ("ny", 9), ("scheme", 1)] {
        assert_eq!(i.set_integer(vr(n), x), Status::Ok);
    }
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Ok);
    assert_eq!(i.get_integer(vr("scheme")), Ok(1));
    let mut cont = Vec::new();
    for k in 0..20 {
        assert_eq!(i.set_real(vr("cx"), 0.002 + 0.01 * k as f64), Status::Ok);
        assert_eq!(i.do_step(k as f64 * 1e-4, 1e-4), Status::Ok);
        cont.push(i.get_real(vr("Fx")).expect("Fx"));
    }
    assert_ne!(cont[..20], one[..20]);
    for (c, r) in cont.iter().zip(&one) {
        assert!((c - r).abs() <= 0.02 * r.abs(), "{c} vs {r}");
    }
    // out of range
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.set_integer(vr("threads"), 0), Status::Error);
    assert_eq!(i.set_integer(vr("threads"), 65), Status::Error);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.get_integer(vr("threads")), Ok(1));
}

#[test]
fn wrong_state_and_unknown_reference_are_errors_with_messages() {
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.do_step(0.0, 1e-3), Status::Error);
    assert_eq!(i.set_real(9999, 1.0), Status::Error);
    let logs = i.take_logs();
    assert!(
        logs[0].text.contains("fmi2DoStep") && logs[0].text.contains("Instantiated"),
        "{logs:?}"
    );
    assert!(logs[1].text.contains("9999"), "{logs:?}");
    let mut i = initialized();
    assert_eq!(i.set_real(vr("mu"), 0.3), Status::Error);
    let logs = i.take_logs();
    assert!(
        logs[0].text.contains("mu") && logs[0].text.contains("fixed parameter"),
        "{logs:?}"
    );
}

#[test]
fn nan_input_is_rejected_and_value_kept() {
    let mut i = initialized();
    assert_eq!(i.set_real(vr("cx"), 0.01), Status::Ok);
    assert_eq!(i.set_real(vr("cx"), f64::NAN), Status::Error);
    assert_eq!(i.get_real(vr("cx")), Ok(0.01));
    let logs = i.take_logs();
    assert!(
        logs[0].text.contains("cx") && logs[0].text.contains("finite"),
        "{logs:?}"
    );
    assert_eq!(i.set_real(vr("FN"), -1.0), Status::Warning);
    assert_eq!(i.do_step(0.0, 1e-4), Status::Ok);
    assert_eq!(i.get_real(vr("Fx")), Ok(0.0));
}

#[test]
fn preset_and_model_conflict_is_reported_at_initialization() {
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.set_string(vr("model"), "fastsim"), Status::Ok);
    assert_eq!(i.set_string(vr("preset"), "dry"), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Error);
    let logs = i.take_logs();
    assert!(
        logs[0].text.contains("fastsim") && logs[0].text.contains("dry"),
        "{logs:?}"
    );
    // still in initialization mode (a corrected parameter and another exit may follow),
    // but no FMU state is handed out until an exit succeeds or fmi2Reset
    assert_eq!(i.phase(), Phase::Initialization);
    assert!(i.try_get_state().is_err());
    assert_eq!(i.reset(), Status::Ok);
    assert!(i.try_get_state().is_ok());
}

#[test]
fn parameters_read_back_from_the_preset_unless_set() {
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.set_string(vr("preset"), "dry"), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    let dry = Config::preset("dry").unwrap();
    assert_eq!(i.get_real(vr("tau_c1_0_GPa")), Ok(dry.params.get(P::Tc10)));
    assert_eq!(i.set_real(vr("tau_c1_0_GPa"), 0.4), Status::Ok);
    assert_eq!(i.get_real(vr("tau_c1_0_GPa")), Ok(0.4));
    assert_eq!(i.set_boolean(vr("effect_transient"), false), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Ok);
    let c = i.model().unwrap().config();
    assert_eq!(c.params.get(P::Tc10), 0.4);
    assert!(!c.effects.has(Effect::Transient));
    assert_eq!(c.params.get(P::Tc20), dry.params.get(P::Tc20));
}

#[test]
fn curvature_geometry_gives_hertz_semi_axes() {
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.set_integer(vr("geometry"), 2), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Ok);
    let a = i.get_real(vr("a")).unwrap();
    let b = i.get_real(vr("b")).unwrap();
    let expect = creep_core::engine::patch_for(i.model().unwrap().config(), 110e3).unwrap();
    assert!(matches!(
        i.model().unwrap().config().geometry,
        Geometry::Curvatures { .. }
    ));
    assert_eq!((a, b), (expect.a, expect.b));
    assert!(
        a > 1e-3 && a < 2e-2 && b > 1e-3 && b < 2e-2,
        "a = {a}, b = {b}"
    );
}
