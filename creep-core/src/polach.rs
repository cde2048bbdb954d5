//! Polach's closed-form creep force model (Polach 1999, 2005; model-spec §8), a baseline.

use crate::config::Config;
use crate::engine::{patch_for, Inputs, Outputs};
use crate::error::Result;
use crate::kalker;
use crate::params::P;
use std::f64::consts::PI;

/// Polach's creep force for the operating point `i` and configuration `cfg`.
///
/// mu = mu0 ((1 - A) exp(-B w) + A), w = s v the slip velocity (s the creepage magnitude),
/// eps = pi G a b c_jj s / (4 F_N mu), c_jj = sqrt((C11 cx/s)^2 + (C22 cy/s)^2),
/// F = 2 F_N mu / pi (k_A eps / (1 + (k_A eps)^2) + arctan(k_S eps)), split along the
/// creepage direction. Spin is not part of this form and is ignored. The seed's
/// parameter set (Sec. 3.1.1) is the preset `polach`.
pub fn polach(cfg: &Config, i: &Inputs) -> Result<Outputs> {
    i.validate()?;
    if i.fn_n <= 0.0 {
        return Ok(Outputs::unloaded(i.t_bulk));
    }
    let p = &cfg.params;
    let patch = patch_for(cfg, i.fn_n)?;
    let (a, b) = (patch.a, patch.b);
    let (ka, kb) = if patch.line { (a, 1e6 * a) } else { (a, b) };
    let c = kalker::coefficients(ka, kb, p.si(P::Nu))?;
    let s = (i.cx * i.cx + i.cy * i.cy).sqrt();
    // the loaded patch; the forces, power and regime fractions are set below (M_z and the
    // plastic fraction stay 0: spin and plasticity are not in this form)
    let mut out = Outputs {
        a,
        b,
        p0: patch.p0,
        ..Outputs::unloaded(i.t_bulk)
    };
    if s <= 0.0 {
        // no creepage: no force, every bristle adheres
        return Ok(out);
    }
    // slip velocity: creepages are slip velocities over |v| (v < 0 rolls backwards, the
    // mirror image, with the same forces for the same creepages: spin is not in this form)
    let w = s * i.v.abs();
    let mu = p.si(P::PolMu0) * ((1.0 - p.si(P::PolA)) * (-p.si(P::PolB) * w).exp() + p.si(P::PolA));
    let cjj = ((c.c11 * i.cx / s).powi(2) + (c.c22 * i.cy / s).powi(2)).sqrt();
    let eps = PI * p.si(P::G) * a * b * cjj * s / (4.0 * i.fn_n * mu.max(1e-12));
    let (k_a, k_s) = (p.si(P::PolKA), p.si(P::PolKS));
    let f = 2.0 * i.fn_n * mu / PI * (k_a * eps / (1.0 + (k_a * eps).powi(2)) + (k_s * eps).atan());
    out.fx = f * i.cx / s;
    out.fy = f * i.cy / s;
    out.f = out.fx / i.fn_n;
    out.p_fric = f * w;
    // adhesion area fraction of Polach's derivation: the adhesion zone length shrinks as 1/(1 + eps)
    let adh = 1.0 / (1.0 + eps);
    out.frac_elastic = adh;
    out.frac_sliding = 1.0 - adh;
    Ok(out)
}
