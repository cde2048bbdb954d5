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
//! The contact is four parts: the law (`law`: the resolved material law, heat kernel,
//! modifiers, scheme and fast paths, built once and read-only while bristles move), the
//! lattice (`law::Lattice`, the grid's geometry), the grid state (`grid_state`: exactly
//! what is saved and restored, with its byte layout; module [`crate::state`] frames it) and
//! per strip its scratch (`strip::StripScratch`); besides them the Hertz patch of the
//! current load, FASTSIM's steady-march caches, the strip symmetry flags, the warnings,
//! the thread pool and how a shared strip is split among its threads. A bristle move is a method of `law::Mover` (law, lattice, the step's
//! kinematics) on one strip's state (`strip::Strip`), nothing else.
//!
//! Where each job lives: this file holds the contact and the time loop (`step`, `steady`);
//! [`io`] the inputs and outputs; `strip` one strip as a unit of work (its state borrowed
//! out of the contact, the strips of a step on `threads` threads) and the cell-by-cell
//! scheme; `share` one strip's bristles split among the threads (cell-by-cell schemes);
//! `pool` the threads; `advance` one bristle move, the sub-step loop and march; `bristle_move` the
//! general move's temperature solve; `kin` a sub-step's kinematics; `grid` the integrals and
//! fields; `modifiers` the formula and custom effects; `softening` the temperature solve of
//! a layer that only softens as it heats (on the law's branch as a scalar function of T);
//! `steady_coulomb` FASTSIM's steady state in one pass. The material law is
//! [`crate::material`], the temperature solve and heat kernel [`crate::thermal`], the Hertz
//! patch [`crate::hertz`].

mod advance;
mod bristle_move;
mod fastpath;
mod grid;
pub(crate) mod grid_state;
pub mod io;
mod kin;
mod law;
mod modifiers;
mod pool;
mod share;
mod softening;
mod steady_coulomb;
mod strip;

pub use crate::hertz::patch_for;
pub use crate::material::layer_material;
pub use crate::scheme::Scheme;
pub use fastpath::FastPath;
pub use io::{FieldPoint, Inputs, Outputs, V_STANDSTILL};

use crate::bristle::{BristleState, Regime};
use crate::config::{Config, Geometry, ModelKind};
use crate::error::{check_range, CreepError, Result};
use crate::hertz::Patch;
use crate::kalker;
use crate::thermal::{self, N_KERNEL};
use grid_state::GridState;
use law::{Lattice, Law, Mover};
use steady_coulomb::CoulombScratch;
use strip::{StripScratch, Symmetry};

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

/// The Hertz patch and Kalker's flexibilities at the last normal force.
#[derive(Clone, Debug)]
struct Load {
    /// The Hertz patch (semi-axes a, b in m, peak pressure p0 in Pa).
    patch: Patch,
    /// Normal force (N) that `patch` and `flex` belong to (NaN: none yet).
    patch_fn: f64,
    /// Kalker's flexibilities (L_x, L_y, L_s) at that force ([`kalker::flexibilities`]).
    flex: (f64, f64, f64),
}

/// The persistent contact: geometry, bristle grid and its state.
#[derive(Clone, Debug)]
pub struct Contact {
    cfg: Config,
    /// The resolved material law, heat kernel, modifiers, scheme and fast paths.
    law: Law,
    /// The bristle grid's geometry.
    lat: Lattice,
    /// What is saved and restored: time, last inputs and outputs, flags and the bristles.
    state: GridState,
    /// The Hertz patch and flexibilities of the current normal force.
    load: Load,
    /// Warnings raised since [`Contact::take_warnings`] last drained them.
    warnings: Vec<String>,
    /// Per strip, the caches its moves keep (module `strip`).
    scratch: Vec<StripScratch>,
    /// FASTSIM's steady march's caches (module `steady_coulomb`).
    coulomb: CoulombScratch,
    /// Whether symmetric strips are computed once (module `strip`).
    sym: Symmetry,
    /// Threads that advance the strips (None: the calling thread alone).
    pool: Option<std::sync::Arc<pool::Pool>>,
    /// How a step's bristles are shared among those threads (module `share`).
    balance: share::Balance,
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
        let lat = Lattice::new(cfg);
        let (nx, ny) = (lat.nx, lat.ny);
        let line = matches!(cfg.geometry, Geometry::Line { .. });
        let patch = Patch {
            a: 1.0,
            b: 1.0,
            p0: 0.0,
            line,
        };
        let mut c = Contact {
            cfg: cfg.clone(),
            law: Law::new(cfg),
            lat,
            state: GridState::new(nx, ny),
            load: Load {
                patch,
                patch_fn: f64::NAN,
                flex: (0.0, 0.0, 0.0),
            },
            warnings: Vec::new(),
            scratch: vec![StripScratch::new(); ny],
            coulomb: CoulombScratch::new(),
            sym: Symmetry::new(),
            pool: None,
            balance: share::Balance::default(),
        };
        for path in FastPath::ALL {
            c.set_fast_path(path, true);
        }
        Ok(c)
    }

    /// The configuration.
    pub fn config(&self) -> &Config {
        &self.cfg
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.state.run.time
    }

    /// Last outputs.
    pub fn outputs(&self) -> Outputs {
        mirror_outputs(self.state.run.out, self.state.run.reversed)
    }

    /// Last inputs.
    pub fn inputs(&self) -> Inputs {
        mirror_inputs(&self.state.run.inputs, self.state.run.reversed)
    }

    /// True while the contact rolls backwards (the last non-zero speed was negative).
    pub fn reversed(&self) -> bool {
        self.state.run.reversed
    }

    /// The rolling direction for `inputs`: backwards for v < 0, forwards for v > 0, unchanged
    /// at standstill.
    fn wants_reversed(&self, inputs: &Inputs) -> bool {
        if inputs.v < 0.0 {
            true
        } else if inputs.v > 0.0 {
            false
        } else {
            self.state.run.reversed
        }
    }

    /// Rolling backwards is rolling forwards in the mirror image x -> -x (docs/model.md
    /// section 3, "Reversed rolling"): the bristles in the contact stay in it, mirrored in
    /// place (their slots reversed, the phase p -> 1 - p, u_x and tau_x negated; heat
    /// histories unchanged).
    fn mirror_grid(&mut self) {
        let nx = self.lat.nx;
        for j in 0..self.lat.ny {
            let p = self.state.phase[j];
            let old: Vec<(BristleState, [f64; N_KERNEL])> = (0..=nx)
                .map(|slot| {
                    let id = self.idx(j, slot);
                    (self.state.st[id], self.state.acc[id])
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
                self.state.st[base + new] = b;
                self.state.acc[base + new] = a;
            }
            if p > 0.0 {
                // past the new trailing edge lies the unloaded material that was ahead of the
                // old leading edge (the quadrature interpolates towards it)
                self.state.st[base + nx] = BristleState {
                    temp: self.state.run.inputs.t_bulk,
                    ..BristleState::default()
                };
                self.state.acc[base + nx] = [0.0; N_KERNEL];
            }
            self.state.head[j] = 0;
            if p > 0.0 {
                self.state.phase[j] = 1.0 - p;
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
        if inputs.fn_n > F_LIFT_OFF && inputs.fn_n != self.load.patch_fn {
            self.load.patch = self.patch_for(inputs.fn_n)?;
            let (a, b) = (self.load.patch.a, self.load.patch.b);
            let (ka, kb) = if self.load.patch.line {
                (a, 1e6 * a)
            } else {
                (a, b)
            };
            let c = kalker::coefficients(ka, kb, self.law.r.bodies.nu)?;
            self.load.flex = kalker::flexibilities(ka, kb, self.law.r.bodies.g, &c);
            if self.load.patch.line {
                // a 2-D strip: Carter's flexibility, not the elliptic one (kalker.rs)
                let (lx, ly) =
                    kalker::line_flexibilities(a, self.law.r.bodies.g, self.law.r.bodies.nu);
                self.load.flex.0 = lx;
                self.load.flex.1 = ly;
            }
            self.load.patch_fn = inputs.fn_n;
        }
        self.state.run.inputs = *inputs;
        self.update_modifiers()?;
        if self.law.r.on.temperature && inputs.v > V_STANDSTILL {
            let vw = inputs.v * (1.0 + inputs.cx).abs();
            if !thermal::peclet_ok(
                self.load.patch.a,
                inputs.v,
                vw,
                self.law.r.bodies.kappa_w,
                self.law.r.bodies.kappa_r,
            ) {
                let msg = format!(
                    "Péclet condition a (v + v_w) > 20 (kappa_r + kappa_w) (Eq. 4.33) not met at v = {} m/s, a = {} mm: the flash temperature model neglects lateral heat conduction that matters here",
                    inputs.v,
                    self.load.patch.a * 1e3
                );
                if !self.warnings.contains(&msg) {
                    self.warnings.push(msg);
                }
            }
            if (1.0 + inputs.cx).abs() < 0.1 && !self.law.r.on.surface_time {
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
        if rev != self.state.run.reversed {
            if self.state.run.initialized {
                self.mirror_grid();
            }
            self.state.run.reversed = rev;
        }
        let out = self.step_forward(dt, &mirror_inputs(inputs, rev))?;
        Ok(mirror_outputs(out, rev))
    }

    /// [`Self::step`] in the frame where the contact rolls forwards (v >= 0).
    fn step_forward(&mut self, dt: f64, inputs: &Inputs) -> Result<Outputs> {
        if !self.law.r.on.transient || !self.state.run.initialized {
            let out = self.steady_forward(inputs)?;
            self.state.run.time += dt;
            return Ok(out);
        }
        self.set_inputs(inputs)?;
        if inputs.fn_n <= F_LIFT_OFF {
            return Ok(self.lift_off());
        }
        if inputs.v <= V_STANDSTILL || dt == 0.0 {
            self.each_strip(|c, sp| {
                let ph = *sp.phase;
                c.substep_strip(sp, dt, 0.0, ph, 0, c.lat.nx + 1)
            });
        } else if inputs.v * dt >= 2.0 * self.load.patch.a {
            // every bristle enters during the step: the steady state of the step's inputs
            // (bounded work however long the step or small the contact)
            self.each_strip(|c, sp| c.march_all(sp, dt));
        } else if self.law.scheme == Scheme::Continuous {
            self.each_strip(|c, sp| c.advance_continuous(sp, dt));
        } else {
            self.each_strip_shared(dt, |c, sp| c.advance_cells(sp, dt));
        }
        self.state.run.time += dt;
        self.state.run.out = self.integrate();
        Ok(self.state.run.out)
    }

    fn lift_off(&mut self) -> Outputs {
        for s in self.state.st.iter_mut() {
            *s = BristleState {
                temp: self.state.run.inputs.t_bulk,
                ..BristleState::default()
            };
        }
        for a in self.state.acc.iter_mut() {
            *a = [0.0; N_KERNEL];
        }
        self.reset_nodes();
        // the bristles are reset, the strips' ring heads and phases are not: equal only
        // where they were (a state of an older strip rule may hold phases a bit apart)
        self.set_mirrored(self.strips_equal());
        self.state.run.out = Outputs::unloaded(self.state.run.inputs.t_bulk);
        self.state.run.out
    }

    /// Sets the grid to the steady state of constant `inputs` and returns its outputs.
    /// Does not advance time.
    pub fn steady(&mut self, inputs: &Inputs) -> Result<Outputs> {
        inputs.validate()?;
        self.state.run.reversed = self.wants_reversed(inputs);
        let out = self.steady_forward(&mirror_inputs(inputs, self.state.run.reversed))?;
        Ok(mirror_outputs(out, self.state.run.reversed))
    }

    /// [`Self::steady`] in the frame where the contact rolls forwards (v >= 0).
    fn steady_forward(&mut self, inputs: &Inputs) -> Result<Outputs> {
        self.set_inputs(inputs)?;
        self.state.run.initialized = true;
        if inputs.fn_n <= F_LIFT_OFF {
            return Ok(self.lift_off());
        }
        // the steady state is the grid a transient run reaches with constant inputs: every
        // bristle entered under these inputs, i.e. the march of newly entered bristles over
        // the whole strip at phase 0
        self.state.run.out = if self.law.coulomb_path() {
            let out = self.steady_coulomb();
            // whether the strips are mirror images: found when a step needs it
            self.sym.unknown = true;
            out
        } else {
            self.steady_march()
        };
        Ok(self.state.run.out)
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
            c.march_new(sp, c.lat.nx + 1, 0.0)
        });
        self.integrate()
    }

    /// Takes the bristles where they are as their committed node states, with nothing of
    /// the current cell travelled since: their next move ends the current cell (after a
    /// change of direction, a lift-off and for states saved before the whole-cell commit).
    fn reset_nodes(&mut self) {
        self.state.reset_nodes();
        self.coulomb.node_acc_zero = false;
    }

    /// What a move reads: the law, the lattice and the current step's kinematics.
    fn mover(&self) -> Mover<'_> {
        Mover {
            law: &self.law,
            lat: &self.lat,
            patch: &self.load.patch,
            flex: self.load.flex,
            inputs: &self.state.run.inputs,
        }
    }

    /// The complete hidden state, for module [`crate::state`] to write. The grid, `inputs`
    /// and `out` are those of the frame the contact rolls forwards in (mirrored x -> -x while
    /// [`Contact::reversed`]).
    pub(crate) fn grid_state(&self) -> &GridState {
        &self.state
    }

    /// Restores a state read by module [`crate::state`] after [`GridState::check`].
    pub(crate) fn restore(&mut self, g: GridState) -> Result<()> {
        g.check((self.lat.nx, self.lat.ny))?;
        self.state.run.time = g.run.time;
        self.state.run.reversed = g.run.reversed;
        self.set_inputs(&g.run.inputs)?;
        self.state = g;
        self.coulomb.node_acc_zero = false;
        self.set_mirrored(self.strips_equal());
        Ok(())
    }

    /// Half-lengths l_j = sqrt(1 - eta_j^2) of the strips (normalized by a), strip by strip:
    /// a strip's cell is 2 l_j a / nx long. For tests that end steps on a lattice node.
    #[doc(hidden)]
    pub fn strip_half_lengths(&self) -> Vec<f64> {
        self.lat.ell.clone()
    }

    /// Switches the march of newly entered bristles off (plain sub-step loop for every
    /// bristle). For tests that show both give identical results.
    #[doc(hidden)]
    pub fn set_march_new_bristles(&mut self, on: bool) {
        self.law.march_new = on;
    }

    /// Switches the higher-order rules' cached start nodes off (each move's start node then
    /// computed where it starts). For a test that shows both give the same results.
    #[doc(hidden)]
    pub fn set_start_node_cache(&mut self, on: bool) {
        self.law.start_cache = on;
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
            &self.law.r,
            self.law.has_modifiers(),
            self.law.modifiers.any_local(),
        );
        self.law.fast.set(path, on && admits);
        was
    }

    /// True if the contact takes the fast path `path`.
    #[doc(hidden)]
    pub fn fast_path(&self, path: FastPath) -> bool {
        match path {
            // the higher-order rules split the leading cell, which FASTSIM's march does not
            FastPath::Coulomb => self.law.coulomb_path(),
            _ => self.law.fast.get(path),
        }
    }

    /// Chooses how a step advances the bristles (at construction: the configuration's
    /// `scheme`, default [`Scheme::CellsMarch`]); the configuration keeps the scheme it was
    /// built with.
    pub fn set_scheme(&mut self, scheme: Scheme) {
        self.law.set_scheme(scheme, self.cfg.model);
    }

    /// How a step advances the bristles.
    pub fn scheme(&self) -> Scheme {
        self.law.scheme
    }

    /// Sets how the local temperature of a bristle move is solved (the configuration's
    /// `temperature_solve` at construction).
    pub fn set_temperature_solve(&mut self, solve: thermal::TemperatureSolve) {
        self.law.t_solve = solve;
    }

    /// How the local temperature of a bristle move is solved.
    pub fn temperature_solve(&self) -> thermal::TemperatureSolve {
        self.law.t_solve
    }

    /// Grid size (nx, ny actually used; a line contact has one strip).
    pub fn grid_size(&self) -> (usize, usize) {
        (self.lat.nx, self.lat.ny)
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
                assert!(c.law.coulomb_path());
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
                    let st_fast = c.state.st.clone();
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
                    for (n, (p, q)) in st_fast.iter().zip(c.state.st.iter()).enumerate() {
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
