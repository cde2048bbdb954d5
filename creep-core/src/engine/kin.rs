//! The kinematics of one sub-step of a strip (Eq. 4.16, 4.21): its length, creepages, flexibilities and heat-flow factors, shared by every kind of bristle move.

use super::law::Mover;
use super::V_STANDSTILL;
use crate::thermal;

/// Per-sub-step kinematic context of one strip.
#[derive(Clone, Copy)]
pub(super) struct Kin {
    pub(super) h: f64,
    pub(super) dist: f64,
    pub(super) cx: f64,
    pub(super) cy: f64,
    pub(super) cs: f64,
    pub(super) lx: f64,
    pub(super) ly: f64,
    pub(super) ls: f64,
    pub(super) heat: bool,
    pub(super) alpha_c: f64,
    pub(super) t_bulk: f64,
    /// alpha_c 2 sqrt(h): the flash temperature per heat density of the sub-step's own
    /// interval (Eq. 4.35's first term), 0 without heat flow.
    pub(super) self_c: f64,
}

impl Kin {
    /// The rigid slip of a move whose midpoint is at (x, y) in the contact frame, m
    /// (Eq. 4.16: du = v h (c_x - c_s y, c_y + c_s x), with v h the distance moved).
    #[inline]
    pub(super) fn rigid_slip(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        let d = self.dist;
        [d * (self.cx - self.cs * y), d * (self.cy + self.cs * x)]
    }

    /// The flexibilities L_x + L_e, L_y + L_e (m/Pa) for the layer's flexibility `le` and the
    /// elastic stress increment of the move at (x, y), Pa (Eq. 4.21).
    #[inline]
    pub(super) fn flex(&self, le: f64, [x, y]: [f64; 2]) -> (f64, f64, [f64; 2]) {
        let d = self.dist;
        let lxe = self.lx + le;
        let lye = self.ly + le;
        let lse = self.ls + le;
        let dtau = [
            d * (self.cx / lxe - self.cs * y / lse),
            d * (self.cy / lye + self.cs * x / lse),
        ];
        (lxe, lye, dtau)
    }
}

/// The stress that multiplies a move's plastic slip in its dissipation (Eq. 4.29): the mean
/// of its start and end stresses, the trapezoidal rule over the move (docs/model.md section
/// 3.4). The end stress alone is first order in the cell
/// length: it overstates the heat where the stress falls along the move and understates it
/// where the stress rises, and the flash temperature carries that error downstream.
#[inline]
pub(super) fn trapezoid_stress(new: [f64; 2], old: [f64; 2]) -> [f64; 2] {
    [0.5 * (new[0] + old[0]), 0.5 * (new[1] + old[1])]
}

impl Mover<'_> {
    /// Kinematic/thermal context for a sub-step of duration `h` moving distance `dist`.
    pub(super) fn kin(&self, h: f64, dist: f64) -> Kin {
        let i = &self.inputs;
        let heat = i.v > V_STANDSTILL && h > 0.0;
        let vw = i.v * (1.0 + i.cx).abs();
        // with surface_time_flash alpha sqrt(v / v_w): Eq. 4.34 over the wheel surface's
        // time x / v_w, written in the layer's time x / v (finite for v_w -> 0)
        let partition = if self.law.r.on.surface_time {
            thermal::surface_time_partition
        } else {
            thermal::heat_partition
        };
        let alpha = partition(
            vw,
            i.v,
            self.law.r.bodies.lambda_w,
            self.law.r.bodies.kappa_w,
            self.law.r.bodies.lambda_r,
            self.law.r.bodies.kappa_r,
        );
        let alpha_c =
            alpha * thermal::flash_factor(self.law.r.bodies.lambda_w, self.law.r.bodies.kappa_w);
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
            alpha_c,
            t_bulk: i.t_bulk,
            self_c: if heat { alpha_c * 2.0 * h.sqrt() } else { 0.0 },
        }
    }
}
