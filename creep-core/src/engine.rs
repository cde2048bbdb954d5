//! The bristle engine: a persistent grid of bristles carried through the contact, one `step(dt, inputs)` for time.
//!
//! Each of `ny` strips across the contact holds `nx + 1` bristles (material points of the
//! third body layer, seed Fig. 4.2) in normalized coordinates xi = x/a in [-l_j, l_j],
//! l_j = sqrt(1 - eta_j^2), eta_j = y/b. Bristles move towards the trailing edge at the
//! vehicle speed; a strip keeps a ring buffer and a phase in [0, 1) that says how far its
//! bristles have moved since the last one entered at the leading edge with zero
//! displacement (Eq. 4.17). A time step is cut into sub-steps at the instants a new bristle
//! enters; in each sub-step every bristle gets the rigid slip increment of Eq. 4.16 and
//! the bristle law (3BL or Coulomb, module [`crate::bristle`]) with the temperature of its
//! own heat history (module [`crate::thermal`]), solved per bristle.
//!
//! Steady state is the same code: [`Contact::steady`] marches one bristle per strip from
//! the leading to the trailing edge with the same sub-step `dx/v` and stores its state at
//! every node, which is exactly the grid the transient step reaches after 2a/v with constant
//! inputs (tested bit for bit).

use crate::bristle::{self, BristleState, Material, Regime, Rule};
use crate::config::{Bound, Config, Geometry, ModelKind};
use crate::effects::Effect;
use crate::error::{check_range, CreepError, Result};
use crate::hertz::{self, Patch};
use crate::kalker;
use crate::params::P;
use crate::thermal::{self, Kernel, N_KERNEL};

/// Speeds below this (m/s) count as standstill: no advection and no frictional heat.
pub const V_STANDSTILL: f64 = 1e-6;

/// Operating point of one contact; may change every step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inputs {
    /// Longitudinal creepage c_x, - (Eq. 4.12; positive: traction, force F_x > 0).
    pub cx: f64,
    /// Lateral creepage c_y, -.
    pub cy: f64,
    /// Spin creepage c_s, 1/m.
    pub spin: f64,
    /// Vehicle speed v, m/s (>= 0).
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
        check_range("v", self.v, 0.0, 1000.0, "m/s")?;
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
    /// Position in rolling direction, m (leading edge at +a).
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

/// Resolved SI parameters used in the inner loop.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Resolved {
    pub coulomb: bool,
    pub plastic: bool,
    pub layer_el: bool,
    pub pressure: bool,
    pub temperature: bool,
    pub transient: bool,
    pub rule: Rule,
    pub parabolic: bool,
    pub mu: f64,
    pub g: f64,
    pub nu: f64,
    pub le0: f64,
    pub le_p: f64,
    pub le_t: f64,
    pub lp0: f64,
    pub lp_p: f64,
    pub lp_t: f64,
    pub tc10: f64,
    pub tc1_p: f64,
    pub tc1_t: f64,
    pub tc20: f64,
    pub tc2_p: f64,
    pub tc2_t: f64,
    pub t0: f64,
    pub lambda_w: f64,
    pub kappa_w: f64,
    pub lambda_r: f64,
    pub kappa_r: f64,
    pub kq: f64,
}

impl Resolved {
    fn from_config(c: &Config) -> Self {
        let p = &c.params;
        Resolved {
            coulomb: c.has(Effect::Coulomb),
            plastic: c.has(Effect::VocePlasticity),
            layer_el: c.has(Effect::LayerElasticity),
            pressure: c.has(Effect::PressureDependence),
            temperature: c.has(Effect::Temperature),
            transient: c.has(Effect::Transient),
            // FASTSIM's clip onto the Coulomb bound is a radial return along the trial
            // stress: the elastic-unloading rule with tau_c1 = tau_c2 = mu p.
            rule: if c.has(Effect::ElasticUnloading) || c.has(Effect::Coulomb) {
                Rule::ElasticUnloading
            } else {
                Rule::SameCharacteristic
            },
            parabolic: c.bound == Bound::Parabolic,
            mu: p.si(P::Mu),
            g: p.si(P::G),
            nu: p.si(P::Nu),
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
            lambda_w: p.si(P::LambdaW),
            kappa_w: p.si(P::KappaW),
            lambda_r: p.si(P::LambdaR),
            kappa_r: p.si(P::KappaR),
            kq: p.si(P::Kq),
        }
    }

    /// Pressure factor 1 - exp(-p c) of Eq. 4.3/4.4 (1 when the effect is off or c = inf).
    #[inline]
    fn pf(&self, p: f64, c: f64) -> f64 {
        if !self.pressure || c.is_infinite() {
            1.0
        } else {
            -(-p * c).exp_m1()
        }
    }

    /// Temperature factor exp(-(T - T0) c) of Eq. 4.3/4.4 (1 when the effect is off).
    #[inline]
    fn tf(&self, t: f64, c: f64) -> f64 {
        if !self.temperature || c == 0.0 {
            1.0
        } else {
            (-(t - self.t0) * c).exp()
        }
    }
}

/// Pressure-only parts of the material at one node (cached per node; Eq. 4.3/4.4).
#[derive(Clone, Copy, Debug, Default)]
struct NodeP {
    p: f64,
    bound: f64,
    tc1: f64,
    tc2: f64,
    le: f64,
    lp: f64,
}

/// Per-sub-step kinematic context of one strip.
struct Kin {
    h: f64,
    dist: f64,
    cx: f64,
    cy: f64,
    cs: f64,
    lx: f64,
    ly: f64,
    ls: f64,
    heat: bool,
    alpha_c: f64,
    t_bulk: f64,
}

/// The persistent contact: geometry, bristle grid and its state.
#[derive(Clone, Debug)]
pub struct Contact {
    cfg: Config,
    r: Resolved,
    kernel: Kernel,
    nx: usize,
    ny: usize,
    /// Normalized strip centres eta_j and half-lengths l_j, strip widths d eta_j.
    eta: Vec<f64>,
    ell: Vec<f64>,
    deta: Vec<f64>,
    /// Ring-buffer head and phase per strip.
    head: Vec<usize>,
    phase: Vec<f64>,
    /// Bristle state (index j * (nx + 1) + slot).
    st: Vec<BristleState>,
    acc: Vec<[f64; N_KERNEL]>,
    /// Time since start, s.
    time: f64,
    inputs: Inputs,
    patch: Patch,
    flex: (f64, f64, f64),
    out: Outputs,
    initialized: bool,
    warnings: Vec<String>,
    /// Temperature tolerance of the local solve, K: 1e-4 / (largest temperature coefficient).
    t_tol: f64,
    /// Compute bristles that enter during a step by a march (identical results, less work).
    march: bool,
    /// Values of the extra (data) columns the formula effects use, by name.
    extra: Vec<(String, f64)>,
    /// Formula variables: local placeholders, operating point, columns (see `formula`).
    fvars: Vec<f64>,
    /// Product of the operating-point-only formula factors per target
    /// (tau_c1, tau_c2, L_e, L_p, mu).
    fstatic: [f64; 5],
    /// True if some formula uses local bristle state.
    flocal: bool,
}

impl Contact {
    /// A new contact for a bristle-model configuration (`ecf` or `fastsim`).
    pub fn new(cfg: &Config) -> Result<Self> {
        if cfg.model == ModelKind::Polach {
            return Err(CreepError::Config {
                source_name: "model".into(),
                message: "polach is a closed-form model, not a bristle model".into(),
            });
        }
        cfg.grid.validate()?;
        let (nx, ny) = (cfg.grid.nx, cfg.grid.ny);
        let line = matches!(cfg.geometry, Geometry::Line { .. });
        let ny = if line { 1 } else { ny };
        let mut eta = Vec::with_capacity(ny);
        let mut ell = Vec::with_capacity(ny);
        let mut deta = Vec::with_capacity(ny);
        for j in 0..ny {
            if line {
                eta.push(0.0);
                ell.push(1.0);
                deta.push(2.0);
            } else {
                let e = -1.0 + (j as f64 + 0.5) * 2.0 / ny as f64;
                eta.push(e);
                ell.push((1.0 - e * e).sqrt());
                deta.push(2.0 / ny as f64);
            }
        }
        let n = ny * (nx + 1);
        let patch = Patch {
            a: 1.0,
            b: 1.0,
            p0: 0.0,
            line,
        };
        Ok(Contact {
            cfg: cfg.clone(),
            r: Resolved::from_config(cfg),
            kernel: Kernel::default(),
            nx,
            ny,
            eta,
            ell,
            deta,
            head: vec![0; ny],
            phase: vec![0.0; ny],
            st: vec![BristleState::default(); n],
            acc: vec![[0.0; N_KERNEL]; n],
            time: 0.0,
            inputs: Inputs::default(),
            patch,
            flex: (0.0, 0.0, 0.0),
            out: Outputs::default(),
            initialized: false,
            warnings: Vec::new(),
            march: true,
            extra: Vec::new(),
            fvars: Vec::new(),
            fstatic: [1.0; 5],
            flocal: cfg.formulas.iter().any(|f| f.local)
                || cfg.custom.iter().any(|c| c.effect.uses_local_state()),
            t_tol: {
                let r = Resolved::from_config(cfg);
                let cmax = r.tc1_t.max(r.tc2_t).max(r.lp_t).max(r.le_t);
                if cmax > 0.0 {
                    (1e-4 / cmax).min(0.1)
                } else {
                    0.1
                }
            },
        })
    }

    /// The configuration.
    pub fn config(&self) -> &Config {
        &self.cfg
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Last outputs.
    pub fn outputs(&self) -> Outputs {
        self.out
    }

    /// Last inputs.
    pub fn inputs(&self) -> Inputs {
        self.inputs
    }

    /// Warnings raised since the last call (e.g. Péclet condition not met), drained.
    pub fn take_warnings(&mut self) -> Vec<String> {
        std::mem::take(&mut self.warnings)
    }

    /// Contact patch for a normal force (geometry of the configuration).
    pub fn patch_for(&self, fn_n: f64) -> Result<Patch> {
        patch_for(&self.cfg, fn_n)
    }

    fn set_inputs(&mut self, inputs: &Inputs) -> Result<()> {
        inputs.validate()?;
        if inputs.fn_n > 0.0 {
            self.patch = self.patch_for(inputs.fn_n)?;
            let (a, b) = (self.patch.a, self.patch.b);
            let (ka, kb) = if self.patch.line {
                (a, 1e6 * a)
            } else {
                (a, b)
            };
            let c = kalker::coefficients(ka, kb, self.r.nu)?;
            self.flex = kalker::flexibilities(ka, kb, self.r.g, &c);
        }
        self.inputs = *inputs;
        self.update_formula_vars()?;
        if self.r.temperature && inputs.v > V_STANDSTILL {
            let vw = inputs.v * (1.0 + inputs.cx).abs();
            if !thermal::peclet_ok(self.patch.a, inputs.v, vw, self.r.kappa_w, self.r.kappa_r) {
                let msg = format!(
                    "Péclet condition a (v + v_w) > 20 (kappa_r + kappa_w) (Eq. 4.33) not met at v = {} m/s, a = {} mm: the flash temperature model neglects lateral heat conduction that matters here",
                    inputs.v,
                    self.patch.a * 1e3
                );
                if !self.warnings.contains(&msg) {
                    self.warnings.push(msg);
                }
            }
        }
        Ok(())
    }

    /// Sets the values of extra (data) columns that formula effects use.
    pub fn set_extra(&mut self, values: &[(String, f64)]) -> Result<()> {
        self.extra = values.to_vec();
        self.update_formula_vars()
    }

    fn update_formula_vars(&mut self) -> Result<()> {
        if self.cfg.formulas.is_empty() && self.cfg.custom.is_empty() {
            return Ok(());
        }
        let i = &self.inputs;
        let mut v = vec![0.0; crate::formula::LOCAL.len()];
        v.extend([i.v, i.fn_n / 1e3, i.cx, i.cy, i.spin]);
        let mut fstatic = [1.0; 5];
        for f in &self.cfg.formulas {
            let mut vars = v.clone();
            for c in &f.columns {
                let x = self
                    .extra
                    .iter()
                    .find(|(n, _)| n == c)
                    .map(|(_, x)| *x)
                    .ok_or_else(|| CreepError::Config {
                        source_name: format!("formula_effects.{}", f.name),
                        message: format!(
                            "uses the column '{c}', which the data do not provide (have: {})",
                            self.extra
                                .iter()
                                .map(|e| e.0.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    })?;
                vars.push(x);
            }
            if !f.local {
                fstatic[f.target as usize] *= f.eval(&vars).max(0.0);
            }
        }
        for c in &self.cfg.custom {
            for col in c.effect.columns() {
                if !self.extra.iter().any(|(n, _)| n == col) {
                    return Err(CreepError::Config {
                        source_name: format!("custom_effects.{}", c.effect.name()),
                        message: format!(
                            "needs the column '{col}', which the data do not provide (have: {})",
                            self.extra
                                .iter()
                                .map(|e| e.0.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    });
                }
            }
            if !c.effect.uses_local_state() {
                fstatic[c.effect.target() as usize] *= c
                    .effect
                    .factor(
                        &c.params,
                        &crate::custom::LocalState::default(),
                        &self.operating_point(),
                    )
                    .max(0.0);
            }
        }
        self.fstatic = fstatic;
        self.fvars = v;
        Ok(())
    }

    fn operating_point(&self) -> crate::custom::OperatingPoint<'_> {
        let i = &self.inputs;
        crate::custom::OperatingPoint {
            v_mps: i.v,
            fn_kn: i.fn_n / 1e3,
            cx: i.cx,
            cy: i.cy,
            spin_per_m: i.spin,
            columns: &self.extra,
        }
    }

    /// Scales a material by the formula effects (local ones evaluated at this bristle).
    #[inline]
    fn apply_formulas(
        &self,
        mut m: Material,
        coulomb: bool,
        p: f64,
        t: f64,
        u: f64,
        slip: f64,
    ) -> Material {
        if self.cfg.formulas.is_empty() && self.cfg.custom.is_empty() {
            return m;
        }
        let mut fac = self.fstatic;
        if self.flocal {
            let mut vars = self.fvars.clone();
            vars[0] = p / 1e9;
            vars[1] = t;
            vars[2] = u * 1e3;
            vars[3] = slip;
            for f in self.cfg.formulas.iter().filter(|f| f.local) {
                let mut vv = vars.clone();
                for c in &f.columns {
                    vv.push(
                        self.extra
                            .iter()
                            .find(|(n, _)| n == c)
                            .map(|(_, x)| *x)
                            .unwrap_or(f64::NAN),
                    );
                }
                fac[f.target as usize] *= f.eval(&vv).max(0.0);
            }
            let local = crate::custom::LocalState {
                p_gpa: p / 1e9,
                t_c: t,
                u_mm: u * 1e3,
                slip_mps: slip,
            };
            for c in self
                .cfg
                .custom
                .iter()
                .filter(|c| c.effect.uses_local_state())
            {
                fac[c.effect.target() as usize] *= c
                    .effect
                    .factor(&c.params, &local, &self.operating_point())
                    .max(0.0);
            }
        }
        if coulomb {
            m.tc1 *= fac[4];
            m.tc2 *= fac[4];
        } else {
            m.tc2 *= fac[1];
            m.tc1 = (m.tc1 * fac[0]).min(m.tc2);
            m.lp *= fac[3];
        }
        m.le *= fac[2];
        m
    }

    /// Kinematic/thermal context for a sub-step of duration `h` moving distance `dist`.
    fn kin(&self, h: f64, dist: f64) -> Kin {
        let i = &self.inputs;
        let heat = i.v > V_STANDSTILL && h > 0.0;
        let vw = i.v * (1.0 + i.cx).abs();
        let alpha = thermal::heat_partition(
            vw,
            i.v,
            self.r.lambda_w,
            self.r.kappa_w,
            self.r.lambda_r,
            self.r.kappa_r,
        );
        Kin {
            h,
            dist,
            cx: i.cx,
            cy: i.cy,
            cs: i.spin,
            lx: self.flex.0,
            ly: self.flex.1,
            ls: self.flex.2,
            heat,
            alpha_c: alpha * thermal::flash_factor(self.r.lambda_w, self.r.kappa_w),
            t_bulk: i.t_bulk,
        }
    }

    /// Pressure-dependent material parts at normalized position (xi, eta).
    fn node_p(&self, xi: f64, eta: f64) -> NodeP {
        let r = &self.r;
        let pt = &self.patch;
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
        let bound = if r.parabolic {
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
        let le = if r.layer_el {
            r.le0 / r.pf(p, r.le_p)
        } else {
            0.0
        };
        // equal coefficients share one exponential (Tab. 4.1 has three equal ones)
        let f1 = r.pf(p, r.tc1_p);
        let f2 = if r.tc2_p == r.tc1_p {
            f1
        } else {
            r.pf(p, r.tc2_p)
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

    /// Full material at temperature `t` (Eq. 4.3, 4.4) with the formula effects at a bristle
    /// with displacement |u| = `u` (m) and rigid slip speed `slip` (m/s).
    #[inline]
    fn material(&self, np: &NodeP, t: f64, u: f64, slip: f64) -> Material {
        let m = self.material_base(np, t);
        self.apply_formulas(m, self.r.coulomb, np.p, t, u, slip)
    }

    #[inline]
    fn material_base(&self, np: &NodeP, t: f64) -> Material {
        let r = &self.r;
        if r.coulomb {
            let le = np.le / r.tf(t, r.le_t);
            return Material {
                tc1: np.bound,
                tc2: np.bound,
                lp: 1.0,
                le,
            };
        }
        if !r.plastic {
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
        let (tf1, tf2, tfp, tfe) = if r.temperature {
            // equal coefficients share one exponential (Tab. 4.1 has three equal ones)
            let tf1 = r.tf(t, r.tc1_t);
            let tf2 = if r.tc2_t == r.tc1_t {
                tf1
            } else {
                r.tf(t, r.tc2_t)
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

    /// Advances one bristle by one sub-step; returns its heat density q (W/m^2, both bodies).
    #[inline]
    fn update_bristle(
        &self,
        k: &Kin,
        np: &NodeP,
        [x, y]: [f64; 2],
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
        fac: &([f64; N_KERNEL], [f64; N_KERNEL]),
    ) -> f64 {
        let d = k.dist;
        let du = [d * (k.cx - k.cs * y), d * (k.cy + k.cs * x)];
        // Temperature from the heat history (all but the newest interval), Eq. 4.35.
        // acc[0] integrates all heat ever received (rate 0): zero means a cold history
        let warm = acc[0] != 0.0;
        let t_hist = if self.r.temperature && k.heat && warm {
            let mut sum = 0.0;
            for ((w, d), a) in self.kernel.weights.iter().zip(fac.0.iter()).zip(acc.iter()) {
                sum += w * d * a;
            }
            k.t_bulk + k.alpha_c * sum
        } else {
            k.t_bulk
        };
        let self_c = if k.heat {
            k.alpha_c * 2.0 * k.h.sqrt()
        } else {
            0.0
        };
        let old = *s;
        let u_abs = old.u[0].hypot(old.u[1]);
        let slip = if k.h > 0.0 {
            du[0].hypot(du[1]) / k.h
        } else {
            0.0
        };
        // Elastic-release heat (the -L dtau part of Eq. 4.29) caused by the sub-step's own
        // self-heating feeds back on the temperature with a gain of about
        // self_c |tau|^2 (L_x + L_e) X_T / h, which grows like 1/sqrt(h): below ~1 us the
        // implicit solve would run away (the half-space kernel has no heat capacity of the
        // layer to stop it). That part of the release is weighted by theta = min(1, 0.8/gain):
        // fully implicit while the sub-step's temperature equation is a contraction with
        // margin (gain < 0.8), damped only for tiny sub-steps (docs/model.md, section 6).
        let release_ref: std::cell::Cell<Option<[f64; 2]>> = std::cell::Cell::new(None);
        let theta = if k.heat && self.r.temperature {
            let cmax = self.r.tc1_t.max(self.r.tc2_t).max(self.r.lp_t);
            let t0 = old.tau[0].hypot(old.tau[1]).max(1.0);
            let gain = self_c * t0 * t0 * (k.lx.max(k.ly) + np.le) * cmax / k.h;
            if gain > 0.8 {
                0.8 / gain
            } else {
                1.0
            }
        } else {
            1.0
        };
        let eval = |t: f64| -> (BristleState, f64) {
            let m = self.material(np, t, u_abs, slip);
            let lxe = k.lx + m.le;
            let lye = k.ly + m.le;
            let lse = k.ls + m.le;
            let dtau = [
                d * (k.cx / lxe - k.cs * y / lse),
                d * (k.cy / lye + k.cs * x / lse),
            ];
            let mut ns = old;
            bristle::update(&mut ns, du, dtau, &m, [lxe, lye], self.r.rule);
            let q = if k.heat {
                let tr = match release_ref.get() {
                    Some(r) => [
                        r[0] + theta * (ns.tau[0] - r[0]),
                        r[1] + theta * (ns.tau[1] - r[1]),
                    ],
                    None => {
                        release_ref.set(Some(ns.tau));
                        ns.tau
                    }
                };
                let dux = du[0] - lxe * (tr[0] - old.tau[0]);
                let duy = du[1] - lye * (tr[1] - old.tau[1]);
                (self.r.kq * (ns.tau[0] * dux + ns.tau[1] * duy) / k.h).max(0.0)
            } else {
                0.0
            };
            (ns, q)
        };
        let (mut ns, mut q) = eval(t_hist);
        if self.r.temperature && q > 0.0 && self_c > 0.0 {
            // Solve T = t_hist + self_c q(T) for the smallest root above t_hist (the temperature
            // the bristle reaches first while heating up; q(T) may rise with T where softening
            // turns an elastic bristle plastic): fixed-point steps upward while
            // g(T) = t_hist + self_c q(T) - T > 0, then Illinois regula falsi once bracketed;
            // tolerance `t_tol`: 1e-4 relative change of the softening factors.
            let g_of = |q: f64, t: f64| t_hist + self_c * q - t;
            let tol = self.t_tol;
            let (mut ta, mut ga) = (t_hist, self_c * q);
            // predictor: this bristle's heat of its previous sub-step, when it lies inside
            // [t_hist, t_hist + self_c q(t_hist)]; else the fixed-point step from t_hist
            let mut tb = ta + ga;
            if old.q > 0.0 && self_c * old.q < ga {
                let tp = t_hist + self_c * old.q;
                let (sp, qp) = eval(tp);
                let gp = g_of(qp, tp);
                if gp.abs() < tol {
                    ns = sp;
                    q = qp;
                    tb = tp;
                    ta = tp;
                } else if gp > 0.0 {
                    ta = tp;
                    ga = gp;
                    tb = tp + gp;
                } else {
                    tb = tp;
                }
            }
            let mut bracketed = false;
            let mut gb = 0.0;
            for _ in 0..60 {
                if tb == ta {
                    break;
                }
                let (sb, qb) = eval(tb);
                ns = sb;
                q = qb;
                gb = g_of(qb, tb);
                if gb.abs() < tol {
                    break;
                }
                if gb > 0.0 {
                    ta = tb;
                    ga = gb;
                    tb += gb;
                } else {
                    bracketed = true;
                    break;
                }
            }
            if bracketed {
                let mut side = 0;
                for _ in 0..60 {
                    let tc = tb - gb * (tb - ta) / (gb - ga);
                    let (sc, qc) = eval(tc);
                    let gc = g_of(qc, tc);
                    ns = sc;
                    q = qc;
                    if gc.abs() < tol || (tb - ta).abs() < 1e-6 {
                        break;
                    }
                    if gc < 0.0 {
                        tb = tc;
                        gb = gc;
                        if side == -1 {
                            ga *= 0.5;
                        }
                        side = -1;
                    } else {
                        ta = tc;
                        ga = gc;
                        if side == 1 {
                            gb *= 0.5;
                        }
                        side = 1;
                    }
                }
            }
        }
        ns.temp = if self.r.temperature {
            t_hist + self_c * q
        } else {
            k.t_bulk
        };
        ns.q = q;
        *s = ns;
        if self.r.temperature && k.heat && (warm || q > 0.0) {
            let qw = q; // alpha is folded into alpha_c
            for ((a, d), g) in acc.iter_mut().zip(fac.0.iter()).zip(fac.1.iter()) {
                *a = d * *a + qw * g;
            }
        }
        q
    }

    #[inline]
    fn idx(&self, j: usize, slot: usize) -> usize {
        j * (self.nx + 1) + (self.head[j] + slot) % (self.nx + 1)
    }

    /// One sub-step of strip `j`: bristles move by `dist` (m) in time `h` (s); the phase is
    /// advanced by the caller. Nodes are evaluated at their end-of-sub-step positions.
    fn substep_strip(
        &mut self,
        j: usize,
        h: f64,
        dist: f64,
        phase_end: f64,
        skip: usize,
        end: usize,
    ) {
        let nx = self.nx;
        let dxi = 2.0 * self.ell[j] / nx as f64;
        let kin = self.kin(h, dist);
        let fac = self.factors(h, kin.heat);
        let inside = if phase_end > 0.0 { nx } else { nx + 1 };
        // update in place (the state vectors are moved out so `self` stays borrowable)
        let mut st = std::mem::take(&mut self.st);
        let mut accs = std::mem::take(&mut self.acc);
        for slot in skip..inside.min(end) {
            let xi = self.ell[j] - (slot as f64 + phase_end) * dxi;
            let id = self.idx(j, slot);
            self.move_bristle(j, xi, &kin, &fac, &mut st[id], &mut accs[id]);
        }
        self.st = st;
        self.acc = accs;
    }

    /// Kernel factors of a sub-step of length `h` (identity when no heat flows).
    fn factors(&self, h: f64, heat: bool) -> ([f64; N_KERNEL], [f64; N_KERNEL]) {
        if self.r.temperature && heat {
            self.kernel.step_factors(h)
        } else {
            ([1.0; N_KERNEL], [h; N_KERNEL])
        }
    }

    /// Moves one bristle of strip `j` over `kin.dist` to its end position `xi_end`
    /// (normalized). The material is taken at the end of the sub-step (Eq. 4.5), but never
    /// closer to the trailing edge than half a cell: the last node stands for the last cell
    /// (docs/model.md); the spin lever arm is the path's midpoint.
    #[inline]
    fn move_bristle(
        &self,
        j: usize,
        xi_end: f64,
        kin: &Kin,
        fac: &([f64; N_KERNEL], [f64; N_KERNEL]),
        s: &mut BristleState,
        acc: &mut [f64; N_KERNEL],
    ) {
        let a = self.patch.a;
        let dxi = 2.0 * self.ell[j] / self.nx as f64;
        let y = if self.patch.line {
            0.0
        } else {
            self.eta[j] * self.patch.b
        };
        let x_mid = a * (xi_end + 0.5 * kin.dist / a);
        let np = self.node_p(xi_end.max(-self.ell[j] + 0.5 * dxi), self.eta[j]);
        self.update_bristle(kin, &np, [x_mid, y], s, acc, fac);
    }

    /// States of the `count` bristles that entered strip `j` during the current step: the one
    /// in slot k made k full cell moves, then the final partial move `d_end` (m) that ends at
    /// the strip's phase. Same updates, positions and sub-step lengths as the sub-step loop.
    fn march_new(&mut self, j: usize, count: usize, d_end: f64) {
        let v = self.inputs.v;
        let dx = 2.0 * self.ell[j] * self.patch.a / self.nx as f64;
        let dxi = 2.0 * self.ell[j] / self.nx as f64;
        let phase_end = self.phase[j];
        // With v = 0 (the steady march at standstill) the march is over distance only and
        // carries no heat: the v -> 0 limit.
        let time = |d: f64| if v > V_STANDSTILL { d / v } else { 0.0 };
        let kin_full = self.kin(time(dx), dx);
        let fac_full = self.factors(time(dx), kin_full.heat);
        let kin_part = self.kin(time(d_end), d_end);
        let fac_part = self.factors(time(d_end), kin_part.heat);
        let mut s = BristleState {
            temp: self.inputs.t_bulk,
            ..BristleState::default()
        };
        let mut acc = [0.0; N_KERNEL];
        for k in 0..count {
            let id = self.idx(j, k);
            // slot nx is past the trailing edge once the phase is > 0: not moved (as in the loop)
            if d_end > 0.0 && k < self.nx {
                let (mut ps, mut pacc) = (s, acc);
                self.move_bristle(
                    j,
                    self.ell[j] - (k as f64 + phase_end) * dxi,
                    &kin_part,
                    &fac_part,
                    &mut ps,
                    &mut pacc,
                );
                self.st[id] = ps;
                self.acc[id] = pacc;
            } else {
                self.st[id] = s;
                self.acc[id] = acc;
            }
            if k + 1 < count {
                self.move_bristle(
                    j,
                    self.ell[j] - (k as f64 + 1.0) * dxi,
                    &kin_full,
                    &fac_full,
                    &mut s,
                    &mut acc,
                );
            }
        }
    }

    /// A new bristle enters strip `j`: the oldest slot is recycled at the leading edge.
    fn enter_bristle(&mut self, j: usize) {
        let nx1 = self.nx + 1;
        self.head[j] = (self.head[j] + self.nx) % nx1;
        let id = self.idx(j, 0);
        self.st[id] = BristleState {
            temp: self.inputs.t_bulk,
            ..BristleState::default()
        };
        self.acc[id] = [0.0; N_KERNEL];
        self.phase[j] = 0.0;
    }

    /// Advances the contact by `dt` seconds with `inputs` held constant over the step
    /// (Eq. 4.15). With the effect `transient` off, returns the quasi-steady state instead.
    pub fn step(&mut self, dt: f64, inputs: &Inputs) -> Result<Outputs> {
        check_range("dt", dt, 0.0, 1e3, "s")?;
        if !self.r.transient || !self.initialized {
            let out = self.steady(inputs)?;
            self.time += dt;
            return Ok(out);
        }
        self.set_inputs(inputs)?;
        if inputs.fn_n <= 0.0 {
            return Ok(self.lift_off());
        }
        let v = inputs.v;
        let a = self.patch.a;
        for j in 0..self.ny {
            let dx = 2.0 * self.ell[j] * a / self.nx as f64;
            if v <= V_STANDSTILL || dt == 0.0 {
                let ph = self.phase[j];
                self.substep_strip(j, dt, 0.0, ph, 0, self.nx + 1);
                continue;
            }
            let mut remaining = v * dt;
            let tol = 1e-9 * dx;
            // Bristles that enter during this step see only this step's (constant) inputs:
            // full cells, then the final partial move. They are computed afterwards by a march
            // (`march_new`), which performs exactly the updates the sub-step loop would, so the
            // loop only advances the bristles that were in the contact before the step
            // (slots >= n_new). With v dt >= 2a the whole step costs one steady march.
            let mut n_new = 0usize;
            let mut d_end = 0.0;
            // Bristles that will leave before the end of the step need no update at all: count
            // this step's entries first (same arithmetic as the loop below).
            let wraps = {
                let (mut rem, mut ph, mut w) = (remaining, self.phase[j], 0usize);
                while rem > tol {
                    let to_next = (1.0 - ph) * dx;
                    if rem >= to_next - tol {
                        w += 1;
                        rem -= to_next;
                        ph = 0.0;
                    } else {
                        rem = 0.0;
                    }
                }
                w
            };
            while remaining > tol {
                let to_next = (1.0 - self.phase[j]) * dx;
                if remaining >= to_next - tol {
                    // end positions are one node further (phase 1), then the slots shift
                    if !self.march {
                        self.substep_strip(j, to_next / v, to_next, 1.0, 0, self.nx + 1);
                    } else if n_new + (wraps - n_new) <= self.nx {
                        self.substep_strip(
                            j,
                            to_next / v,
                            to_next,
                            1.0,
                            n_new,
                            self.nx + 1 - (wraps - n_new),
                        );
                    }
                    // all bristles moved one node: the slot numbering shifts by recycling the oldest
                    self.enter_bristle(j);
                    n_new += 1;
                    remaining -= to_next;
                } else {
                    let ph = self.phase[j] + remaining / dx;
                    if !self.march {
                        self.substep_strip(j, remaining / v, remaining, ph, 0, self.nx + 1);
                    } else if n_new <= self.nx {
                        self.substep_strip(j, remaining / v, remaining, ph, n_new, self.nx + 1);
                    }
                    self.phase[j] = ph;
                    d_end = remaining;
                    remaining = 0.0;
                }
            }
            if n_new > 0 && self.march {
                self.march_new(j, n_new.min(self.nx + 1), d_end);
            }
        }
        self.time += dt;
        self.out = self.integrate();
        Ok(self.out)
    }

    fn lift_off(&mut self) -> Outputs {
        for s in self.st.iter_mut() {
            *s = BristleState {
                temp: self.inputs.t_bulk,
                ..BristleState::default()
            };
        }
        for a in self.acc.iter_mut() {
            *a = [0.0; N_KERNEL];
        }
        self.out = Outputs {
            t_max: self.inputs.t_bulk,
            t_mean: self.inputs.t_bulk,
            frac_elastic: 1.0,
            ..Outputs::default()
        };
        self.out
    }

    /// Sets the grid to the steady state of constant `inputs` and returns its outputs.
    /// Does not advance time.
    pub fn steady(&mut self, inputs: &Inputs) -> Result<Outputs> {
        self.set_inputs(inputs)?;
        self.initialized = true;
        if inputs.fn_n <= 0.0 {
            return Ok(self.lift_off());
        }
        // the steady state is the grid a transient run reaches with constant inputs: every
        // bristle entered under these inputs, i.e. the march of newly entered bristles over
        // the whole strip at phase 0
        for j in 0..self.ny {
            self.head[j] = 0;
            self.phase[j] = 0.0;
            self.march_new(j, self.nx + 1, 0.0);
        }
        self.out = self.integrate();
        Ok(self.out)
    }

    /// Quadrature weights (normalized length) of the nodes of strip `j` for its phase.
    fn weights(&self, j: usize, w: &mut [f64]) {
        let nx = self.nx;
        let dxi = 2.0 * self.ell[j] / nx as f64;
        let ph = self.phase[j];
        for x in w.iter_mut() {
            *x = 0.0;
        }
        w[0] += 0.5 * ph * dxi;
        for k in 0..nx - 1 {
            w[k] += 0.5 * dxi;
            w[k + 1] += 0.5 * dxi;
        }
        let lt = (1.0 - ph) * dxi;
        w[nx - 1] += 0.5 * lt * (1.0 + ph);
        w[nx] += 0.5 * lt * (1.0 - ph);
    }

    fn integrate(&self) -> Outputs {
        let (a, b) = (self.patch.a, self.patch.b);
        let nx = self.nx;
        let mut w = vec![0.0; nx + 1];
        let (mut fx, mut fy, mut mz, mut pf, mut tsum, mut area) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        let mut fr = [0.0; 3];
        let mut tmax = f64::NEG_INFINITY;
        for j in 0..self.ny {
            self.weights(j, &mut w);
            let dy = if self.patch.line {
                2.0 * b
            } else {
                self.deta[j] * b
            };
            let y = if self.patch.line {
                0.0
            } else {
                self.eta[j] * b
            };
            let dxi = 2.0 * self.ell[j] / nx as f64;
            for (slot, wk) in w.iter().enumerate() {
                let s = &self.st[self.idx(j, slot)];
                let da = wk * a * dy;
                let x = a * (self.ell[j] - (slot as f64 + self.phase[j]) * dxi);
                fx += s.tau[0] * da;
                fy += s.tau[1] * da;
                mz += (x * s.tau[1] - y * s.tau[0]) * da;
                pf += s.q * da;
                if *wk > 0.0 {
                    tsum += s.temp * da;
                    area += da;
                    fr[s.regime as usize] += da;
                    tmax = tmax.max(s.temp);
                }
            }
        }
        let fn_n = self.inputs.fn_n;
        let area = area.max(f64::MIN_POSITIVE);
        Outputs {
            fx,
            fy,
            mz,
            f: if fn_n > 0.0 { fx / fn_n } else { 0.0 },
            t_max: if tmax.is_finite() {
                tmax
            } else {
                self.inputs.t_bulk
            },
            t_mean: tsum / area,
            p_fric: pf,
            frac_elastic: fr[0] / area,
            frac_plastic: fr[1] / area,
            frac_sliding: fr[2] / area,
            a,
            b,
            p0: self.patch.p0,
        }
    }

    /// Fields along the strip nearest y = 0, from the leading to the trailing edge.
    pub fn field_y0(&self) -> Vec<FieldPoint> {
        let j = (0..self.ny)
            .min_by(|&p, &q| self.eta[p].abs().total_cmp(&self.eta[q].abs()))
            .unwrap_or(0);
        let nx = self.nx;
        let dxi = 2.0 * self.ell[j] / nx as f64;
        let inside = if self.phase[j] > 0.0 { nx } else { nx + 1 };
        (0..inside)
            .map(|slot| {
                let xi = self.ell[j] - (slot as f64 + self.phase[j]) * dxi;
                let s = &self.st[self.idx(j, slot)];
                let np = self.node_p(xi, self.eta[j]);
                let v = self.inputs.v;
                let slip = v
                    * (self.inputs.cx - self.inputs.spin * self.eta[j] * self.patch.b)
                        .hypot(self.inputs.cy + self.inputs.spin * xi * self.patch.a);
                let m = self.material(&np, s.temp, s.u[0].hypot(s.u[1]), slip);
                FieldPoint {
                    x: xi * self.patch.a,
                    tau: (s.tau[0] * s.tau[0] + s.tau[1] * s.tau[1]).sqrt(),
                    tau_x: s.tau[0],
                    tau_c1: m.tc1,
                    tau_c2: m.tc2,
                    p: np.p,
                    t: s.temp,
                    regime: s.regime as u8,
                }
            })
            .collect()
    }

    /// Raw state for serialization: (time, inputs, heads, phases, bristles, accumulators, initialized).
    #[allow(clippy::type_complexity)]
    pub(crate) fn raw_state(
        &self,
    ) -> (
        f64,
        Inputs,
        &[usize],
        &[f64],
        &[BristleState],
        &[[f64; N_KERNEL]],
        bool,
        Outputs,
    ) {
        (
            self.time,
            self.inputs,
            &self.head,
            &self.phase,
            &self.st,
            &self.acc,
            self.initialized,
            self.out,
        )
    }

    /// Restores a raw state; checks the sizes.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn set_raw_state(
        &mut self,
        time: f64,
        inputs: Inputs,
        head: Vec<usize>,
        phase: Vec<f64>,
        st: Vec<BristleState>,
        acc: Vec<[f64; N_KERNEL]>,
        initialized: bool,
        out: Outputs,
    ) -> Result<()> {
        if head.len() != self.ny
            || phase.len() != self.ny
            || st.len() != self.st.len()
            || acc.len() != self.acc.len()
        {
            return Err(CreepError::State(format!(
                "grid mismatch: state has {} strips / {} bristles, contact has {} / {}",
                head.len(),
                st.len(),
                self.ny,
                self.st.len()
            )));
        }
        if head.iter().any(|&h| h > self.nx) || phase.iter().any(|p| !(0.0..1.0).contains(p)) {
            return Err(CreepError::State(
                "corrupt ring-buffer head or phase".into(),
            ));
        }
        self.time = time;
        self.set_inputs(&inputs)?;
        self.head = head;
        self.phase = phase;
        self.st = st;
        self.acc = acc;
        self.initialized = initialized;
        self.out = out;
        Ok(())
    }

    /// Switches the march of newly entered bristles off (plain sub-step loop for every
    /// bristle). For tests that show both give identical results.
    #[doc(hidden)]
    pub fn set_march_new_bristles(&mut self, on: bool) {
        self.march = on;
    }

    /// Grid size (nx, ny actually used; a line contact has one strip).
    pub fn grid_size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
}

/// Regime counter helper for tests and callers.
pub fn regime_name(r: Regime) -> &'static str {
    match r {
        Regime::Elastic => "elastic",
        Regime::Plastic => "plastic",
        Regime::Sliding => "sliding",
    }
}

/// The layer's material alone at normal stress `p` (Pa) and temperature `t` (degC), from
/// the configuration's parameters and effects (Eq. 4.3, 4.4; formula effects not applied).
pub fn layer_material(cfg: &Config, p: f64, t: f64) -> Material {
    let r = Resolved::from_config(cfg);
    let le = if r.layer_el {
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

/// Contact patch of a configuration at a normal force.
pub fn patch_for(cfg: &Config, fn_n: f64) -> Result<Patch> {
    let p = &cfg.params;
    match cfg.geometry {
        Geometry::SemiAxes { a, b, fn_ref } => {
            let s = (fn_n / fn_ref).cbrt();
            Patch::from_semi_axes(a * s, b * s, fn_n)
        }
        Geometry::Curvatures { rx, ry } => {
            hertz::hertz_from_curvatures(rx, ry, fn_n, p.si(P::G), p.si(P::Nu))
        }
        Geometry::Line { r, width } => {
            hertz::line_contact(r, fn_n / width, width, p.si(P::G), p.si(P::Nu))
        }
    }
}
