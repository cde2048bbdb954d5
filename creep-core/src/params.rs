//! The parameter registry: every model parameter with name, unit, SI factor, default, bounds and meaning.
//!
//! Values are stored in the display unit that the parameter's name carries (GPa, mm,
//! µm/GPa, 1/°C, ...) and converted to SI with [`ParamSpec::to_si`] where the physics
//! uses them. One table, [`SPECS`], is the single source of truth for configuration
//! files, the CLI, the FMU's variable table and the fitting code.

use crate::error::{CreepError, Result};

/// Identifier of a model parameter (index into [`SPECS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[allow(non_camel_case_types)]
pub enum P {
    /// Coulomb friction coefficient.
    Mu,
    /// Shear modulus of wheel and rail.
    G,
    /// Poisson's ratio of wheel and rail.
    Nu,
    /// 3BL inverted elastic stiffness at full compression, room temperature.
    Le0,
    /// Pressure coefficient of L_e.
    LeP,
    /// Temperature coefficient of L_e.
    LeT,
    /// 3BL plasticity factor at full compression, room temperature.
    Lp0,
    /// Pressure coefficient of L_p.
    LpP,
    /// Temperature coefficient of L_p.
    LpT,
    /// Maximum first critical shear stress (yield stress) of the 3BL.
    Tc10,
    /// Pressure coefficient of tau_c1.
    Tc1P,
    /// Temperature coefficient of tau_c1.
    Tc1T,
    /// Maximum second critical shear stress (shear strength) of the 3BL.
    Tc20,
    /// Pressure coefficient of tau_c2.
    Tc2P,
    /// Temperature coefficient of tau_c2.
    Tc2T,
    /// Reference (room) temperature of the material laws.
    T0,
    /// Thermal conductivity of the wheel.
    LambdaW,
    /// Thermal diffusivity of the wheel.
    KappaW,
    /// Thermal conductivity of the rail.
    LambdaR,
    /// Thermal diffusivity of the rail.
    KappaR,
    /// Fraction of plastic work dissipated as heat.
    Kq,
    /// Polach: static friction coefficient.
    PolMu0,
    /// Polach: ratio of limit friction at infinite slip velocity to mu0.
    PolA,
    /// Polach: exponential friction decrease rate.
    PolB,
    /// Polach: reduction factor in the area of adhesion.
    PolKA,
    /// Polach: reduction factor in the area of slip.
    PolKS,
}

/// Description of one parameter.
#[derive(Clone, Copy, Debug)]
pub struct ParamSpec {
    /// Identifier.
    pub id: P,
    /// Name used in configuration files, the CLI, the FMU and saved states (carries the unit).
    pub name: &'static str,
    /// Value reference of the FMU variable: written here, never derived from a position; a
    /// released one never changes (fmu-crate's test `value_references` pins them).
    pub vr: u32,
    /// Display unit of the stored value.
    pub unit: &'static str,
    /// Factor from the display unit to SI.
    pub to_si: f64,
    /// Default value in the display unit.
    pub default: f64,
    /// Lower bound (display unit).
    pub min: f64,
    /// Upper bound (display unit; may be infinite).
    pub max: f64,
    /// Effect the parameter belongs to (see [`crate::effects`]).
    pub effect: &'static str,
    /// One-line physical meaning.
    pub description: &'static str,
}

const INF: f64 = f64::INFINITY;

/// The parameter table. Defaults are the seed's Tab. 4.1/4.2 set (with the sign typo of
/// tau_c1_0 corrected, model-spec §7), steel thermal data (model-spec §5) and the Polach
/// vehicle-test set (seed Sec. 3.1.1).
pub const SPECS: &[ParamSpec] = &[
    ParamSpec {
        id: P::Mu,
        name: "mu",
        vr: 100,
        unit: "-",
        to_si: 1.0,
        default: 0.25,
        min: 0.0,
        max: 2.0,
        effect: "coulomb",
        description: "Coulomb friction coefficient of the bound |tau| <= mu p (FASTSIM)",
    },
    ParamSpec {
        id: P::G,
        name: "G_GPa",
        vr: 101,
        unit: "GPa",
        to_si: 1e9,
        default: 79.3,
        min: 1.0,
        max: 1000.0,
        effect: "elastic_bodies",
        description: "shear modulus of wheel and rail (seed Sec. 5.1)",
    },
    ParamSpec {
        id: P::Nu,
        name: "nu",
        vr: 102,
        unit: "-",
        to_si: 1.0,
        default: 0.28,
        min: 0.0,
        max: 0.5,
        effect: "elastic_bodies",
        description: "Poisson's ratio of wheel and rail",
    },
    ParamSpec {
        id: P::Le0,
        name: "L_e_0_um_per_GPa",
        vr: 103,
        unit: "um/GPa",
        to_si: 1e-6 / 1e9,
        default: 0.2522,
        min: 0.0,
        max: 1e6,
        effect: "layer_elasticity",
        description: "minimum inverted elastic stiffness of the 3BL (Eq. 4.4)",
    },
    ParamSpec {
        id: P::LeP,
        name: "L_e_p_per_GPa",
        vr: 104,
        unit: "1/GPa",
        to_si: 1e-9,
        default: INF,
        min: 0.0,
        max: INF,
        effect: "pressure_dependence",
        description: "pressure coefficient of L_e; inf = no pressure dependence (Eq. 4.4)",
    },
    ParamSpec {
        id: P::LeT,
        name: "L_e_T_per_C",
        vr: 105,
        unit: "1/degC",
        to_si: 1.0,
        default: 0.0,
        min: 0.0,
        max: 10.0,
        effect: "temperature",
        description: "temperature coefficient of L_e (Eq. 4.4)",
    },
    ParamSpec {
        id: P::Lp0,
        name: "L_p_0_mm",
        vr: 106,
        unit: "mm",
        to_si: 1e-3,
        default: 0.25,
        min: 1e-9,
        max: 1e3,
        effect: "voce_plasticity",
        description:
            "minimum plasticity factor: displacement scale of Voce hardening (Eq. 4.2, 4.4)",
    },
    ParamSpec {
        id: P::LpP,
        name: "L_p_p_per_GPa",
        vr: 107,
        unit: "1/GPa",
        to_si: 1e-9,
        default: 1.0,
        min: 0.0,
        max: INF,
        effect: "pressure_dependence",
        description: "pressure coefficient of L_p (Eq. 4.4)",
    },
    ParamSpec {
        id: P::LpT,
        name: "L_p_T_per_C",
        vr: 108,
        unit: "1/degC",
        to_si: 1.0,
        default: 0.0025,
        min: 0.0,
        max: 10.0,
        effect: "temperature",
        description: "temperature coefficient of L_p (Eq. 4.4)",
    },
    ParamSpec {
        id: P::Tc10,
        name: "tau_c1_0_GPa",
        vr: 109,
        unit: "GPa",
        to_si: 1e9,
        default: 0.3,
        min: 0.0,
        max: 1e4,
        effect: "voce_plasticity",
        description: "maximum first critical shear stress (yield stress) of the 3BL (Eq. 4.3)",
    },
    ParamSpec {
        id: P::Tc1P,
        name: "tau_c1_p_per_GPa",
        vr: 110,
        unit: "1/GPa",
        to_si: 1e-9,
        default: 1.0,
        min: 0.0,
        max: INF,
        effect: "pressure_dependence",
        description: "pressure coefficient of tau_c1 (Eq. 4.3)",
    },
    ParamSpec {
        id: P::Tc1T,
        name: "tau_c1_T_per_C",
        vr: 111,
        unit: "1/degC",
        to_si: 1.0,
        default: 0.0025,
        min: 0.0,
        max: 10.0,
        effect: "temperature",
        description: "temperature coefficient of tau_c1 (Eq. 4.3)",
    },
    ParamSpec {
        id: P::Tc20,
        name: "tau_c2_0_GPa",
        vr: 112,
        unit: "GPa",
        to_si: 1e9,
        default: 1.1,
        min: 0.0,
        max: 1e4,
        effect: "voce_plasticity",
        description: "maximum second critical shear stress (shear strength) of the 3BL (Eq. 4.3)",
    },
    ParamSpec {
        id: P::Tc2P,
        name: "tau_c2_p_per_GPa",
        vr: 113,
        unit: "1/GPa",
        to_si: 1e-9,
        default: 1.0,
        min: 0.0,
        max: INF,
        effect: "pressure_dependence",
        description: "pressure coefficient of tau_c2 (Eq. 4.3)",
    },
    ParamSpec {
        id: P::Tc2T,
        name: "tau_c2_T_per_C",
        vr: 114,
        unit: "1/degC",
        to_si: 1.0,
        default: 0.0025,
        min: 0.0,
        max: 10.0,
        effect: "temperature",
        description: "temperature coefficient of tau_c2 (Eq. 4.3)",
    },
    ParamSpec {
        id: P::T0,
        name: "T0_C",
        vr: 115,
        unit: "degC",
        to_si: 1.0,
        default: 20.0,
        min: -100.0,
        max: 1000.0,
        effect: "temperature",
        description: "reference (room) temperature T0 of the material laws (Eq. 4.3, 4.4)",
    },
    ParamSpec {
        id: P::LambdaW,
        name: "lambda_w_W_per_mK",
        vr: 116,
        unit: "W/(m K)",
        to_si: 1.0,
        default: 50.0,
        min: 1e-3,
        max: 1e4,
        effect: "temperature",
        description: "thermal conductivity of the wheel (Eq. 4.31, 4.35)",
    },
    ParamSpec {
        id: P::KappaW,
        name: "kappa_w_mm2_per_s",
        vr: 117,
        unit: "mm^2/s",
        to_si: 1e-6,
        default: 14.0,
        min: 1e-3,
        max: 1e4,
        effect: "temperature",
        description: "thermal diffusivity of the wheel (Eq. 4.31, 4.35)",
    },
    ParamSpec {
        id: P::LambdaR,
        name: "lambda_r_W_per_mK",
        vr: 118,
        unit: "W/(m K)",
        to_si: 1.0,
        default: 50.0,
        min: 1e-3,
        max: 1e4,
        effect: "temperature",
        description: "thermal conductivity of the rail (Eq. 4.31)",
    },
    ParamSpec {
        id: P::KappaR,
        name: "kappa_r_mm2_per_s",
        vr: 119,
        unit: "mm^2/s",
        to_si: 1e-6,
        default: 14.0,
        min: 1e-3,
        max: 1e4,
        effect: "temperature",
        description: "thermal diffusivity of the rail (Eq. 4.31)",
    },
    ParamSpec {
        id: P::Kq,
        name: "k_q",
        vr: 120,
        unit: "-",
        to_si: 1.0,
        default: 1.0,
        min: 0.0,
        max: 1.0,
        effect: "temperature",
        description: "fraction of plastic work dissipated as heat (Eq. 4.22)",
    },
    ParamSpec {
        id: P::PolMu0,
        name: "polach_mu0",
        vr: 121,
        unit: "-",
        to_si: 1.0,
        default: 0.35,
        min: 0.0,
        max: 2.0,
        effect: "polach",
        description: "Polach: maximum (static) friction coefficient mu0",
    },
    ParamSpec {
        id: P::PolA,
        name: "polach_A",
        vr: 122,
        unit: "-",
        to_si: 1.0,
        default: 0.3,
        min: 0.0,
        max: 1.0,
        effect: "polach",
        description: "Polach: A = mu_inf/mu0, friction at infinite slip velocity relative to mu0",
    },
    ParamSpec {
        id: P::PolB,
        name: "polach_B_s_per_m",
        vr: 123,
        unit: "s/m",
        to_si: 1.0,
        default: 0.7,
        min: 0.0,
        max: 100.0,
        effect: "polach",
        description: "Polach: rate B of the exponential friction decrease with slip velocity",
    },
    ParamSpec {
        id: P::PolKA,
        name: "polach_kA",
        vr: 124,
        unit: "-",
        to_si: 1.0,
        default: 0.68,
        min: 0.0,
        max: 1.0,
        effect: "polach",
        description: "Polach: reduction factor k_A in the area of adhesion",
    },
    ParamSpec {
        id: P::PolKS,
        name: "polach_kS",
        vr: 125,
        unit: "-",
        to_si: 1.0,
        default: 0.14,
        min: 0.0,
        max: 1.0,
        effect: "polach",
        description: "Polach: reduction factor k_S in the area of slip (k_S <= k_A)",
    },
];

/// Number of parameters.
pub const N_PARAMS: usize = 26;

/// Returns the spec of a parameter.
pub fn spec(id: P) -> &'static ParamSpec {
    &SPECS[id as usize]
}

/// Finds a parameter by its name.
pub fn by_name(name: &str) -> Option<P> {
    SPECS.iter().find(|s| s.name == name).map(|s| s.id)
}

/// Plausible physical range of a parameter (display unit): values the seed's tables
/// (Tab. 4.1, 5.2, 5.4: the presets), its measurements and steel data make credible,
/// widened generously. A fitted value outside it is not refused but warned about.
pub fn plausible(id: P) -> (f64, f64) {
    match id {
        P::Mu => (0.02, 0.8),
        P::G => (60.0, 100.0),
        P::Nu => (0.2, 0.35),
        P::Le0 => (0.005, 10.0),
        P::LeP => (0.1, INF),
        P::LeT => (0.0, 0.1),
        P::Lp0 => (1e-3, 5.0),
        P::LpP => (0.0, 500.0),
        P::LpT => (0.0, 0.1),
        P::Tc10 => (0.005, 1.5),
        P::Tc1P => (0.0, 20.0),
        P::Tc1T => (0.0, 0.1),
        P::Tc20 => (0.02, 3.0),
        P::Tc2P => (0.0, 20.0),
        P::Tc2T => (0.0, 0.1),
        P::T0 => (-40.0, 60.0),
        P::LambdaW | P::LambdaR => (10.0, 100.0),
        P::KappaW | P::KappaR => (3.0, 30.0),
        P::Kq => (0.5, 1.0),
        P::PolMu0 => (0.03, 0.8),
        P::PolA => (0.05, 1.0),
        P::PolB => (0.0, 5.0),
        P::PolKA => (0.05, 1.0),
        P::PolKS => (0.005, 1.0),
    }
}

/// A full set of parameter values, in display units, with the bounds a fit may use (the
/// registry's, or narrower ones the user gave).
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    values: [f64; N_PARAMS],
    lo: [f64; N_PARAMS],
    hi: [f64; N_PARAMS],
}

impl Default for Params {
    fn default() -> Self {
        let mut values = [0.0; N_PARAMS];
        let mut lo = [0.0; N_PARAMS];
        let mut hi = [0.0; N_PARAMS];
        for s in SPECS {
            values[s.id as usize] = s.default;
            lo[s.id as usize] = s.min;
            hi[s.id as usize] = s.max;
        }
        Params { values, lo, hi }
    }
}

impl Params {
    /// Value in the display unit.
    pub fn get(&self, id: P) -> f64 {
        self.values[id as usize]
    }

    /// Value in SI units.
    pub fn si(&self, id: P) -> f64 {
        let v = self.values[id as usize];
        v * spec(id).to_si
    }

    /// Sets a value (display unit), checking its bounds. NaN is rejected; `max` may be infinite.
    pub fn set(&mut self, id: P, value: f64) -> Result<()> {
        let s = spec(id);
        let (lo, hi) = self.bounds(id);
        if value.is_nan() || value < lo || value > hi || (value.is_infinite() && hi.is_finite()) {
            return Err(CreepError::OutOfRange {
                field: s.name.to_string(),
                value,
                expected: format!("must be within [{lo}, {hi}] {} ({})", s.unit, s.description),
            });
        }
        self.values[id as usize] = value;
        Ok(())
    }

    /// Bounds a fit keeps the parameter in (display unit).
    pub fn bounds(&self, id: P) -> (f64, f64) {
        (self.lo[id as usize], self.hi[id as usize])
    }

    /// True if the bounds are narrower than the registry's.
    pub fn narrowed(&self, id: P) -> bool {
        let s = spec(id);
        self.bounds(id) != (s.min, s.max)
    }

    /// Narrows the bounds of a parameter for fitting: `lo < hi`, both within the registry's
    /// bounds, and the current value inside.
    pub fn set_bounds(&mut self, id: P, lo: f64, hi: f64) -> Result<()> {
        let s = spec(id);
        if lo.is_nan() || hi.is_nan() || lo >= hi || lo < s.min || hi > s.max {
            return Err(CreepError::OutOfRange {
                field: format!("bounds of {}", s.name),
                value: if lo.is_nan() || lo < s.min || lo >= hi {
                    lo
                } else {
                    hi
                },
                expected: format!(
                    "need min < max within the registry's bounds [{}, {}] {}",
                    s.min, s.max, s.unit
                ),
            });
        }
        let v = self.get(id);
        if v < lo || v > hi {
            return Err(CreepError::OutOfRange {
                field: s.name.to_string(),
                value: v,
                expected: format!(
                    "the value must lie within its bounds [{lo}, {hi}] {}",
                    s.unit
                ),
            });
        }
        self.lo[id as usize] = lo;
        self.hi[id as usize] = hi;
        Ok(())
    }

    /// Sets a value by name.
    pub fn set_by_name(&mut self, name: &str, value: f64) -> Result<()> {
        let id = by_name(name).ok_or_else(|| CreepError::Unknown {
            kind: "parameter".into(),
            name: name.into(),
            accepted: SPECS.iter().map(|s| s.name).collect::<Vec<_>>().join(", "),
        })?;
        self.set(id, value)
    }

    /// All values as (name, value) pairs in table order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        SPECS
            .iter()
            .map(move |s| (s.name, self.values[s.id as usize]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_indexed_by_id() {
        assert_eq!(SPECS.len(), N_PARAMS);
        for (i, s) in SPECS.iter().enumerate() {
            assert_eq!(s.id as usize, i, "{} out of order", s.name);
            assert!(
                s.default >= s.min && s.default <= s.max,
                "{} default out of bounds",
                s.name
            );
        }
    }

    #[test]
    fn set_rejects_out_of_bounds_and_nan() {
        let mut p = Params::default();
        assert!(p.set(P::Nu, 0.7).is_err());
        assert!(p.set(P::Mu, f64::NAN).is_err());
        assert!(p.set(P::LeP, f64::INFINITY).is_ok());
        assert!(p.set(P::Mu, f64::INFINITY).is_err());
        assert!(p.set_by_name("no_such", 1.0).is_err());
        p.set_by_name("tau_c1_0_GPa", 0.5).unwrap();
        assert!((p.si(P::Tc10) - 0.5e9).abs() < 1.0);
    }
}
