//! Accuracy per cost: transient responses on refined grids, their observed order of convergence, the extrapolated limit, and each grid's and scheme's error against it beside its cost on one core.
//!
//! Cases (F_N = 110 kN, a = 7.63 mm, b = 7.88 mm, presets dry, table4.1, wet): creepage steps
//! at 5 m/s with 1 ms steps (c_x 1 % -> 15 %), 20 m/s with 0.1 ms (0.2 % -> 5 %), 30 m/s with
//! 0.25 ms (1 % -> 15 %), and a sinusoidal creepage c_x = 2 % + 1.5 % sin(2 pi 50 Hz t) at
//! 20 m/s with 0.25 ms steps. Each starts from the steady state of its first input and runs six
//! contact-transit times 2a/v (the sine: one period after a quarter period).
//!
//! Quantities: F_x (N), the rise of the maximum flash temperature T_max - T_bulk (K) and the
//! frictional power P_fric (W), each a time series at the communication points. The grids
//! double in nx from 20x5 (10x3, 14x3, 20x3, 20x5, 40x5, 80x7, 160x11, 320x21, optionally
//! 640x41; 14x3 and 20x3 are candidates for the tolerance only); the strips sit at
//! Gauss-Legendre nodes, whose lateral error is small beside the error along the strips
//! (below 0.05 % from 7 strips on), so ny grows slowly. With the
//! differences d_k = max_t |X_k(t) - X_{k-1}(t)| of successive grids, the observed order is
//! p = log2(d_{n-1} / d_n) over the three finest, and the limit is the Richardson
//! extrapolation L(t) = X_n(t) + (X_n(t) - X_{n-1}(t)) / (2^p - 1) (p clamped to [0.5, 4]);
//! its uncertainty is stated as max_t |L - X_n| (the size of the correction). Errors are in
//! % of max_t |L| (for the temperature, of the largest rise).
//!
//! Schemes: `cells` is [`Scheme::CellsMarch`], what `ecf --scheme cells` and the FMU's
//! `scheme = 3` run, so that the costs are those a user gets; the reference without the march
//! of new bristles (`Contact::set_march_new_bristles`) gives the same results bit for bit at
//! a higher cost. `continuous` is [`Scheme::Continuous`], `cells-ho` is
//! [`Scheme::CellsHigher`] (the higher-order rules along each move).
//!
//! The full run (not `--quick`) also writes the table as CSV to
//! `creep-core/data/accuracy.csv` ([`CSV_PATH`]), which `creep_core::tolerance` reads at
//! compile time: regenerate it with `bash scripts/bench.sh --only accuracy`, never by hand.
//! `ECF_ACCURACY_CSV=path` writes it elsewhere instead (with `--quick` too).
//!
//! `ECF_ACCURACY_COSTS_FROM=path` keeps the costs of an earlier table: every row's
//! `wall_per_sim` is taken from the row of that file with the same preset, case, grid and
//! scheme (a row missing there ends the run before its first case), and the header says
//! so. For re-measuring the errors after a change that leaves the costs within their noise,
//! on a machine whose speed drifted since (the costs are wall times: on 2026-11-29 every
//! scheme, the unchanged ones too, ran 1.37-1.43x slower than on 2026-11-26).
use creep_core::engine::Scheme;
use creep_core::thermal::TemperatureSolve;
use creep_core::{Config, Contact, Grid, Inputs};
use std::time::Instant;

/// One transient test case.
#[derive(Clone, Copy)]
pub struct Case {
    pub preset: &'static str,
    pub v: f64,
    pub dt: f64,
    pub kind: Kind,
}

/// The creepage history of a case.
#[derive(Clone, Copy)]
pub enum Kind {
    /// c_x jumps from `from` to `to` at t = 0.
    Step { from: f64, to: f64 },
    /// c_x = mean + amp sin(2 pi f t).
    Sine { mean: f64, amp: f64, f_hz: f64 },
}

pub(crate) const FN: f64 = 110e3;
pub(crate) const A: f64 = 7.63e-3;
const B: f64 = 7.88e-3;

impl Case {
    pub(crate) fn name(&self) -> String {
        match self.kind {
            Kind::Step { from, to } => format!(
                "{} step {}->{} % at {} m/s, {} ms steps",
                self.preset,
                from * 100.0,
                to * 100.0,
                self.v,
                self.dt * 1e3
            ),
            Kind::Sine { mean, amp, f_hz } => format!(
                "{} sine {}+-{} % {} Hz at {} m/s, {} ms steps",
                self.preset,
                mean * 100.0,
                amp * 100.0,
                f_hz,
                self.v,
                self.dt * 1e3
            ),
        }
    }

    /// The case kind in the CSV: `step` or `sine`.
    fn kind_name(&self) -> &'static str {
        match self.kind {
            Kind::Step { .. } => "step",
            Kind::Sine { .. } => "sine",
        }
    }

    pub(crate) fn steps(&self) -> usize {
        let dur = match self.kind {
            Kind::Step { .. } => 6.0 * 2.0 * A / self.v,
            Kind::Sine { f_hz, .. } => 1.25 / f_hz,
        };
        ((dur / self.dt).round() as usize).max(10)
    }

    pub(crate) fn cx(&self, k: usize) -> f64 {
        match self.kind {
            Kind::Step { from, to } => {
                if k == 0 {
                    from
                } else {
                    to
                }
            }
            // k = 0: the steady state before the run (the value at t = 0); k >= 1: the input
            // held over step k, its value at the step's start (zero-order hold, as a master does)
            Kind::Sine { mean, amp, f_hz } => {
                let t = k.saturating_sub(1) as f64 * self.dt;
                mean + amp * (2.0 * std::f64::consts::PI * f_hz * t).sin()
            }
        }
    }
}

/// The standard cases of the accuracy benchmark.
pub fn cases() -> Vec<Case> {
    let step = |preset, v, dt, from, to| Case {
        preset,
        v,
        dt,
        kind: Kind::Step { from, to },
    };
    let mut v = Vec::new();
    for preset in ["dry", "table4.1", "wet"] {
        v.push(step(preset, 5.0, 1e-3, 0.01, 0.15));
        v.push(step(preset, 20.0, 1e-4, 0.002, 0.05));
        v.push(step(preset, 30.0, 2.5e-4, 0.01, 0.15));
        v.push(Case {
            preset,
            v: 20.0,
            dt: 2.5e-4,
            kind: Kind::Sine {
                mean: 0.02,
                amp: 0.015,
                f_hz: 50.0,
            },
        });
    }
    v
}

/// The schemes of the table, in its order.
const SCHEMES: [Scheme; 3] = [Scheme::CellsMarch, Scheme::Continuous, Scheme::CellsHigher];

/// A response: per communication point F_x (N), T_max - T_bulk (K), P_fric (W); and the wall time of the run (s).
pub struct Response {
    pub x: Vec<[f64; 3]>,
    pub wall: f64,
}

/// The benchmark's configuration: `preset` on an `nx` x `ny` grid, semi-axes a, b at F_N.
pub(crate) fn config(preset: &str, nx: usize, ny: usize) -> Config {
    let mut c = Config::preset(preset).expect("preset");
    c.grid = Grid { nx, ny };
    c.geometry = creep_core::config::Geometry::SemiAxes {
        a: A,
        b: B,
        fn_ref: FN,
    };
    c
}

/// Runs one case on one grid and scheme (one thread).
pub fn run(case: &Case, nx: usize, ny: usize, scheme: Scheme) -> Response {
    run_solve(case, nx, ny, scheme, None)
}

/// [`run`] with the local temperature solved by `solve` (None: the configuration's).
pub fn run_solve(
    case: &Case,
    nx: usize,
    ny: usize,
    scheme: Scheme,
    solve: Option<TemperatureSolve>,
) -> Response {
    let mut c = Contact::new(&config(case.preset, nx, ny)).expect("contact");
    c.set_scheme(scheme);
    if let Some(solve) = solve {
        c.set_temperature_solve(solve);
    }
    // every strip computed: the cases have no spin, and computing the symmetric strips once
    // would make their costs those of such inputs only (the results are bit-identical
    // either way); the table's costs hold for any inputs
    c.set_mirror_strips(false);
    let inp = |cx: f64| Inputs {
        cx,
        v: case.v,
        fn_n: FN,
        t_bulk: 20.0,
        ..Inputs::default()
    };
    c.steady(&inp(case.cx(0))).expect("steady");
    // the cost of the transient steps alone
    let t0 = Instant::now();
    let mut x = Vec::with_capacity(case.steps());
    for k in 1..=case.steps() {
        let o = c.step(case.dt, &inp(case.cx(k))).expect("step");
        x.push([o.fx, o.t_max - 20.0, o.p_fric]);
    }
    Response {
        x,
        wall: t0.elapsed().as_secs_f64(),
    }
}

fn max_diff(a: &[[f64; 3]], b: &[[f64; 3]], q: usize) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x[q] - y[q]).abs())
        .fold(0.0, f64::max)
}

/// The extrapolated limit of one case: per quantity the observed order, the limit series and its uncertainty (% of max |L|).
pub struct Limit {
    pub order: [f64; 3],
    pub x: Vec<[f64; 3]>,
    pub uncertainty: [f64; 3],
    pub scale: [f64; 3],
}

/// Richardson extrapolation from the three finest responses (coarse to fine).
pub fn limit(seq: &[&Response]) -> Limit {
    let n = seq.len();
    assert!(n >= 3, "three grids at least");
    let (c, m, f) = (&seq[n - 3].x, &seq[n - 2].x, &seq[n - 1].x);
    let mut order = [0.0; 3];
    let mut x = f.clone();
    let mut unc = [0.0; 3];
    let mut scale = [0.0; 3];
    for q in 0..3 {
        let d1 = max_diff(c, m, q);
        let d2 = max_diff(m, f, q);
        let p = if d2 > 0.0 && d1 > 0.0 {
            (d1 / d2).log2()
        } else {
            1.0
        };
        order[q] = p;
        let pc = p.clamp(0.5, 4.0);
        let r = 1.0 / (2f64.powf(pc) - 1.0);
        for (k, xk) in x.iter_mut().enumerate() {
            xk[q] = f[k][q] + (f[k][q] - m[k][q]) * r;
        }
        scale[q] = x.iter().map(|v| v[q].abs()).fold(0.0, f64::max).max(1e-300);
        unc[q] = 100.0 * max_diff(&x, f, q) / scale[q];
    }
    Limit {
        order,
        x,
        uncertainty: unc,
        scale,
    }
}

/// Errors of a response against the limit, % of max |L|: largest over the response, mean, at the end.
pub fn errors(r: &Response, l: &Limit, q: usize) -> (f64, f64, f64) {
    let n = r.x.len();
    let d: Vec<f64> =
        r.x.iter()
            .zip(&l.x)
            .map(|(a, b)| 100.0 * (a[q] - b[q]).abs() / l.scale[q])
            .collect();
    let max = d.iter().copied().fold(0.0, f64::max);
    let mean = d.iter().sum::<f64>() / n as f64;
    (max, mean, d[n - 1])
}

/// Prints the accuracy table of every case. `finest`: the finest nx (320 or 640); `quick`: two cases, grids up to 80x21.
pub fn table(quick: bool, finest: usize) {
    // nx doubles from 20x5 on; the strips at the Gauss-Legendre nodes need few (5 are within
    // 0.1-0.3 % of 81 on the 20 and 30 m/s steps, 7 within 0.1 %), so ny grows slowly and the
    // finest three (the limit's) carry a lateral error below 0.05 %. 14x3 and 20x3 are
    // candidates between 10x3 and 20x5 for the tolerance's choice (on 20 m/s steps 20x3
    // cells-ho meets 1 % for each preset at about 60 % of 20x5's cost)
    let mut grids = vec![
        (10usize, 3usize),
        (14, 3),
        (20, 3),
        (20, 5),
        (40, 5),
        (80, 7),
        (160, 11),
        (320, 21),
        (640, 41),
    ];
    grids.retain(|g| g.0 <= if quick { 80 } else { finest });
    let all = cases();
    let cases: Vec<Case> = if quick { vec![all[1], all[5]] } else { all };
    println!("== accuracy per cost: errors against the extrapolated limit, % of its largest value (F_x, T_max - T_bulk, P_fric); wall time / simulated time on one thread");
    let mut rows = Vec::new();
    // the commit and the time the measurement starts on (later commits during the run do not count)
    let mut measured = format!("commit {} at {} UTC", git_commit(), utc_now());
    let kept = std::env::var("ECF_ACCURACY_COSTS_FROM").ok().map(|path| {
        let (rows, when) = earlier_costs(&path).unwrap_or_else(|e| {
            eprintln!("ecf-bench: ECF_ACCURACY_COSTS_FROM: {e}");
            std::process::exit(1);
        });
        measured = format!("{measured}; errors from this run, costs (wall_per_sim) kept from the table measured on {when} ({path})");
        rows
    });
    // the kept cost of a case, grid and scheme (None: the earlier table has no such row)
    let kept_cost =
        |rows: &[creep_core::tolerance::Row], case: &Case, nx: usize, ny: usize, scheme: Scheme| {
            rows.iter()
                .find(|r| {
                    r.preset == case.preset
                        && r.kind == case.kind_name()
                        && r.v == case.v
                        && (r.dt_ms - case.dt * 1e3).abs() < 1e-9
                        && (r.nx, r.ny) == (nx, ny)
                        && r.scheme == scheme
                })
                .map(|r| r.cost)
        };
    // every row the run will need is looked up before the first case runs: a missing one
    // ends the run at once, not after minutes of the cases before it
    if let Some(rows) = &kept {
        let missing: Vec<String> = cases
            .iter()
            .flat_map(|case| grids.iter().map(move |&g| (case, g)))
            .flat_map(|(case, (nx, ny))| SCHEMES.iter().map(move |&s| (case, nx, ny, s)))
            .filter(|&(case, nx, ny, s)| kept_cost(rows, case, nx, ny, s).is_none())
            .map(|(case, nx, ny, s)| format!("{} {nx}x{ny} {}", case.name(), s.name()))
            .collect();
        if !missing.is_empty() {
            eprintln!(
                "ecf-bench: ECF_ACCURACY_COSTS_FROM has no row for {} of the run's rows, e.g. {}",
                missing.len(),
                missing[..missing.len().min(3)].join("; ")
            );
            std::process::exit(1);
        }
    }
    let cost_of = |case: &Case, nx: usize, ny: usize, scheme: Scheme, measured_cost: f64| {
        match &kept {
            // checked above: every row is there
            Some(rows) => kept_cost(rows, case, nx, ny, scheme).unwrap_or(measured_cost),
            None => measured_cost,
        }
    };
    for case in &cases {
        let sim = case.steps() as f64 * case.dt;
        let cells: Vec<Response> = grids
            .iter()
            .map(|&(nx, ny)| run(case, nx, ny, Scheme::CellsMarch))
            .collect();
        let refs: Vec<&Response> = cells.iter().collect();
        let l = limit(&refs);
        println!(
            "-- {} ({} steps, {:.1} ms)",
            case.name(),
            case.steps(),
            sim * 1e3
        );
        println!(
            "   observed order (three finest grids) F_x {:.2}, T rise {:.2}, P_fric {:.2}; limit uncertainty {:.3} / {:.3} / {:.3} %",
            l.order[0], l.order[1], l.order[2], l.uncertainty[0], l.uncertainty[1], l.uncertainty[2]
        );
        println!(
            "   {:>8} {:>10} {:>26} {:>26} {:>26} {:>10}",
            "grid",
            "scheme",
            "F_x max/mean/end %",
            "T rise max/mean/end %",
            "P_fric max/mean/end %",
            "x real t"
        );
        for (gi, &(nx, ny)) in grids.iter().enumerate() {
            for scheme in SCHEMES {
                let r;
                let resp = match scheme {
                    Scheme::CellsMarch => &cells[gi],
                    _ => {
                        r = run(case, nx, ny, scheme);
                        &r
                    }
                };
                let e: Vec<(f64, f64, f64)> = (0..3).map(|q| errors(resp, &l, q)).collect();
                let f = |t: (f64, f64, f64)| format!("{:.2} / {:.2} / {:.2}", t.0, t.1, t.2);
                let cost = cost_of(case, nx, ny, scheme, resp.wall / sim);
                rows.push(csv_row(case, nx, ny, scheme, &e, cost, &l));
                println!(
                    "   {:>8} {:>10} {:>26} {:>26} {:>26} {:>10.2}",
                    format!("{nx}x{ny}"),
                    scheme.name(),
                    f(e[0]),
                    f(e[1]),
                    f(e[2]),
                    cost
                );
            }
        }
    }
    // ECF_ACCURACY_CSV: another destination (also for --quick, which otherwise writes nothing)
    let dest = std::env::var("ECF_ACCURACY_CSV")
        .ok()
        .or_else(|| (!quick).then(|| CSV_PATH.to_string()));
    if let Some(dest) = dest {
        let path = std::path::Path::new(&dest);
        match std::fs::write(path, csv_text(&rows, &measured, grids[grids.len() - 1])) {
            Ok(()) => println!("== accuracy table written to {}", path.display()),
            Err(e) => {
                eprintln!("ecf-bench: cannot write {}: {e}", path.display());
                std::process::exit(1);
            }
        }
    }
}

/// Where the full run writes the machine-readable table (read by `creep_core::tolerance`).
pub const CSV_PATH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../creep-core/data/accuracy.csv"
);

/// The CSV header (column names); the units are on the comment lines above it.
pub const CSV_COLUMNS: &str = "preset,kind,v_m_s,dt_ms,nx,ny,scheme,fx_max_pct,fx_mean_pct,fx_end_pct,trise_max_pct,trise_mean_pct,trise_end_pct,pfric_max_pct,pfric_mean_pct,pfric_end_pct,wall_per_sim,fx_limit_unc_pct";

/// One CSV line: the case, the grid and scheme, the nine errors (%), the cost, and the limit's F_x uncertainty (%).
fn csv_row(
    case: &Case,
    nx: usize,
    ny: usize,
    scheme: Scheme,
    e: &[(f64, f64, f64)],
    cost: f64,
    l: &Limit,
) -> String {
    let mut s = format!(
        "{},{},{},{},{nx},{ny},{}",
        case.preset,
        case.kind_name(),
        case.v,
        case.dt * 1e3,
        scheme.name()
    );
    for t in e {
        s.push_str(&format!(",{:.3},{:.3},{:.3}", t.0, t.1, t.2));
    }
    s.push_str(&format!(",{cost:.4},{:.3}", l.uncertainty[0]));
    s
}

/// The whole CSV file: comment lines (what, units, the commit and date measured on), the header and the rows.
fn csv_text(rows: &[String], measured: &str, finest: (usize, usize)) -> String {
    let mut s = String::new();
    s.push_str("# ECF accuracy per cost, written by `bash scripts/bench.sh --only accuracy` (ecf-bench/src/accuracy.rs); do not edit by hand\n");
    s.push_str(&format!(
        "# measured on {measured} (start of the run); finest grid {}x{}; F_N = 110 kN, a = 7.63 mm, b = 7.88 mm; one thread (pinned to one core by bench.sh), machine under load: costs +-30 %\n",
        finest.0,
        finest.1
    ));
    s.push_str("# units: v in m/s; dt (communication step) in ms; nx, ny in cells; *_pct: error against the Richardson limit in % of the limit's largest value over the response (F_x; T_max - T_bulk; P_fric), largest (max), mean over the communication points, and at the end; wall_per_sim: wall time / simulated time (-, 1 = real time); fx_limit_unc_pct: uncertainty of the limit itself, F_x, %\n");
    s.push_str("# cases: step = c_x 1 -> 15 % (5 and 30 m/s) or 0.2 -> 5 % (20 m/s) at t = 0, six transits 2a/v; sine = c_x 2 % + 1.5 % sin(2 pi 50 Hz t), 1.25 periods\n");
    s.push_str(CSV_COLUMNS);
    s.push('\n');
    for r in rows {
        s.push_str(r);
        s.push('\n');
    }
    s
}

/// The rows of an earlier accuracy table and the "commit ... UTC" it was measured on.
fn earlier_costs(path: &str) -> Result<(Vec<creep_core::tolerance::Row>, String), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let when = text
        .lines()
        .find_map(|l| l.strip_prefix("# measured on "))
        .and_then(|l| l.split(" (start of the run)").next())
        .ok_or_else(|| format!("{path}: no '# measured on' line"))?
        .to_string();
    let rows = creep_core::tolerance::parse(&text, path).map_err(|e| e.to_string())?;
    Ok((rows, when))
}

/// The short commit hash of the working tree, with `+dirty` for uncommitted changes; `unknown` without git.
fn git_commit() -> String {
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match git(&["rev-parse", "--short=10", "HEAD"]) {
        None => "unknown".into(),
        Some(h) => {
            // the table itself is the one file the run changes: it does not make the tree dirty
            let dirty = git(&[
                "status",
                "--porcelain",
                "--untracked-files=no",
                "--",
                ":/",
                ":(top,exclude)creep-core/data/accuracy.csv",
            ])
            .is_some_and(|s| !s.is_empty());
            if dirty {
                format!("{h}+dirty")
            } else {
                h
            }
        }
    }
}

/// The current UTC time as `YYYY-MM-DD HH:MM` (civil calendar from the Unix day count).
fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86400), secs.rem_euclid(86400));
    // Howard Hinnant's days_from_civil inverse
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}",
        rem / 3600,
        rem % 3600 / 60
    )
}
