//! The plain C FASTSIM reference of the benchmarks, and the contact data it needs from creep-core.

#![warn(clippy::too_many_lines)] // at most 150 lines a function (clippy.toml)

use creep_core::params::P;
use creep_core::{engine, kalker, Config, Result};

extern "C" {
    fn fastsim_ref(
        nx: i32,
        ny: i32,
        a: f64,
        b: f64,
        p0: f64,
        mu: f64,
        lx: f64,
        ly: f64,
        ls: f64,
        cx: f64,
        cy: f64,
        cs: f64,
        fy_out: *mut f64,
    ) -> f64;
}

/// Geometry and flexibilities of an elliptic contact at a normal force, as FASTSIM needs them.
#[derive(Clone, Copy, Debug)]
pub struct Contact {
    /// Semi-axes a (rolling), b, m.
    pub a: f64,
    /// Lateral semi-axis, m.
    pub b: f64,
    /// Peak Hertz pressure, Pa.
    pub p0: f64,
    /// Coulomb friction coefficient, -.
    pub mu: f64,
    /// Kalker's flexibilities L_x, L_y (m/Pa) and L_s (m^2/Pa... per 1/m spin).
    pub flex: (f64, f64, f64),
}

impl Contact {
    /// The contact of a configuration (elliptic geometry) at normal force `fn_n` (N).
    pub fn new(cfg: &Config, fn_n: f64) -> Result<Self> {
        let patch = engine::patch_for(cfg, fn_n)?;
        let c = kalker::coefficients(patch.a, patch.b, cfg.params.si(P::Nu))?;
        Ok(Contact {
            a: patch.a,
            b: patch.b,
            p0: patch.p0,
            mu: cfg.params.si(P::Mu),
            flex: kalker::flexibilities(patch.a, patch.b, cfg.params.si(P::G), &c),
        })
    }

    /// Steady forces (F_x, F_y) in N from the C reference on an nx x ny grid for creepages
    /// c_x, c_y (-) and spin c_s (1/m).
    pub fn c_fastsim(&self, nx: usize, ny: usize, cx: f64, cy: f64, cs: f64) -> (f64, f64) {
        let mut fy = 0.0;
        let (lx, ly, ls) = self.flex;
        // SAFETY: fastsim_ref reads only its scalar arguments and writes one f64 through
        // `fy_out`, which points to a live local; nx, ny are small positive grid sizes.
        let fx = unsafe {
            fastsim_ref(
                nx as i32, ny as i32, self.a, self.b, self.p0, self.mu, lx, ly, ls, cx, cy, cs,
                &mut fy,
            )
        };
        (fx, fy)
    }
}
