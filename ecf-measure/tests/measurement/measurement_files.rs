//! Reading measurement files: units and spellings in headers, delimiters, creepage units,
//! missing quantities and the messages of bad files (docs/measurements.md, "Measurement files").
use creep_core::Config;
use ecf_measure::measure::{CreepageUnit, Dataset, Defaults};

fn read(text: &str) -> Result<Dataset, String> {
    Dataset::from_csv_str(text, "m.csv", &Defaults::default()).map_err(|e| e.to_string())
}

fn read_err(text: &str) -> String {
    read(text).expect_err(text)
}

#[test]
fn header_units_and_spellings_are_recognised_and_converted() {
    // the same point written five ways
    let files = [
        "cx,f,v_mps,fn_kN\n0.02,0.3,10,110\n",
        "cx [%],f,v [km/h],FN [kN]\n2,0.3,36,110\n",
        "creepage_pct,f,v_kmh,Fn_N\n2,0.3,36,110000\n",
        "c_x (-),traction,speed (m/s),normal_force [N]\n0.02,0.3,10,110000\n",
        "cx_pct,f,v [m/s],load_kN,T [K]\n2,0.3,10,110,293.15\n",
    ];
    for t in files {
        let d = read(t).unwrap_or_else(|e| panic!("{t:?}: {e}"));
        let r = &d.rows[0];
        assert!((r.cx - 0.02).abs() < 1e-12, "{t:?}: cx {}", r.cx);
        assert!((r.v - 10.0).abs() < 1e-9, "{t:?}: v {}", r.v);
        assert!((r.fn_n - 110e3).abs() < 1e-6, "{t:?}: F_N {}", r.fn_n);
        assert!((r.t_bulk - 20.0).abs() < 1e-9, "{t:?}: T {}", r.t_bulk);
        assert!(d.extra_names.is_empty(), "{t:?}: {:?}", d.extra_names);
    }
    // the mapping says which column became which quantity in what unit
    let d = read("cx [%],f,v [km/h],Fn_N,humidity\n2,0.3,36,110000,40\n").unwrap();
    let m = d.mapping_text();
    assert!(
        m.contains("'v [km/h]'") && m.contains("v_mps") && m.contains("km/h"),
        "{m}"
    );
    assert!(
        m.contains("'Fn_N'") && m.contains("fn_kN") && m.contains("in N"),
        "{m}"
    );
    assert!(m.contains("'humidity'") && m.contains("extra"), "{m}");
    assert_eq!(d.extra_names, vec!["humidity"]);
}

#[test]
fn a_missing_speed_or_load_is_an_error_unless_given() {
    let t = "cx,f\n0.01,0.3\n";
    let e = read_err(t);
    assert!(
        e.contains("data file m.csv") && e.contains("speed") && e.contains("--v-mps"),
        "{e}"
    );
    let e = read_err("cx,f,v_mps\n0.01,0.3,5\n");
    assert!(e.contains("normal force") && e.contains("--fn-kN"), "{e}");
    let given = Defaults {
        v_mps: Some(7.0),
        fn_kn: Some(90.0),
        ..Defaults::default()
    };
    let d = Dataset::from_csv_str(t, "m.csv", &given).unwrap();
    assert_eq!((d.rows[0].v, d.rows[0].fn_n), (7.0, 90e3));
    assert!(d.mapping_text().contains("not in the file: 7 m/s"));
    // a dimensional quantity without a unit, or with a wrong one
    let e = read_err("cx,f,v,fn_kN\n0.01,0.3,5,110\n");
    assert!(
        e.contains("column 'v'") && e.contains("needs a unit"),
        "{e}"
    );
    let e = read_err("cx,f,v [furlongs],fn_kN\n0.01,0.3,5,110\n");
    assert!(e.contains("furlongs") && e.contains("km/h"), "{e}");
    let e = read_err("cx,f,v_mps,v_kmh,fn_kN\n0.01,0.3,5,18,110\n");
    assert!(e.contains("both"), "{e}");
}

#[test]
fn delimiters_and_decimal_comma() {
    let semi = read("cx;f;v_mps;fn_kN\n0,012;0,31;5;110\n").unwrap();
    assert_eq!((semi.rows[0].cx, semi.rows[0].f), (0.012, 0.31));
    assert_eq!(semi.delimiter, ';');
    let tab = read("cx\tf\tv_mps\tfn_kN\n0.012\t0.31\t5\t110\n").unwrap();
    assert_eq!((tab.rows[0].cx, tab.delimiter), (0.012, '\t'));
    // a decimal comma is not taken in a comma-separated file
    let e = read_err("cx,f,v_mps,fn_kN\n0.01,0.3,5,110,7\n");
    assert!(e.contains("line 2") && e.contains("5 fields"), "{e}");
}

#[test]
fn creepage_in_percent_needs_a_unit_and_percent_looking_values_stop() {
    let t = "cx,f,v_mps,fn_kN\n0.5,0.2,5,110\n2,0.3,5,110\n8,0.31,5,110\n";
    let e = read_err(t);
    assert!(
        e.contains("line 4") && e.contains("looks like percent") && e.contains("--cx-unit"),
        "{e}"
    );
    let pct = Defaults {
        cx_unit: Some(CreepageUnit::Percent),
        ..Defaults::default()
    };
    let d = Dataset::from_csv_str(t, "m.csv", &pct).unwrap();
    assert!((d.rows[2].cx - 0.08).abs() < 1e-12);
    // explicitly dimensionless values are taken as written
    let dimless = Defaults {
        cx_unit: Some(CreepageUnit::Dimensionless),
        ..Defaults::default()
    };
    let d = Dataset::from_csv_str("cx,f,v_mps,fn_kN\n0.8,0.3,5,110\n", "m.csv", &dimless).unwrap();
    assert_eq!(d.rows[0].cx, 0.8);
    // header and flag that disagree
    let e = Dataset::from_csv_str("cx [%],f,v_mps,fn_kN\n2,0.3,5,110\n", "m.csv", &dimless)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--cx-unit"), "{e}");
}

#[test]
fn a_header_unit_settles_the_creepage_unit_of_locked_wheel_rows() {
    // braking toward a locked wheel: c_x down to -0.9, dimensionless
    let rows = "-0.9,-0.2,5,110\n-0.6,-0.21,5,110\n0.01,0.3,5,110\n";
    let e = read_err(&format!("cx,f,v_mps,fn_kN\n{rows}"));
    assert!(
        e.contains("looks like percent")
            && e.contains("'cx [-]'")
            && e.contains("'cx [1]'")
            && e.contains("--cx-unit 1"),
        "{e}"
    );
    for h in ["cx [-]", "cx [1]", "cx (-)"] {
        let d = read(&format!("{h},f,v_mps,fn_kN\n{rows}")).unwrap_or_else(|e| panic!("{h}: {e}"));
        assert_eq!(d.rows[0].cx, -0.9, "{h}");
        assert!(d.mapping_text().contains("dimensionless"), "{h}");
    }
    // the same rows in percent under a percent header
    let pct = rows
        .replace("-0.9,", "-90,")
        .replace("-0.6,", "-60,")
        .replace("0.01,", "1,");
    let d = read(&format!("cx [%],f,v_mps,fn_kN\n{pct}")).unwrap();
    assert!((d.rows[0].cx + 0.9).abs() < 1e-12 && (d.rows[2].cx - 0.01).abs() < 1e-12);
}

#[test]
fn messages_name_the_data_file_line_and_cut_long_cells() {
    let bytes = b"cx,f,v_mps,fn_kN\n0.01,0.3,5,110\n0.02,0.3\xe9,5,110\n";
    let e = ecf_measure::measure::utf8_text(bytes, "m.csv")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("data file m.csv") && e.contains("line 3") && e.contains("UTF-8"),
        "{e}"
    );
    let big = "x".repeat(1_000_000);
    let e = read_err(&format!("cx,f,v_mps,fn_kN\n0.01,{big},5,110\n"));
    assert!(
        e.len() < 300 && e.contains("1000000 characters"),
        "{} chars",
        e.len()
    );
    assert!(!e.contains("configuration"), "{e}");
    let e = read_err("cx,f,v_mps,fn_kN\n0.01,0.3,5,110\n# a comment\n0.02,x,5,110\n");
    assert!(e.contains("line 4, column 'f'"), "{e}");
}

#[test]
fn configuration_errors_name_the_file_and_mixed_effect_lists_are_refused() {
    for (text, needle) in [
        ("{\"preset\": \"moist\"}", "moist"),
        ("{\"model\": \"ecf\", \"effects\": [\"heat\"]}", "heat"),
        ("{\"model\": \"ecf\", \"effects\": [\"+heat\"]}", "heat"),
        ("{\"model\": \"ecx\"}", "ecx"),
        (
            "{\"preset\": \"dry\", \"effects\": [\"+temperature\", \"coulomb\"]}",
            "mixes",
        ),
    ] {
        let e = Config::from_json_str(text, "cfg.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("cfg.json") && e.contains(needle), "{text}: {e}");
    }
    // a formula column the data file does not have: both names in the message
    let cfg = Config::from_json_str(
        "{\"preset\": \"dry\", \"formula_effects\": [{\"name\": \"h\", \"target\": \"tau_c2\", \"factor\": \"1 + 0*humidity\"}]}",
        "cfg.json",
    )
    .unwrap();
    let d = read("cx,f,v_mps,fn_kN\n0.01,0.3,5,110\n").unwrap();
    let e = ecf_measure::evaluate::predict(&cfg, &d, 1)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("m.csv") && e.contains("humidity") && e.contains("'h'"),
        "{e}"
    );
}

#[test]
fn parameter_bounds_in_the_configuration() {
    let c = Config::from_json_str(
        "{\"preset\": \"dry\", \"params\": {\"tau_c2_0_GPa\": {\"value\": 0.6, \"min\": 0.2, \"max\": 2}}}",
        "cfg.json",
    )
    .unwrap();
    let id = creep_core::params::P::Tc20;
    assert_eq!(c.params.get(id), 0.6);
    assert_eq!(c.params.bounds(id), (0.2, 2.0));
    let back = Config::from_json_str(&c.to_json().to_string(), "back").unwrap();
    assert_eq!(back.params, c.params);
    let e = Config::from_json_str(
        "{\"preset\": \"dry\", \"params\": {\"tau_c2_0_GPa\": {\"value\": 3, \"min\": 0.2, \"max\": 2}}}",
        "cfg.json",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("cfg.json") && e.contains("tau_c2_0_GPa"), "{e}");
}
