//! The `ecf` binary: CSV output with headers, and clear errors (flag, value, accepted range, exit code != 0) for bad input.
mod common;
use common::ecf;

#[test]
fn curve_prints_csv_with_header_and_units_in_names() {
    let (code, out, err) = ecf(&[
        "curve",
        "--preset",
        "table4.1",
        "--v-mps",
        "20",
        "--fn-kn",
        "110",
        "--a-mm",
        "7.63",
        "--b-mm",
        "7.88",
        "--cx",
        "0.001:0.5:5",
    ]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert!(
        lines[0].starts_with("cx,f,Fx_N,Fy_N,Mz_Nm,T_max_C"),
        "{}",
        lines[0]
    );
    assert_eq!(lines.len(), 6);
    let f: Vec<f64> = lines[1..]
        .iter()
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert!(f.iter().all(|x| *x > 0.0 && *x < 0.6), "{f:?}");
}

#[test]
fn step_sine_and_field_run() {
    let (code, out, err) = ecf(&[
        "step",
        "--preset",
        "table4.1",
        "--v-mps",
        "5",
        "--cx-from",
        "0.001",
        "--cx-to",
        "0.01",
        "--duration-ms",
        "1",
        "--dt-ms",
        "0.1",
        "--grid",
        "20x7",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("t_s,cx,f,"));
    assert_eq!(out.lines().count(), 12);
    let (code, out, err) = ecf(&[
        "sine",
        "--model",
        "fastsim",
        "--v-mps",
        "5",
        "--cm",
        "0.01",
        "--ca",
        "0.005",
        "--freq-hz",
        "100",
        "--cycles",
        "1",
        "--grid",
        "20x7",
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 202);
    let (code, out, err) = ecf(&["field", "--preset", "dry", "--cx", "0.05", "--grid", "20x7"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("x_mm,tau_Pa"));
}

#[test]
fn bad_input_names_the_flag_and_range_and_fails() {
    let cases: &[(&[&str], &str)] = &[
        (&["curve", "--v-mps", "-1500", "--cx", "0.01"], "--v-mps"), // negative rolls backwards; this is out of range
        (&["curve", "--v-mps", "NaN", "--cx", "0.01"], "--v-mps"),
        (&["curve", "--fn-kn", "0", "--cx", "0.01"], "--fn-kN"),
        (&["curve", "--grid", "0x5", "--cx", "0.01"], "--grid"),
        (&["curve", "--preset", "moist", "--cx", "0.01"], "moist"),
        (&["curve", "--cx", "0.01,abc"], "--cx"),
        (&["curve", "--cx", "20"], "--cx"),
        (&["curve", "--a-mm", "7"], "--a-mm"),
        (&["curve", "--param", "nu=0.9", "--cx", "0.01"], "nu"),
    ];
    for (args, needle) in cases {
        let (code, _, err) = ecf(args);
        assert_ne!(code, 0, "{args:?} must fail");
        assert!(
            err.contains(needle),
            "{args:?}: '{err}' should name {needle}"
        );
        assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    }
}

#[test]
fn malformed_config_file_reports_line_and_column() {
    let dir = std::env::temp_dir().join(format!("ecf-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("bad.json");
    std::fs::write(
        &p,
        "{\n  \"model\": \"ecf\",\n  \"params\": {\"tau_c1_0_GPa\": }\n}\n",
    )
    .unwrap();
    let (code, _, err) = ecf(&["curve", "--config", p.to_str().unwrap(), "--cx", "0.01"]);
    assert_ne!(code, 0);
    assert!(err.contains("bad.json") && err.contains("line 3"), "{err}");
    let (code, _, err) = ecf(&[
        "curve",
        "--config",
        dir.join("missing.json").to_str().unwrap(),
        "--cx",
        "0.01",
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("missing.json"), "{err}");
}

#[test]
fn compare_and_fit_on_a_generated_file() {
    let dir = std::env::temp_dir().join(format!("ecf-cli-fit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // "measurements" from the dry preset at two speeds; compared with table4.1 they differ
    let mut csv = String::from("cx,f,series,v_mps,fn_kN,humidity\n");
    for v in ["5", "20"] {
        let (code, out, err) = ecf(&[
            "curve",
            "--preset",
            "dry",
            "--grid",
            "20x7",
            "--v-mps",
            v,
            "--cx",
            "0.001:0.3:12",
        ]);
        assert_eq!(code, 0, "{err}");
        for (k, l) in out.lines().skip(1).enumerate() {
            let c: Vec<&str> = l.split(',').collect();
            csv.push_str(&format!("{},{},v{v},{v},110,{}\n", c[0], c[1], 40 + k));
        }
    }
    let data = dir.join("m.csv");
    std::fs::write(&data, csv).unwrap();
    let plots = dir.join("plots");
    let (code, out, err) = ecf(&[
        "compare",
        data.to_str().unwrap(),
        "--preset",
        "table4.1",
        "--grid",
        "20x7",
        "--json",
        "--plots",
        plots.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let before = v["cv_rmse_pct"].as_f64().unwrap();
    assert!(before > 1.0, "table4.1 vs dry data must differ: {before}");
    assert!(v["groups"]
        .as_array()
        .unwrap()
        .iter()
        .any(|g| g["by"] == "v_mps" && g["value"] == "20"));
    for png in [
        "series_00_v5.png",
        "series_01_v20.png",
        "residual_over_cx.png",
        "residual_over_humidity.png",
        "residual_over_T_max.png",
    ] {
        let p = plots.join(png);
        let bytes = std::fs::read(&p).unwrap_or_else(|_| panic!("{} missing", p.display()));
        assert_eq!(&bytes[1..4], b"PNG");
    }
    let fitted = dir.join("fitted.json");
    let (code, out, err) = ecf(&[
        "fit",
        data.to_str().unwrap(),
        "--preset",
        "table4.1",
        "--grid",
        "20x7",
        "--free",
        "tau_c1_0_GPa,tau_c2_0_GPa",
        "--out",
        fitted.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&out).unwrap();
    let after = r["cv_rmse_pct_after"].as_f64().unwrap();
    assert!((r["cv_rmse_pct_before"].as_f64().unwrap() - before).abs() < 1e-9);
    assert!(
        after < 0.5 * before,
        "fit must reduce the error: {before} -> {after}"
    );
    assert!(r["stderr"]["tau_c1_0_GPa"].as_f64().unwrap() > 0.0);
    // the written configuration reproduces the fitted error
    let (code, out, err) = ecf(&[
        "compare",
        data.to_str().unwrap(),
        "--config",
        fitted.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!((v["cv_rmse_pct"].as_f64().unwrap() - after).abs() < 1e-6);
    // diagnose (JSON) and the HTML report, before and after side by side
    let (code, out, err) = ecf(&[
        "diagnose",
        data.to_str().unwrap(),
        "--preset",
        "table4.1",
        "--grid",
        "20x7",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let d: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(d["baseline_cv_rmse_pct"].as_f64().unwrap() > 0.0);
    assert!(d["correlations"]
        .as_array()
        .unwrap()
        .iter()
        .any(|c| c["variable"] == "humidity"));
    assert!(d["candidates"].is_array() && d["verdict"].is_string());
    let html = dir.join("report.html");
    let (code, _, err) = ecf(&[
        "report",
        data.to_str().unwrap(),
        "--preset",
        "table4.1",
        "--grid",
        "20x7",
        "--compare-with",
        fitted.to_str().unwrap(),
        "--out",
        html.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&html).unwrap();
    assert!(
        text.contains("data:image/png;base64,")
            && text.contains("before:")
            && text.contains("after:")
    );
    assert!(
        !text.contains("src=\"/") && !text.contains("src=\"file:"),
        "images must be embedded"
    );
    // bad --free name
    let (code, _, err) = ecf(&[
        "fit",
        data.to_str().unwrap(),
        "--preset",
        "table4.1",
        "--free",
        "tau_c9",
        "--out",
        fitted.to_str().unwrap(),
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("tau_c9"), "{err}");
}

#[test]
fn hpt_files_are_compared_and_fitted() {
    let dir = std::env::temp_dir().join(format!("ecf-cli-hpt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = dir.join("hpt.csv");
    std::fs::write(&data, "p_MPa,u_mm,tau_MPa,series\n500,0.1,150,a\n500,0.3,250,a\n500,0.6,300,a\n500,1.0,320,a\n1000,0.1,200,b\n1000,0.3,330,b\n1000,0.6,400,b\n1000,1.0,430,b\n").unwrap();
    let (code, out, err) = ecf(&[
        "compare",
        data.to_str().unwrap(),
        "--preset",
        "dry",
        "--json",
        "--plots",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let before = v["cv_rmse_pct"].as_f64().unwrap();
    assert!(dir.join("hpt.png").exists());
    let (code, out, err) = ecf(&[
        "fit",
        data.to_str().unwrap(),
        "--preset",
        "dry",
        "--out",
        dir.join("f.json").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!((r["cv_rmse_pct_before"].as_f64().unwrap() - before).abs() < 1e-9);
    assert!(r["cv_rmse_pct_after"].as_f64().unwrap() < 0.2 * before);
    // a bad HPT file names line and column
    std::fs::write(&data, "p_MPa,u_mm,tau_MPa\n500,x,150\n").unwrap();
    let (code, _, err) = ecf(&["compare", data.to_str().unwrap(), "--preset", "dry"]);
    assert_ne!(code, 0);
    assert!(err.contains("line 2") && err.contains("u_mm"), "{err}");
    // values beyond any test's range are refused, not compared into "CV(RMSE) = NaN %"
    std::fs::write(&data, "p_MPa,u_mm,tau_MPa\n500,0.1,150\n500,0.3,1e308\n").unwrap();
    let (code, out, err) = ecf(&["compare", data.to_str().unwrap(), "--preset", "dry"]);
    assert_ne!(code, 0, "{out}");
    assert!(
        err.contains("line 3") && err.contains("tau_MPa") && err.contains("range"),
        "{err}"
    );
    assert!(!out.contains("NaN"), "{out}");
}

#[test]
fn compare_says_when_no_row_reaches_one_percent() {
    let dir = std::env::temp_dir().join(format!("ecf-cli-small-cx-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = dir.join("small.csv");
    std::fs::write(
        &data,
        "cx,f,v_mps,fn_kN\n0.001,0.15,20,110\n0.002,0.2,20,110\n",
    )
    .unwrap();
    let (code, out, err) = ecf(&["compare", data.to_str().unwrap(), "--preset", "dry"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("no row at c_x >= 1 %"), "{out}");
    assert!(!out.contains("NaN"), "{out}");
}

/// Columns of a CSV text by header name.
fn columns(csv: &str) -> std::collections::HashMap<String, Vec<String>> {
    let mut lines = csv.lines();
    let head: Vec<String> = lines
        .next()
        .unwrap_or("")
        .split(',')
        .map(String::from)
        .collect();
    let mut cols: std::collections::HashMap<String, Vec<String>> =
        head.iter().map(|h| (h.clone(), vec![])).collect();
    for l in lines {
        for (h, x) in head.iter().zip(l.split(',')) {
            cols.get_mut(h).unwrap().push(x.to_string());
        }
    }
    cols
}

#[test]
fn step_field_at_ms_starts_at_the_steady_field_and_ends_at_the_new_one() {
    // 5 m/s, 2a = 15.3 mm: the contact is renewed after 3.05 ms; at 8 ms it is the steady
    // field of the new creepage
    let common = [
        "--preset", "dry", "--v-mps", "5", "--a-mm", "7.63", "--b-mm", "7.88", "--grid", "40x11",
    ];
    let steady = |cx: &str| {
        let mut a = vec!["field"];
        a.extend(common);
        a.extend(["--cx", cx]);
        let (code, out, err) = ecf(&a);
        assert_eq!(code, 0, "{err}");
        columns(&out)
    };
    let mut a = vec!["step"];
    a.extend(common);
    a.extend([
        "--cx-from",
        "0.002",
        "--cx-to",
        "0.02",
        "--dt-ms",
        "0.05",
        "--field-at-ms",
        "8,0,1.5",
    ]);
    let (code, out, err) = ecf(&a);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.starts_with(
            "t_ms,f,x_mm,x_rail_mm,tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime\n"
        ),
        "{out}"
    );
    let c = columns(&out);
    let at = |t: &str, col: &str| -> Vec<f64> {
        c["t_ms"]
            .iter()
            .zip(&c[col])
            .filter(|(tt, _)| tt.parse::<f64>().unwrap() == t.parse::<f64>().unwrap())
            .map(|(_, x)| x.parse().unwrap())
            .collect()
    };
    let num = |v: &[String]| -> Vec<f64> { v.iter().map(|x| x.parse().unwrap()).collect() };
    // t = 0: exactly the steady field of cx_from
    let s0 = steady("0.002");
    assert_eq!(at("0", "tau_Pa"), num(&s0["tau_Pa"]));
    assert_eq!(at("0", "x_mm"), num(&s0["x_mm"]));
    // mid-transient: neither field; x_rail = x + v t
    let s1 = steady("0.02");
    let mid = at("1.5", "tau_Pa");
    assert_ne!(mid, num(&s0["tau_Pa"]));
    let (x, xr) = (at("1.5", "x_mm"), at("1.5", "x_rail_mm"));
    for (x, xr) in x.iter().zip(&xr) {
        assert!((xr - x - 7.5).abs() < 2e-5, "x_rail {xr} != x {x} + 7.5 mm");
    }
    // t = 8 ms: the steady field of cx_to (the transient converges to it)
    // (its bristles sit between the lattice nodes now: the steady field is interpolated,
    // away from the edges: at the leading one tau follows tau_c1 ~ the steep rise of the
    // pressure, and the trailing node stands for the whole last cell)
    let (end, x_end) = (at("8", "tau_Pa"), at("8", "x_mm"));
    let (want, xs) = (num(&s1["tau_Pa"]), num(&s1["x_mm"]));
    let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(end.len() >= want.len() - 1);
    let f_end = at("8", "f")[0];
    let (code, curve, err) = {
        let mut a = vec!["curve"];
        a.extend(common);
        a.extend(["--cx", "0.02"]);
        ecf(&a)
    };
    assert_eq!(code, 0, "{err}");
    let f_steady: f64 = num(&columns(&curve)["f"])[0];
    assert!(
        (f_end / f_steady - 1.0).abs() < 2e-3,
        "f(8 ms) {f_end} vs steady {f_steady}"
    );
    for (e, x) in end
        .iter()
        .zip(&x_end)
        .filter(|(_, x)| **x < xs[2] && **x > xs[xs.len() - 2])
    {
        // x_mm runs from the leading edge (+a) down
        let k = xs
            .iter()
            .position(|xx| xx <= x)
            .unwrap_or(xs.len() - 1)
            .max(1);
        let w = want[k - 1] + (x - xs[k - 1]) / (xs[k] - xs[k - 1]) * (want[k] - want[k - 1]);
        assert!(
            (e - w).abs() <= 0.02 * scale,
            "tau {e} vs steady {w} at x = {x} mm"
        );
    }
    // a bad instant names the flag
    let mut a = vec!["step"];
    a.extend(common);
    a.extend(["--cx-from", "0", "--cx-to", "0.01", "--field-at-ms", "1,-2"]);
    let (code, _, err) = ecf(&a);
    assert_ne!(code, 0);
    assert!(err.contains("--field-at-ms") && err.contains("-2"), "{err}");
}

#[test]
fn step_and_sine_take_the_scheme() {
    // --scheme cells-ho is ECF's default; cells and continuous give other numbers within
    // about 2 %; a bad value names the flag and the accepted values
    let run = |cmd: &str, scheme: Option<&str>| {
        let mut args = vec![cmd, "--preset", "dry", "--grid", "40x11", "--v-mps", "20"];
        if cmd == "step" {
            args.extend(["--cx-from", "0.002", "--cx-to", "0.05"]);
            args.extend(["--duration-ms", "1", "--dt-ms", "0.1"]);
        } else {
            args.extend(["--cm", "0.02", "--ca", "0.01", "--freq-hz", "50"]);
            args.extend(["--cycles", "1", "--steps-per-cycle", "200"]);
        }
        if let Some(s) = scheme {
            args.extend(["--scheme", s]);
        }
        let (code, out, err) = ecf(&args);
        assert_eq!(code, 0, "{err}");
        let last = out.lines().last().unwrap().to_string();
        last.split(',').nth(2).unwrap().parse::<f64>().unwrap()
    };
    for cmd in ["step", "sine"] {
        let default = run(cmd, None);
        assert_eq!(default, run(cmd, Some("cells-ho")), "{cmd}");
        let cells = run(cmd, Some("cells"));
        let cont = run(cmd, Some("continuous"));
        for (name, other) in [("cells", cells), ("continuous", cont)] {
            assert!(other != default, "{cmd}: {name} must change the numbers");
            assert!(
                (other - default).abs() < 0.02 * default,
                "{cmd}: {name} {other} vs {default}"
            );
        }
        assert!(cont != cells, "{cmd}");
    }
    let (code, _, err) = ecf(&[
        "step",
        "--cx-from",
        "0",
        "--cx-to",
        "0.1",
        "--scheme",
        "fast",
    ]);
    assert_ne!(code, 0);
    assert!(
        err.contains("--scheme") && err.contains("continuous"),
        "{err}"
    );
}

#[test]
fn curve_and_field_take_the_steady_scheme() {
    // the steady commands take --scheme cells or cells-ho (ECF's default), whose higher-order
    // rules change the steady march by about the grid's error; continuous, whose steady
    // state is the cells march, is refused with the accepted values
    let curve = |scheme: Option<&str>| {
        let mut args = vec![
            "curve", "--preset", "wet", "--grid", "20x5", "--v-mps", "30",
        ];
        args.extend(["--cx", "0.01,0.15"]);
        if let Some(s) = scheme {
            args.extend(["--scheme", s]);
        }
        let (code, out, err) = ecf(&args);
        assert_eq!(code, 0, "{err}");
        out.lines()
            .skip(1)
            .map(|l| l.split(',').nth(1).unwrap().parse::<f64>().unwrap())
            .collect::<Vec<f64>>()
    };
    let default = curve(None);
    assert_eq!(default, curve(Some("cells-ho")));
    let cells = curve(Some("cells"));
    for (d, h) in cells.iter().zip(&default) {
        assert!(h != d, "cells-ho must change the steady march: {h} vs {d}");
        assert!((h - d).abs() < 0.03 * d, "{h} vs {d}");
    }
    let field = |scheme: &str| {
        let args = [
            "field", "--preset", "wet", "--grid", "20x5", "--v-mps", "30", "--cx", "0.05",
            "--scheme", scheme,
        ];
        let (code, out, err) = ecf(&args);
        assert_eq!(code, 0, "{err}");
        out
    };
    assert_ne!(field("cells"), field("cells-ho"));
    let (code, _, err) = ecf(&["curve", "--cx", "0.01", "--scheme", "continuous"]);
    assert_ne!(code, 0);
    assert!(
        err.contains("--scheme") && err.contains("cells-ho"),
        "{err}"
    );
    // with --tol the explicit scheme restricts the choice to its rows
    let (code, _, err) = ecf(&[
        "curve", "--preset", "dry", "--v-mps", "20", "--cx", "0.01", "--tol", "0.02", "--scheme",
        "cells",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("within the explicit --grid/--scheme") && err.contains("scheme cells:"),
        "{err}"
    );
}

#[test]
fn a_formula_nested_ten_thousand_deep_is_an_error_not_a_crash() {
    let dir = std::env::temp_dir().join(format!("ecf_cli_deep_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("deep.json");
    let factor = format!("{}1{}", "(".repeat(10_000), ")".repeat(10_000));
    std::fs::write(
        &p,
        format!(r#"{{"preset": "dry", "formula_effects": [{{"name": "d", "target": "mu", "factor": "{factor}"}}]}}"#),
    )
    .unwrap();
    let (code, out, err) = ecf(&["curve", "--config", p.to_str().unwrap(), "--cx", "0.01"]);
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty());
    assert!(err.contains("nests deeper than 50 levels"), "{err}");
    assert!(
        err.len() < 1000,
        "the message quotes the formula's start only: {} bytes",
        err.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A temporary file with `text` (removed when dropped).
struct TempFile(std::path::PathBuf);
impl TempFile {
    fn new(name: &str, text: &str) -> Self {
        let p = std::env::temp_dir().join(format!("ecf-cli-{}-{name}", std::process::id()));
        std::fs::write(&p, text).expect("write temp file");
        TempFile(p)
    }
    fn path(&self) -> &str {
        self.0.to_str().expect("utf-8 temp path")
    }
}
impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Inputs that could give NaN or inf with exit status 0 fail, naming what is wrong,
/// and print no table.
#[test]
fn inputs_that_gave_nan_or_inf_are_errors() {
    let huge = ecf(&[
        "curve", "--a-mm", "1e300", "--b-mm", "1e300", "--cx", "0.01",
    ]);
    let tiny = ecf(&["curve", "--a-mm", "1e-300", "--b-mm", "5", "--cx", "0.01"]);
    for (code, out, err) in [&huge, &tiny] {
        assert_ne!(*code, 0, "{out}");
        assert!(out.is_empty(), "a table was printed: {out}");
        assert!(
            err.contains("--a-mm/--b-mm") && err.contains("contact semi-axis a (m)"),
            "{err}"
        );
        assert!(err.contains("[1e-6, 10000] mm"), "{err}");
    }
    // numbers in exponent form, not 300 digits
    assert!(huge.2.contains("= 1e297"), "{}", huge.2);
    assert!(huge.2.len() < 400, "{}", huge.2);
    // a small load above lift-off has a usable patch, even a line contact's (half-width
    // ~ sqrt(F_N): 0.37 um at 10 mN), and a load below lift-off is lift-off, not an error
    for fn_kn in ["1e-5", "1e-12"] {
        let (code, out, err) = ecf(&[
            "curve",
            "--preset",
            "twin_disc",
            "--fn-kN",
            fn_kn,
            "--cx",
            "0.01",
        ]);
        assert_eq!(code, 0, "F_N = {fn_kn} kN: {err}");
        assert!(!out.contains("NaN"), "{out}");
    }

    // a formula reading a data column: a NaN column value is refused where it is parsed; a
    // finite value that drives an output to inf is refused by the output check
    let cfg = TempFile::new(
        "wild.json",
        r#"{"preset": "dry", "grid": {"nx": 20, "ny": 5},
            "formula_effects": [{"name": "wild", "target": "tau_c2", "factor": "humidity / 50", "params": {}}]}"#,
    );
    let run = |x: &str| {
        ecf(&[
            "curve",
            "--config",
            cfg.path(),
            "--extra",
            &format!("humidity={x}"),
            "--cx",
            "0.01",
        ])
    };
    for x in ["nan", "inf", "-inf"] {
        let (code, out, err) = run(x);
        assert_ne!(code, 0, "humidity={x}: {out}");
        assert!(
            err.contains("--extra")
                && err.contains(&format!("'humidity={x}'"))
                && err.contains("finite"),
            "{err}"
        );
    }
    let (code, out, err) = run("1e308");
    assert_ne!(code, 0, "{out}");
    assert!(out.is_empty(), "{out}");
    assert!(
        err.contains("not finite") && err.contains("f = inf"),
        "{err}"
    );
    // the same configuration at an ordinary humidity runs
    let (code, out, err) = run("60");
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 2, "{out}");
}

/// A geometry with semi-axes and radii both given is refused (the radii were taken silently).
#[test]
fn a_geometry_given_two_ways_is_an_error() {
    let cfg = TempFile::new(
        "twoways.json",
        r#"{"preset": "dry", "geometry": {"a_mm": 7, "b_mm": 8, "fn_ref_kN": 110, "rx_mm": 460, "ry_mm": 300}}"#,
    );
    let (code, out, err) = ecf(&["curve", "--config", cfg.path(), "--cx", "0.01"]);
    assert_ne!(code, 0, "{out}");
    assert!(
        err.contains("give one of") && err.contains("a_mm, b_mm, fn_ref_kN and rx_mm, ry_mm"),
        "{err}"
    );
    // each way alone is accepted
    for g in [
        r#"{"a_mm": 7, "b_mm": 8, "fn_ref_kN": 110}"#,
        r#"{"rx_mm": 460, "ry_mm": 300}"#,
    ] {
        let one = TempFile::new(
            "oneway.json",
            &format!(r#"{{"preset": "dry", "grid": {{"nx": 20, "ny": 5}}, "geometry": {g}}}"#),
        );
        let (code, _, err) = ecf(&["curve", "--config", one.path(), "--cx", "0.01"]);
        assert_eq!(code, 0, "{g}: {err}");
    }
}

/// A time step so small that the run would never end (the CLI fuzzer's find: --dt-ms 1e-300
/// over 4.9 ms ran for ever) is refused, naming the flag and the step count.
#[test]
fn a_run_of_too_many_steps_is_refused() {
    let (code, out, err) = ecf(&[
        "step",
        "--grid",
        "5x3",
        "--cx-from",
        "0",
        "--cx-to",
        "0.005",
        "--duration-ms",
        "4.9",
        "--dt-ms",
        "1e-300",
    ]);
    assert_ne!(code, 0, "{out}");
    assert!(
        err.contains("--dt-ms = 1e-300") && err.contains("time steps; at most 1e7"),
        "{err}"
    );
    let (code, _, err) = ecf(&[
        "sine",
        "--grid",
        "5x3",
        "--cm",
        "0.01",
        "--ca",
        "0.001",
        "--freq-hz",
        "10",
        "--cycles",
        "100000",
        "--steps-per-cycle",
        "1000",
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("--cycles/--steps-per-cycle"), "{err}");
}

/// A configuration file's `scheme` is the one `curve` and `step` run (the output of the
/// explicit --scheme), and --scheme overrides it.
#[test]
fn a_configuration_files_scheme_runs_unless_scheme_is_given() {
    let dir = std::env::temp_dir().join(format!("ecf-cli-scheme-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("cells.json");
    std::fs::write(
        &file,
        r#"{"preset": "dry", "grid": {"nx": 20, "ny": 5}, "scheme": "cells"}"#,
    )
    .unwrap();
    let run = |cmd: &[&str], source: &[&str], scheme: Option<&str>| {
        let mut a: Vec<&str> = cmd.to_vec();
        a.extend_from_slice(source);
        if let Some(s) = scheme {
            a.extend_from_slice(&["--scheme", s]);
        }
        let (code, out, err) = ecf(&a);
        assert_eq!(code, 0, "{a:?}: {err}");
        out
    };
    let f = file.to_str().unwrap();
    let preset = ["--preset", "dry", "--grid", "20x5"];
    for cmd in [
        &["curve", "--cx", "0.002,0.01,0.05"][..],
        &[
            "step",
            "--cx-from",
            "0.002",
            "--cx-to",
            "0.01",
            "--duration-ms",
            "3",
            "--dt-ms",
            "0.25",
        ][..],
    ] {
        let from_file = run(cmd, &["--config", f], None);
        assert_eq!(from_file, run(cmd, &preset, Some("cells")), "{cmd:?}");
        // the preset names no scheme: ECF's default, cells-ho
        let default = run(cmd, &preset, None);
        assert_ne!(from_file, default, "{cmd:?}");
        assert_eq!(
            run(cmd, &["--config", f], Some("cells-ho")),
            default,
            "{cmd:?}"
        );
    }
    // --tol chooses among the rows of the file's scheme (as the FMU's rel_tol does)
    let cont = dir.join("continuous.json");
    std::fs::write(&cont, r#"{"preset": "dry", "scheme": "continuous"}"#).unwrap();
    let (code, _, err) = ecf(&[
        "step",
        "--config",
        cont.to_str().unwrap(),
        "--tol",
        "0.02",
        "--cx-from",
        "0.002",
        "--cx-to",
        "0.01",
        "--duration-ms",
        "1",
        "--dt-ms",
        "0.25",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("within the configuration's scheme continuous")
            && err.contains("scheme continuous:"),
        "{err}"
    );
    // a fit writes the scheme it ran with into the fitted configuration
    let ex = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/measurements");
    let out = dir.join("fitted.json");
    let (code, _, err) = ecf(&[
        "fit",
        ex.join("humid.csv").to_str().unwrap(),
        "--config",
        ex.join("dry-humid.json").to_str().unwrap(),
        "--free",
        "humid.k",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let fitted: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(fitted["scheme"], "cells-ho");
    let _ = std::fs::remove_dir_all(&dir);
}
