//! The instance's unit tests: threads and state restore, call rules and messages, parameters read back, geometry.

use super::*;
use crate::settings::DEFAULT_REL_TOL;
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

/// The parameter `temperature_solve`: it reads back as set (0: the configuration's, the predictor-corrector),
/// its predictor-corrector agrees with the exact solve within 0.1 % without being bit-equal,
/// a restored state keeps the instance's setting and repeats its step, and codes outside
/// [0, 2] are refused.
#[test]
fn temperature_solve_is_a_setting_of_the_instance() {
    let run = |code: i32| {
        let mut i = Instance::new("t", None, false);
        for (n, x) in [("nx", 20), ("ny", 3), ("temperature_solve", code)] {
            assert_eq!(i.set_integer(vr(n), x), Status::Ok);
        }
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok);
        assert_eq!(
            i.get_integer(vr("temperature_solve")),
            Ok(if code == 0 { 2 } else { code })
        );
        let mut fx = Vec::new();
        let mut saved = None;
        for k in 0..20 {
            assert_eq!(i.set_real(vr("cx"), 0.002 + 0.002 * k as f64), Status::Ok);
            assert_eq!(i.do_step(k as f64 * 1e-4, 1e-4), Status::Ok);
            fx.push(i.get_real(vr("Fx")).expect("Fx"));
            if k == 10 {
                saved = Some(i.get_state());
            }
        }
        assert_eq!(i.set_state(saved.as_ref().expect("state")), Status::Ok);
        assert_eq!(
            i.get_integer(vr("temperature_solve")),
            Ok(if code == 0 { 2 } else { code })
        );
        assert_eq!(i.set_real(vr("cx"), 0.002 + 0.002 * 11.0), Status::Ok);
        assert_eq!(i.do_step(11e-4, 1e-4), Status::Ok);
        fx.push(i.get_real(vr("Fx")).expect("Fx"));
        fx
    };
    let (unset, exact, pc) = (run(0), run(1), run(2));
    assert_eq!(unset, pc);
    assert_eq!(pc[11], pc[20], "a restored state repeats its step");
    assert_ne!(pc[..20], exact[..20]);
    for (c, r) in pc.iter().zip(&exact) {
        assert!((c - r).abs() <= 1e-3 * r.abs(), "{c} vs {r}");
    }
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.set_integer(vr("temperature_solve"), 3), Status::Error);
    assert_eq!(i.set_integer(vr("temperature_solve"), -1), Status::Error);
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

/// An instance with rel_tol, the speed v and the integer settings given, initialized;
/// returns it with its exit_initialization status and logs.
fn with_tol(rel_tol: f64, v: f64, ints: &[(&str, i32)]) -> (Instance, Status, Vec<LogMsg>) {
    let mut i = Instance::new("t", None, true);
    assert_eq!(i.set_real(vr("rel_tol"), rel_tol), Status::Ok);
    assert_eq!(i.set_real(vr("v"), v), Status::Ok);
    for (n, x) in ints {
        assert_eq!(i.set_integer(vr(n), *x), Status::Ok);
    }
    assert_eq!(i.enter_initialization(), Status::Ok);
    let st = i.exit_initialization();
    let logs = i.take_logs();
    (i, st, logs)
}

/// The tolerance filter of the FMU's default configuration (table4.1, unchanged: its own rows).
fn table41() -> creep_core::tolerance::Filter {
    creep_core::tolerance::Filter {
        preset: Some("table4.1"),
        ..Default::default()
    }
}

#[test]
fn rel_tol_runs_on_the_grid_and_scheme_the_table_gives_and_logs_them() {
    use creep_core::tolerance;
    for (tol, v) in [(0.05, 5.0), (0.02, 30.0), (0.01, 5.0), (0.01, 20.0)] {
        let c = tolerance::choose(tol, v, None, table41()).expect("choice");
        assert!(c.met, "{tol} at {v}: the test wants a met tolerance");
        let (mut i, st, logs) = with_tol(tol, v, &[]);
        assert_eq!(st, Status::Ok, "{logs:?}");
        assert_eq!(i.get_integer(vr("nx")), Ok(c.nx as i32));
        assert_eq!(i.get_integer(vr("ny")), Ok(c.ny as i32));
        let code = crate::settings::scheme_code(c.scheme);
        assert_eq!(i.get_integer(vr("scheme")), Ok(code));
        assert_eq!(i.get_real(vr("rel_tol")), Ok(tol));
        let m = i.model().expect("model");
        assert_eq!(m.config().grid.nx, c.nx);
        let grid = format!("grid {}x{}", c.nx, c.ny);
        assert!(
            logs.iter().any(|l| l.category == "logEvents"
                && l.text.contains(&grid)
                && l.text.contains(&format!("{:.2} %", c.fx_err_pct))),
            "{logs:?}"
        );
        // the chosen scheme is the one that steps: the same Fx as the explicit settings
        let mut j = Instance::new("t", None, false);
        assert_eq!(j.set_real(vr("v"), v), Status::Ok);
        for (n, x) in [("nx", c.nx as i32), ("ny", c.ny as i32), ("scheme", code)] {
            assert_eq!(j.set_integer(vr(n), x), Status::Ok);
        }
        assert_eq!(j.enter_initialization(), Status::Ok);
        assert_eq!(j.exit_initialization(), Status::Ok);
        for inst in [&mut i, &mut j] {
            assert_eq!(inst.set_real(vr("cx"), 0.05), Status::Ok);
            assert_eq!(inst.do_step(0.0, 2.5e-4), Status::Ok);
        }
        assert_eq!(i.get_real(vr("Fx")), j.get_real(vr("Fx")));
    }
}

#[test]
fn rel_tol_off_and_explicit_settings_keep_the_grid() {
    let preset = default_grid();
    // off: the preset's grid and ECF's default scheme, the higher-order rules
    let (mut i, st, _) = with_tol(0.0, 5.0, &[]);
    assert_eq!(st, Status::Ok);
    assert_eq!(i.get_integer(vr("nx")), Ok(preset.0));
    assert_eq!(i.get_integer(vr("scheme")), Ok(2));
    // explicit nx, ny override a loose tolerance that would choose another grid
    let loose = creep_core::tolerance::choose(0.5, 5.0, None, table41()).expect("c");
    assert_ne!((loose.nx, loose.ny), (80, 7));
    let (mut i, st, logs) = with_tol(0.5, 5.0, &[("nx", 80), ("ny", 7)]);
    assert_eq!(st, Status::Ok, "{logs:?}");
    assert_eq!(i.get_integer(vr("nx")), Ok(80));
    assert_eq!(i.get_integer(vr("ny")), Ok(7));
    // an explicit grid the table does not have: used, with a warning
    let (mut i, st, logs) = with_tol(0.01, 5.0, &[("nx", 30), ("ny", 7)]);
    assert_eq!(st, Status::Warning, "{logs:?}");
    assert_eq!(i.get_integer(vr("nx")), Ok(30));
    assert!(logs.iter().any(|l| l.text.contains("nx = 30")), "{logs:?}");
}

fn default_grid() -> (i32, i32) {
    let g = vars::default_config().grid;
    (g.nx as i32, g.ny as i32)
}

#[test]
fn a_rel_tol_no_grid_meets_warns_with_the_error_reached() {
    let (mut i, st, logs) = with_tol(1e-5, 20.0, &[]);
    assert_eq!(st, Status::Warning, "{logs:?}");
    let c = creep_core::tolerance::choose(1e-5, 20.0, None, table41()).expect("c");
    assert_eq!(i.get_integer(vr("nx")), Ok(c.nx as i32));
    assert!(
        logs.iter()
            .any(|l| l.category == "logStatusWarning" && l.text.contains("NOT met")),
        "{logs:?}"
    );
}

#[test]
fn rel_tol_follows_v_set_during_initialization_not_after() {
    use creep_core::tolerance::choose;
    // a tolerance at which the table chooses two grids at 5 and 20 m/s
    let grid = |c: creep_core::tolerance::Choice| (c.nx as i32, c.ny as i32);
    let (tol, at5, at20) = [0.01, 0.005, 0.02, 0.002]
        .into_iter()
        .map(|t| {
            let at = |v| grid(choose(t, v, None, table41()).expect("c"));
            (t, at(5.0), at(20.0))
        })
        .find(|(_, a, b)| a != b)
        .expect("the test needs two grids");
    let read = |i: &mut Instance| (i.get_integer(vr("nx")), i.get_integer(vr("ny")));
    let mut i = Instance::new("t", None, false);
    assert_eq!(i.set_real(vr("rel_tol"), tol), Status::Ok);
    assert_eq!(i.set_real(vr("v"), 5.0), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(read(&mut i), (Ok(at5.0), Ok(at5.1)));
    assert_eq!(i.set_real(vr("v"), 20.0), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Ok);
    assert_eq!(read(&mut i), (Ok(at20.0), Ok(at20.1)));
    assert_eq!(i.set_real(vr("v"), 5.0), Status::Ok);
    assert_eq!(i.do_step(0.0, 1e-3), Status::Ok);
    assert_eq!(read(&mut i), (Ok(at20.0), Ok(at20.1)));
}

#[test]
fn bad_rel_tol_is_refused_with_a_message_and_the_value_kept() {
    for bad in [-0.01, f64::NAN, f64::INFINITY, 1.5] {
        let mut i = Instance::new("t", None, false);
        assert_eq!(i.set_real(vr("rel_tol"), bad), Status::Error, "{bad}");
        let logs = i.take_logs();
        assert!(
            logs.iter().any(|l| l.text.contains("rel_tol")),
            "{bad}: {logs:?}"
        );
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.get_real(vr("rel_tol")), Ok(DEFAULT_REL_TOL));
    }
    // fastsim: ignored with a warning
    let mut i = Instance::new("t", None, true);
    assert_eq!(i.set_real(vr("rel_tol"), 0.01), Status::Ok);
    assert_eq!(i.set_string(vr("preset"), "fastsim"), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Warning);
    assert!(i.take_logs().iter().any(|l| l.text.contains("ECF model")));
    // its start value is no request: no warning
    let mut i = Instance::new("t", None, true);
    assert_eq!(i.set_string(vr("preset"), "fastsim"), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Ok, "{:?}", i.take_logs());
}

#[test]
fn the_default_rel_tol_runs_in_real_time_at_20_m_s_and_an_explicit_grid_turns_it_off() {
    use creep_core::tolerance::{self, Filter};
    // The FMU's choice at 20 m/s: it does not know the step at initialization, so it takes
    // the grid that meets rel_tol at the lowest cost over the speed's steps; the table's cost
    // of that grid at 0.25 ms steps is below real time for each preset (dry: 14x3 cells-ho,
    // docs/fmu.md "Grid and scheme for a tolerance"; history: docs/history.md)
    let cost_at_quarter_ms = |c: &tolerance::Choice, preset: Option<&'static str>| {
        let only = Filter {
            preset,
            nx: Some(c.nx),
            ny: Some(c.ny),
            scheme: Some(c.scheme),
            steady: false,
        };
        tolerance::choose(DEFAULT_REL_TOL, 20.0, Some(2.5e-4), only)
            .expect("the chosen grid's row")
            .cost
    };
    for p in ["table4.1", "dry", "wet"] {
        let f = Filter {
            preset: Some(p),
            ..Filter::default()
        };
        let c = tolerance::choose(DEFAULT_REL_TOL, 20.0, None, f).expect("choice");
        assert!(c.met, "{p}: {c:?}");
        let cost = cost_at_quarter_ms(&c, Some(p));
        assert!(cost < 1.0, "{p}: {c:?} costs {cost} at 0.25 ms");
        // and the FMU with nothing set but the preset and v runs on that grid
        let mut i = Instance::new("t", None, true);
        assert_eq!(i.set_string(vr("preset"), p), Status::Ok);
        assert_eq!(i.set_real(vr("v"), 20.0), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        let st = i.exit_initialization();
        let logs = i.take_logs();
        assert_eq!(st, Status::Ok, "{p}: {logs:?}");
        assert_eq!(i.get_integer(vr("nx")), Ok(c.nx as i32), "{p}");
        assert_eq!(i.get_integer(vr("ny")), Ok(c.ny as i32), "{p}");
        let code = crate::settings::scheme_code(c.scheme);
        assert_eq!(i.get_integer(vr("scheme")), Ok(code), "{p}");
        assert!(
            logs.iter()
                .any(|l| l.text.contains(&format!("worst of {p}, steps"))),
            "{p}: {logs:?}"
        );
    }
    // a changed parameter: the worst over every preset, also in real time at 0.25 ms
    let all = tolerance::choose(DEFAULT_REL_TOL, 20.0, None, Filter::default()).expect("c");
    let cost = cost_at_quarter_ms(&all, None);
    assert!(all.met && cost < 1.0, "{all:?} costs {cost} at 0.25 ms");
    let mut i = Instance::new("t", None, true);
    assert_eq!(i.set_real(vr("v"), 20.0), Status::Ok);
    assert_eq!(i.set_real(vr("tau_c2_0_GPa"), 1.2), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    let _ = i.exit_initialization();
    assert_eq!(i.get_integer(vr("nx")), Ok(all.nx as i32));
    assert!(i
        .take_logs()
        .iter()
        .any(|l| l.text.contains("worst of dry, table4.1, wet")));
    // both nx and ny given: the default does not apply (no choice, no warning, the scheme kept)
    for (nx, ny) in [(30, 7), (20, 5)] {
        let mut i = Instance::new("t", None, true);
        assert_eq!(i.set_real(vr("v"), 20.0), Status::Ok);
        assert_eq!(i.set_integer(vr("nx"), nx), Status::Ok);
        assert_eq!(i.set_integer(vr("ny"), ny), Status::Ok);
        assert_eq!(i.enter_initialization(), Status::Ok);
        assert_eq!(i.exit_initialization(), Status::Ok, "{:?}", i.take_logs());
        assert_eq!(i.get_integer(vr("nx")), Ok(nx));
        assert_eq!(i.get_integer(vr("scheme")), Ok(2));
        assert_eq!(i.get_real(vr("rel_tol")), Ok(DEFAULT_REL_TOL));
        assert!(i.take_logs().iter().all(|l| !l.text.contains("rel_tol")));
    }
    // one of them given: the default chooses among the table's rows with it
    let f = Filter {
        preset: Some("table4.1"),
        nx: Some(40),
        ..Filter::default()
    };
    let c = tolerance::choose(DEFAULT_REL_TOL, 20.0, None, f).expect("choice");
    let (mut i, _, _) = with_tol(DEFAULT_REL_TOL, 20.0, &[("nx", 40)]);
    assert_eq!(i.get_integer(vr("ny")), Ok(c.ny as i32));
}

/// An instance reading the configuration file `file`, with the integer settings `ints`, at
/// v = 20 m/s, initialized (logs kept).
fn initialized_from(file: &std::path::Path, ints: &[(&str, i32)]) -> Instance {
    let mut i = Instance::new("t", None, true);
    assert_eq!(
        i.set_string(vr("config_file"), file.to_str().unwrap()),
        Status::Ok
    );
    for (n, x) in ints {
        assert_eq!(i.set_integer(vr(n), *x), Status::Ok, "{n} = {x}");
    }
    assert_eq!(i.set_real(vr("v"), 20.0), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.exit_initialization(), Status::Ok, "{:?}", i.take_logs());
    i
}

/// The start value of rel_tol is off when the configuration file gives a `grid` (even after a
/// state restore, where the configuration was not resolved from the file) and chooses the
/// table's grid when it does not.
#[test]
fn a_configuration_file_with_a_grid_turns_the_default_rel_tol_off() {
    let dir = std::env::temp_dir().join(format!("ecf-file-grid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let with = dir.join("with.json");
    let without = dir.join("without.json");
    std::fs::write(
        &with,
        r#"{"preset": "table4.1", "grid": {"nx": 30, "ny": 7}}"#,
    )
    .expect("w");
    std::fs::write(&without, r#"{"preset": "table4.1"}"#).expect("w");
    let c = creep_core::tolerance::choose(DEFAULT_REL_TOL, 20.0, None, table41()).expect("c");
    assert_ne!(
        (c.nx, c.ny),
        (30, 7),
        "the test needs the table's grid to differ"
    );
    let init = |file: &std::path::Path| {
        let mut i = initialized_from(file, &[]);
        let grid = (i.get_integer(vr("nx")), i.get_integer(vr("ny")));
        let chose = i.take_logs().iter().any(|l| l.text.contains("rel_tol"));
        (i, grid, chose)
    };
    let (mut i, grid, chose) = init(&with);
    assert_eq!((grid, chose), ((Ok(30), Ok(7)), false));
    let (_, grid, chose) = init(&without);
    assert_eq!((grid, chose), ((Ok(c.nx as i32), Ok(c.ny as i32)), true));
    // a state taken in initialization mode, restored: its configuration comes with it, not
    // from the file, and the default rel_tol stays off (no choice, no log of one)
    let mut j = Instance::new("t", None, true);
    assert_eq!(
        j.set_string(vr("config_file"), with.to_str().unwrap()),
        Status::Ok
    );
    assert_eq!(j.set_real(vr("v"), 20.0), Status::Ok);
    assert_eq!(j.enter_initialization(), Status::Ok);
    assert_eq!(j.get_integer(vr("nx")), Ok(30));
    let s = j.get_state();
    assert_eq!(i.set_state(&s), Status::Ok);
    let _ = i.take_logs();
    assert_eq!(i.exit_initialization(), Status::Ok, "{:?}", i.take_logs());
    let logs = i.take_logs();
    assert!(logs.iter().all(|l| !l.text.contains("rel_tol")), "{logs:?}");
    assert_eq!(
        (i.get_integer(vr("nx")), i.get_integer(vr("ny"))),
        (Ok(30), Ok(7))
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A configuration file's `scheme` is the one the model runs while the parameter `scheme` is
/// at its start value (which then reads back the file's), and travels with a serialized state
/// into a fresh instance; a parameter set to another scheme overrides it. A file that names
/// no scheme runs ECF's default, the higher-order rules (2).
#[test]
fn a_configuration_files_scheme_runs_unless_the_parameter_sets_another() {
    let dir = std::env::temp_dir().join(format!("ecf-file-scheme-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let (ho, plain) = (dir.join("ho.json"), dir.join("plain.json"));
    let cells_file = dir.join("cells.json");
    let grid = r#""preset": "dry", "grid": {"nx": 20, "ny": 5}"#;
    std::fs::write(&ho, format!(r#"{{{grid}, "scheme": "cells-ho"}}"#)).expect("w");
    std::fs::write(&plain, format!("{{{grid}}}")).expect("w");
    std::fs::write(&cells_file, format!(r#"{{{grid}, "scheme": "cells"}}"#)).expect("w");
    let run = |file: &std::path::Path, scheme: Option<i32>| {
        let scheme: Vec<(&str, i32)> = scheme.map(|s| ("scheme", s)).into_iter().collect();
        let mut i = initialized_from(file, &scheme);
        let code = i.get_integer(vr("scheme"));
        let mut fx = Vec::new();
        let mut saved = None;
        for k in 0..10 {
            assert_eq!(i.set_real(vr("cx"), 0.002 + 0.004 * k as f64), Status::Ok);
            assert_eq!(i.do_step(k as f64 * 1e-4, 1e-4), Status::Ok);
            fx.push(i.get_real(vr("Fx")).expect("Fx"));
            if k == 4 {
                saved = Some(crate::state::serialize(&i.get_state()));
            }
        }
        (code, fx, saved.expect("state"))
    };
    let (code, from_file, bytes) = run(&ho, None);
    assert_eq!(code, Ok(2));
    let (code, set, _) = run(&plain, Some(2));
    assert_eq!((code, &set), (Ok(2), &from_file));
    let (code, default, _) = run(&plain, None);
    assert_eq!((code, &default), (Ok(2), &from_file));
    let (code, cells, _) = run(&cells_file, None);
    assert_eq!(code, Ok(3));
    assert_ne!(cells, from_file);
    let (code, set, _) = run(&plain, Some(3));
    assert_eq!((code, &set), (Ok(3), &cells));
    let (code, continuous, _) = run(&ho, Some(1));
    assert_eq!(code, Ok(1));
    // the initialization's log names the scheme that runs, not only the file's
    let logs = initialized_from(&ho, &[("scheme", 1)]).take_logs();
    assert!(
        logs.iter()
            .any(|l| l.text.contains("\"scheme\":\"cells-ho\"")
                && l.text.contains("running scheme continuous")),
        "{logs:?}"
    );
    assert_ne!(continuous, from_file);
    // a fresh instance, no file: the deserialized state continues in the file's scheme
    let mut i = Instance::new("t", None, false);
    let snap = crate::state::deserialize(&bytes).expect("deserialize");
    assert_eq!(i.set_state(&snap), Status::Ok);
    assert_eq!(i.get_integer(vr("scheme")), Ok(2));
    for (k, fx) in from_file.iter().enumerate().skip(5) {
        assert_eq!(i.set_real(vr("cx"), 0.002 + 0.004 * k as f64), Status::Ok);
        assert_eq!(i.do_step(k as f64 * 1e-4, 1e-4), Status::Ok);
        assert_eq!(i.get_real(vr("Fx")), Ok(*fx), "step {k}");
    }
    // without a grid in the file the start value of rel_tol chooses the grid among the table's
    // rows of the file's scheme, as for an explicit scheme = 1
    let cont = dir.join("continuous.json");
    std::fs::write(&cont, r#"{"preset": "dry", "scheme": "continuous"}"#).expect("w");
    let mut i = initialized_from(&cont, &[]);
    assert_eq!(i.get_integer(vr("scheme")), Ok(1));
    let logs = i.take_logs();
    assert!(
        logs.iter()
            .any(|l| l.text.contains("rel_tol") && l.text.contains("continuous")),
        "{logs:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
