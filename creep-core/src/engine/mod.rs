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
//!
//! Where each job lives: this file holds the contact's state and the time loop (`step`,
//! `steady`); `raw_state` that state borrowed out and restored for module [`crate::state`];
//! [`io`] the inputs and outputs; `strip` one strip as a unit of
//! work (its state borrowed out of the contact, the strips of a step on `threads` threads)
//! and the cell-by-cell scheme; `advance` one bristle move, the sub-step loop and march;
//! `grid` the integrals and fields; `modifiers` the formula and custom effects; `softening`
//! the temperature solve of a layer that only softens as it heats (on the law's branch as a
//! scalar function of T). The material law is [`crate::material`], the temperature solve and heat
//! kernel [`crate::thermal`], the Hertz patch [`crate::hertz`].

mod advance;
mod bristle_move;
mod fastpath;
mod grid;
pub mod io;
mod kin;
mod modifiers;
mod raw_state;
mod softening;
mod steady_coulomb;
mod strip;

pub use crate::hertz::patch_for;
pub use crate::material::layer_material;
pub use fastpath::FastPath;
pub use io::{FieldPoint, Inputs, Outputs, V_STANDSTILL};
pub(crate) use raw_state::OwnedRawState;

use crate::bristle::{BristleState, Regime};
use crate::config::{Config, Geometry, ModelKind};
use crate::error::{check_range, CreepError, Result};
use crate::hertz::Patch;
use crate::kalker;
use crate::material::Resolved;
use crate::thermal::{self, Kernel, N_KERNEL};

/// How [`Contact::step`] advances the bristles that were in the contact before the step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scheme {
    /// Default: one sub-step per cell crossing for every bristle (the steady march's cells),
    /// new bristles by a march. Independent of the communication step within 0.5 %.
    CellsMarch,
    /// Faster (about 3x fewer bristle moves at 0.1-0.25 ms steps on 80x21): the bristles
    /// that stay move continuously, in equal sub-steps of at most [`MAX_SUBSTEP_CELLS`]
    /// cells, cut into one-cell pieces within [`EDGE_CELLS`] cells of the trailing edge and
    /// ending each step with a one-cell piece; a sub-step of n > 1 cells weighs its start
    /// stress by (1 - 1/n)/2 in its dissipation (Eq. 4.29), as n one-cell moves would.
    /// Bristles that enter during the step are marched cell by cell. On 80x21 its
    /// dependence on the communication step after a creepage step at 20 m/s (1 x 1 ms vs
    /// 10 x 0.1 ms) is 0.05-0.4 % for table4.1 (within the grid's own error) and 0.9-1.5 %
    /// for dry; forces under inputs that jump every step follow [`Scheme::CellsMarch`]
    /// within 1.5 % (docs/model.md section 3).
    Continuous,
    /// Reference: one sub-step per cell crossing for every bristle, no march (slowest).
    Cells,
    /// [`Scheme::CellsMarch`] with the higher-order rules along each move (ECF's
    /// same-characteristic law; docs/model.md section 9, step 8): tau_c2 linear and 1/L_p
    /// along the move's temperature profile from the start material's to the end
    /// material's, the newest interval of Eq. 4.35 with the heat rate linear over the move,
    /// the move from the leading edge in [`advance::EDGE_SUB`] graded sub-moves, and the
    /// leading cell's sqrt(s) term in the quadrature. About twice the cost of
    /// [`Scheme::CellsMarch`] on the same grid, and more accurate on a grid of equal cost.
    /// FASTSIM (and any other perfectly plastic or elastic-unloading layer) takes
    /// [`Scheme::CellsMarch`].
    CellsHigher,
}

impl Scheme {
    /// The names a configuration file and the command line give the schemes.
    pub const NAMES: &'static str = "cells, cells-ho or continuous";

    /// The scheme's name in a configuration file, the accuracy table and on the command
    /// line (`cells` is [`Scheme::CellsMarch`]; the reference [`Scheme::Cells`] too).
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Continuous => "continuous",
            Scheme::CellsMarch | Scheme::Cells => "cells",
            Scheme::CellsHigher => "cells-ho",
        }
    }

    /// The scheme a model runs when its configuration names none: `cells-ho` for ECF (on the
    /// default grid 80x21 its steady curves are within 0.2 % of 640x168 for dry, table4.1
    /// and wet at 5-30 m/s where `cells` was up to 1.2 %, for about 10 % more cost in steady
    /// curves and twice the cost in time steps; docs/model.md section 9), `cells` for
    /// FASTSIM and Polach (their layers take the cell-by-cell rules in any case).
    pub fn default_for(model: crate::ModelKind) -> Scheme {
        match model {
            crate::ModelKind::Ecf => Scheme::CellsHigher,
            crate::ModelKind::Fastsim | crate::ModelKind::Polach => Scheme::CellsMarch,
        }
    }

    /// The scheme of a name ([`Scheme::name`]), None for any other text.
    pub fn by_name(name: &str) -> Option<Scheme> {
        match name {
            "cells" => Some(Scheme::CellsMarch),
            "continuous" => Some(Scheme::Continuous),
            "cells-ho" => Some(Scheme::CellsHigher),
            _ => None,
        }
    }
}

/// Normal forces at or below this (N) are lift-off: the contact carries nothing. (The
/// contact length shrinks like F_N^(1/3); a vanishing contact is not a tiny one.)
pub const F_LIFT_OFF: f64 = 1e-3;

/// Longest sub-step of a bristle in [`Scheme::Continuous`], in cells of the central strip.
pub const MAX_SUBSTEP_CELLS: f64 = 8.0;

/// Width of the zone at the trailing edge, in cells of the strip, in which
/// [`Scheme::Continuous`] moves the bristles by at most one cell per sub-step.
pub const EDGE_CELLS: f64 = 4.0;

/// The part of the current cell a strip has travelled since its bristles' last lattice node
/// (the whole-cell commit, docs/model.md section 3): sums over the steps' pieces of it.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Partial {
    /// Distance travelled, m.
    pub d: f64,
    /// Time taken, s.
    pub h: f64,
    /// Sum of distance x longitudinal creepage, m.
    pub dcx: f64,
    /// Sum of distance x lateral creepage, m.
    pub dcy: f64,
    /// Sum of distance x spin creepage (1/m), dimensionless.
    pub dcs: f64,
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
    /// Whole-cell commit: each bristle's state and accumulators at its last lattice node
    /// (`st`, `acc` hold it at the strip's phase, for the outputs), and per strip the part
    /// of the current cell travelled since (see [`Partial`]).
    node_st: Vec<BristleState>,
    /// Heat-kernel accumulators at the last lattice node (same index as `node_st`), J/m^2.
    node_acc: Vec<[f64; N_KERNEL]>,
    /// Per strip, the part of the current cell travelled since that node.
    part: Vec<Partial>,
    /// Time since start, s.
    time: f64,
    inputs: Inputs,
    patch: Patch,
    /// Normal force (N) that `patch` and `flex` belong to (NaN: none yet).
    patch_fn: f64,
    flex: (f64, f64, f64),
    out: Outputs,
    initialized: bool,
    warnings: Vec<String>,
    /// Temperature tolerance of the local solve, K ([`thermal::temperature_tolerance`] of the
    /// largest temperature coefficient).
    t_tol: f64,
    /// How the local temperature of a move is solved ([`thermal::TemperatureSolve`]).
    t_solve: thermal::TemperatureSolve,
    /// The predictor's miss (K) above which the predictor-corrector takes a third
    /// evaluation ([`thermal::pc_miss`] of the largest temperature coefficient).
    pc_miss: f64,
    /// Pressure parts of the lattice nodes per strip, for the peak pressure in `np_cache_p0`.
    np_cache: Vec<Vec<crate::material::NodeP>>,
    np_cache_p0: Vec<f64>,
    /// Coulomb bounds of the lattice nodes, strips side by side (FASTSIM's steady march),
    /// for the peak pressure in `bound_cache_p0`.
    bound_cache: Vec<[f64; steady_coulomb::LANES]>,
    bound_cache_p0: f64,
    /// Kernel factors of recent sub-step lengths (h, factors), per strip.
    fac_cache: Vec<Vec<(f64, thermal::StepFactors)>>,
    /// Threads that advance the strips (None: the calling thread alone).
    pool: Option<std::sync::Arc<rayon::ThreadPool>>,
    /// How a step advances the bristles (see [`Scheme`]).
    scheme: Scheme,
    /// The higher-order rules apply ([`Scheme::CellsHigher`] on an ECF layer under the
    /// same-characteristic rule).
    ho: bool,
    /// The higher-order rules' start nodes from the lattice cache (or the previous edge
    /// sub-move) where a move starts on a node; off: each computed where the move starts
    /// (for a test that shows both agree).
    start_cache: bool,
    /// Rolling backwards (the last non-zero speed was negative): the grid and `inputs`,
    /// `out` are held in the mirrored frame x -> -x, where the contact rolls forwards.
    reversed: bool,
    /// The configuration's formula and Rust effects at the current operating point.
    modifiers: modifiers::Modifiers,
    /// True if moves with heat flow take the scalar temperature solve of `softening`
    /// ([`FastPath::Softening`]: a layer that only softens as it heats, the
    /// same-characteristic rule, no modifier of the local bristle state).
    softening_fast: bool,
    /// The other fast paths this contact takes ([`FastPath::Coulomb`], [`FastPath::FixedLe`],
    /// [`FastPath::Cold`];
    /// module `fastpath` states what each supports).
    fast: fastpath::Taken,
    /// Every strip's state equals its mirror image's about y = 0 (strip ny - 1 - j), bit for
    /// bit: then, while the inputs are symmetric too, one of each pair is computed and copied
    /// ([`Contact::each_strip`]).
    strips_mirrored: bool,
    /// `strips_mirrored` is still to be found from the state FASTSIM's steady march left
    /// ([`Contact::settle_mirrored`]): a run of steady states alone never needs it, so the
    /// comparison of every strip with its mirror image waits for the next step.
    mirrored_unknown: bool,
    /// Every node accumulator in `node_acc` is 0 (bit for bit): FASTSIM's steady march then
    /// need not clear them again. Whatever may write them (a step, a restored state, a reset
    /// of the nodes) sets this false.
    node_acc_zero: bool,
    /// Symmetric strips are computed once ([`Contact::set_mirror_strips`]; off for tests and
    /// benchmarks that compare both).
    mirror_strips: bool,
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
        // the strips at the Gauss-Legendre nodes in eta = y/b, each with its weight as its
        // width (grid::strip_rule); a line contact has one strip of width 2
        let (eta, deta): (Vec<f64>, Vec<f64>) = if line {
            (vec![0.0], vec![2.0])
        } else {
            grid::strip_rule(ny).into_iter().unzip()
        };
        let ell = eta.iter().map(|e| (1.0 - e * e).sqrt()).collect();
        let n = ny * (nx + 1);
        let patch = Patch {
            a: 1.0,
            b: 1.0,
            p0: 0.0,
            line,
        };
        let mut c = Contact {
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
            node_st: vec![BristleState::default(); n],
            node_acc: vec![[0.0; N_KERNEL]; n],
            part: vec![Partial::default(); ny],
            time: 0.0,
            inputs: Inputs::default(),
            patch,
            patch_fn: f64::NAN,
            flex: (0.0, 0.0, 0.0),
            out: Outputs::default(),
            initialized: false,
            warnings: Vec::new(),
            scheme: cfg.scheme,
            ho: false,
            start_cache: true,
            reversed: false,
            np_cache: vec![Vec::new(); ny],
            np_cache_p0: vec![f64::NAN; ny],
            bound_cache: Vec::new(),
            bound_cache_p0: f64::NAN,
            fac_cache: vec![Vec::new(); ny],
            pool: None,
            modifiers: modifiers::Modifiers::new(&cfg.modifiers),
            softening_fast: false,
            fast: fastpath::Taken::default(),
            strips_mirrored: true,
            mirrored_unknown: false,
            node_acc_zero: true,
            mirror_strips: true,
            t_solve: cfg.temperature_solve,
            t_tol: {
                let r = Resolved::from_config(cfg);
                let cmax = r.tc1_t.max(r.tc2_t).max(r.lp_t).max(r.le_t);
                thermal::temperature_tolerance(cmax)
            },
            pc_miss: {
                let r = Resolved::from_config(cfg);
                thermal::pc_miss(r.tc1_t.max(r.tc2_t).max(r.lp_t).max(r.le_t))
            },
        };
        for path in FastPath::ALL {
            c.set_fast_path(path, true);
        }
        // the configuration's scheme, with the higher-order rules where they apply
        c.set_scheme(cfg.scheme);
        Ok(c)
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
        mirror_outputs(self.out, self.reversed)
    }

    /// Last inputs.
    pub fn inputs(&self) -> Inputs {
        mirror_inputs(&self.inputs, self.reversed)
    }

    /// True while the contact rolls backwards (the last non-zero speed was negative).
    pub fn reversed(&self) -> bool {
        self.reversed
    }

    /// The rolling direction for `inputs`: backwards for v < 0, forwards for v > 0, unchanged
    /// at standstill.
    fn wants_reversed(&self, inputs: &Inputs) -> bool {
        if inputs.v < 0.0 {
            true
        } else if inputs.v > 0.0 {
            false
        } else {
            self.reversed
        }
    }

    /// Rolling backwards is rolling forwards in the mirror image x -> -x (docs/model.md
    /// section 3, "Reversed rolling"): the bristles in the contact stay in it, mirrored in
    /// place (their slots reversed, the phase p -> 1 - p, u_x and tau_x negated; heat
    /// histories unchanged).
    fn mirror_grid(&mut self) {
        let nx = self.nx;
        for j in 0..self.ny {
            let p = self.phase[j];
            let old: Vec<(BristleState, [f64; N_KERNEL])> = (0..=nx)
                .map(|slot| {
                    let id = self.idx(j, slot);
                    (self.st[id], self.acc[id])
                })
                .collect();
            let base = j * (nx + 1);
            for (slot, (mut b, a)) in old.into_iter().enumerate() {
                b.u[0] = -b.u[0];
                b.tau[0] = -b.tau[0];
                // node positions xi_k = l - (k + p) dxi map to -xi_k
                if p > 0.0 && slot == nx {
                    continue; // it had left at the old trailing edge: ahead of the new leading one
                }
                let new = if p > 0.0 { nx - 1 - slot } else { nx - slot };
                self.st[base + new] = b;
                self.acc[base + new] = a;
            }
            if p > 0.0 {
                // past the new trailing edge lies the unloaded material that was ahead of the
                // old leading edge (the quadrature interpolates towards it)
                self.st[base + nx] = BristleState {
                    temp: self.inputs.t_bulk,
                    ..BristleState::default()
                };
                self.acc[base + nx] = [0.0; N_KERNEL];
            }
            self.head[j] = 0;
            if p > 0.0 {
                self.phase[j] = 1.0 - p;
            }
        }
        self.reset_nodes();
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
        // the patch and flexibilities depend on F_N only (the configuration is fixed)
        if inputs.fn_n > F_LIFT_OFF && inputs.fn_n != self.patch_fn {
            self.patch = self.patch_for(inputs.fn_n)?;
            let (a, b) = (self.patch.a, self.patch.b);
            let (ka, kb) = if self.patch.line {
                (a, 1e6 * a)
            } else {
                (a, b)
            };
            let c = kalker::coefficients(ka, kb, self.r.nu)?;
            self.flex = kalker::flexibilities(ka, kb, self.r.g, &c);
            if self.patch.line {
                // a 2-D strip: Carter's flexibility, not the elliptic one (kalker.rs)
                let (lx, ly) = kalker::line_flexibilities(a, self.r.g, self.r.nu);
                self.flex.0 = lx;
                self.flex.1 = ly;
            }
            self.patch_fn = inputs.fn_n;
        }
        self.inputs = *inputs;
        self.update_modifiers()?;
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
            if (1.0 + inputs.cx).abs() < 0.1 && !self.r.surface_time {
                let msg = format!(
                    "wheel surface speed v (1 + c_x) = {:.3} m/s is below 10 % of v (c_x = {}, wheel slide): the heat partition of Eq. 4.30 sends the heat into the rail and the seed's flash temperature (Eq. 4.34, evaluated in the layer's time) then underestimates the contact temperature by about sqrt(v_w/v), down to none for a locked wheel; the effect surface_time_flash evaluates it over the wheel surface's own time (docs/model.md section 11)",
                    inputs.v * (1.0 + inputs.cx).abs(),
                    inputs.cx
                );
                if !self
                    .warnings
                    .iter()
                    .any(|w| w.starts_with("wheel surface speed"))
                {
                    self.warnings.push(msg);
                }
            }
        }
        Ok(())
    }

    /// Advances the contact by `dt` seconds with `inputs` held constant over the step
    /// (Eq. 4.15). With the effect `transient` off, returns the quasi-steady state instead.
    /// A negative speed rolls the contact backwards (the mirror image, see
    /// [`Contact::reversed`]); a change of direction keeps the bristles in the contact.
    pub fn step(&mut self, dt: f64, inputs: &Inputs) -> Result<Outputs> {
        check_range("dt", dt, 0.0, 1e3, "s")?;
        inputs.validate()?;
        // on the state as the last steady state left it (before a reversal mirrors it)
        self.settle_mirrored();
        let rev = self.wants_reversed(inputs);
        if rev != self.reversed {
            if self.initialized {
                self.mirror_grid();
            }
            self.reversed = rev;
        }
        let out = self.step_forward(dt, &mirror_inputs(inputs, rev))?;
        Ok(mirror_outputs(out, rev))
    }

    /// [`Self::step`] in the frame where the contact rolls forwards (v >= 0).
    fn step_forward(&mut self, dt: f64, inputs: &Inputs) -> Result<Outputs> {
        if !self.r.transient || !self.initialized {
            let out = self.steady_forward(inputs)?;
            self.time += dt;
            return Ok(out);
        }
        self.set_inputs(inputs)?;
        if inputs.fn_n <= F_LIFT_OFF {
            return Ok(self.lift_off());
        }
        if inputs.v <= V_STANDSTILL || dt == 0.0 {
            self.each_strip(|c, sp| {
                let ph = *sp.phase;
                c.substep_strip(sp, dt, 0.0, ph, 0, c.nx + 1)
            });
        } else if inputs.v * dt >= 2.0 * self.patch.a {
            // every bristle enters during the step: the steady state of the step's inputs
            // (bounded work however long the step or small the contact)
            self.each_strip(|c, sp| c.march_all(sp, dt));
        } else if self.scheme == Scheme::Continuous {
            self.each_strip(|c, sp| c.advance_continuous(sp, dt));
        } else {
            self.each_strip(|c, sp| c.advance_cells(sp, dt));
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
        self.reset_nodes();
        // the bristles are reset, the strips' ring heads and phases are not: equal only
        // where they were (a state of an older strip rule may hold phases a bit apart)
        self.set_mirrored(self.strips_equal());
        self.out = Outputs::unloaded(self.inputs.t_bulk);
        self.out
    }

    /// Sets the grid to the steady state of constant `inputs` and returns its outputs.
    /// Does not advance time.
    pub fn steady(&mut self, inputs: &Inputs) -> Result<Outputs> {
        inputs.validate()?;
        self.reversed = self.wants_reversed(inputs);
        let out = self.steady_forward(&mirror_inputs(inputs, self.reversed))?;
        Ok(mirror_outputs(out, self.reversed))
    }

    /// [`Self::steady`] in the frame where the contact rolls forwards (v >= 0).
    fn steady_forward(&mut self, inputs: &Inputs) -> Result<Outputs> {
        self.set_inputs(inputs)?;
        self.initialized = true;
        if inputs.fn_n <= F_LIFT_OFF {
            return Ok(self.lift_off());
        }
        // the steady state is the grid a transient run reaches with constant inputs: every
        // bristle entered under these inputs, i.e. the march of newly entered bristles over
        // the whole strip at phase 0
        self.out = if self.coulomb_path() {
            let out = self.steady_coulomb();
            // whether the strips are mirror images: found when a step needs it
            self.mirrored_unknown = true;
            out
        } else {
            self.steady_march()
        };
        Ok(self.out)
    }

    /// The steady march of every strip (the general path of [`Self::steady`]).
    #[inline(never)]
    fn steady_march(&mut self) -> Outputs {
        // every strip is marched afresh: mirror images from the start where the inputs are
        // symmetric
        self.set_mirrored(true);
        self.each_strip(|c, sp| {
            *sp.head = 0;
            *sp.phase = 0.0;
            *sp.part = Partial::default();
            c.march_new(sp, c.nx + 1, 0.0)
        });
        self.integrate()
    }

    /// Takes the bristles where they are as their committed node states, with nothing of
    /// the current cell travelled since: their next move ends the current cell (after a
    /// change of direction, a lift-off and for states saved before the whole-cell commit).
    fn reset_nodes(&mut self) {
        self.node_st.copy_from_slice(&self.st);
        self.node_acc.copy_from_slice(&self.acc);
        self.node_acc_zero = false;
        self.part.iter_mut().for_each(|p| *p = Partial::default());
    }

    /// Switches the march of newly entered bristles off (plain sub-step loop for every
    /// bristle). For tests that show both give identical results.
    #[doc(hidden)]
    pub fn set_march_new_bristles(&mut self, on: bool) {
        self.scheme = if on {
            Scheme::CellsMarch
        } else {
            Scheme::Cells
        };
    }

    /// Switches the higher-order rules' cached start nodes off (each move's start node then
    /// computed where it starts). For a test that shows both give the same results.
    #[doc(hidden)]
    pub fn set_start_node_cache(&mut self, on: bool) {
        self.start_cache = on;
    }

    /// Switches the scalar temperature solve of module `softening` off (every move then takes
    /// the general solve). For tests that compare both; returns whether it applied before.
    #[doc(hidden)]
    pub fn set_softening_solve(&mut self, on: bool) -> bool {
        self.set_fast_path(FastPath::Softening, on)
    }

    /// Switches a fast path on (taken if the configuration lies within what it supports,
    /// module `fastpath`) or off (the general path). For tests that compare both; returns
    /// whether it applied before.
    #[doc(hidden)]
    pub fn set_fast_path(&mut self, path: FastPath, on: bool) -> bool {
        let was = self.fast_path(path);
        let admits = path.support().admits(
            self.cfg.effects,
            &self.r,
            self.has_modifiers(),
            self.modifiers.any_local(),
        );
        let take = on && admits;
        match path {
            FastPath::Softening => self.softening_fast = take,
            _ => self.fast.set(path, take),
        }
        was
    }

    /// True if the contact takes the fast path `path`.
    #[doc(hidden)]
    pub fn fast_path(&self, path: FastPath) -> bool {
        match path {
            FastPath::Softening => self.softening_fast,
            // the higher-order rules split the leading cell, which FASTSIM's march does not
            FastPath::Coulomb => self.fast.get(path) && !self.ho,
            _ => self.fast.get(path),
        }
    }

    /// Chooses how a step advances the bristles (at construction: the configuration's
    /// `scheme`, default [`Scheme::CellsMarch`]); the configuration keeps the scheme it was
    /// built with.
    pub fn set_scheme(&mut self, scheme: Scheme) {
        self.scheme = scheme;
        self.ho = scheme == Scheme::CellsHigher
            && self.cfg.model == ModelKind::Ecf
            && self.r.rule == crate::bristle::Rule::SameCharacteristic;
    }

    /// How a step advances the bristles.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// Sets how the local temperature of a bristle move is solved (the configuration's
    /// `temperature_solve` at construction).
    pub fn set_temperature_solve(&mut self, solve: thermal::TemperatureSolve) {
        self.t_solve = solve;
    }

    /// How the local temperature of a bristle move is solved.
    pub fn temperature_solve(&self) -> thermal::TemperatureSolve {
        self.t_solve
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

/// Inputs of the mirror image x -> -x (`on`): c_x, spin and v change sign, c_y does not
/// (creepages are slip velocities over |v|). An involution.
pub(crate) fn mirror_inputs(i: &Inputs, on: bool) -> Inputs {
    if !on {
        return *i;
    }
    Inputs {
        cx: -i.cx,
        spin: -i.spin,
        v: -i.v,
        ..*i
    }
}

/// Outputs of the mirror image x -> -x (`on`, [`Outputs::mirrored`]). An involution.
fn mirror_outputs(o: Outputs, on: bool) -> Outputs {
    if !on {
        return o;
    }
    o.mirrored()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Grid;

    /// The lockstep FASTSIM march equals the general march and quadrature to rounding, in
    /// forces, moment, heat, regime fractions and every bristle's state.
    #[test]
    fn steady_coulomb_equals_general_march() {
        let cases = [
            (0.002, 0.0, 0.0, 20.0),
            (0.01, 0.004, 0.0, 20.0),
            (-0.03, 0.0, 0.8, 5.0),
            (0.3, -0.02, -1.5, 30.0),
            (0.01, 0.0, 0.0, 0.0),
        ];
        for (nx, ny) in [(40, 21), (13, 5), (7, 1), (20, 4)] {
            for preset in ["fastsim", "fastsim on a line contact"] {
                let mut cfg = Config::preset("fastsim").expect("preset");
                if preset != "fastsim" {
                    cfg.geometry = Geometry::Line {
                        r: 0.3,
                        width: 0.01,
                    };
                }
                cfg.grid = Grid { nx, ny };
                let mut c = Contact::new(&cfg).expect("contact");
                assert!(c.coulomb_path());
                for &(cx, cy, spin, v) in &cases {
                    let i = Inputs {
                        cx,
                        cy,
                        spin,
                        v,
                        fn_n: 80e3,
                        ..Inputs::default()
                    };
                    let fast = c.steady(&i).expect("steady");
                    let st_fast = c.st.clone();
                    let slow = c.steady_march();
                    let close =
                        |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs()));
                    for (name, x, y) in [
                        ("fx", fast.fx, slow.fx),
                        ("fy", fast.fy, slow.fy),
                        ("mz", fast.mz, slow.mz),
                        ("p_fric", fast.p_fric, slow.p_fric),
                        ("frac_elastic", fast.frac_elastic, slow.frac_elastic),
                        ("frac_sliding", fast.frac_sliding, slow.frac_sliding),
                        ("t_mean", fast.t_mean, slow.t_mean),
                        ("t_max", fast.t_max, slow.t_max),
                    ] {
                        assert!(close(x, y), "{preset} {nx}x{ny} {i:?}: {name} {x} vs {y}");
                    }
                    for (n, (p, q)) in st_fast.iter().zip(c.st.iter()).enumerate() {
                        assert_eq!(p.regime, q.regime, "{preset} {nx}x{ny} {i:?}: node {n}");
                        for (x, y) in [
                            (p.tau[0], q.tau[0]),
                            (p.tau[1], q.tau[1]),
                            (p.u[0], q.u[0]),
                            (p.u[1], q.u[1]),
                            (p.sh, q.sh),
                            (p.q, q.q),
                            (p.temp, q.temp),
                        ] {
                            assert!(
                                close(x, y),
                                "{preset} {nx}x{ny} {i:?}: node {n}: {x} vs {y}\n{p:?}\n{q:?}"
                            );
                        }
                    }
                }
            }
        }
    }
}
