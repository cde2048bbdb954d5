//! Measurement files with a hidden effect outside the catalogue, made from seeds and truths that the search code never reads: the judge of the search of formula forms.
//!
//! A file is steady curves of a truth (a preset on a fine grid, 80 x 21 cells with the
//! higher-order rules, 0.16 % from the converged limit, plus a formula effect that no
//! catalogue entry has) at 5 speeds x 3 loads, 10 creepages each (150 rows), with the noise
//! of a traction rig: normal, standard deviation 2 % of |f| plus 0.003. Extra columns hold
//! one value per curve, drawn from the seed; a distractor column has no effect. A second
//! layout ([`Layout::other`]) changes everything the search might have been tuned to: 4
//! speeds x 2 loads, 16 creepages from 0.1 % to 20 % (128 rows), noise of 1 % of |f| plus
//! 0.005. A third ([`Layout::sparse`]) has few rows and much noise: 3 speeds x 3 loads, 7
//! creepages from 0.5 % to 15 % (63 rows), noise of 3 % of |f| plus 0.002. A fourth
//! ([`Layout::precise`]) has little noise: 4 speeds x 3 loads, 12 creepages from 0.2 % to
//! 20 % (144 rows), noise of 0.4 % of |f| plus 0.001. A fifth ([`Layout::one_load`]) is a
//! speed sweep at one load: 7 speeds x 12 creepages from 0.2 % to 20 % (84 rows).
//! Shared by the test `diagnose_unseen` and the sweep `cargo run --release -p ecf-measure
//! --example loop_sweep`.
#![allow(dead_code)]

use creep_core::{Config, Inputs, Model};
use ecf_measure::measure::{Dataset, Defaults};

/// A hidden effect: the truth's formula effect and the variable the search must name.
pub struct Case {
    /// Short name.
    pub name: &'static str,
    /// The preset the truth starts from (and the configuration under test is).
    pub preset: &'static str,
    /// Target of the hidden factor (`tau_c1`, `tau_c2`, `strengths`, ...).
    pub target: &'static str,
    /// The hidden factor.
    pub factor: &'static str,
    /// An extra column the factor reads, with the range its per-curve values are drawn from.
    pub column: Option<(&'static str, f64, f64)>,
    /// A second extra column with no effect, drawn from [0, 1].
    pub distractor: bool,
    /// Variables that name the truth (the load and the Hertz pressure are one variable at a
    /// fixed geometry).
    pub variables: &'static [&'static str],
}

/// The cases: speed, load, slip speed, local and bulk temperature and an extra column; linear,
/// reciprocal, saturating and threshold shapes; one strength and both together.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "speed-reciprocal-strengths",
            preset: "dry",
            target: "strengths",
            factor: "1 / (1 + 0.5 * (v_mps - 5) / 10)",
            column: None,
            distractor: false,
            variables: &["v_mps"],
        },
        Case {
            name: "load-linear-tau_c2",
            preset: "dry",
            target: "tau_c2",
            factor: "1 - 0.3 * (fn_kN - 100) / 40",
            column: None,
            distractor: true,
            variables: &["fn_kN", "p_GPa"],
        },
        Case {
            name: "slip-saturating-strengths",
            preset: "dry",
            target: "strengths",
            factor: "1 - 0.35 * (1 - exp(-slip_mps / 0.5))",
            column: None,
            distractor: false,
            variables: &["slip_mps"],
        },
        Case {
            name: "temperature-threshold-tau_c2",
            preset: "dry",
            target: "tau_c2",
            factor: "1 - 0.5 / (1 + exp(-(T_C - 120) / 15))",
            column: None,
            distractor: false,
            variables: &["T_C"],
        },
        Case {
            name: "column-saturating-strengths",
            preset: "dry",
            target: "strengths",
            factor: "1 - 0.35 * (1 - exp(-contamination / 2))",
            column: Some(("contamination", 0.0, 6.0)),
            distractor: true,
            variables: &["contamination"],
        },
        Case {
            name: "column-linear-tau_c2",
            preset: "table4.1",
            target: "tau_c2",
            factor: "1 - 0.06 * (moisture - 50) / 10",
            column: Some(("moisture", 20.0, 80.0)),
            distractor: true,
            variables: &["moisture"],
        },
        Case {
            name: "speed-threshold-tau_c2",
            preset: "wet",
            target: "tau_c2",
            factor: "1 - 0.3 / (1 + exp(-(v_mps - 14) / 2))",
            column: None,
            distractor: false,
            variables: &["v_mps"],
        },
        Case {
            name: "load-reciprocal-strengths",
            preset: "table4.1",
            target: "strengths",
            factor: "1 / (1 + 0.4 * (fn_kN - 60) / 80)",
            column: None,
            distractor: false,
            variables: &["fn_kN", "p_GPa"],
        },
        Case {
            name: "column-threshold-tau_c1",
            preset: "dry",
            target: "tau_c1",
            factor: "1 + 0.6 / (1 + exp(-(sand_g - 5) / 0.8))",
            column: Some(("sand_g", 0.0, 10.0)),
            distractor: false,
            variables: &["sand_g"],
        },
        Case {
            name: "bulk-threshold-tau_c2",
            preset: "dry",
            target: "tau_c2",
            factor: "1 - 0.25 / (1 + exp(-(t_bulk_C - 30) / 3))",
            column: Some((BULK, 0.0, 50.0)),
            distractor: false,
            variables: &[BULK],
        },
    ]
}

/// The column of the bulk temperature: a file's `t_bulk_C` is the model's input T_B, not a
/// data column, so a case's per-curve values of it go to the truth's inputs.
pub const BULK: &str = "t_bulk_C";

/// A truth: `preset` on 80 x 21 cells (higher-order rules) with `factor` on `target` (no
/// factor: the preset itself).
pub fn truth(preset: &str, target: &str, factor: Option<&str>) -> Config {
    let mut j = Config::preset(preset).expect("preset").to_json();
    j["grid"] = serde_json::json!({"nx": 80, "ny": 21});
    j["scheme"] = serde_json::json!("cells-ho");
    if let Some(f) = factor {
        j["formula_effects"] = serde_json::json!([{"name": "hidden", "target": target,
            "factor": f, "params": {}}]);
    }
    Config::from_json_str(&j.to_string(), "truth.json").expect("truth")
}

/// A small deterministic generator (splitmix64).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03)
    }
    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Standard normal (Box-Muller).
    pub fn normal(&mut self) -> f64 {
        let u = self.uniform().max(1e-300);
        let v = self.uniform();
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

/// Where a file's rows sit and how noisy they are.
pub struct Layout {
    /// Rolling speeds, m/s.
    pub speeds: &'static [f64],
    /// Normal loads, kN.
    pub loads: &'static [f64],
    /// Creepages per curve, log-spaced from `cx_range.0` to `cx_range.1` (-).
    pub creepages: usize,
    /// First and last creepage, -.
    pub cx_range: (f64, f64),
    /// Noise standard deviation: `noise.0` |f| + `noise.1`, -.
    pub noise: (f64, f64),
}

impl Layout {
    /// The layout of the cases: 5 speeds x 3 loads x 10 creepages, noise 2 % of |f| + 0.003.
    pub fn standard() -> Self {
        Layout {
            speeds: &[5.0, 10.0, 15.0, 20.0, 25.0],
            loads: &[60.0, 100.0, 140.0],
            creepages: 10,
            cx_range: (0.0015, 0.25),
            noise: (0.02, 0.003),
        }
    }
    /// Another rig: 4 speeds x 2 loads x 16 creepages, noise 1 % of |f| + 0.005.
    pub fn other() -> Self {
        Layout {
            speeds: &[6.0, 12.0, 18.0, 28.0],
            loads: &[80.0, 120.0],
            creepages: 16,
            cx_range: (0.001, 0.2),
            noise: (0.01, 0.005),
        }
    }
    /// A third rig, few rows and noisy: 3 speeds x 3 loads x 7 creepages from 0.5 % to 15 %
    /// (63 rows), noise 3 % of |f| + 0.002.
    pub fn sparse() -> Self {
        Layout {
            speeds: &[8.0, 16.0, 30.0],
            loads: &[50.0, 90.0, 130.0],
            creepages: 7,
            cx_range: (0.005, 0.15),
            noise: (0.03, 0.002),
        }
    }
    /// A fourth rig, precise: 4 speeds x 3 loads x 12 creepages from 0.2 % to 20 % (144
    /// rows), noise 0.4 % of |f| + 0.001, a noise level under 1 % at which the diagnosis
    /// needs a fine grid.
    pub fn precise() -> Self {
        Layout {
            speeds: &[7.0, 13.0, 19.0, 27.0],
            loads: &[70.0, 105.0, 145.0],
            creepages: 12,
            cx_range: (0.002, 0.2),
            noise: (0.004, 0.001),
        }
    }
    /// A fifth rig, one load: 7 speeds x 1 load of 110 kN x 12 creepages from 0.2 % to
    /// 20 % (84 rows), noise 2 % of |f| + 0.003. Load effects are a constant factor here,
    /// which the fitted strengths take up: nothing to find.
    pub fn one_load() -> Self {
        Layout {
            speeds: &[4.0, 8.0, 12.0, 16.0, 20.0, 25.0, 30.0],
            loads: &[110.0],
            creepages: 12,
            cx_range: (0.002, 0.2),
            noise: (0.02, 0.003),
        }
    }
    /// The layout of a name: `standard`, `other`, `sparse`, `precise` or `one-load`.
    pub fn by_name(name: &str) -> Option<Self> {
        match name {
            "one-load" => Some(Self::one_load()),
            "standard" => Some(Self::standard()),
            "other" => Some(Self::other()),
            "sparse" => Some(Self::sparse()),
            "precise" => Some(Self::precise()),
            _ => None,
        }
    }
    /// Standard deviation of the rig's noise at traction coefficient `f`.
    pub fn noise_sd(&self, f: f64) -> f64 {
        self.noise.0 * f.abs() + self.noise.1
    }
}

/// The file of `truth` with noise from `seed`: columns cx, f, v_mps, fn_kN, then `column`
/// and the distractor when given. Also the noise-free values.
pub fn file(
    truth: &Config,
    column: Option<(&str, f64, f64)>,
    distractor: bool,
    seed: u64,
) -> (Dataset, Vec<f64>) {
    file_in(&Layout::standard(), truth, column, distractor, seed)
}

/// [`file`] in `layout`.
pub fn file_in(
    layout: &Layout,
    truth: &Config,
    column: Option<(&str, f64, f64)>,
    distractor: bool,
    seed: u64,
) -> (Dataset, Vec<f64>) {
    let (csv, clean) = csv_text_in(layout, truth, column, distractor, seed);
    (dataset(&csv), clean)
}

/// A file's CSV text read as a user's file would be.
pub fn dataset(csv: &str) -> Dataset {
    Dataset::from_csv_str(csv, "unseen.csv", &Defaults::default()).expect("file")
}

/// [`file`] as CSV text, with the noise-free values.
pub fn csv_text(
    truth: &Config,
    column: Option<(&str, f64, f64)>,
    distractor: bool,
    seed: u64,
) -> (String, Vec<f64>) {
    csv_text_in(&Layout::standard(), truth, column, distractor, seed)
}

/// [`csv_text`] in `layout`.
pub fn csv_text_in(
    layout: &Layout,
    truth: &Config,
    column: Option<(&str, f64, f64)>,
    distractor: bool,
    seed: u64,
) -> (String, Vec<f64>) {
    let mut rng = Rng::new(seed);
    let mut head = String::from("cx,f,v_mps,fn_kN");
    if let Some((c, _, _)) = column {
        head += &format!(",{c}");
    }
    if distractor {
        head += ",distractor";
    }
    let mut csv = head + "\n";
    let mut clean = Vec::new();
    let n = layout.creepages;
    let (cx0, cx1) = layout.cx_range;
    for &v in layout.speeds {
        for &fkn in layout.loads {
            let mut extras = Vec::new();
            if let Some((c, lo, hi)) = column {
                extras.push((c.to_string(), lo + (hi - lo) * rng.uniform()));
            }
            if distractor {
                extras.push(("distractor".to_string(), rng.uniform()));
            }
            // the values as written (4 decimals), so that the model reads what the file says
            for e in extras.iter_mut() {
                e.1 = (e.1 * 1e4).round() / 1e4;
            }
            let t_bulk = extras.iter().find(|e| e.0 == BULK).map(|e| e.1);
            let data_columns: Vec<(String, f64)> =
                extras.iter().filter(|e| e.0 != BULK).cloned().collect();
            let mut m = Model::new(truth).expect("model");
            if !data_columns.is_empty() {
                m.set_extra(&data_columns).expect("extras");
            }
            for i in 0..n {
                let cx = cx0 * (cx1 / cx0).powf(i as f64 / (n - 1) as f64);
                let cx = (cx * 1e6).round() / 1e6;
                let f = m
                    .steady(&Inputs {
                        cx,
                        v,
                        fn_n: fkn * 1e3,
                        t_bulk: t_bulk.unwrap_or(Inputs::default().t_bulk),
                        ..Inputs::default()
                    })
                    .expect("steady")
                    .f;
                clean.push(f);
                let y = f + layout.noise_sd(f) * rng.normal();
                csv += &format!("{cx},{y:.6},{v},{fkn}");
                for e in &extras {
                    csv += &format!(",{}", e.1);
                }
                csv += "\n";
            }
        }
    }
    (csv, clean)
}

/// The true noise of `data` against its noise-free values as a CV(RMSE), %.
pub fn true_noise_cv(data: &Dataset, clean: &[f64]) -> f64 {
    let n = data.rows.len() as f64;
    let ss: f64 = data
        .rows
        .iter()
        .zip(clean)
        .map(|(r, c)| (r.f - c).powi(2))
        .sum();
    let mean: f64 = data.rows.iter().map(|r| r.f).sum::<f64>() / n;
    100.0 * (ss / n).sqrt() / mean
}
