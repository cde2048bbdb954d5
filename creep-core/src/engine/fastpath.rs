//! The engine's fast paths, each stated by what it supports: a path is taken only when every switched-on effect, the parameters and the modifiers lie within its set.
//!
//! A fast path does the work of the general bristle update with fewer operations for a
//! part of the configurations. Each one names the effects it needs, the further effects it
//! implements, a condition on the resolved parameters and the modifiers it copes with; the
//! engine takes it only when the configuration is inside that set ([`Support::admits`]).
//! An effect that is in no list keeps the configuration off the path, so a new catalogue
//! effect runs on the general path until someone adds it here deliberately (and the test
//! `fast_paths` in creep-core's physics tests, which switches on each catalogue effect,
//! checks that the fast and the general path then agree).

use crate::effects::{Effect, EffectSet};
use crate::material::Resolved;

/// A fast path of the bristle engine (see the module's text).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FastPath {
    /// FASTSIM's march and steady state (`Law::coulomb_path`, `march_coulomb` in
    /// engine/advance.rs, `steady_coulomb` in engine/steady_coulomb.rs): Kalker's brush with the radial return
    /// onto the Coulomb bound mu p in one tight loop, no heat.
    Coulomb,
    /// The scalar temperature solve of a layer that only softens as it heats
    /// (engine/softening.rs `update_softening`).
    Softening,
    /// The layer's compliance L_e taken once per bristle move instead of once per trial
    /// temperature of the local solve (the `fixed` flexibilities of `update_bristle`).
    FixedLe,
    /// The bristle move of an isothermal layer (engine/advance.rs `update_bristle_cold`):
    /// the general material and stress update without the temperature solve and the heat
    /// kernel (FASTSIM's moves off its march, an ECF configuration without temperature).
    Cold,
}

impl FastPath {
    /// Every fast path.
    pub const ALL: [FastPath; 4] = [
        FastPath::Coulomb,
        FastPath::Softening,
        FastPath::FixedLe,
        FastPath::Cold,
    ];

    /// What the path supports.
    pub(crate) fn support(self) -> &'static Support {
        match self {
            FastPath::Coulomb => &COULOMB,
            FastPath::Softening => &SOFTENING,
            FastPath::FixedLe => &FIXED_LE,
            FastPath::Cold => &COLD,
        }
    }
}

/// Which formula and Rust effects (modifiers) a fast path copes with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ModifierSupport {
    /// None at all.
    None,
    /// Factors at the operating point only (none of the bristle's local state).
    OperatingPoint,
}

/// The set of configurations a fast path implements.
#[derive(Debug)]
pub(crate) struct Support {
    /// Effects that must be on.
    pub needs: &'static [Effect],
    /// Further effects the path implements when they are on. Every other effect of the
    /// catalogue, and every effect added later, keeps the configuration off the path.
    pub implements: &'static [Effect],
    /// The condition on the resolved parameters under which the path is exact (or within
    /// its stated tolerance), in words and as a test.
    pub params: (&'static str, fn(&Resolved) -> bool),
    /// The modifiers it copes with.
    pub modifiers: ModifierSupport,
}

/// FASTSIM: the Coulomb bound replaces the layer's strengths (so Voce plasticity and the
/// pressure dependence of tau_c1, tau_c2, L_p change nothing, and the rule is the elastic
/// unloading either way); the brush stays isothermal, so the surface-time flash has nothing
/// to act on; the march serves the transient grid as it serves the steady state. Not
/// implemented: the layer's compliance (L_e = 0 in the loop) and the temperature.
pub(crate) const COULOMB: Support = Support {
    needs: &[Effect::Coulomb],
    implements: &[
        Effect::VocePlasticity,
        Effect::PressureDependence,
        Effect::Transient,
        Effect::ElasticUnloading,
        Effect::SurfaceTimeFlash,
    ],
    params: ("none", |_| true),
    modifiers: ModifierSupport::None,
};

/// The scalar solve follows the Voce law's branch as the layer heats: it needs the
/// temperature and the Voce law, implements the layer's compliance (constant in T), the
/// pressure factors, the transient grid and the surface-time flash. Not implemented: the
/// Coulomb bound and the elastic-unloading rule (the law's same-characteristic rule only).
pub(crate) const SOFTENING: Support = Support {
    needs: &[Effect::Temperature, Effect::VocePlasticity],
    implements: &[
        Effect::LayerElasticity,
        Effect::PressureDependence,
        Effect::Transient,
        Effect::SurfaceTimeFlash,
    ],
    params: (
        "tau_c1, tau_c2 fall and L_p rises with T (X_T >= 0), L_e does not depend on T (X_T = 0)",
        Resolved::monotone_softening,
    ),
    modifiers: ModifierSupport::OperatingPoint,
};

/// L_e once per move: exact (the material divides the node's L_e by a temperature factor of
/// exactly 1) for every effect of today's catalogue as long as L_e does not depend on the
/// temperature.
pub(crate) const FIXED_LE: Support = Support {
    needs: &[],
    implements: &[
        Effect::Coulomb,
        Effect::LayerElasticity,
        Effect::VocePlasticity,
        Effect::PressureDependence,
        Effect::Temperature,
        Effect::Transient,
        Effect::ElasticUnloading,
        Effect::SurfaceTimeFlash,
    ],
    params: (
        "L_e does not depend on T (X_T = 0 or no temperature)",
        |r| r.le_t == 0.0 || !r.on.temperature,
    ),
    modifiers: ModifierSupport::None,
};

/// The isothermal move calls the layer's material law (`material_base`) and the general
/// stress update (`bristle::update`), so it implements every effect of the law; it keeps the
/// bristle at the bulk temperature with no heat history, so not the temperature, and it
/// takes the material without the modifiers' factors, so no formula or Rust effects.
pub(crate) const COLD: Support = Support {
    needs: &[],
    implements: &[
        Effect::Coulomb,
        Effect::LayerElasticity,
        Effect::VocePlasticity,
        Effect::PressureDependence,
        Effect::Transient,
        Effect::ElasticUnloading,
        Effect::SurfaceTimeFlash,
    ],
    params: ("none", |_| true),
    modifiers: ModifierSupport::None,
};

impl Support {
    /// True if a configuration with the effects `on`, the resolved parameters `r` and
    /// modifiers (`any`: at least one; `local`: at least one of the bristle's local state)
    /// lies within this set.
    pub(crate) fn admits(&self, on: EffectSet, r: &Resolved, any: bool, local: bool) -> bool {
        let needed = EffectSet::from_slice(self.needs);
        let mut known = EffectSet::from_slice(self.implements);
        for e in self.needs {
            known.insert(*e);
        }
        let effects = on.bits() & needed.bits() == needed.bits() && on.bits() & !known.bits() == 0;
        let modifiers = match self.modifiers {
            ModifierSupport::None => !any,
            ModifierSupport::OperatingPoint => !local,
        };
        effects && modifiers && (self.params.1)(r)
    }
}

/// The fast paths a contact takes (all decided once, from its configuration).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Taken {
    /// [`FastPath::Coulomb`].
    pub coulomb: bool,
    /// [`FastPath::Softening`].
    pub softening: bool,
    /// [`FastPath::FixedLe`].
    pub fixed_le: bool,
    /// [`FastPath::Cold`].
    pub cold: bool,
}

impl Taken {
    /// Whether `path` is taken.
    pub(crate) fn get(&self, path: FastPath) -> bool {
        match path {
            FastPath::Coulomb => self.coulomb,
            FastPath::Softening => self.softening,
            FastPath::FixedLe => self.fixed_le,
            FastPath::Cold => self.cold,
        }
    }

    /// Sets whether `path` is taken.
    pub(crate) fn set(&mut self, path: FastPath, on: bool) {
        match path {
            FastPath::Coulomb => self.coulomb = on,
            FastPath::Softening => self.softening = on,
            FastPath::FixedLe => self.fixed_le = on,
            FastPath::Cold => self.cold = on,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::effects::CATALOGUE;

    /// The negative lists the engine had before the paths said what they support
    /// (advance.rs `coulomb_path`, mod.rs `set_softening_solve`, advance.rs `fixed`,
    /// advance.rs `move_bristle_with` for the isothermal move).
    fn before(path: FastPath, r: &Resolved, any: bool, local: bool) -> bool {
        use crate::bristle::Rule;
        match path {
            FastPath::Coulomb => {
                r.on.coulomb
                    && !r.on.layer_el
                    && !r.on.temperature
                    && r.on.rule == Rule::ElasticUnloading
                    && !any
            }
            FastPath::Softening => {
                r.on.temperature
                    && r.on.plastic
                    && !r.on.coulomb
                    && r.tc1_t >= 0.0
                    && r.tc2_t >= 0.0
                    && r.lp_t >= 0.0
                    && r.le_t == 0.0
                    && r.on.rule == Rule::SameCharacteristic
                    && !local
            }
            FastPath::FixedLe => !any && (r.le_t == 0.0 || !r.on.temperature),
            FastPath::Cold => !(r.on.temperature || any),
        }
    }

    /// Effects in the catalogue when the exclusion lists were replaced by support sets
    /// (coulomb ... surface_time_flash): the old lists decided only over these.
    const OLD_CATALOGUE: usize = 8;

    /// Every subset of the catalogue the old lists knew (its first [`OLD_CATALOGUE`]
    /// effects), with temperature coefficients of each sign and with and without modifiers:
    /// each path is taken exactly where the old lists took it, so those configurations run
    /// the same operations as before. (An effect added since is off every path until it is
    /// added to one deliberately: `an_effect_no_path_names_is_off_every_path`.)
    #[test]
    fn the_supported_sets_take_the_paths_the_old_lists_took() {
        let n = OLD_CATALOGUE;
        assert!(CATALOGUE.len() >= n);
        let mut taken = [0usize; FastPath::ALL.len()];
        for bits in 0..(1u32 << n) {
            // the preset's coefficients (all >= 0, L_e's 0), then one changed at a time (the
            // negative ones only reachable in the resolved parameters: SPECS bounds them)
            for (coefficient, value) in [
                ("none", 0.0),
                ("tc1_t", -1e-3),
                ("tc2_t", -1e-3),
                ("lp_t", -1e-3),
                ("le_t", 1e-3),
                ("le_t", -1e-3),
            ] {
                let mut cfg = Config::preset("table4.1").unwrap();
                cfg.effects = EffectSet::empty();
                for (k, info) in CATALOGUE.iter().enumerate() {
                    if bits & (1 << k) != 0 {
                        cfg.effects.insert(info.effect);
                    }
                }
                let mut r = Resolved::from_config(&cfg);
                match coefficient {
                    "tc1_t" => r.tc1_t = value,
                    "tc2_t" => r.tc2_t = value,
                    "lp_t" => r.lp_t = value,
                    "le_t" => r.le_t = value,
                    _ => {}
                }
                for (any, local) in [(false, false), (true, false), (true, true)] {
                    for (p, path) in FastPath::ALL.into_iter().enumerate() {
                        let now = path.support().admits(cfg.effects, &r, any, local);
                        assert_eq!(
                            now,
                            before(path, &r, any, local),
                            "{path:?}: {:?}, {coefficient} = {value}, modifiers {any}/{local}",
                            cfg.effects.to_vec()
                        );
                        taken[p] += now as usize;
                    }
                }
            }
        }
        // each path is taken somewhere and left somewhere
        for (p, t) in taken.iter().enumerate() {
            assert!(
                *t > 0 && *t < (1 << n) * 6 * 3,
                "{:?}: {t}",
                FastPath::ALL[p]
            );
        }
    }

    /// An effect that no path names (here: the catalogue's bits beyond today's effects)
    /// keeps the configuration off every path.
    #[test]
    fn an_effect_no_path_names_is_off_every_path() {
        let cfg = Config::preset("table4.1").unwrap();
        let r = Resolved::from_config(&cfg);
        for path in FastPath::ALL {
            let s = path.support();
            let mut on = EffectSet::from_slice(s.needs);
            if path == FastPath::Softening {
                // the preset's effects, within the path's set
                on = cfg.effects;
            }
            assert!(
                s.admits(on, &r, false, false),
                "{path:?}: {:?}",
                on.to_vec()
            );
            let unknown = EffectSet::from_bits(on.bits() | 1 << CATALOGUE.len());
            assert!(!s.admits(unknown, &r, false, false), "{path:?}");
        }
    }
}
