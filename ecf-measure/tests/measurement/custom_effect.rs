//! An effect written in Rust (custom catalogue) acts like the equivalent formula effect and is fitted like any parameter.
use creep_core::{Config, Inputs, Model};
use ecf_measure::fit::{fit_params, FreeParam};

const FORMULA: &str = r#"{"preset": "dry", "grid": {"nx": 20, "ny": 7},
    "formula_effects": [{"name": "humid", "target": "tau_c2", "factor": "1 - k * (humidity - 50) / 50",
                         "params": {"k": {"value": 0.3, "min": -1, "max": 1}}}]}"#;
const CUSTOM: &str = r#"{"preset": "dry", "grid": {"nx": 20, "ny": 7},
    "custom_effects": [{"name": "humidity_softening", "params": {"k": 0.3, "h0_pct": 50}}]}"#;

#[test]
fn custom_effect_equals_the_formula_effect() {
    let f = Config::from_json_str(FORMULA, "formula").unwrap();
    let c = Config::from_json_str(CUSTOM, "custom").unwrap();
    let plain = Config::from_json_str(r#"{"preset": "dry", "grid": {"nx": 20, "ny": 7}}"#, "plain")
        .unwrap();
    for h in [30.0, 70.0] {
        let col = [("humidity".to_string(), h)];
        let mut mf = Model::new(&f).unwrap();
        let mut mc = Model::new(&c).unwrap();
        let mut mp = Model::new(&plain).unwrap();
        mf.set_extra(&col).unwrap();
        mc.set_extra(&col).unwrap();
        for cx in [0.002, 0.03, 0.2] {
            let i = Inputs {
                cx,
                v: 10.0,
                fn_n: 110e3,
                ..Inputs::default()
            };
            let (a, b, p) = (
                mf.steady(&i).unwrap().f,
                mc.steady(&i).unwrap().f,
                mp.steady(&i).unwrap().f,
            );
            assert!(
                (a - b).abs() < 1e-12,
                "h = {h}, cx = {cx}: formula {a} vs custom {b}"
            );
            if cx > 0.01 {
                // drier air (30 %) strengthens the layer, humid air (70 %) weakens it
                assert!(
                    if h < 50.0 { b > p } else { b < p },
                    "h = {h}: {b} vs plain {p}"
                );
            }
        }
    }
    // a missing column is an error naming it; a bad parameter is refused with its range
    let mut m = Model::new(&c).unwrap();
    let e = m.steady(&Inputs::default()).unwrap_err().to_string();
    assert!(e.contains("humidity"), "{e}");
    let e = Config::from_json_str(&CUSTOM.replace("0.3", "7"), "x")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("humidity_softening.k") && e.contains("[-1, 1]"),
        "{e}"
    );
    let e = Config::from_json_str(&CUSTOM.replace("humidity_softening", "rain"), "x")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("rain") && e.contains("humidity_softening"),
        "{e}"
    );
    // round trip through JSON
    let back = Config::from_json_str(&c.to_json().to_string(), "back").unwrap();
    assert_eq!(back, c);
}

#[test]
fn custom_effect_parameter_is_fitted() {
    let truth = Config::from_json_str(CUSTOM, "truth").unwrap();
    let mut csv = String::from("cx,f,series,v_mps,fn_kN,humidity\n");
    for h in [30.0, 50.0, 70.0] {
        let mut m = Model::new(&truth).unwrap();
        m.set_extra(&[("humidity".to_string(), h)]).unwrap();
        for i in 0..10 {
            let cx = 0.002 * 1.6f64.powi(i);
            let f = m
                .steady(&Inputs {
                    cx,
                    v: 10.0,
                    fn_n: 110e3,
                    ..Inputs::default()
                })
                .unwrap()
                .f;
            csv.push_str(&format!("{cx},{f},h{h},10,110,{h}\n"));
        }
    }
    let data =
        ecf_measure::measure::Dataset::from_csv_str(&csv, "h.csv", &Default::default()).unwrap();
    let start =
        Config::from_json_str(&CUSTOM.replace("\"k\": 0.3", "\"k\": 0.0"), "start").unwrap();
    let free = [FreeParam::resolve(&start, "humidity_softening.k").unwrap()];
    let r = fit_params(&start, &data, &free, 2, &|_| {}).unwrap();
    assert!(
        (r.params[0].value - 0.3).abs() < 1e-3,
        "k = {}",
        r.params[0].value
    );
    assert!(r.cv_rmse_pct_after < 0.05 * r.cv_rmse_pct_before);
}
