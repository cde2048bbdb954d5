//! The layer's material law once: pressure and temperature dependence of tau_c1, tau_c2, L_p, L_e (seed Eq. 4.3, 4.4), resolved to SI.

use crate::bristle::{Material, Rule};
use crate::config::{Bound, Config};
use crate::effects::Effect;
use crate::fastexp::{exp_fast, exp_pair};
use crate::hertz::Patch;
use crate::params::P;

/// Resolved SI parameters used in the inner loop: the effect switches of the configuration
/// and the registry's parameters ([`crate::params`], display units there) converted to SI.
///
/// The layer's laws (seed Eq. 4.3 for tau_c1, tau_c2; Eq. 4.4 for L_p, L_e), with the
/// pressure factor [`Resolved::pf`] and the temperature factor [`Resolved::tf`]:
/// tau_ci(p, T) = tau_ci,0 pf(p, X_p) tf(T, X_T) (tau_c1 capped at tau_c2) and
/// L(p, T) = L_0 / (pf(p, X_p) tf(T, X_T)) for L = L_p, L_e: strengths rise and compliances
/// fall as the layer is compressed, and the reverse as it heats.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Resolved {
    /// The effect switches and the unloading rule.
    pub on: Switches,
    /// Wheel and rail: elastic and thermal properties.
    pub bodies: Bodies,
    /// Coulomb friction coefficient mu of the bound |tau| <= mu p, -.
    pub mu: f64,
    /// L_e,0: inverted elastic stiffness of the layer at full compression and T0 (its
    /// minimum), m/Pa (Eq. 4.4).
    pub le0: f64,
    /// Pressure coefficient X_p of L_e, 1/Pa (inf: no pressure dependence) (Eq. 4.4).
    pub le_p: f64,
    /// Temperature coefficient X_T of L_e, 1/K (Eq. 4.4).
    pub le_t: f64,
    /// L_p,0: plasticity factor (displacement scale of Voce hardening) at full compression
    /// and T0 (its minimum), m (Eq. 4.4).
    pub lp0: f64,
    /// Pressure coefficient X_p of L_p, 1/Pa (Eq. 4.4).
    pub lp_p: f64,
    /// Temperature coefficient X_T of L_p, 1/K (Eq. 4.4).
    pub lp_t: f64,
    /// tau_c1,0: first critical shear stress (yield stress) of the layer at full compression
    /// and T0 (its maximum), Pa (Eq. 4.3).
    pub tc10: f64,
    /// Pressure coefficient X_p of tau_c1, 1/Pa (Eq. 4.3).
    pub tc1_p: f64,
    /// Temperature coefficient X_T of tau_c1, 1/K (Eq. 4.3).
    pub tc1_t: f64,
    /// tau_c2,0: second critical shear stress (shear strength) of the layer at full
    /// compression and T0 (its maximum), Pa (Eq. 4.3).
    pub tc20: f64,
    /// Pressure coefficient X_p of tau_c2, 1/Pa (Eq. 4.3).
    pub tc2_p: f64,
    /// Temperature coefficient X_T of tau_c2, 1/K (Eq. 4.3).
    pub tc2_t: f64,
    /// Reference temperature T0 of the material laws, degC (Eq. 4.3, 4.4; not the bulk
    /// temperature T_B, which is an input).
    pub t0: f64,
    /// k_q: fraction of the work dissipated in the layer that becomes heat, - (Eq. 4.29): a
    /// bristle's heat density (both bodies, before the partition) is
    /// q = k_q tau . (du - du_e) / h, W/m^2, du_e the elastic part of its displacement
    /// increment du over the sub-step h.
    pub kq: f64,
}

/// The configuration's effect switches and rules the inner loop branches on ([`Resolved::on`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Switches {
    /// Effect `coulomb`: FASTSIM's bound |tau| <= mu p replaces the layer's strengths
    /// (tau_c1 = tau_c2 = mu p).
    pub coulomb: bool,
    /// Effect `voce_plasticity`: Voce hardening from tau_c1 to tau_c2 (Eq. 4.2); with neither
    /// this nor `coulomb` the bristles are purely elastic (Kalker's linear theory).
    pub plastic: bool,
    /// Effect `layer_elasticity`: the layer's compliance L_e in series with the bodies'
    /// (L_k + L_e, Eq. 4.21); off: L_e = 0.
    pub layer_el: bool,
    /// Effect `pressure_dependence`: the pressure factors of Eq. 4.3, 4.4 (off: 1).
    pub pressure: bool,
    /// Effect `temperature`: heat, flash temperature (Eq. 4.22-4.35) and the temperature
    /// factors of Eq. 4.3, 4.4 (off: 1, bristles at the bulk temperature).
    pub temperature: bool,
    /// Effect `transient`: the bristle grid persists between steps (off: every step is the
    /// quasi-steady state of its inputs).
    pub transient: bool,
    /// Effect `surface_time_flash`: Eq. 4.34 over the wheel surface's own time x / v_w.
    pub surface_time: bool,
    /// Unloading rule of the bristle law: elastic unloading with effect `elastic_unloading`
    /// or `coulomb` (FASTSIM's radial return), else the seed's same characteristic.
    pub rule: Rule,
    /// Configuration `bound` = parabolic: the Coulomb bound follows Kalker's parabolic
    /// pressure (same total force) instead of the elliptic Hertz pressure.
    pub parabolic: bool,
}

/// Elastic and thermal properties of the wheel and the rail, SI ([`Resolved::bodies`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bodies {
    /// Shear modulus G of wheel and rail, Pa (Kalker's flexibilities L_x, L_y, L_s).
    pub g: f64,
    /// Poisson's ratio nu of wheel and rail, - (Kalker's coefficients).
    pub nu: f64,
    /// Thermal conductivity lambda_w of the wheel, W/(m K) (heat partition Eq. 4.30, 4.31;
    /// flash factor sqrt(kappa_w)/(lambda_w sqrt(pi)) of Eq. 4.34).
    pub lambda_w: f64,
    /// Thermal diffusivity kappa_w of the wheel, m^2/s (Eq. 4.31, Péclet condition Eq. 4.33,
    /// Eq. 4.34).
    pub kappa_w: f64,
    /// Thermal conductivity lambda_r of the rail, W/(m K) (heat partition Eq. 4.31).
    pub lambda_r: f64,
    /// Thermal diffusivity kappa_r of the rail, m^2/s (Eq. 4.31, Péclet condition Eq. 4.33).
    pub kappa_r: f64,
}

impl Resolved {
    pub(crate) fn from_config(c: &Config) -> Self {
        let p = &c.params;
        Resolved {
            on: Switches {
                coulomb: c.has(Effect::Coulomb),
                plastic: c.has(Effect::VocePlasticity),
                layer_el: c.has(Effect::LayerElasticity),
                pressure: c.has(Effect::PressureDependence),
                temperature: c.has(Effect::Temperature),
                transient: c.has(Effect::Transient),
                surface_time: c.has(Effect::SurfaceTimeFlash),
                // FASTSIM's clip onto the Coulomb bound is a radial return along the trial
                // stress: the elastic-unloading rule with tau_c1 = tau_c2 = mu p.
                rule: if c.has(Effect::ElasticUnloading) || c.has(Effect::Coulomb) {
                    Rule::ElasticUnloading
                } else {
                    Rule::SameCharacteristic
                },
                parabolic: c.bound == Bound::Parabolic,
            },
            bodies: Bodies {
                g: p.si(P::G),
                nu: p.si(P::Nu),
                lambda_w: p.si(P::LambdaW),
                kappa_w: p.si(P::KappaW),
                lambda_r: p.si(P::LambdaR),
                kappa_r: p.si(P::KappaR),
            },
            mu: p.si(P::Mu),
            le0: p.si(P::Le0),
            le_p: p.si(P::LeP),
            le_t: p.si(P::LeT),
            lp0: p.si(P::Lp0),
            lp_p: p.si(P::LpP),
            lp_t: p.si(P::LpT),
            tc10: p.si(P::Tc10),
            tc1_p: p.si(P::Tc1P),
            tc1_t: p.si(P::Tc1T),
            tc20: p.si(P::Tc20),
            tc2_p: p.si(P::Tc2P),
            tc2_t: p.si(P::Tc2T),
            t0: p.si(P::T0),
            kq: p.si(P::Kq),
        }
    }

    /// Pressure factor 1 - exp(-p c) of Eq. 4.3/4.4 (1 when the effect is off or c = inf).
    /// `p`: normal stress, Pa; `c`: the pressure coefficient X_p of one material function
    /// (`tc1_p`, `tc2_p`, `lp_p` or `le_p`), 1/Pa. In [0, 1]: the strengths tau_c1, tau_c2
    /// are multiplied by it, the compliances L_p, L_e divided.
    #[inline]
    pub(crate) fn pf(&self, p: f64, c: f64) -> f64 {
        if !self.on.pressure || c.is_infinite() {
            1.0
        } else {
            let x = p * c;
            // 1 - exp(-x) loses no accuracy that matters above x = 1e-3 and exp is cheaper
            if x > 1e-3 {
                1.0 - exp_fast(-x)
            } else {
                -(-x).exp_m1()
            }
        }
    }

    /// ([`Self::pf`] of `c1`, of `c2`) at pressure `p`: one two-lane exponential where both
    /// need one.
    #[inline]
    fn pf_pair(&self, p: f64, c1: f64, c2: f64) -> (f64, f64) {
        let (x1, x2) = (p * c1, p * c2);
        if self.on.pressure && x1 > 1e-3 && x2 > 1e-3 && x1.is_finite() && x2.is_finite() {
            let (e1, e2) = exp_pair(-x1, -x2);
            (1.0 - e1, 1.0 - e2)
        } else {
            (self.pf(p, c1), self.pf(p, c2))
        }
    }

    /// Temperature factor exp(-(T - T0) c) of Eq. 4.3/4.4 (1 when the effect is off).
    /// `t`: temperature T, degC; `c`: the temperature coefficient X_T of one material
    /// function (`tc1_t`, `tc2_t`, `lp_t` or `le_t`), 1/K. Below 1 above T0: the strengths
    /// are multiplied by it, the compliances divided.
    #[inline]
    pub(crate) fn tf(&self, t: f64, c: f64) -> f64 {
        if !self.on.temperature || c == 0.0 {
            1.0
        } else {
            (-(t - self.t0) * c).exp()
        }
    }
}

/// Pressure-only parts of the material at one node (cached per node; Eq. 4.3/4.4).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NodeP {
    pub p: f64,
    pub bound: f64,
    tc1: f64,
    tc2: f64,
    pub le: f64,
    lp: f64,
}

impl Resolved {
    /// Pressure-dependent material parts at normalized position (xi, eta).
    pub(crate) fn node_p(&self, pt: &Patch, xi: f64, eta: f64) -> NodeP {
        let r = self;
        let rr = if pt.line {
            xi * xi
        } else {
            xi * xi + eta * eta
        };
        let p = if rr >= 1.0 {
            0.0
        } else {
            pt.p0 * (1.0 - rr).sqrt()
        };
        let bound = if r.on.parabolic {
            // Kalker's parabolic pressure with the same total force: 2 F_N/(pi a b) = 4/3 p0 for the
            // ellipse; 3 pi/8 p0 for the line contact.
            let k = if pt.line {
                3.0 * std::f64::consts::PI / 8.0
            } else {
                4.0 / 3.0
            };
            r.mu * (k * pt.p0 * (1.0 - rr)).max(0.0)
        } else {
            r.mu * p
        };
        if p <= 0.0 {
            return NodeP {
                p,
                bound,
                tc1: 0.0,
                tc2: 0.0,
                le: 0.0,
                lp: 1.0,
            };
        }
        let le = if r.on.layer_el {
            r.le0 / r.pf(p, r.le_p)
        } else {
            0.0
        };
        // equal coefficients share one exponential (Tab. 4.1 has three equal ones)
        let (f1, f2) = if r.tc2_p == r.tc1_p {
            let f1 = r.pf(p, r.tc1_p);
            (f1, f1)
        } else {
            r.pf_pair(p, r.tc1_p, r.tc2_p)
        };
        let fp = if r.lp_p == r.tc1_p {
            f1
        } else if r.lp_p == r.tc2_p {
            f2
        } else {
            r.pf(p, r.lp_p)
        };
        NodeP {
            p,
            bound,
            tc1: r.tc10 * f1,
            tc2: r.tc20 * f2,
            le,
            lp: r.lp0 / fp,
        }
    }

    /// Material at temperature `t` (Eq. 4.3, 4.4) from the node's pressure parts, formula
    /// effects not applied.
    #[inline(always)]
    pub(crate) fn material_base(&self, np: &NodeP, t: f64) -> Material {
        let r = self;
        if r.on.coulomb {
            let le = np.le / r.tf(t, r.le_t);
            return Material {
                tc1: np.bound,
                tc2: np.bound,
                lp: 1.0,
                le,
            };
        }
        if !r.on.plastic {
            let le = np.le / r.tf(t, r.le_t);
            return Material {
                tc1: f64::INFINITY,
                tc2: f64::INFINITY,
                lp: 1.0,
                le,
            };
        }
        if np.p <= 0.0 {
            return Material {
                tc1: 0.0,
                tc2: 0.0,
                lp: 1.0,
                le: 0.0,
            };
        }
        let (tf1, tf2, tfp, tfe) = if r.on.temperature {
            // equal coefficients share one exponential (Tab. 4.1 has three equal ones);
            // two different ones (the dry presets) are taken in one two-lane exponential
            let (tf1, tf2) = if r.tc2_t == r.tc1_t {
                let tf1 = r.tf(t, r.tc1_t);
                (tf1, tf1)
            } else {
                let dt = -(t - r.t0);
                exp_pair(dt * r.tc1_t, dt * r.tc2_t)
            };
            let tfp = if r.lp_t == r.tc1_t {
                tf1
            } else if r.lp_t == r.tc2_t {
                tf2
            } else {
                r.tf(t, r.lp_t)
            };
            (tf1, tf2, tfp, r.tf(t, r.le_t))
        } else {
            (1.0, 1.0, 1.0, 1.0)
        };
        let tc2 = np.tc2 * tf2;
        let tc1 = (np.tc1 * tf1).min(tc2);
        Material {
            tc1,
            tc2,
            lp: np.lp / tfp,
            le: np.le / tfe,
        }
    }
}

impl Resolved {
    /// The temperature coefficient X (1/K) in the gain of the elastic-release loop that the
    /// release weight theta bounds (docs/model.md, section 6, "X in the gain"): the largest
    /// coefficient of the strengths a move's stress follows over its whole temperature rise.
    /// * [`Rule::SameCharacteristic`] (the default): tau_c2's and L_p's. A move that crosses
    ///   the yield surface yields at tau_c1 of its heat history's temperature, fixed during
    ///   the temperature solve; tau_c1(T) enters only as the floor max(tau_c1(T), Voce) of a
    ///   bristle riding on the yield surface, over a bounded temperature range
    ///   ((tau_c1 - t_Voce) / (tau_c1 X_c1), a fraction of a kelvin) and so with bounded
    ///   release heat, as long as the gain of the ride stays below 1; a bristle that may
    ///   ride takes [`Self::release_t_riding`]. With tau_c1's coefficient in X for every move
    ///   (an earlier rule; history: docs/history.md),
    ///   theta damped hardening and sliding bristles of dry (tau_c1 0.034 /K against tau_c2
    ///   0.0025 /K) and wet (0.55 against 0.0015 /K) by a weight that depends on the cell
    ///   length: the fine grids drifted (dry, 20 m/s, c_x 1.06 %: +1.8 % on 640 cells).
    /// * [`Rule::ElasticUnloading`] (effects `elastic_unloading`, `coulomb`): the plastic part
    ///   of a crossing starts at tau_c1(T), so tau_c1's coefficient too.
    #[inline]
    pub(crate) fn release_t(&self) -> f64 {
        match self.on.rule {
            Rule::SameCharacteristic => self.tc2_t.max(self.lp_t),
            Rule::ElasticUnloading => self.tc1_t.max(self.tc2_t).max(self.lp_t),
        }
    }

    /// [`Self::release_t`] for a plastic bristle below tau_c1 at the temperature of its heat
    /// history, which may ride on tau_c1 over the move: there its heat follows tau_c1(T), so
    /// tau_c1's coefficient counts too. Without it, on short moves (dry: cells shorter than
    /// about 25 um) the gain of the ride passed 1 and the solve's only root was the elastic
    /// one at t_hist: the bristle left tau_c1 for one cell and yielded again higher
    /// (docs/model.md, section 6, "Riding bristles").
    #[inline]
    pub(crate) fn release_t_riding(&self) -> f64 {
        self.release_t().max(self.tc1_t)
    }

    /// True if the layer's parameters only soften it as it heats (tau_c1, tau_c2 fall and
    /// L_p rises with T, L_e does not depend on T). With the Voce law and the temperature on
    /// and no Coulomb bound (the effects of [`crate::engine::FastPath::Softening`],
    /// engine/fastpath.rs `SOFTENING`), a bristle that is elastic, hardening or sliding at
    /// the lowest temperature of its solve then stays so along the solve's path
    /// ([`crate::bristle::SofteningPath`]) while the hardening span tau_c2 - tau_c1 stays
    /// open (see [`Self::span_may_close`]).
    pub(crate) fn monotone_softening(&self) -> bool {
        self.tc1_t >= 0.0 && self.tc2_t >= 0.0 && self.lp_t >= 0.0 && self.le_t == 0.0
    }

    /// True if tau_c1 softens more slowly than tau_c2: heating then narrows the span
    /// tau_c2 - tau_c1 until tau_c1 = tau_c2 (a perfectly plastic layer, whose law has no
    /// hardening branch), at one temperature, above which it stays closed.
    pub(crate) fn span_may_close(&self) -> bool {
        self.tc1_t < self.tc2_t
    }
}

/// The layer's material alone at normal stress `p` (Pa) and temperature `t` (degC), from
/// the configuration's parameters and effects (Eq. 4.3, 4.4; formula effects not applied).
pub fn layer_material(cfg: &Config, p: f64, t: f64) -> Material {
    let r = Resolved::from_config(cfg);
    let le = if r.on.layer_el {
        r.le0 / r.pf(p, r.le_p) / r.tf(t, r.le_t)
    } else {
        0.0
    };
    let tc2 = r.tc20 * r.pf(p, r.tc2_p) * r.tf(t, r.tc2_t);
    let tc1 = (r.tc10 * r.pf(p, r.tc1_p) * r.tf(t, r.tc1_t)).min(tc2);
    Material {
        tc1,
        tc2,
        lp: r.lp0 / r.pf(p, r.lp_p) / r.tf(t, r.lp_t),
        le,
    }
}
