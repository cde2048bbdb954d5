//! The catalogue of switchable physical effects of the bristle engine: one row an effect, with its name, physical description, parameters and what the diagnosis of measurements needs.

use crate::error::{CreepError, Result};
use crate::params::P;
use serde::{Deserialize, Serialize};

/// A switchable physical effect of the bristle (brush) engine.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Effect {
    /// Coulomb bound |tau| <= mu p (FASTSIM).
    Coulomb,
    /// Elastic compliance L_e of the third body layer.
    LayerElasticity,
    /// Elasto-plastic 3BL with Voce hardening between tau_c1 and tau_c2.
    VocePlasticity,
    /// Normal-stress dependence of the 3BL material functions.
    PressureDependence,
    /// Flash temperature and thermal softening of the 3BL.
    Temperature,
    /// Time-dependent (transient) bristle grid.
    Transient,
    /// Elastic unloading with stored hardening (incremental plasticity).
    ElasticUnloading,
    /// Flash temperature over the wheel surface's own time in the contact (wheel slide).
    SurfaceTimeFlash,
}

/// Which measured data can show an effect, so that the diagnosis (ecf-measure) tries adding
/// it: what the effect needs of the data to act on them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Applies {
    /// Never a candidate: a model of its own rather than an addition to the layer (FASTSIM's
    /// Coulomb bound replaces the layer strengths).
    Never,
    /// Any data, steady curves included.
    Always,
    /// Time series only (rows with a time column): the effect acts between time steps, so
    /// steady rows cannot show it.
    TimeSeries,
    /// Rows that slide (|1 + c_x| < 0.5) under a configuration with the effect `temperature`:
    /// elsewhere the effect changes the flash temperature too little to be seen.
    WheelSlide,
}

impl Applies {
    /// True if the effect can act on data with these properties: `on`, the configuration's
    /// effects; `time_series`, some row has a time; `sliding`, some row has |1 + c_x| < 0.5.
    pub fn holds(self, on: EffectSet, time_series: bool, sliding: bool) -> bool {
        match self {
            Applies::Never => false,
            Applies::Always => true,
            Applies::TimeSeries => time_series,
            Applies::WheelSlide => sliding && on.has(Effect::Temperature),
        }
    }
}

/// Catalogue entry of an effect: everything the program knows about it besides its physics.
#[derive(Clone, Copy, Debug)]
pub struct EffectInfo {
    /// The effect.
    pub effect: Effect,
    /// Name in configuration files, the FMU (`effect_<name>`) and saved states.
    pub name: &'static str,
    /// Value reference of the FMU's switch `effect_<name>`: written here, never derived from
    /// a position; a released one never changes (fmu-crate's test `value_references`).
    pub vr: u32,
    /// One-paragraph physical description.
    pub description: &'static str,
    /// Parameters the effect uses.
    pub params: &'static [P],
    /// Parameters a fit frees when the diagnosis adds the effect to a configuration (a subset
    /// of `params`; empty: the effect brings nothing to fit).
    pub fit: &'static [P],
    /// Measurement variables whose residual correlation is evidence for the effect (the
    /// names of ecf-measure's residual correlations: `cx`, `slip_velocity_mps`,
    /// `frictional_power_W`, `model_T_max_C`, `v_mps`, `fn_kN`, `p0_MPa`, `dcx_dt_per_s`).
    pub signature: &'static [&'static str],
    /// Which measured data can show it ([`Applies`]).
    pub applies: Applies,
}

/// All effects with their descriptions.
pub const CATALOGUE: &[EffectInfo] = &[
    EffectInfo {
        effect: Effect::Coulomb,
        name: "coulomb",
        vr: 50,
        description: "Dry Coulomb friction at the bristle tips: a bristle sticks while its stress is below mu times the local normal pressure and slides at that bound otherwise. With elastic wheel and rail (Kalker's simplified theory) this is FASTSIM. The bound follows the elliptic Hertz pressure by default (parabolic on request, as in Kalker's original). It replaces the layer strengths tau_c1, tau_c2 when switched on.",
        params: &[P::Mu],
        fit: &[],
        signature: &["cx"],
        applies: Applies::Never,
    },
    EffectInfo {
        effect: Effect::LayerElasticity,
        name: "layer_elasticity",
        vr: 51,
        description: "The third body layer (oxides, wear particles, fluids, surface asperities, some micrometres thick) is an elastic spring in series with the elastic wheel and rail: the bristle flexibility becomes L_k + L_e (seed Eq. 4.1, 4.21). It lowers the initial slope of the creep curve (regime R1); the seed's L_e_0 is tiny, so the effect shows only when L_e_0 is raised by orders of magnitude.",
        params: &[P::Le0],
        fit: &[P::Le0],
        signature: &["cx"],
        applies: Applies::Always,
    },
    EffectInfo {
        effect: Effect::VocePlasticity,
        name: "voce_plasticity",
        vr: 52,
        description: "Above the first critical shear stress tau_c1 the layer deforms plastically and hardens after Voce's law towards the second critical shear stress tau_c2, which it never exceeds; the displacement scale of the hardening is L_p (seed Eq. 4.2, 4.19). When a change of pressure or temperature lowers tau_c2 below the bristle's stress, the layer breaks and slides inside itself at tau_c2 (Eq. 4.7). This gives the moderate rise of traction at medium creepage (regime R2).",
        params: &[P::Lp0, P::Tc10, P::Tc20],
        fit: &[P::Tc10, P::Tc20, P::Lp0],
        signature: &["cx"],
        applies: Applies::Always,
    },
    EffectInfo {
        effect: Effect::PressureDependence,
        name: "pressure_dependence",
        vr: 53,
        description: "The layer behaves like a granular material: the more it is compressed, the more its particles and asperities interlock, so its strengths rise and its compliances fall with the local normal stress, saturating at high pressure: factor 1 - exp(-p X_p) (seed Eq. 4.3, 4.4; high-pressure-torsion tests, Sec. 3.3). It makes the traction coefficient depend on the normal load. Off: factor 1.",
        params: &[P::LeP, P::LpP, P::Tc1P, P::Tc2P],
        fit: &[P::Tc1P, P::Tc2P],
        signature: &["fn_kN", "p0_MPa"],
        applies: Applies::Always,
    },
    EffectInfo {
        effect: Effect::Temperature,
        name: "temperature",
        vr: 54,
        description: "Plastic work in the layer turns into heat (fraction k_q), split between wheel and rail by the heat partition factor; each bristle's flash temperature follows from its own heat history by the 1/sqrt(t) conduction kernel (seed Eq. 4.22-4.35). Heat softens the layer: strengths fall and compliances rise as exp(-(T - T0) X_T) (Eq. 4.3, 4.4). It causes the maximum of the creep curve, the falling branch at high creepage (R3) and the lower traction at higher speed and load.",
        params: &[P::LeT, P::LpT, P::Tc1T, P::Tc2T, P::T0, P::LambdaW, P::KappaW, P::LambdaR, P::KappaR, P::Kq],
        fit: &[P::Tc1T, P::Tc2T],
        signature: &[
            "frictional_power_W",
            "slip_velocity_mps",
            "v_mps",
            "model_T_max_C",
        ],
        applies: Applies::Always,
    },
    EffectInfo {
        effect: Effect::Transient,
        name: "transient",
        vr: 55,
        description: "Bristles are material points carried through the contact at the vehicle speed; their displacement, stress, hardening and heat history persist from one time step to the next, so the force responds to a change of creepage, speed or load within the time 2a/v a bristle needs to cross the contact (seed Sec. 4.5). Off: every step returns the quasi-steady state of the current inputs.",
        params: &[],
        fit: &[],
        signature: &["dcx_dt_per_s"],
        applies: Applies::TimeSeries,
    },
    EffectInfo {
        effect: Effect::ElasticUnloading,
        name: "elastic_unloading",
        vr: 56,
        description: "Unloading rule variant: a plastically deformed bristle whose load decreases unloads elastically along the layer-plus-body stiffness and keeps its hardening (incremental plasticity with radial return and a stored Voce hardening variable), instead of retracing the loading characteristic (the seed-faithful default). It matters when the creepage oscillates or reverses.",
        params: &[],
        fit: &[],
        signature: &["dcx_dt_per_s"],
        applies: Applies::TimeSeries,
    },
    EffectInfo {
        effect: Effect::SurfaceTimeFlash,
        name: "surface_time_flash",
        vr: 57,
        description: "The wheel's flash temperature over the time a point of the wheel surface spends in the contact, x / v_w with v_w = v |1 + c_x|, instead of the layer's time x / v in which the seed evaluates Eq. 4.34. With Blok's partition (Eq. 4.30) this is the same temperature as the rail side's formula with the rail's share of the heat, so it stays finite down to a locked wheel (c_x = -1), where the seed's form sends all heat into the rail and reports no temperature rise at all. Identical to the seed at c_x = 0; the temperature rise differs by sqrt(v / v_w): 12 % lower at c_x = +0.3, 20 % higher at -0.3. For wheel slide and hard braking; off: the seed's form.",
        params: &[],
        fit: &[],
        signature: &["cx", "model_T_max_C"],
        applies: Applies::WheelSlide,
    },
];

/// Catalogue entry of an effect.
pub fn info(effect: Effect) -> &'static EffectInfo {
    CATALOGUE
        .iter()
        .find(|e| e.effect == effect)
        .unwrap_or(&CATALOGUE[0])
}

/// Looks an effect up by name.
pub fn by_name(name: &str) -> Result<Effect> {
    CATALOGUE
        .iter()
        .find(|e| e.name == name)
        .map(|e| e.effect)
        .ok_or_else(|| CreepError::Unknown {
            kind: "effect".into(),
            name: name.into(),
            accepted: CATALOGUE
                .iter()
                .map(|e| e.name)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// A set of effects.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EffectSet(u32);

impl EffectSet {
    /// Empty set.
    pub fn empty() -> Self {
        EffectSet(0)
    }
    /// Set from a list.
    pub fn from_slice(effects: &[Effect]) -> Self {
        let mut s = EffectSet(0);
        for e in effects {
            s.insert(*e);
        }
        s
    }
    /// Adds an effect.
    pub fn insert(&mut self, e: Effect) {
        self.0 |= 1 << (e as u32);
    }
    /// Removes an effect.
    pub fn remove(&mut self, e: Effect) {
        self.0 &= !(1 << (e as u32));
    }
    /// True if the effect is on.
    pub fn has(&self, e: Effect) -> bool {
        self.0 & (1 << (e as u32)) != 0
    }
    /// The effects in catalogue order.
    pub fn to_vec(&self) -> Vec<Effect> {
        CATALOGUE
            .iter()
            .map(|i| i.effect)
            .filter(|e| self.has(*e))
            .collect()
    }
    /// Raw bits (for serialization).
    pub fn bits(&self) -> u32 {
        self.0
    }
    /// From raw bits.
    pub fn from_bits(bits: u32) -> Self {
        EffectSet(bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_row_fits_only_its_own_parameters() {
        for i in CATALOGUE {
            for p in i.fit {
                assert!(
                    i.params.contains(p),
                    "{}: fits {p:?}, which it does not use",
                    i.name
                );
            }
        }
    }

    #[test]
    fn each_candidate_names_its_evidence() {
        for i in CATALOGUE {
            if i.applies != Applies::Never {
                assert!(!i.signature.is_empty(), "{} has no signature", i.name);
            }
        }
    }

    #[test]
    fn where_an_effect_applies() {
        let on = EffectSet::from_slice(&[Effect::Temperature]);
        let off = EffectSet::empty();
        assert!(!Applies::Never.holds(on, true, true));
        assert!(Applies::Always.holds(off, false, false));
        assert!(Applies::TimeSeries.holds(off, true, false));
        assert!(!Applies::TimeSeries.holds(on, false, true));
        assert!(Applies::WheelSlide.holds(on, false, true));
        assert!(!Applies::WheelSlide.holds(off, true, true));
        assert!(!Applies::WheelSlide.holds(on, true, false));
    }
}
