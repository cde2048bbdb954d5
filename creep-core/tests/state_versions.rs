//! A state of every format version (1 to 4), written by the build of its era, loads into a model built from its own configuration and continues as that build continued it, within what the model's changes since explain.

use creep_core::thermal::TemperatureSolve;
use creep_core::{Inputs, Model};

/// The states (data/state_core_vN.bin) and the outputs their builds gave over the three
/// steps after them (data/state_core_vN.out); data/README.md says how each was made.
const FIXTURES: [(u32, &[u8], &str); 4] = [
    (
        1,
        include_bytes!("data/state_core_v1.bin"),
        include_str!("data/state_core_v1.out"),
    ),
    (
        2,
        include_bytes!("data/state_core_v2.bin"),
        include_str!("data/state_core_v2.out"),
    ),
    (
        3,
        include_bytes!("data/state_core_v3.bin"),
        include_str!("data/state_core_v3.out"),
    ),
    (
        4,
        include_bytes!("data/state_core_v4.bin"),
        include_str!("data/state_core_v4.out"),
    ),
];

/// The inputs of step `k` of the run that wrote the fixtures (steps of 0.5 ms).
fn inputs(k: usize) -> Inputs {
    Inputs {
        cx: 0.004 * k as f64,
        v: 20.0,
        ..Inputs::default()
    }
}

/// A model restored from `bytes`, built from the configuration the state holds, with the
/// exact temperature solve (the only one of the builds that wrote the fixtures).
fn restored(bytes: &[u8]) -> Model {
    let cfg = creep_core::state::saved_config(bytes).expect("the configuration loads");
    let mut m = Model::new(&cfg).expect("a model of it");
    m.set_temperature_solve(TemperatureSolve::Exact);
    m.load_state(bytes).expect("the state loads");
    m
}

/// Steps 5 to 7 from a restored model: (step, output name, value).
fn continued(mut m: Model) -> Vec<(usize, &'static str, f64)> {
    let mut out = Vec::new();
    for k in 5..=7 {
        let o = m.step(5e-4, &inputs(k)).expect("a step");
        for (n, x) in [
            ("fx", o.fx),
            ("fy", o.fy),
            ("mz", o.mz),
            ("f", o.f),
            ("t_max", o.t_max),
            ("t_mean", o.t_mean),
            ("p_fric", o.p_fric),
            ("frac_elastic", o.frac_elastic),
            ("frac_plastic", o.frac_plastic),
            ("frac_sliding", o.frac_sliding),
            ("a", o.a),
            ("b", o.b),
        ] {
            out.push((k, n, x));
        }
    }
    out
}

/// The outputs a fixture's build gave: lines `step name f64-bits-in-hex value`.
fn expected(text: &str) -> Vec<(usize, String, f64)> {
    text.lines()
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            let bits = u64::from_str_radix(f[2], 16).expect("hex bits");
            (
                f[0].parse().expect("step"),
                f[1].to_string(),
                f64::from_bits(bits),
            )
        })
        .collect()
}

/// The largest difference of a continuation from what the fixture's build gave: relative
/// to the larger magnitude for forces, moments, power and semi-axes, of the rise above the
/// bulk temperature (20 degC) for temperatures, absolute for area fractions; values below
/// 1e-6 in both (Fy and Mz of pure longitudinal creepage are rounding noise) are skipped.
fn largest_difference(got: &[(usize, &str, f64)], want: &[(usize, String, f64)]) -> f64 {
    assert_eq!(got.len(), want.len());
    let mut worst = 0.0f64;
    for ((k, n, x), (kw, nw, w)) in got.iter().zip(want) {
        assert_eq!((k, *n), (kw, nw.as_str()));
        let d = if n.starts_with("frac") {
            (x - w).abs()
        } else if n.starts_with("t_") {
            let (x, w) = (x - 20.0, w - 20.0);
            (x - w).abs() / x.abs().max(w.abs())
        } else if x.abs().max(w.abs()) < 1e-6 {
            0.0
        } else {
            (x - w).abs() / x.abs().max(w.abs())
        };
        worst = worst.max(d);
    }
    worst
}

/// The largest difference ([`largest_difference`]) of a continuation of a state of version
/// 1 to 3 from what its build gave. Those builds predate model changes that move this 8 x 3
/// case (docs/history.md: the whole-cell commit, the cold crossing, the Gauss-Legendre
/// strips and the trapezoidal dissipation): measured over the three steps, P_fric 1.25e-1,
/// the rise of T_mean 1.03e-1 and of T_max 7.9e-2, F_x and f 8.5e-2, the area fractions
/// 5.3e-2 (absolute). States of version 4 continue bit for bit.
const CHANGED_SINCE: f64 = 0.13;

#[test]
fn every_version_loads_and_continues_as_its_build_did() {
    for (version, bytes, out) in FIXTURES {
        assert_eq!(
            u32::from_le_bytes(bytes[8..12].try_into().unwrap()),
            version
        );
        let m = restored(bytes);
        // saved again in the current format, the state continues bit for bit as it does
        let again = restored(&m.save_state());
        let (a, b) = (continued(m), continued(again));
        for (x, y) in a.iter().zip(&b) {
            assert_eq!(
                x.2.to_bits(),
                y.2.to_bits(),
                "version {version}: {x:?} {y:?}"
            );
        }
        let want = expected(out);
        if version >= 4 {
            for (k, n, w) in &want {
                let x = a
                    .iter()
                    .find(|g| g.0 == *k && g.1 == *n)
                    .expect("the output")
                    .2;
                assert_eq!(x.to_bits(), w.to_bits(), "version {version}, step {k}: {n}");
            }
        } else {
            let d = largest_difference(&a, &want);
            assert!(d <= CHANGED_SINCE, "version {version}: {d}");
        }
    }
}
