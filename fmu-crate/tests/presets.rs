//! Presets against start values: an importer that writes every start value (in declaration order, in reverse, before or after the preset) gets exactly the preset's behaviour; single overrides still apply; a model that contradicts the preset gets a clear message; a configuration's data column comes from an auxiliary input.

mod common;
use common::*;
use creep_core::{Config, Inputs, Model};
use ecf_contact::ffi::*;
use ecf_contact::vars::{self, Causality, Start};
use std::ffi::CString;

fn write_starts(f: &Fmu, reverse: bool) {
    let mut t: Vec<vars::Var> = vars::table()
        .into_iter()
        .filter(|v| v.causality != Causality::Output)
        .collect();
    if reverse {
        t.reverse();
    }
    for v in t {
        let st = match &v.start {
            Start::Real(x) => unsafe { fmi2SetReal(f.c, &v.vr, 1, x) },
            Start::Integer(x) => unsafe { fmi2SetInteger(f.c, &v.vr, 1, x) },
            Start::Boolean(x) => {
                let b = *x as i32;
                unsafe { fmi2SetBoolean(f.c, &v.vr, 1, &b) }
            }
            Start::String(x) => {
                let s = CString::new(x.as_str()).unwrap();
                let p = s.as_ptr();
                unsafe { fmi2SetString(f.c, &v.vr, 1, &p) }
            }
            Start::None => OK,
        };
        assert_eq!(st, OK, "start value of {}", v.name);
    }
}

const INPUTS: Inputs = Inputs {
    cx: 0.05,
    cy: 0.002,
    spin: 0.1,
    v: 20.0,
    fn_n: 110e3,
    t_bulk: 20.0,
};

fn fmu_outputs(f: &mut Fmu) -> [f64; N_OUTPUTS] {
    f.inputs(INPUTS.cx, INPUTS.cy, INPUTS.spin, INPUTS.v, INPUTS.fn_n);
    assert_eq!(f.init(), OK, "{:?}", f.messages());
    f.outputs()
}

#[test]
fn start_values_in_any_order_give_exactly_the_preset() {
    for (preset, _) in creep_core::config::PRESETS {
        let mut cfg = Config::preset(preset).unwrap();
        // the grid the start value of rel_tol chooses
        cfg.grid = default_grid(&cfg, INPUTS.v);
        let mut model = Model::new(&cfg).unwrap();
        // and the scheme it chooses (the higher-order rules change the steady state too)
        model.set_scheme(default_scheme(&cfg, INPUTS.v));
        let want = model.steady(&INPUTS).unwrap().to_array();
        for order in 0..3 {
            let mut f = Fmu::new(&format!("starts-{preset}-{order}"));
            match order {
                0 => write_starts(&f, false),
                1 => write_starts(&f, true),
                _ => {
                    // the preset first, then every start value but the preset's own
                    assert_eq!(f.set_string("preset", preset), OK);
                    write_starts(&f, false);
                }
            }
            assert_eq!(f.set_string("preset", preset), OK);
            let got = fmu_outputs(&mut f);
            assert_eq!(got, want, "{preset}, order {order}");
            // no warnings about parameters set but ignored
            assert!(
                !f.messages().iter().any(|(l, _)| *l <= log::Level::Warn),
                "{preset}: {:?}",
                f.messages()
            );
        }
    }
}

#[test]
fn single_overrides_apply_beside_start_values() {
    let mut cfg = Config::preset("wet").unwrap();
    cfg.params.set(creep_core::params::P::Tc20, 0.5).unwrap();
    cfg.effects.remove(creep_core::effects::Effect::Temperature);
    cfg.grid = creep_core::Grid { nx: 30, ny: 9 };
    let want = Model::new(&cfg)
        .unwrap()
        .steady(&INPUTS)
        .unwrap()
        .to_array();
    let mut f = Fmu::new("override");
    write_starts(&f, true);
    assert_eq!(f.set_string("preset", "wet"), OK);
    assert_eq!(f.set_real("tau_c2_0_GPa", 0.5), OK);
    assert_eq!(f.set_bool("effect_temperature", false), OK);
    assert_eq!(f.set_int("nx", 30), OK);
    assert_eq!(f.set_int("ny", 9), OK);
    assert_eq!(fmu_outputs(&mut f), want);
}

#[test]
fn model_contradicting_the_preset_is_a_clear_error_and_empty_model_follows_it() {
    let mut f = Fmu::new("fastsim-ecf");
    assert_eq!(f.set_string("model", "ecf"), OK);
    assert_eq!(f.set_string("preset", "fastsim"), OK);
    f.inputs(0.01, 0.0, 0.0, 20.0, 110e3);
    assert_eq!(f.init(), ERROR);
    assert!(
        f.messages().iter().any(|(_, m)| m
            .contains("model = 'ecf' but preset 'fastsim' is a 'fastsim' configuration")
            && m.contains("leave model empty")
            && m.contains("table4.1")),
        "{:?}",
        f.messages()
    );
    let mut f = Fmu::new("fastsim-empty");
    assert_eq!(f.set_string("model", ""), OK);
    assert_eq!(f.set_string("preset", "fastsim"), OK);
    f.inputs(0.01, 0.0, 0.0, 20.0, 110e3);
    assert_eq!(f.init(), OK);
    assert_eq!(f.get_string("model"), "fastsim");
}

#[test]
fn a_data_column_comes_from_an_auxiliary_input_or_a_constant() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/measurements/dry-humid.json"
    );
    let mut cfg = Config::from_file(std::path::Path::new(path)).unwrap();
    creep_core::Modifier::set_param(&mut cfg.modifiers[0], 0, 0.3);
    let want = |h: f64| {
        let mut m = Model::new(&cfg).unwrap();
        m.set_extra(&[("humidity".to_string(), h)]).unwrap();
        m.steady(&INPUTS).unwrap().to_array()
    };
    let dir = std::env::temp_dir().join(format!("ecf-aux-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("humid.json");
    std::fs::write(&file, cfg.to_json().to_string()).unwrap();
    // unmapped: the message names the column and the parameter
    let mut f = Fmu::new("aux-unmapped");
    assert_eq!(f.set_string("config_file", file.to_str().unwrap()), OK);
    f.inputs(INPUTS.cx, INPUTS.cy, INPUTS.spin, INPUTS.v, INPUTS.fn_n);
    assert_eq!(f.init(), ERROR);
    assert!(
        f.messages()
            .iter()
            .any(|(_, m)| m.contains("'humidity'") && m.contains("columns")),
        "{:?}",
        f.messages()
    );
    assert_eq!(f.set_string("columns", "humidity=aux5"), ERROR);
    assert_eq!(f.set_string("columns", "humidity"), ERROR);
    // from aux2, then changed in initialization mode
    let mut f = Fmu::new("aux-input");
    assert_eq!(f.set_string("config_file", file.to_str().unwrap()), OK);
    assert_eq!(f.set_string("columns", "salt=0.1, humidity=aux2"), OK);
    assert_eq!(f.set_real("aux2", 30.0), OK);
    assert_eq!(f.set_real("aux2", f64::NAN), ERROR);
    let o30 = fmu_outputs(&mut f);
    assert_eq!(o30, want(30.0));
    // in a step: the new humidity acts (quasi-steady step = steady state of the inputs)
    let mut g = Fmu::new("aux-const");
    assert_eq!(g.set_string("config_file", file.to_str().unwrap()), OK);
    assert_eq!(g.set_string("columns", "humidity=70"), OK);
    assert_eq!(g.set_bool("effect_transient", false), OK);
    assert_eq!(fmu_outputs(&mut g), want(70.0));
    assert_ne!(want(70.0), want(30.0));
    let _ = std::fs::remove_dir_all(&dir);
}
