//! The third body layer alone against high-pressure-torsion tests (seed Sec. 3.3, 5.1): shear stress over displacement at fixed normal stress.
//!
//! Monotonic loading of the layer at normal stress p and the reference temperature T0 (the
//! seed's HPT discs turn slowly, no frictional heating): elastic tau = u / L_e (Eq. 4.1) up to
//! tau_c1 at u_y = tau_c1 L_e, then Voce's law tau = tau_c1 + (tau_c2 - tau_c1)(1 - exp(-(u -
//! u_y)/L_p)) (Eq. 4.2 with Delta u = tau_c1 L_e as printed). Fitting these curves gives the
//! pressure coefficients and the maximum values of the material laws (seed Sec. 5.1).

use crate::fit::{fit_generic, FitResult, FreeParam};
use crate::measure::HptRow;
use crate::stats::cv_rmse_pct;
use creep_core::bristle::voce;
use creep_core::config::Config;
use creep_core::engine::layer_material;
use creep_core::error::Result;
use creep_core::params::P;

/// Model shear stress (Pa) of each HPT row.
pub fn predict(cfg: &Config, rows: &[HptRow]) -> Vec<f64> {
    let t0 = cfg.params.si(P::T0);
    rows.iter()
        .map(|r| {
            let m = layer_material(cfg, r.p, t0);
            if m.tc2 <= 0.0 {
                return 0.0;
            }
            let uy = m.tc1 * m.le;
            if r.u <= uy && m.le > 0.0 {
                r.u / m.le
            } else {
                voce(&m, r.u - uy)
            }
        })
        .collect()
}

/// CV(RMSE) of the model against HPT rows, %.
pub fn cv_rmse(cfg: &Config, rows: &[HptRow]) -> f64 {
    let meas: Vec<f64> = rows.iter().map(|r| r.tau).collect();
    cv_rmse_pct(&meas, &predict(cfg, rows))
}

/// Parameters fitted to HPT curves by default (seed Sec. 5.1 without the temperature ones).
pub fn default_free() -> Vec<P> {
    vec![P::Tc10, P::Tc20, P::Lp0, P::Tc1P, P::Tc2P]
}

/// Fits the layer's parameters to HPT curves.
pub fn fit(
    cfg: &Config,
    source: &str,
    rows: &[HptRow],
    free: &[FreeParam],
    progress: &(dyn Fn(usize) + Sync),
) -> Result<FitResult> {
    // residuals in GPa keep the problem well scaled
    let meas: Vec<f64> = rows.iter().map(|r| r.tau * 1e-9).collect();
    let model = |c: &Config| -> Result<Vec<f64>> {
        Ok(predict(c, rows).iter().map(|t| t * 1e-9).collect())
    };
    fit_generic(cfg, source, &meas, &model, free, progress)
}
