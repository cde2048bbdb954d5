//! The error statistics of the measurement loop, in one place: CV(RMSE) (seed Eq. 2.8, 2.9), mean, standard deviation, median and Pearson's correlation.
//!
//! Every score of a model against measurements (compare, fit, diagnose, search, the noise
//! level, high-pressure torsion) is computed here, so they all divide by the same mean and
//! sum in the same order.

/// CV(RMSE) in percent (Eq. 2.9): 100 sqrt(mean((k - k_hat)^2)) / mean(k), over the first
/// `min(len)` values of both; NaN for no values.
pub fn cv_rmse_pct(measured: &[f64], model: &[f64]) -> f64 {
    let n = measured.len().min(model.len());
    if n == 0 {
        return f64::NAN;
    }
    let sq = measured
        .iter()
        .zip(model)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>();
    let sum = measured.iter().take(n).sum::<f64>();
    cv_rmse_from_sums(sq, sum, n)
}

/// CV(RMSE) in percent from running sums: `sq` the sum of squared residuals, `sum_measured`
/// the sum of the measured values, `n` their number; NaN for `n` = 0.
pub fn cv_rmse_from_sums(sq: f64, sum_measured: f64, n: usize) -> f64 {
    if n == 0 {
        return f64::NAN;
    }
    let n = n as f64;
    100.0 * (sq / n).sqrt() / (sum_measured / n).abs()
}

/// A standard deviation as a CV(RMSE), percent: what a model that is off by `sd` everywhere
/// scores against values of mean `mean`.
pub fn cv_pct(sd: f64, mean: f64) -> f64 {
    100.0 * sd / mean.abs()
}

/// CV(RMSE) and mean residual (model - measured) of one group, accumulated row by row.
#[derive(Default, Clone, Copy, Debug)]
pub struct Residuals {
    /// Number of rows.
    pub n: usize,
    sq: f64,
    meas: f64,
    res: f64,
}

impl Residuals {
    /// Adds one row.
    pub fn add(&mut self, measured: f64, model: f64) {
        self.n += 1;
        self.sq += (model - measured) * (model - measured);
        self.meas += measured;
        self.res += model - measured;
    }
    /// CV(RMSE) of the rows so far, % (NaN for none); the same value as [`cv_rmse_pct`].
    pub fn cv_rmse_pct(&self) -> f64 {
        cv_rmse_from_sums(self.sq, self.meas, self.n)
    }
    /// Mean residual model - measured (NaN for none).
    pub fn mean_residual(&self) -> f64 {
        if self.n == 0 {
            f64::NAN
        } else {
            self.res / self.n as f64
        }
    }
}

/// Arithmetic mean (0 for no values).
pub fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len().max(1) as f64
}

/// Mean and population standard deviation (divided by n; (0, 0) for no values).
pub fn mean_sd(x: &[f64]) -> (f64, f64) {
    let m = mean(x);
    let s = (x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / x.len().max(1) as f64).sqrt();
    (m, s)
}

/// Median of values (sorted in place by `total_cmp`); NaN for none.
pub fn median(x: &mut [f64]) -> f64 {
    x.sort_by(f64::total_cmp);
    let n = x.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        x[n / 2]
    } else {
        0.5 * (x[n / 2 - 1] + x[n / 2])
    }
}

/// Pearson's correlation coefficient of x and y; 0 where either does not vary.
pub fn pearson(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    if sxx <= 0.0 || syy <= 0.0 {
        0.0
    } else {
        sxy / (sxx * syy).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cv_rmse_is_eq_2_9() {
        assert!((cv_rmse_pct(&[1.0, 3.0], &[1.0, 3.0])).abs() < 1e-12);
        // rmse = 1, mean = 2 -> 50 %
        assert!((cv_rmse_pct(&[1.0, 3.0], &[2.0, 2.0]) - 50.0).abs() < 1e-12);
        assert!(cv_rmse_pct(&[], &[]).is_nan());
    }

    #[test]
    fn the_accumulator_gives_the_same_bits_as_the_slices() {
        let meas = [0.21, 0.33, 0.37, 0.36, 0.351, -0.02];
        let model = [0.2, 0.35, 0.36, 0.365, 0.34, 0.01];
        let mut acc = Residuals::default();
        for (a, b) in meas.iter().zip(&model) {
            acc.add(*a, *b);
        }
        assert_eq!(
            acc.cv_rmse_pct().to_bits(),
            cv_rmse_pct(&meas, &model).to_bits()
        );
        let res: f64 = model.iter().zip(&meas).map(|(y, m)| y - m).sum::<f64>() / 6.0;
        assert!((acc.mean_residual() - res).abs() < 1e-15);
        assert!(Residuals::default().cv_rmse_pct().is_nan());
    }

    #[test]
    fn mean_sd_median_pearson() {
        let (m, s) = mean_sd(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(m, 2.5);
        assert!((s - 1.25f64.sqrt()).abs() < 1e-15);
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!((pearson(&[1.0, 2.0, 3.0], &[2.0, 4.0, 6.0]) - 1.0).abs() < 1e-15);
        assert!((pearson(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]) + 1.0).abs() < 1e-15);
        assert_eq!(pearson(&[1.0, 1.0, 1.0], &[3.0, 2.0, 1.0]), 0.0);
        assert_eq!(cv_pct(1.0, -4.0), 25.0);
    }
}
