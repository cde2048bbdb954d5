//! The operating point of a contact (`Inputs`), its integral results (`Outputs`) and the fields along y = 0 (`FieldPoint`), with units.

use crate::error::{check_range, Result};

/// Speeds below this (m/s) count as standstill: no advection and no frictional heat.
pub const V_STANDSTILL: f64 = 1e-6;

/// Operating point of one contact; may change every step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inputs {
    /// Longitudinal creepage c_x = v_x/|v|, - (Eq. 4.12; positive: traction, force F_x > 0).
    pub cx: f64,
    /// Lateral creepage c_y, -.
    pub cy: f64,
    /// Spin creepage c_s, 1/m.
    pub spin: f64,
    /// Rolling (vehicle) speed v, m/s; negative: rolling backwards (the mirror image of rolling
    /// forwards; creepages are slip velocities over |v|).
    pub v: f64,
    /// Normal force F_N, N.
    pub fn_n: f64,
    /// Bulk temperature T_B, degC.
    pub t_bulk: f64,
}

impl Default for Inputs {
    fn default() -> Self {
        Inputs {
            cx: 0.0,
            cy: 0.0,
            spin: 0.0,
            v: 5.0,
            fn_n: 110e3,
            t_bulk: 20.0,
        }
    }
}

impl Inputs {
    /// Checks every input; names the field and the accepted range on error.
    pub fn validate(&self) -> Result<()> {
        check_range("cx", self.cx, -10.0, 10.0, "(-)")?;
        check_range("cy", self.cy, -10.0, 10.0, "(-)")?;
        check_range("spin", self.spin, -1e4, 1e4, "1/m")?;
        check_range("v", self.v, -1000.0, 1000.0, "m/s")?;
        check_range("F_N", self.fn_n, 0.0, 1e8, "N")?;
        check_range("T_bulk", self.t_bulk, -273.15, 2000.0, "degC")?;
        Ok(())
    }
}

/// Integral results of a step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Outputs {
    /// Longitudinal creep force F_x = int tau_x dA, N.
    pub fx: f64,
    /// Lateral creep force F_y, N.
    pub fy: f64,
    /// Spin moment M_z = int (x tau_y - y tau_x) dA, N m.
    pub mz: f64,
    /// Traction coefficient f = F_x / F_N, -.
    pub f: f64,
    /// Maximum bristle temperature, degC.
    pub t_max: f64,
    /// Area-weighted mean bristle temperature, degC.
    pub t_mean: f64,
    /// Frictional power int q dA (both bodies), W.
    pub p_fric: f64,
    /// Area fraction of elastic (adhering) bristles, -.
    pub frac_elastic: f64,
    /// Area fraction of plastically hardening bristles, -.
    pub frac_plastic: f64,
    /// Area fraction of sliding bristles (Coulomb bound or broken layer), -.
    pub frac_sliding: f64,
    /// Semi-axis in rolling direction, m.
    pub a: f64,
    /// Lateral semi-axis, m.
    pub b: f64,
    /// Maximum Hertz pressure, Pa.
    pub p0: f64,
}

impl Outputs {
    /// The outputs in declaration order: F_x, F_y, M_z, f, T_max, T_mean, P_fric, the three
    /// area fractions, a, b, p0 (the order of the state format and of the FMU's outputs).
    pub fn to_array(&self) -> [f64; 13] {
        [
            self.fx,
            self.fy,
            self.mz,
            self.f,
            self.t_max,
            self.t_mean,
            self.p_fric,
            self.frac_elastic,
            self.frac_plastic,
            self.frac_sliding,
            self.a,
            self.b,
            self.p0,
        ]
    }
}

/// One point of the fields along the strip nearest y = 0 (seed Fig. 4.9, 4.10).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldPoint {
    /// Position along x, m (leading edge at +a; at -a when rolling backwards).
    pub x: f64,
    /// Shear stress |tau|, Pa.
    pub tau: f64,
    /// Longitudinal shear stress tau_x, Pa.
    pub tau_x: f64,
    /// First critical shear stress (or Coulomb bound), Pa.
    pub tau_c1: f64,
    /// Second critical shear stress (or Coulomb bound), Pa.
    pub tau_c2: f64,
    /// Normal pressure, Pa.
    pub p: f64,
    /// Temperature, degC.
    pub t: f64,
    /// Regime: 0 elastic, 1 plastic, 2 sliding.
    pub regime: u8,
}
