//! What a bristle move reads: the contact's law (built once, read-only while bristles move), its lattice, and the mover that joins them with the step's kinematics.

use super::fastpath::Taken;
use super::modifiers::Modifiers;
use super::{grid, Inputs};
use crate::config::{Config, Geometry, ModelKind};
use crate::hertz::Patch;
use crate::material::Resolved;
use crate::scheme::Scheme;
use crate::thermal::{self, Kernel};

/// The contact's law: the resolved material law, heat kernel, modifiers, scheme and fast
/// paths. Built once per contact from its configuration; a step may move the modifiers to its
/// operating point, and nothing changes it while the bristles move.
#[derive(Clone, Debug)]
pub(super) struct Law {
    /// The material law resolved from the configuration's parameters and effects.
    pub r: Resolved,
    /// The flash temperature's heat kernel (module [`crate::thermal`]).
    pub kernel: Kernel,
    /// Temperature tolerance of the local solve, K ([`thermal::temperature_tolerance`] of the
    /// largest temperature coefficient).
    pub t_tol: f64,
    /// How the local temperature of a move is solved ([`thermal::TemperatureSolve`]).
    pub t_solve: thermal::TemperatureSolve,
    /// The predictor's miss (K) above which the predictor-corrector takes a third
    /// evaluation ([`thermal::pc_miss`] of the largest temperature coefficient).
    pub pc_miss: f64,
    /// The configuration's formula and Rust effects at the current operating point.
    pub modifiers: Modifiers,
    /// How a step advances the bristles (see [`Scheme`]).
    pub scheme: Scheme,
    /// The higher-order rules apply ([`Scheme::CellsHigher`] on an ECF layer under the
    /// same-characteristic rule).
    pub ho: bool,
    /// The fast paths this contact takes (module `fastpath` states what each supports).
    pub fast: Taken,
    /// Test switch: the cell schemes march the bristles that enter during a step (off: the
    /// plain sub-step loop for every bristle, the reference a test compares the march with).
    pub march_new: bool,
    /// Test switch: the higher-order rules take their start nodes from the lattice cache (or
    /// the previous edge sub-move) where a move starts on a node (off: each computed where
    /// the move starts, for a test that shows both agree).
    pub start_cache: bool,
}

impl Law {
    /// The law of a configuration, with its scheme and no fast path yet (the contact sets
    /// them, [`super::Contact::set_fast_path`]).
    pub fn new(cfg: &Config) -> Self {
        let r = Resolved::from_config(cfg);
        let cmax = r.tc1_t.max(r.tc2_t).max(r.lp_t).max(r.le_t);
        let mut law = Law {
            r,
            kernel: Kernel::default(),
            t_tol: thermal::temperature_tolerance(cmax),
            t_solve: cfg.temperature_solve,
            pc_miss: thermal::pc_miss(cmax),
            modifiers: Modifiers::new(&cfg.modifiers),
            scheme: cfg.scheme,
            ho: false,
            fast: Taken::default(),
            march_new: true,
            start_cache: true,
        };
        law.set_scheme(cfg.scheme, cfg.model);
        law
    }

    /// Sets the scheme, with the higher-order rules where they apply (model `model`).
    pub fn set_scheme(&mut self, scheme: Scheme, model: ModelKind) {
        self.scheme = scheme;
        self.ho = scheme == Scheme::CellsHigher
            && model == ModelKind::Ecf
            && self.r.on.rule == crate::bristle::Rule::SameCharacteristic;
    }

    /// True if the dedicated FASTSIM march applies: the configuration lies within what
    /// [`super::FastPath::Coulomb`] supports (engine/fastpath.rs `COULOMB`; the `fastsim`
    /// preset).
    #[inline]
    pub fn coulomb_path(&self) -> bool {
        self.fast.coulomb && !self.ho
    }

    /// True if formula or custom effects modify the material.
    #[inline]
    pub fn has_modifiers(&self) -> bool {
        !self.modifiers.is_empty()
    }
}

/// The bristle grid's geometry: `ny` strips at the Gauss-Legendre nodes in eta = y/b (a line
/// contact: one strip of width 2), each of `nx` cells.
#[derive(Clone, Debug)]
pub(super) struct Lattice {
    /// Cells per strip.
    pub nx: usize,
    /// Strips.
    pub ny: usize,
    /// Normalized strip centres eta_j = y/b.
    pub eta: Vec<f64>,
    /// Normalized strip half-lengths l_j = sqrt(1 - eta_j^2).
    pub ell: Vec<f64>,
    /// Strip widths d eta_j (the Gauss-Legendre weights).
    pub deta: Vec<f64>,
}

impl Lattice {
    /// The lattice of a configuration's grid and geometry.
    pub fn new(cfg: &Config) -> Self {
        let (nx, ny) = (cfg.grid.nx, cfg.grid.ny);
        let line = matches!(cfg.geometry, Geometry::Line { .. });
        let ny = if line { 1 } else { ny };
        // the strips at the Gauss-Legendre nodes in eta = y/b, each with its weight as its
        // width (grid::strip_rule); a line contact has one strip of width 2
        let (eta, deta): (Vec<f64>, Vec<f64>) = if line {
            (vec![0.0], vec![2.0])
        } else {
            grid::strip_rule(ny).into_iter().unzip()
        };
        let ell = eta.iter().map(|e| (1.0 - e * e).sqrt()).collect();
        Lattice {
            nx,
            ny,
            eta,
            ell,
            deta,
        }
    }
}

/// What a bristle move reads: the law, the lattice, and the step's kinematics (the patch and
/// flexibilities at the step's normal force and the step's inputs, forward frame). The
/// moves are its methods: functions of it and the strip they advance, nothing else.
#[derive(Clone, Copy)]
pub(super) struct Mover<'a> {
    /// The contact's law.
    pub law: &'a Law,
    /// The bristle grid's geometry.
    pub lat: &'a Lattice,
    /// The Hertz patch at the step's normal force.
    pub patch: &'a Patch,
    /// Kalker's flexibilities (L_x, L_y, L_s) at that force, as
    /// [`crate::kalker::flexibilities`] gives them.
    pub flex: (f64, f64, f64),
    /// The step's inputs, forward frame (v >= 0).
    pub inputs: &'a Inputs,
}
