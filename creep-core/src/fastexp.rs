//! Inlined two-lane exp and exp_m1 for the hot loops: cheaper than the C library's calls, within 1e-15 of them.

/// (exp(a), exp(b)) in one two-lane evaluation (SSE2 on baseline x86-64, inlined): about
/// 40 instructions where two calls to the C library's exp take about 100. exp(x) =
/// 2^n exp(r), x = n ln 2 + r, |r| <= ln 2 / 2 (n rounded by the 1.5 * 2^52 shift), exp(r)
/// by its Taylor polynomial to degree 13 (truncation below 1e-17; the constants and scheme
/// of wide's `f64x2::exp`). Arguments outside +-700 take the scalar exp.
#[inline(always)]
pub(crate) fn exp_pair(a: f64, b: f64) -> (f64, f64) {
    if !(a.abs() < 700.0 && b.abs() < 700.0) {
        return (a.exp(), b.exp());
    }
    let (m, pow2) = exp_parts(a, b);
    ((m[0] + 1.0) * pow2[0], (m[1] + 1.0) * pow2[1])
}

/// ((exp(a), exp(a) - 1), (exp(b), exp(b) - 1)) by [`exp_pair`]'s polynomial: where n = 0
/// (|x| < ln 2 / 2) exp(x) - 1 is the polynomial without its constant term, free of
/// cancellation; elsewhere |exp(x) - 1| > 0.29 and exp(x) - 1 loses at most 2 bits. The
/// relative error of exp(x) - 1 is below 1e-15 (tested). Arguments outside +-700 take the
/// C library's exp and exp_m1.
#[inline(always)]
pub(crate) fn exp_m1_pair(a: f64, b: f64) -> ((f64, f64), (f64, f64)) {
    if !(a.abs() < 700.0 && b.abs() < 700.0) {
        return ((a.exp(), a.exp_m1()), (b.exp(), b.exp_m1()));
    }
    let (m, pow2) = exp_parts(a, b);
    let one = |i: usize| {
        let e = (m[i] + 1.0) * pow2[i];
        (e, if pow2[i] == 1.0 { m[i] } else { e - 1.0 })
    };
    (one(0), one(1))
}

/// The shared part of [`exp_pair`] and [`exp_m1_pair`] for |a|, |b| < 700: exp(r) - 1 and
/// 2^n per lane.
#[inline(always)]
fn exp_parts(a: f64, b: f64) -> ([f64; 2], [f64; 2]) {
    use wide::f64x2;
    const SHIFT: f64 = 6755399441055744.0; // 1.5 * 2^52
    const LN2_HI: f64 = 0.693145751953125; // few mantissa bits: n LN2_HI is exact
    const LN2_LO: f64 = 1.428_606_820_309_417_2e-6;
    let c = |k: f64| f64x2::splat(k);
    let x = f64x2::new([a, b]);
    let t = x * c(std::f64::consts::LOG2_E) + c(SHIFT);
    let n = t - c(SHIFT);
    let r = x - n * c(LN2_HI) - n * c(LN2_LO);
    // exp(r) - 1 = r + r^2/2! + ... + r^13/13! (Estrin)
    let f = |k: u32| c(1.0 / (1..=k).map(f64::from).product::<f64>());
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let hi = r4 * (r * f(13) + f(12)) + (r2 * (r * f(11) + f(10)) + (r * f(9) + f(8)));
    let lo = r4 * (r2 * (r * f(7) + f(6)) + (r * f(5) + f(4))) + (r2 * (r * f(3) + f(2)) + r);
    let m = (r8 * hi + lo).to_array();
    // 2^n from the integer n in the low mantissa bits of t
    let tt = t.to_array();
    let pow2 =
        |t: f64| f64::from_bits(t.to_bits().wrapping_sub(SHIFT.to_bits()).wrapping_add(1023) << 52);
    (m, [pow2(tt[0]), pow2(tt[1])])
}

/// exp(x) by [`exp_pair`]'s inlined polynomial (one lane used): cheaper than a call to the
/// C library's exp in the scalar temperature solve.
#[inline(always)]
pub(crate) fn exp_fast(x: f64) -> f64 {
    exp_pair(x, 0.0).0
}

#[cfg(test)]
mod tests {
    use super::exp_pair;

    #[test]
    fn exp_pair_matches_exp() {
        let mut worst: f64 = 0.0;
        let mut x = -745.0;
        while x < 745.0 {
            for (a, b) in [(x, -x), (x * 1e-3, x * 1e-6)] {
                let (ea, eb) = exp_pair(a, b);
                for (e, v) in [(ea, a), (eb, b)] {
                    let rel = (e - v.exp()).abs() / v.exp().max(f64::MIN_POSITIVE);
                    worst = worst.max(rel);
                }
            }
            x += 0.0137;
        }
        assert!(worst < 1e-15, "worst relative error {worst:e}");
        assert_eq!(exp_pair(0.0, 0.0), (1.0, 1.0));
    }

    /// exp(x) - 1 within 1e-15 of the C library's exp_m1 (relative), also for |x| down to
    /// 1e-12 where exp(x) - 1 computed from exp(x) would cancel, and on both sides of the
    /// n = 0 interval |x| < ln 2 / 2.
    #[test]
    fn exp_m1_pair_matches_exp_m1() {
        let mut worst: f64 = 0.0;
        let mut xs = vec![];
        let mut x = 1e-12;
        while x < 745.0 {
            xs.push(x);
            xs.push(-x);
            x *= 1.0173;
        }
        for w in xs.chunks(2) {
            let ((ea, ma), (eb, mb)) = super::exp_m1_pair(w[0], w[1]);
            for (e, m, v) in [(ea, ma, w[0]), (eb, mb, w[1])] {
                let r = v.exp_m1();
                if r.is_infinite() {
                    assert_eq!(m, r, "exp_m1 at {v}");
                } else {
                    // a NaN fails the comparison
                    let rel = (m - r).abs() / r.abs();
                    assert!(rel < 1e-15, "exp_m1 at {v}: {m} vs {r}");
                    worst = worst.max(rel);
                }
                assert_eq!(e.to_bits(), exp_pair(v, 0.0).0.to_bits(), "exp at {v}");
            }
        }
        assert!(
            worst > 0.0 && worst < 1e-15,
            "worst relative error {worst:e}"
        );
    }
}
