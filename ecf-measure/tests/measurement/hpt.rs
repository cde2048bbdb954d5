//! High-pressure-torsion curves of the layer alone (seed Sec. 5.1): shape of Eq. 4.1/4.2 and recovery of the parameters by fitting.
use crate::common::*;
use ecf_measure::fit::FreeParam;
use ecf_measure::hpt;
use ecf_measure::measure::read_hpt;

fn curves(cfg: &creep_core::Config) -> String {
    let mut csv = String::from("p_MPa,u_mm,tau_MPa,series\n");
    let probe: Vec<_> = [500.0, 1000.0]
        .iter()
        .flat_map(|&p| (1..=20).map(move |k| (p, 0.05 * k as f64)))
        .collect();
    let rows = read_hpt(
        &probe
            .iter()
            .map(|(p, u)| format!("{p},{u},0,p{p}\n"))
            .fold(String::from("p_MPa,u_mm,tau_MPa,series\n"), |a, b| a + &b),
        "probe",
    )
    .unwrap();
    for (r, t) in rows.iter().zip(hpt::predict(cfg, &rows)) {
        csv.push_str(&format!(
            "{},{},{},{}\n",
            r.p / 1e6,
            r.u * 1e3,
            t / 1e6,
            r.series
        ));
    }
    csv
}

#[test]
fn hpt_curve_rises_towards_tau_c2_and_more_with_pressure() {
    let cfg = preset("dry");
    let rows = read_hpt(&curves(&cfg), "dry.csv").unwrap();
    let (lo, hi): (Vec<_>, Vec<_>) = rows.iter().partition(|r| r.p < 700e6);
    for set in [&lo, &hi] {
        for w in set.windows(2) {
            assert!(w[1].tau >= w[0].tau, "monotonic loading must not soften");
        }
    }
    assert!(
        hi.last().unwrap().tau > lo.last().unwrap().tau,
        "granular: more shear strength at higher normal stress"
    );
}

#[test]
fn fitting_hpt_curves_recovers_the_layer_parameters() {
    let truth = preset("dry");
    let data = read_hpt(&curves(&truth), "dry.csv").unwrap();
    let start = preset("table4.1");
    let free: Vec<FreeParam> = [
        creep_core::params::P::Tc10,
        creep_core::params::P::Tc20,
        creep_core::params::P::Lp0,
    ]
    .iter()
    .map(|p| FreeParam::Builtin(*p))
    .collect();
    let before = hpt::cv_rmse(&start, &data);
    // L_p's pressure coefficient is part of the truth: give it, fit the rest
    let mut start = start;
    start
        .params
        .set_by_name(
            "L_p_p_per_GPa",
            truth.params.get(creep_core::params::P::LpP),
        )
        .unwrap();
    start
        .params
        .set_by_name(
            "tau_c1_p_per_GPa",
            truth.params.get(creep_core::params::P::Tc1P),
        )
        .unwrap();
    start
        .params
        .set_by_name(
            "tau_c2_p_per_GPa",
            truth.params.get(creep_core::params::P::Tc2P),
        )
        .unwrap();
    let r = hpt::fit(&start, "dry.csv", &data, &free, &|_| {}).unwrap();
    assert!(before > 10.0, "start must be off: {before} %");
    assert!(r.cv_rmse_pct_after < 0.1, "after {} %", r.cv_rmse_pct_after);
    for p in &r.params {
        let (n, v) = (&p.name, &p.value);
        let t = truth.params.get(creep_core::params::by_name(n).unwrap());
        assert!((v - t).abs() < 1e-3 * t, "{n}: {v} vs {t}");
    }
}
