//! Shared helpers of the scenario tests.
#![allow(dead_code)]

use creep_core::{Config, Effect, Grid, Inputs, Model, Outputs};

/// Seed's Vectron operating point (Tab. 4.1): F_N = 110 kN, a = 7.63 mm, b = 7.88 mm.
pub fn vectron(cx: f64, v: f64) -> Inputs {
    Inputs {
        cx,
        v,
        fn_n: 110e3,
        ..Inputs::default()
    }
}

pub fn steady(cfg: &Config, i: &Inputs) -> Outputs {
    Model::new(cfg).expect("model").steady(i).expect("steady")
}

pub fn f_of(cfg: &Config, cx: f64, v: f64) -> f64 {
    steady(cfg, &vectron(cx, v)).f
}

pub fn preset(name: &str) -> Config {
    Config::preset(name).expect("preset")
}

pub fn without(mut cfg: Config, e: Effect) -> Config {
    cfg.effects.remove(e);
    cfg
}

pub fn with_grid(mut cfg: Config, nx: usize, ny: usize) -> Config {
    cfg.grid = Grid { nx, ny };
    cfg
}

/// `cfg` with the scheme `s` in place of its own (ECF's default is `cells-ho`).
pub fn with_scheme(mut cfg: Config, s: creep_core::engine::Scheme) -> Config {
    cfg.scheme = s;
    cfg
}

/// Contact and grid of the reference FASTSIM.
pub struct RefCase {
    pub a: f64,
    pub b: f64,
    pub fn_n: f64,
    pub mu: f64,
    pub lx: f64,
    pub ly: f64,
    pub nx: usize,
    pub ny: usize,
}

/// Independent textbook FASTSIM (Kalker 1982) on the same strips, for comparisons: strips at
/// eta_j = -1 + (j + 1/2) 2/ny, nx cells per strip, elliptic bound mu p at the cell ends (the
/// last one half a cell inside the trailing edge), trapezoidal rule. Returns (F_x, F_y) in N.
pub fn reference_fastsim(r: &RefCase, cx: f64, cy: f64) -> (f64, f64) {
    let RefCase {
        a,
        b,
        fn_n,
        mu,
        lx,
        ly,
        nx,
        ny,
    } = *r;
    let p0 = 3.0 * fn_n / (2.0 * std::f64::consts::PI * a * b);
    let (mut fx, mut fy) = (0.0, 0.0);
    for j in 0..ny {
        let eta = -1.0 + (j as f64 + 0.5) * 2.0 / ny as f64;
        let l = (1.0 - eta * eta).sqrt();
        let dx = 2.0 * l * a / nx as f64;
        let (mut tx, mut ty) = (0.0f64, 0.0f64);
        let mut sx = 0.0;
        let mut sy = 0.0;
        for k in 1..=nx {
            let x = (l * a - k as f64 * dx).max(-l * a + 0.5 * dx);
            let r = (x / a).powi(2) + eta * eta;
            let p = if r < 1.0 { p0 * (1.0 - r).sqrt() } else { 0.0 };
            tx += dx * cx / lx;
            ty += dx * cy / ly;
            let n = (tx * tx + ty * ty).sqrt();
            if n > mu * p {
                let s = if n > 0.0 { mu * p / n } else { 0.0 };
                tx *= s;
                ty *= s;
            }
            let w = if k == nx { 0.5 } else { 1.0 };
            sx += w * tx * dx;
            sy += w * ty * dx;
        }
        fx += sx * b * 2.0 / ny as f64;
        fy += sy * b * 2.0 / ny as f64;
    }
    (fx, fy)
}
