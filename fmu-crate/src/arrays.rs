//! The FMI 3.0 FMU's own variables: the independent variable `time`, the structural parameter `n_field` and the field arrays along the strip at y = 0, sampled from the engine's field.
//!
//! The engine gives the field of the strip nearest y = 0 at its nodes (one per bristle cell;
//! nx or nx + 1 of them, as the strip's phase places them), from the leading edge to the
//! trailing edge. The arrays hold `n_field` points equally spaced from the first node to the
//! last: x, pressure, tau_x, tau_c2 and temperature interpolated linearly between the two
//! nodes around each point, the regime code of the nearest node. With `n_field` equal to the
//! node count the points are the nodes themselves, bit for bit.

use crate::vars::{default_config, Kind};
use creep_core::FieldPoint;

/// Value reference of the independent variable `time`, s.
pub const VR_TIME: u32 = 0;
/// Value reference of the structural parameter `n_field`.
pub const VR_N_FIELD: u32 = 200;
/// Largest `n_field` (the largest grid's nx).
pub const N_FIELD_MAX: u64 = 2000;

/// One field array of the FMI 3.0 FMU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// Position along x, m.
    X,
    /// Normal pressure, Pa.
    P,
    /// Longitudinal shear stress, Pa.
    TauX,
    /// Strength (second critical shear stress), Pa.
    TauC2,
    /// Temperature, degC.
    T,
    /// Regime code.
    Regime,
}

/// A field array's declaration: name, value reference, type, unit and description.
#[derive(Clone, Copy, Debug)]
pub struct ArrayVar {
    /// Which field.
    pub field: Field,
    /// Name in modelDescription.xml.
    pub name: &'static str,
    /// Value reference.
    pub vr: u32,
    /// Base type: Real (Float64) or Integer (Int32).
    pub kind: Kind,
    /// Unit (a `Unit` of the UnitDefinitions), none for the regime code.
    pub unit: Option<&'static str>,
    /// One-line description.
    pub description: &'static str,
}

const ALONG: &str = "along the strip at y = 0, n_field points equally spaced from the leading node (index 0) to the trailing node";

/// The field arrays, in the order of modelDescription.xml.
pub const ARRAYS: [ArrayVar; 6] = [
    ArrayVar {
        field: Field::X,
        name: "field_x",
        vr: 201,
        kind: Kind::Real,
        unit: Some("m"),
        description: "position x of each field point (leading edge at +a, at -a when rolling backwards)",
    },
    ArrayVar {
        field: Field::P,
        name: "field_p",
        vr: 202,
        kind: Kind::Real,
        unit: Some("Pa"),
        description: "normal pressure at each field point",
    },
    ArrayVar {
        field: Field::TauX,
        name: "field_tau_x",
        vr: 203,
        kind: Kind::Real,
        unit: Some("Pa"),
        description: "longitudinal shear stress tau_x at each field point",
    },
    ArrayVar {
        field: Field::TauC2,
        name: "field_tau_c2",
        vr: 204,
        kind: Kind::Real,
        unit: Some("Pa"),
        description: "strength tau_c2 (second critical shear stress, or the Coulomb bound) at each field point; -1 where it has no limit",
    },
    ArrayVar {
        field: Field::T,
        name: "field_T",
        vr: 205,
        kind: Kind::Real,
        unit: Some("degC"),
        description: "temperature of the surface at each field point",
    },
    ArrayVar {
        field: Field::Regime,
        name: "field_regime",
        vr: 206,
        kind: Kind::Integer,
        unit: None,
        description: "regime of the bristle nearest each field point: 0 elastic, 1 plastic, 2 sliding; -1 for Polach (no bristle grid)",
    },
];

impl ArrayVar {
    /// The description as modelDescription.xml gives it (where the points lie appended).
    pub fn full_description(&self) -> String {
        format!("{}; {ALONG}; computed when read", self.description)
    }
}

/// The array of a value reference, if it is one.
pub fn array_of(vr: u32) -> Option<&'static ArrayVar> {
    ARRAYS.iter().find(|a| a.vr == vr)
}

/// Start value of `n_field`: the presets' cells per strip.
pub fn n_field_start() -> u64 {
    default_config().grid.nx as u64
}

/// Description of `n_field`.
pub fn n_field_description() -> String {
    format!("points of the field arrays (field_x, field_p, field_tau_x, field_tau_c2, field_T, field_regime) along the strip at y = 0; equal to the node count of the strip (nx or nx + 1) they are its nodes, else the nodes interpolated linearly (the presets' grid has {} cells per strip)", n_field_start())
}

/// The field arrays at `n` points.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sampled {
    /// Position, m.
    pub x: Vec<f64>,
    /// Pressure, Pa.
    pub p: Vec<f64>,
    /// tau_x, Pa.
    pub tau_x: Vec<f64>,
    /// tau_c2, Pa (-1: no limit).
    pub tau_c2: Vec<f64>,
    /// Temperature, degC.
    pub t: Vec<f64>,
    /// Regime code (-1: no grid).
    pub regime: Vec<i32>,
}

impl Sampled {
    /// The Float64 values of an array (None for the regime).
    pub fn real(&self, f: Field) -> Option<&[f64]> {
        match f {
            Field::X => Some(&self.x),
            Field::P => Some(&self.p),
            Field::TauX => Some(&self.tau_x),
            Field::TauC2 => Some(&self.tau_c2),
            Field::T => Some(&self.t),
            Field::Regime => None,
        }
    }
}

/// Samples the nodes `points` (leading to trailing) at `n` equally spaced points; without
/// nodes (Polach) x spans +a to -a and the other fields are 0, the regime -1.
pub fn sample(points: Option<&[FieldPoint]>, a: f64, n: usize) -> Sampled {
    let mut s = Sampled::default();
    let pts = match points {
        Some(p) if !p.is_empty() => p,
        _ => {
            for k in 0..n {
                let u = if n > 1 {
                    k as f64 / (n - 1) as f64
                } else {
                    0.0
                };
                s.x.push(a - 2.0 * a * u);
            }
            s.p = vec![0.0; n];
            s.tau_x = vec![0.0; n];
            s.tau_c2 = vec![0.0; n];
            s.t = vec![0.0; n];
            s.regime = vec![-1; n];
            return s;
        }
    };
    let m = pts.len();
    let strength = |x: f64| if x.is_finite() { x } else { -1.0 };
    for k in 0..n {
        // the position in node indices: exactly k when n equals the node count
        let pos = if n > 1 {
            (k * (m - 1)) as f64 / (n - 1) as f64
        } else {
            0.0
        };
        let i = (pos.floor() as usize).min(m - 1);
        let w = pos - i as f64;
        let (a0, a1) = (&pts[i], &pts[(i + 1).min(m - 1)]);
        let lerp = |u: f64, v: f64| if w == 0.0 { u } else { u + w * (v - u) };
        s.x.push(lerp(a0.x, a1.x));
        s.p.push(lerp(a0.p, a1.p));
        s.tau_x.push(lerp(a0.tau_x, a1.tau_x));
        let (c0, c1) = (strength(a0.tau_c2), strength(a1.tau_c2));
        s.tau_c2.push(if c0 < 0.0 || c1 < 0.0 {
            -1.0
        } else {
            lerp(c0, c1)
        });
        s.t.push(lerp(a0.t, a1.t));
        s.regime
            .push(i32::from(if w < 0.5 { a0.regime } else { a1.regime }));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(x: f64, r: u8) -> FieldPoint {
        FieldPoint {
            x,
            tau: 0.0,
            tau_x: 10.0 * x,
            tau_c1: 0.0,
            tau_c2: if r == 2 { f64::INFINITY } else { 5.0 },
            p: 100.0 * x,
            t: 20.0 + x,
            regime: r,
        }
    }

    #[test]
    fn as_many_points_as_nodes_are_the_nodes_and_others_interpolate() {
        let nodes: Vec<FieldPoint> = (0..5)
            .map(|k| node(0.4 - 0.2 * k as f64, (k % 2) as u8))
            .collect();
        let s = sample(Some(&nodes), 0.4, 5);
        for (k, n) in nodes.iter().enumerate() {
            assert_eq!(s.x[k].to_bits(), n.x.to_bits());
            assert_eq!(s.p[k].to_bits(), n.p.to_bits());
            assert_eq!(s.regime[k], i32::from(n.regime));
        }
        let s = sample(Some(&nodes), 0.4, 9);
        assert_eq!(s.x.len(), 9);
        // the midpoint between nodes 0 and 1
        assert!((s.x[1] - 0.3).abs() < 1e-15 && (s.p[1] - 30.0).abs() < 1e-12);
        assert_eq!((s.x[0], s.x[8]), (0.4, nodes[4].x));
    }

    #[test]
    fn no_limit_is_minus_one_and_no_grid_is_regime_minus_one() {
        let nodes = [node(0.1, 2), node(-0.1, 0)];
        let s = sample(Some(&nodes), 0.1, 3);
        assert_eq!(s.tau_c2, vec![-1.0, -1.0, 5.0]);
        let s = sample(None, 0.01, 3);
        assert_eq!(s.x, vec![0.01, 0.0, -0.01]);
        assert_eq!(s.regime, vec![-1; 3]);
    }
}
