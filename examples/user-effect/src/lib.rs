//! A user's own Rust effect, outside the project's source tree: an oil film on the rail weakens the third body layer; registered with creep-core at link time.
//!
//! Build an `ecf` binary and an FMU that contain it, without forking the project:
//! `bash scripts/build-fmu.sh --effects examples/user-effect` (docs/measurements.md,
//! "Effects in Rust"). A configuration then switches it on with
//! `"custom_effects": [{"name": "oil_film", "params": {"h0_um": 0.5}}]`, and `ecf fit` fits
//! its parameters like any other (`--free oil_film.h0_um`).
#![forbid(unsafe_code)]

use creep_core::custom::{CustomEffect, LocalState, OperatingPoint};
use creep_core::formula::Target;

/// An oil film of thickness h (data column `oil_um`, µm) carries part of the shear: the
/// layer's strength tau_c2 falls from its dry value to the fraction `f_min` of it,
/// tau_c2 <- tau_c2 (f_min + (1 - f_min) exp(-h / h0)).
#[derive(Debug)]
pub struct OilFilm;

impl CustomEffect for OilFilm {
    fn name(&self) -> &'static str {
        "oil_film"
    }
    fn description(&self) -> &'static str {
        "An oil film on the rail (data column 'oil_um', µm) carries part of the shear: the layer's strength tau_c2 falls exponentially with the film thickness, from its dry value to the fraction f_min of it (example of an effect in a user's own crate)."
    }
    fn target(&self) -> Target {
        Target::TauC2
    }
    fn params(&self) -> &'static [(&'static str, f64, f64, f64, &'static str)] {
        &[
            (
                "h0_um",
                1.0,
                0.01,
                100.0,
                "film thickness over which the strength falls by 1/e of its range, µm",
            ),
            (
                "f_min",
                0.3,
                0.0,
                1.0,
                "strength left under a thick film, fraction of the dry strength, -",
            ),
        ]
    }
    fn columns(&self) -> &'static [&'static str] {
        &["oil_um"]
    }
    fn factor(&self, p: &[f64], _local: &LocalState, op: &OperatingPoint) -> f64 {
        let h = op.column("oil_um").unwrap_or(0.0).max(0.0);
        p[1] + (1.0 - p[1]) * (-h / p[0]).exp()
    }
}

static OIL_FILM: OilFilm = OilFilm;
creep_core::register_effect!(OIL_FILM);

#[cfg(test)]
mod tests {
    use super::*;

    fn at(h: f64) -> f64 {
        let cols = [("oil_um".to_string(), h)];
        let op = OperatingPoint {
            v_mps: 20.0,
            fn_kn: 110.0,
            cx: 0.01,
            cy: 0.0,
            spin_per_m: 0.0,
            t_bulk_c: 20.0,
            columns: &cols,
        };
        OilFilm.factor(&[1.0, 0.3], &LocalState::default(), &op)
    }

    #[test]
    fn dry_rail_is_unchanged_and_a_thick_film_leaves_f_min() {
        assert_eq!(at(0.0), 1.0);
        assert!((at(1.0) - (0.3 + 0.7 * (-1.0f64).exp())).abs() < 1e-15);
        assert!((at(1e3) - 0.3).abs() < 1e-12);
    }

    #[test]
    fn it_is_in_the_catalogue_once_linked() {
        let names: Vec<&str> = creep_core::custom::catalogue()
            .iter()
            .map(|e| e.name())
            .collect();
        assert!(names.contains(&"oil_film"), "{names:?}");
        assert!(names.contains(&"humidity_softening"), "{names:?}");
    }
}
