//! One way to extend the material law: a [`Modifier`] scales one material function by a factor of the operating point and, where it says so, of the bristle's local state.
//!
//! Formula effects ([`crate::formula::FormulaEffect`], written in the configuration) and
//! Rust effects ([`crate::custom::CustomUse`], a [`crate::custom::CustomEffect`] linked into
//! the program) are its two kinds. A configuration holds them in one list,
//! [`crate::Config::modifiers`] ([`crate::config::AnyModifier`]); the engine evaluates them through
//! [`Modifier::factor`] (module `engine::modifiers`), the fit reaches their parameters
//! through [`Modifier::param`] and [`Modifier::set_param`]. Nothing else in the engine or the
//! fit knows which kind a modifier is.
//!
//! The factors of all modifiers of one target multiply the material function wherever the
//! engine evaluates it: tau_c1, tau_c2, L_p, L_e (Eq. 4.3, 4.4, 4.21) or mu of the Coulomb
//! bound; formula effects first, then Rust effects, each in list order.
//!
//! Users extend the law with a formula effect (configuration) or by implementing
//! [`crate::custom::CustomEffect`] in their own crate, not this trait: `Modifier` is what the
//! engine, the fit and the FMU state see of both. A third kind would implement it and add a
//! variant to [`crate::config::AnyModifier`].

use crate::error::{CreepError, Result};

/// Material function a modifier scales.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// First critical shear stress.
    TauC1,
    /// Second critical shear stress.
    TauC2,
    /// Inverted elastic stiffness of the layer.
    Le,
    /// Plasticity factor.
    Lp,
    /// Coulomb friction coefficient.
    Mu,
    /// Both layer strengths, tau_c1 and tau_c2, by the same factor: a change of the layer's
    /// strength as a whole.
    Strengths,
}

impl Target {
    /// Parses a target name.
    pub fn parse(s: &str) -> Result<Self> {
        Ok(match s {
            "tau_c1" => Target::TauC1,
            "tau_c2" => Target::TauC2,
            "L_e" => Target::Le,
            "L_p" => Target::Lp,
            "mu" => Target::Mu,
            "strengths" => Target::Strengths,
            _ => {
                return Err(CreepError::Unknown {
                    kind: "formula target".into(),
                    name: s.into(),
                    accepted: "tau_c1, tau_c2, strengths (tau_c1 and tau_c2), L_e, L_p, mu".into(),
                })
            }
        })
    }
    /// Name of the target.
    pub fn name(&self) -> &'static str {
        match self {
            Target::TauC1 => "tau_c1",
            Target::TauC2 => "tau_c2",
            Target::Le => "L_e",
            Target::Lp => "L_p",
            Target::Mu => "mu",
            Target::Strengths => "strengths",
        }
    }
    /// Multiplies the factor `f` into the per-function factors `fac` (indexed by
    /// [`Target::TauC1`] ... [`Target::Mu`] as `usize`): [`Target::Strengths`] scales both
    /// strengths.
    #[inline]
    pub fn scale(self, fac: &mut [f64; 5], f: f64) {
        match self {
            Target::Strengths => {
                fac[Target::TauC1 as usize] *= f;
                fac[Target::TauC2 as usize] *= f;
            }
            t => fac[t as usize] *= f,
        }
    }
}

/// Local state of a bristle.
#[derive(Clone, Copy, Debug, Default)]
pub struct LocalState {
    /// Normal pressure, GPa.
    pub p_gpa: f64,
    /// Temperature, degC.
    pub t_c: f64,
    /// |u|, mm.
    pub u_mm: f64,
    /// Rigid slip speed, m/s.
    pub slip_mps: f64,
}

/// Operating point of the contact.
#[derive(Clone, Copy, Debug)]
pub struct OperatingPoint<'a> {
    /// Vehicle speed, m/s: the user's operating point, negative when rolling backwards (the
    /// engine's mirrored frame is not shown to modifiers; c_x, c_y and spin likewise keep the
    /// user's signs).
    pub v_mps: f64,
    /// Normal force, kN.
    pub fn_kn: f64,
    /// Longitudinal creepage, -.
    pub cx: f64,
    /// Lateral creepage, -.
    pub cy: f64,
    /// Spin, 1/m.
    pub spin_per_m: f64,
    /// Bulk temperature of wheel and rail T_B, degC (the input of the flash temperature,
    /// seed Eq. 4.35).
    pub t_bulk_c: f64,
    /// Data columns (name, value) of the current measurement row.
    pub columns: &'a [(String, f64)],
}

impl OperatingPoint<'_> {
    /// Value of a data column.
    pub fn column(&self, name: &str) -> Option<f64> {
        self.columns
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| *v)
    }
}

/// One parameter of a modifier, as a fit sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct ModifierParam {
    /// Name (without the modifier's name).
    pub name: String,
    /// Current value (the modifier's own unit; fits show "-").
    pub value: f64,
    /// Lower bound a fit keeps (narrowed by the user where given).
    pub min: f64,
    /// Upper bound a fit keeps.
    pub max: f64,
    /// The bounds a user may narrow to (`--bound` checks against them): a Rust effect's
    /// declared bounds; a formula's current ones (narrowing a formula parameter replaces them).
    pub limits: (f64, f64),
}

/// A modifier of the material functions at an operating point (see the module).
pub trait Modifier {
    /// Name in configuration files and in parameter names (`NAME.PARAM`).
    fn name(&self) -> &str;
    /// How reports name it, e.g. "formula effect 'x' (factor '...')".
    fn describe(&self) -> String;
    /// The material function it scales.
    fn target(&self) -> Target;
    /// True if the factor depends on the bristle's local state (p, T, |u|, slip): evaluated
    /// per bristle; otherwise once per operating point.
    fn uses_local_state(&self) -> bool;
    /// Data columns it reads, in the order [`Modifier::factor`] receives their values.
    fn columns(&self) -> Vec<&str>;
    /// Number of parameters.
    fn n_params(&self) -> usize;
    /// Parameter `k` (0 <= k < [`Modifier::n_params`]).
    fn param(&self, k: usize) -> ModifierParam;
    /// Sets parameter `k` (a fit keeps it within its bounds; no check here).
    fn set_param(&mut self, k: usize, v: f64);
    /// Narrows the bounds of parameter `k` (the caller checks them against its limits).
    fn set_bounds(&mut self, k: usize, lo: f64, hi: f64);
    /// The factor (finite and >= 0 where the modifier is sensible; the engine clamps
    /// negative values and NaN to 0) at the bristle's `local` state and the operating point `op`;
    /// `cols` holds the values of [`Modifier::columns`] in their order, resolved once per
    /// operating point.
    fn factor(&self, local: &LocalState, op: &OperatingPoint, cols: &[f64]) -> f64;
}
