//! The grid's integrals: quadrature weights of a strip for its phase, forces, moment, heat and regime fractions, and the fields along y = 0.

use super::{Contact, FieldPoint, Outputs};

/// Where the trailing node of a strip samples the pressure, in cells inside the trailing
/// edge (a node on the edge itself would carry no pressure): 4 zeta(-1/2)^2. There the
/// sliding stress falls like the square root of the distance from the edge, and the
/// trapezoidal rule over the nodes, with the edge node's value taken at this offset, is
/// second order in the cell length (the generalised Euler-Maclaurin expansion of the
/// trapezoid for sqrt(s): its leading error -zeta(-1/2) h^1.5 is what this node adds);
/// half a cell overstates the force by 0.15 h^1.5 of p0, at the edge node the rule would
/// understate it by 0.21 h^1.5 (docs/model.md section 3.4).
pub(super) const TRAILING_NODE: f64 = 0.172_866_730_280_115;

/// The strips across the contact: `ny` Gauss-Legendre nodes eta_j in (-1, 1) (eta = y/b,
/// ascending) and their weights, the strips' widths in eta (summing to 2). The force of a
/// strip per unit width is a smooth function of eta inside the contact, and Gauss-Legendre
/// integrates it to high order where equal strips at their midpoints are second order:
/// on a dry creepage step 5 strips are within 0.1 % of 81 (equal strips: 2.4 %; docs/model.md
/// section 3.1). Newton on the Legendre recurrence from Chebyshev's guess, to rounding.
pub(super) fn strip_rule(ny: usize) -> Vec<(f64, f64)> {
    let n = ny as f64;
    let mut out = Vec::with_capacity(ny);
    for i in 0..ny {
        // the i-th root counted from -1
        let mut x = -(std::f64::consts::PI * (i as f64 + 0.75) / (n + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_n(x) and P_{n-1}(x) by the three-term recurrence
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=ny {
                let kk = k as f64;
                (p0, p1) = (p1, ((2.0 * kk - 1.0) * x * p1 - (kk - 1.0) * p0) / kk);
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    // exactly symmetric about eta = 0 (the roots of the upper half mirror those of the lower
    // half, the middle one of an odd rule is 0): a strip and its mirror image then compute
    // the same states, bit for bit, where the inputs are symmetric ([`Contact::each_strip`])
    for i in 0..ny / 2 {
        let (x, w) = out[i];
        out[ny - 1 - i] = (-x, w);
    }
    if ny % 2 == 1 {
        out[ny / 2].0 = 0.0;
    }
    out
}

impl Contact {
    #[inline]
    pub(super) fn idx(&self, j: usize, slot: usize) -> usize {
        j * (self.lat.nx + 1) + (self.state.head[j] + slot) % (self.lat.nx + 1)
    }

    /// Quadrature weights (normalized length) of the nodes of strip `j` for its phase.
    pub(super) fn weights(&self, j: usize, w: &mut [f64]) {
        let nx = self.lat.nx;
        let dxi = 2.0 * self.lat.ell[j] / nx as f64;
        let ph = self.state.phase[j];
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

    pub(super) fn integrate(&self) -> Outputs {
        let (a, b) = (self.load.patch.a, self.load.patch.b);
        let nx = self.lat.nx;
        let mut w = vec![0.0; nx + 1];
        let (mut fx, mut fy, mut mz, mut pf, mut tsum, mut area) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        let mut fr = [0.0; 3];
        let mut tmax = f64::NEG_INFINITY;
        for j in 0..self.lat.ny {
            self.weights(j, &mut w);
            let dy = if self.load.patch.line {
                2.0 * b
            } else {
                self.lat.deta[j] * b
            };
            let y = if self.load.patch.line {
                0.0
            } else {
                self.lat.eta[j] * b
            };
            let dxi = 2.0 * self.lat.ell[j] / nx as f64;
            let lead = if self.law.ho && nx >= 3 {
                lead_correction(self.state.phase[j], dxi)
            } else {
                [0.0; 2]
            };
            for (slot, wk) in w.iter().enumerate() {
                let s = &self.state.st[self.idx(j, slot)];
                let da = wk * a * dy;
                // the forces' and the power's weight: with the leading cell's term
                let df = match slot {
                    1 | 2 => (wk + lead[slot - 1]) * a * dy,
                    _ => da,
                };
                let x = a * (self.lat.ell[j] - (slot as f64 + self.state.phase[j]) * dxi);
                fx += s.tau[0] * df;
                fy += s.tau[1] * df;
                mz += (x * s.tau[1] - y * s.tau[0]) * df;
                pf += s.q * df;
                if *wk > 0.0 {
                    tsum += s.temp * da;
                    area += da;
                    fr[s.regime as usize] += da;
                    tmax = tmax.max(s.temp);
                }
            }
        }
        let fn_n = self.state.run.inputs.fn_n;
        let area = area.max(f64::MIN_POSITIVE);
        Outputs {
            fx,
            fy,
            mz,
            f: if fn_n > 0.0 { fx / fn_n } else { 0.0 },
            t_max: if tmax.is_finite() {
                tmax
            } else {
                self.state.run.inputs.t_bulk
            },
            t_mean: tsum / area,
            p_fric: pf,
            frac_elastic: fr[0] / area,
            frac_plastic: fr[1] / area,
            frac_sliding: fr[2] / area,
            a,
            b,
            p0: self.load.patch.p0,
        }
    }

    /// Fields along the strip nearest y = 0, from the leading to the trailing edge.
    pub fn field_y0(&self) -> Vec<FieldPoint> {
        let j = (0..self.lat.ny)
            .min_by(|&p, &q| self.lat.eta[p].abs().total_cmp(&self.lat.eta[q].abs()))
            .unwrap_or(0);
        let nx = self.lat.nx;
        let dxi = 2.0 * self.lat.ell[j] / nx as f64;
        let inside = if self.state.phase[j] > 0.0 {
            nx
        } else {
            nx + 1
        };
        (0..inside)
            .map(|slot| {
                let xi = self.lat.ell[j] - (slot as f64 + self.state.phase[j]) * dxi;
                let s = &self.state.st[self.idx(j, slot)];
                let np = self.law.r.node_p(&self.load.patch, xi, self.lat.eta[j]);
                let v = self.state.run.inputs.v;
                let slip = v
                    * (self.state.run.inputs.cx
                        - self.state.run.inputs.spin * self.lat.eta[j] * self.load.patch.b)
                        .hypot(
                            self.state.run.inputs.cy
                                + self.state.run.inputs.spin * xi * self.load.patch.a,
                        );
                let m = self.law.material(&np, s.temp, s.u[0].hypot(s.u[1]), slip);
                // rolling backwards: the grid is held mirrored (x -> -x, tau_x -> -tau_x)
                let sgn = if self.state.run.reversed { -1.0 } else { 1.0 };
                FieldPoint {
                    x: sgn * xi * self.load.patch.a,
                    tau: (s.tau[0] * s.tau[0] + s.tau[1] * s.tau[1]).sqrt(),
                    tau_x: sgn * s.tau[0],
                    tau_c1: m.tc1,
                    tau_c2: m.tc2,
                    p: np.p,
                    t: s.temp,
                    regime: s.regime as u8,
                }
            })
            .collect()
    }
}

/// The leading cell's term of the quadrature under the higher-order rules (docs/model.md
/// section 3.3): where the layer yields at once the stress rises like c sqrt(s) from
/// the leading edge, and the trapezoid over the nodes at s_k = (k + ph) h (0 at the edge)
/// misses -E(ph) c h^1.5, E(ph) = zeta(-1/2, ph) - (1 - ph) sqrt(ph) / 2 (the generalized
/// Euler-Maclaurin formula; zeta the Hurwitz zeta function). c sqrt(h) is taken from the
/// nodes 1 and 2 (exact for c sqrt(s) + d s). Returns the weights (normalized length, as
/// [`Contact::weights`]) added to nodes 1 and 2; `ph` the strip's phase, `dxi` its cell.
fn lead_correction(ph: f64, dxi: f64) -> [f64; 2] {
    let e = hurwitz_zeta_m05(ph) - 0.5 * (1.0 - ph) * ph.sqrt();
    let (s1, s2) = (1.0 + ph, 2.0 + ph);
    let d = s1.sqrt() * s2 - s2.sqrt() * s1;
    [-e * s2 / d * dxi, e * s1 / d * dxi]
}

/// The Hurwitz zeta function zeta(-1/2, q) for 0 <= q <= 1 (q = 0: zeta(-1/2, 1) =
/// zeta(-1/2)): Euler-Maclaurin summation with 8 terms and 3 Bernoulli corrections (error
/// below 1e-10).
fn hurwitz_zeta_m05(q: f64) -> f64 {
    let q = if q <= 0.0 { 1.0 } else { q };
    let s = -0.5_f64;
    let n = 8usize;
    let mut r: f64 = (0..n).map(|k| (k as f64 + q).sqrt()).sum();
    let x = n as f64 + q;
    r += x.powf(1.5) / (s - 1.0) + 0.5 * x.sqrt();
    // B_2j / (2j)! times the rising product s (s + 1) ... (s + 2j - 2)
    let b = [1.0 / 6.0, -1.0 / 30.0, 1.0 / 42.0];
    let fact = [2.0, 24.0, 720.0];
    let mut poch = s;
    for jj in 0..3 {
        if jj > 0 {
            let jf = jj as f64;
            poch *= (s + 2.0 * jf - 1.0) * (s + 2.0 * jf);
        }
        r += b[jj] / fact[jj] * poch * x.powf(-s - 2.0 * jj as f64 - 1.0);
    }
    r
}

#[cfg(test)]
mod tests {
    use super::{hurwitz_zeta_m05, strip_rule, TRAILING_NODE};

    #[test]
    fn hurwitz_zeta_at_minus_one_half() {
        // zeta(-1/2) = -zeta(3/2) / (4 pi) = -0.207886224977...
        assert!((hurwitz_zeta_m05(1.0) + 0.207_886_224_977_354_6).abs() < 1e-10);
        assert_eq!(hurwitz_zeta_m05(0.0), hurwitz_zeta_m05(1.0));
        // zeta(s, q) = q^-s + zeta(s, q + 1): zeta(-1/2, 1/2) = sqrt(1/2) + zeta(-1/2, 3/2)
        // and zeta(-1/2, 1/2) = (2^(-1/2) - 1) zeta(-1/2)
        let half = (0.5_f64.sqrt() - 1.0) * hurwitz_zeta_m05(1.0);
        assert!((hurwitz_zeta_m05(0.5) - half).abs() < 1e-10);
    }

    #[test]
    fn strips_are_gauss_legendre() {
        for ny in 1..=41 {
            let r = strip_rule(ny);
            assert_eq!(r.len(), ny);
            // inside (-1, 1), ascending, symmetric, positive weights summing to 2
            for (k, &(x, w)) in r.iter().enumerate() {
                assert!(
                    x > -1.0 && x < 1.0 && w > 0.0,
                    "ny {ny}: node {k} ({x}, {w})"
                );
                // exactly: mirrored strips compute bit-identical states (Contact::each_strip)
                let (xm, wm) = r[ny - 1 - k];
                assert!(
                    x.to_bits() == (-xm).to_bits() || (x == 0.0 && k == ny / 2),
                    "ny {ny}: symmetry of node {k}: {x} vs {xm}"
                );
                assert_eq!(w.to_bits(), wm.to_bits(), "ny {ny}: symmetry of weight {k}");
                if k > 0 {
                    assert!(x > r[k - 1].0, "ny {ny}: ascending");
                }
            }
            // exact for the monomials up to degree 2 ny - 1 (a rule with the right nodes and
            // the wrong weights, or vice versa, is not)
            for d in 0..2 * ny {
                let q: f64 = r.iter().map(|&(x, w)| w * x.powi(d as i32)).sum();
                let exact = if d % 2 == 1 {
                    0.0
                } else {
                    2.0 / (d as f64 + 1.0)
                };
                assert!(
                    (q - exact).abs() < 1e-12,
                    "ny {ny}, degree {d}: {q} vs {exact}"
                );
            }
        }
        // the known 3-point rule
        let r = strip_rule(3);
        assert!((r[2].0 - 0.6f64.sqrt()).abs() < 1e-15 && (r[1].1 - 8.0 / 9.0).abs() < 1e-15);
    }

    #[test]
    fn the_trailing_node_makes_the_trapezoid_second_order_on_a_square_root() {
        // sqrt(s) on [0, 1] (the sliding stress near the trailing edge) by the trapezoid over
        // n cells with the edge node's value taken TRAILING_NODE cells inside: the error
        // falls by 4 per halving (second order); at half a cell it falls like h^1.5
        let err = |n: usize, off: f64| {
            let h = 1.0 / n as f64;
            let inner: f64 = (1..n).map(|k| (k as f64 * h).sqrt()).sum();
            let t = h * (0.5 * (off * h).sqrt() + inner + 0.5);
            (t - 2.0 / 3.0).abs()
        };
        for n in [10, 20, 40] {
            let r = err(n, TRAILING_NODE) / err(2 * n, TRAILING_NODE);
            assert!((r - 4.0).abs() < 0.1, "n {n}: ratio {r}");
            let r_half = err(n, 0.5) / err(2 * n, 0.5);
            assert!(r_half < 3.0, "n {n}: half a cell, ratio {r_half}");
            assert!(err(n, TRAILING_NODE) < 0.1 * err(n, 0.5));
        }
    }
}
