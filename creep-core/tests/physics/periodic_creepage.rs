//! Seed Sec. 4.5.2: sine creepage gives a periodic f (limit cycle) that approaches the steady curve as the frequency goes to 0.
use crate::common::*;
use creep_core::Model;
use std::f64::consts::PI;

/// The limit-cycle physics does not need the fine default grid.
fn coarse() -> creep_core::Config {
    with_grid(preset("table4.1"), 40, 11)
}

/// Runs `cycles` periods; returns per-period samples of (cx, f) of the last two periods.
type Loop = Vec<(f64, f64)>;

fn run(f0: f64, cm: f64, ca: f64, cycles: usize, n: usize) -> (Loop, Loop) {
    let cfg = coarse();
    let mut m = Model::new(&cfg).unwrap();
    m.steady(&vectron(cm, 5.0)).unwrap();
    let dt = 1.0 / (f0 * n as f64);
    let mut all = Vec::new();
    for k in 1..=cycles * n {
        let c = cm + ca * (2.0 * PI * f0 * k as f64 * dt).sin();
        let o = m.step(dt, &vectron(c, 5.0)).unwrap();
        all.push((c, o.f));
    }
    let last = all[(cycles - 1) * n..].to_vec();
    let prev = all[(cycles - 2) * n..(cycles - 1) * n].to_vec();
    (prev, last)
}

#[test]
fn sine_creepage_reaches_a_limit_cycle() {
    let (prev, last) = run(100.0, 0.2, 0.1, 4, 100);
    let diff = prev
        .iter()
        .zip(&last)
        .map(|(a, b)| (a.1 - b.1).abs())
        .fold(0.0, f64::max);
    let fmax = last.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    let fmin = last.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    // periodic up to the grid's phase ripple (bristle entry instants do not repeat exactly
    // from one period to the next): consecutive periods agree within 2 % of the swing of f
    assert!(
        diff < 0.02 * (fmax - fmin),
        "consecutive periods differ by {diff}, swing {}",
        fmax - fmin
    );
    // a real hysteresis: the loop encloses area
    let area: f64 = last
        .windows(2)
        .map(|w| (w[1].0 - w[0].0) * 0.5 * (w[1].1 + w[0].1))
        .sum();
    assert!(area.abs() > 1e-5, "loop area {area}");
}

#[test]
fn limit_cycle_approaches_the_steady_curve_as_frequency_falls() {
    let cfg = coarse();
    let mut devs = Vec::new();
    for f0 in [200.0, 20.0, 2.0] {
        let (_, last) = run(f0, 0.25, 0.2, 3, 100);
        let dev = last
            .iter()
            .map(|&(c, f)| (f - f_of(&cfg, c, 5.0)).abs())
            .fold(0.0, f64::max);
        devs.push(dev);
    }
    assert!(
        devs[0] > devs[1] && devs[1] > devs[2],
        "deviation from the steady curve must fall with frequency: {devs:?}"
    );
    assert!(
        devs[2] < 0.01,
        "at 2 Hz the loop must lie on the steady curve: {devs:?}"
    );
}
