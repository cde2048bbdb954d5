//! `--tol`: the grid and scheme chosen from creep-core's accuracy table, printed on stderr; explicit --grid and --scheme override it; bad tolerances are refused.
use creep_core::tolerance::{self, Filter};
mod common;
use common::ecf;

/// The choice for the dry preset unchanged: judged on its own rows.
const DRY: Filter = Filter {
    preset: Some("dry"),
    nx: None,
    ny: None,
    scheme: None,
    steady: false,
};

/// A short dry creepage step at 5 m/s with 1 ms steps, plus `extra` flags.
fn step(extra: &[&str]) -> (i32, String, String) {
    let mut a = vec![
        "step",
        "--preset",
        "dry",
        "--v-mps",
        "5",
        "--cx-from",
        "0.01",
        "--cx-to",
        "0.15",
        "--dt-ms",
        "1",
        "--duration-ms",
        "3",
    ];
    a.extend_from_slice(extra);
    ecf(&a)
}

#[test]
fn tol_runs_on_the_grid_and_scheme_the_table_gives_and_says_which() {
    // a loose and a tight tolerance: the library's choice, not a hard-coded grid
    for tol in [0.05, 0.006] {
        let c = tolerance::choose(tol, 5.0, Some(1e-3), DRY).expect("choice");
        let t = tol.to_string();
        let (code, out, err) = step(&["--tol", &t]);
        assert_eq!(code, 0, "{err}");
        let grid = format!("{}x{}", c.nx, c.ny);
        let scheme = c.scheme.name();
        assert!(
            err.contains(&format!("grid {grid}, scheme {scheme}"))
                && err.contains(&format!("{:.2} %", c.fx_err_pct)),
            "{err}"
        );
        // the same output as the explicit grid and scheme
        let (code2, out2, err2) = step(&["--grid", &grid, "--scheme", scheme]);
        assert_eq!(code2, 0, "{err2}");
        assert_eq!(out, out2, "--tol {tol} is not the run on {grid} {scheme}");
    }
}

#[test]
fn explicit_grid_and_scheme_override_tol() {
    let loose = tolerance::choose(0.5, 5.0, Some(1e-3), DRY).expect("choice");
    assert_ne!((loose.nx, loose.ny), (80, 7), "the test needs another grid");
    let (_, plain, _) = step(&["--grid", "80x7", "--scheme", "cells"]);
    let (code, out, err) = step(&["--tol", "0.5", "--grid", "80x7"]);
    assert_eq!(code, 0, "{err}");
    let (_, chosen, _) = step(&["--tol", "0.5"]);
    // the grid is the explicit one; the scheme is chosen among the table's rows on 80x7
    let on80 = tolerance::choose(
        0.5,
        5.0,
        Some(1e-3),
        Filter {
            nx: Some(80),
            ny: Some(7),
            ..DRY
        },
    )
    .expect("80x7 is tabulated");
    let (_, explicit, _) = step(&["--grid", "80x7", "--scheme", on80.scheme.name()]);
    assert_eq!(out, explicit);
    assert_ne!(out, chosen, "--grid 80x7 was not used");
    assert!(err.contains("grid 80x7"), "{err}");
    // both explicit: exactly the run without --tol
    let (_, both, _) = step(&["--tol", "0.5", "--grid", "80x7", "--scheme", "cells"]);
    assert_eq!(both, plain);
    // a scheme alone: the choice keeps it
    let (code, _, err) = step(&["--tol", "0.5", "--scheme", "continuous"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("scheme continuous"), "{err}");
    // a grid the table does not have: used as given, with a note
    let (code, out, err) = step(&["--tol", "0.01", "--grid", "30x7"]);
    let (_, plain30, _) = step(&["--grid", "30x7"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, plain30);
    assert!(err.contains("not measured"), "{err}");
}

#[test]
fn a_tolerance_no_grid_meets_is_a_warning_with_the_error_reached() {
    // the choice `ecf curve --tol` makes: a steady computation, cells or cells-ho
    let c = tolerance::choose(
        1e-5,
        20.0,
        None,
        Filter {
            steady: true,
            ..DRY
        },
    )
    .expect("choice");
    assert!(!c.met);
    let (code, out, err) = ecf(&[
        "curve", "--preset", "dry", "--v-mps", "20", "--cx", "0.01", "--tol", "1e-5",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("cx,"), "{out}");
    assert!(
        err.contains("warning")
            && err.contains("NOT met")
            && err.contains(&format!(
                "grid {}x{}, scheme {}",
                c.nx,
                c.ny,
                c.scheme.name()
            )),
        "{err}"
    );
}

#[test]
fn a_preset_unchanged_is_judged_on_its_rows_and_a_changed_one_on_every_preset() {
    let own = tolerance::choose(0.01, 5.0, Some(1e-3), DRY).expect("choice");
    let all = tolerance::choose(0.01, 5.0, Some(1e-3), Filter::default()).expect("choice");
    let (code, _, err) = step(&["--tol", "0.01"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("worst of dry, steps") && err.contains(&format!("{:.2} %", own.fx_err_pct)),
        "{err}"
    );
    // a parameter changed: no longer the tabulated preset
    let (code, _, err) = step(&["--tol", "0.01", "--param", "tau_c2_0_GPa=1.2"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("worst of dry, table4.1, wet")
            && err.contains(&format!("grid {}x{}", all.nx, all.ny))
            && err.contains(&format!("{:.2} %", all.fx_err_pct)),
        "{err}"
    );
}

#[test]
fn bad_tolerances_are_refused_with_a_clear_message() {
    for (bad, says) in [
        ("0", "> 0"),
        ("-0.01", "> 0"),
        ("nan", "> 0"),
        ("inf", "> 0"),
        ("1%", "not a number"),
        ("abc", "not a number"),
    ] {
        let (code, out, err) = ecf(&[
            "curve",
            "--preset",
            "dry",
            "--cx",
            "0.01",
            &format!("--tol={bad}"),
        ]);
        assert_ne!(code, 0, "--tol {bad} accepted");
        assert!(out.is_empty(), "{out}");
        assert!(
            err.contains("--tol") && err.contains(says),
            "--tol {bad}: {err}"
        );
    }
    let (code, _, err) = ecf(&[
        "curve", "--model", "polach", "--cx", "0.01", "--tol", "0.01",
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("ECF model"), "{err}");
}
