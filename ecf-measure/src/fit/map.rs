//! The change of variables that keeps a fitted parameter within its bounds, where a fit starts, and when a result is stuck at a bound.

/// Fractions of the interval (logistic map) from which a fit stuck at a bound that does not
/// hold its optimum, or worse than its start, is tried again; for a parameter bounded below only, the distances from the
/// bound are the start's times 10^(-1), 10 and 100.
pub const STARTS: [f64; 3] = [0.1, 0.5, 0.9];

/// A fitted value this close to a bound (fraction of the interval, or of the start's distance
/// from a lower bound) counts as stuck there.
pub(super) const NEAR: f64 = 1e-3;

#[derive(Clone, Copy, Debug)]
pub(super) enum Map {
    Identity,
    Exp { lo: f64 },
    Logistic { lo: f64, hi: f64 },
}

impl Map {
    /// Exponential map for a lower bound only (or an upper bound three orders of magnitude
    /// above the start), logistic for a finite interval, identity when unbounded. Returns the
    /// map and the value the solver starts from: the start itself, or, where the start lies on
    /// a bound or within [`NEAR`] of it (the map has no slope there, so the solver could not
    /// move), a point a hundredth of the interval inside (for a lower bound with no finite
    /// upper bound near: a hundredth of max(|lower bound|, 1) above it).
    pub(super) fn new((lo, hi): (f64, f64), start: f64) -> (Self, f64) {
        let far = |h: f64| h.is_infinite() || h >= 1e3 * start.abs().max(lo.abs()).max(1e-12);
        if lo.is_finite() && start > lo && far(hi) {
            (Map::Exp { lo }, start)
        } else if lo.is_finite() && hi.is_finite() && hi > lo {
            let w = hi - lo;
            if start <= lo && w > 1e3 * lo.abs().max(1.0) {
                // on the lower bound of a very wide interval: a hundredth of the interval
                // would be far off any value of interest
                return (Map::Exp { lo }, lo + 1e-2 * lo.abs().max(1.0));
            }
            let r = ((start - lo) / w).clamp(0.0, 1.0);
            let s = if r < NEAR {
                lo + 1e-2 * w
            } else if r > 1.0 - NEAR {
                hi - 1e-2 * w
            } else {
                start
            };
            (Map::Logistic { lo, hi }, s)
        } else if lo.is_finite() && start <= lo {
            (Map::Exp { lo }, lo + 1e-2 * lo.abs().max(1.0))
        } else {
            (Map::Identity, start)
        }
    }
    pub(super) fn to_p(self, z: f64) -> f64 {
        match self {
            Map::Identity => z,
            Map::Exp { lo } => lo + z.exp(),
            Map::Logistic { lo, hi } => lo + (hi - lo) / (1.0 + (-z).exp()),
        }
    }
    pub(super) fn to_z(self, p: f64) -> f64 {
        match self {
            Map::Identity => p,
            Map::Exp { lo } => (p - lo).max(1e-12).ln(),
            Map::Logistic { lo, hi } => {
                let r = ((p - lo) / (hi - lo)).clamp(1e-9, 1.0 - 1e-9);
                (r / (1.0 - r)).ln()
            }
        }
    }
    /// The bound `p` is stuck at, if any: on or beyond it, or within [`NEAR`] of the interval
    /// (logistic) or of the solver's start's distance `s0 - lo` (exponential).
    pub(super) fn stuck(self, p: f64, (lo, hi): (f64, f64), s0: f64) -> Option<Bound> {
        if p <= lo {
            return Some(Bound::Lower);
        }
        if p >= hi {
            return Some(Bound::Upper);
        }
        match self {
            Map::Logistic { lo, hi } => {
                let r = (p - lo) / (hi - lo);
                if r < NEAR {
                    Some(Bound::Lower)
                } else if r > 1.0 - NEAR {
                    Some(Bound::Upper)
                } else {
                    None
                }
            }
            Map::Exp { lo } => (p - lo < NEAR * (s0 - lo)).then_some(Bound::Lower),
            Map::Identity => None,
        }
    }
    /// The solver's other starts ([`STARTS`]), from the first start `s0`.
    pub(super) fn starts(self, s0: f64) -> Vec<f64> {
        match self {
            Map::Logistic { lo, hi } => STARTS.iter().map(|f| lo + f * (hi - lo)).collect(),
            Map::Exp { lo } => [0.1, 10.0, 100.0]
                .iter()
                .map(|f| lo + f * (s0 - lo))
                .collect(),
            Map::Identity => {
                let d = s0.abs().max(1.0);
                vec![s0 - d, s0 + d, s0 + 10.0 * d]
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Bound {
    Lower,
    Upper,
}

impl Bound {
    /// This bound of the interval `(lo, hi)`.
    pub(super) fn of(self, (lo, hi): (f64, f64)) -> f64 {
        match self {
            Bound::Lower => lo,
            Bound::Upper => hi,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use creep_core::params::{spec, P};

    #[test]
    fn maps_round_trip_and_respect_bounds() {
        for (id, p) in [
            (P::Tc10, 0.3),
            (P::Kq, 0.7),
            (P::Mu, 0.25),
            (P::PolKA, 0.68),
        ] {
            let (m, s0) = Map::new((spec(id).min, spec(id).max), p);
            assert_eq!(s0, p, "{id:?}: a start inside its bounds is kept");
            assert!((m.to_p(m.to_z(p)) - p).abs() < 1e-9 * p.max(1.0), "{id:?}");
            let s = spec(id);
            for z in [-50.0, 0.0, 50.0] {
                let v = m.to_p(z);
                assert!(
                    v >= s.min
                        && (v <= s.max || s.max.is_infinite() || matches!(m, Map::Exp { .. }))
                );
            }
        }
    }

    #[test]
    fn starts_on_a_bound_begin_inside_where_the_map_has_a_slope() {
        // on the lower bound of a finite interval: a hundredth of the interval inside
        let (m, s0) = Map::new((0.0, 20.0), 0.0);
        assert!(matches!(m, Map::Logistic { .. }) && (s0 - 0.2).abs() < 1e-12);
        // on the upper bound
        let (_, s0) = Map::new((-1.0, 3.0), 3.0);
        assert!((s0 - 2.96).abs() < 1e-12, "{s0}");
        // on the lower bound of a very wide interval: near the bound, not at 1e7
        let (m, s0) = Map::new((0.0, 1e9), 0.0);
        assert!(matches!(m, Map::Exp { .. }) && (s0 - 0.01).abs() < 1e-12);
        // the slope of the map at the solver's start is not zero
        for (b, s) in [((0.0, 20.0), 0.0), ((-0.01, 20.0), 0.0), ((0.0, 1e9), 0.0)] {
            let (m, s0) = Map::new(b, s);
            let z = m.to_z(s0);
            let slope = (m.to_p(z + 1e-3) - m.to_p(z)) / 1e-3;
            assert!(slope > 1e-3, "{b:?}: slope {slope}");
        }
    }
}
