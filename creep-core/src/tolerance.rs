//! The grid and scheme for a relative tolerance on F_x, chosen from the accuracy benchmark's table (`data/accuracy.csv`).
//!
//! The table is written by `bash scripts/bench.sh --only accuracy` (ecf-bench/src/accuracy.rs)
//! and compiled in: one row per preset (dry, table4.1, wet) x case (creepage step or 50 Hz
//! sine, at a speed v and a communication step dt) x grid x scheme, with the largest F_x
//! error over the response against the extrapolated limit (% of the limit's largest value)
//! and the cost (wall time / simulated time on one thread).
//!
//! # The rule ([`choose`])
//! 1. **Speed.** The tabulated speed used is the smallest one not below |v|; above the
//!    fastest, the fastest (the error there is not measured beyond it).
//! 2. **Error of a (grid, scheme)** at that speed: the largest `fx_max_pct` over the rows in
//!    scope at that speed, every case and every step size tabulated there. The scope is the
//!    configuration's own preset when it is a tabulated one, unchanged (same model, effects,
//!    parameters, Coulomb bound and modifiers; [`scope_of`]): its own measured error. Any
//!    other configuration (another preset, changed parameters, added effects) takes the worst
//!    over every tabulated preset. Geometry and step are not part of the scope: the error is
//!    the measured one at the table's geometry, whatever the user's.
//! 3. **Cost of a (grid, scheme)**: the largest `wall_per_sim` over its rows at that speed;
//!    with a step size dt, over the rows whose tabulated step is the nearest to dt (in ratio;
//!    a tie goes to the smaller step) only. The cost ranks the candidates and is shown; it is
//!    a measurement under load (+-30 %).
//! 4. **Choice.** Among the (grid, scheme) pairs with every case at that speed tabulated and
//!    allowed by the [`Filter`] (an explicit grid or scheme), the cheapest whose error is at
//!    most 100 x `tol` %; ties by cost go to the smaller error, then the smaller grid.
//! 5. **None meets it** (`met = false`): the errors of the most accurate rows are measured
//!    against a limit that is itself uncertain (`limit_unc_pct`, the largest over the scope's
//!    cases at that speed), so rows whose errors differ by less than that cannot be ranked.
//!    The choice is the cheapest row whose error is within `limit_unc_pct` of the smallest
//!    (ties: the smaller error, then the smaller grid). Where the limit is well known this is
//!    the most accurate row; where it is not (the dry 50 Hz sine at 20 m/s, 2.3 %) it is not a
//!    grid hundreds of times slower than real time for an accuracy the table cannot show.
//!
//! The error stated is the benchmark's measured error at the tabulated speed and cases,
//! nothing more: it is not a bound for other inputs, and the limit it is measured against
//! has its own uncertainty (`limit_unc_pct`).

use crate::error::{CreepError, Result};
use crate::scheme::Scheme;

/// The accuracy table as written by the benchmark (comment lines `#`, a header, the rows).
pub const TABLE_CSV: &str = include_str!("../data/accuracy.csv");

/// One row of the accuracy table.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Preset name (dry, table4.1, wet).
    pub preset: String,
    /// Case kind: `step` (creepage step) or `sine` (50 Hz creepage).
    pub kind: String,
    /// Rolling speed, m/s.
    pub v: f64,
    /// Communication step, ms.
    pub dt_ms: f64,
    /// Cells per strip (-).
    pub nx: usize,
    /// Strips (-).
    pub ny: usize,
    /// Scheme: `cells` is [`Scheme::CellsMarch`], `continuous` is [`Scheme::Continuous`],
    /// `cells-ho` is [`Scheme::CellsHigher`].
    pub scheme: Scheme,
    /// Largest F_x error over the response, % of the limit's largest |F_x|.
    pub fx_max_pct: f64,
    /// Largest error of the rise T_max - T_bulk over the response, % of the limit's largest rise.
    pub trise_max_pct: f64,
    /// Largest P_fric error over the response, % of the limit's largest P_fric.
    pub pfric_max_pct: f64,
    /// Wall time / simulated time on one thread (-; 1 = real time).
    pub cost: f64,
    /// Uncertainty of the extrapolated F_x limit itself, %.
    pub limit_unc_pct: f64,
}

/// Parses an accuracy table (the format of [`TABLE_CSV`]); `name` appears in errors.
pub fn parse(text: &str, name: &str) -> Result<Vec<Row>> {
    let err = |line: usize, m: String| CreepError::Config {
        source_name: name.to_string(),
        message: format!("line {line}: {m}"),
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (hl, header) = lines
        .next()
        .ok_or_else(|| err(0, "no header line".into()))?;
    let cols: Vec<&str> = header.split(',').map(str::trim).collect();
    let col = |n: &str| {
        cols.iter()
            .position(|c| *c == n)
            .ok_or_else(|| err(hl, format!("no column '{n}'")))
    };
    let idx = [
        col("preset")?,
        col("kind")?,
        col("v_m_s")?,
        col("dt_ms")?,
        col("nx")?,
        col("ny")?,
        col("scheme")?,
        col("fx_max_pct")?,
        col("trise_max_pct")?,
        col("pfric_max_pct")?,
        col("wall_per_sim")?,
        col("fx_limit_unc_pct")?,
    ];
    let mut rows = Vec::new();
    for (ln, l) in lines {
        let f: Vec<&str> = l.split(',').map(str::trim).collect();
        if f.len() != cols.len() {
            return Err(err(
                ln,
                format!("{} fields, the header has {}", f.len(), cols.len()),
            ));
        }
        let num = |i: usize| -> Result<f64> {
            f[idx[i]]
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x >= 0.0)
                .ok_or_else(|| {
                    err(
                        ln,
                        format!("{}: '{}' is not a number >= 0", cols[idx[i]], f[idx[i]]),
                    )
                })
        };
        let count = |i: usize| -> Result<usize> {
            f[idx[i]].parse::<usize>().map_err(|_| {
                err(
                    ln,
                    format!("{}: '{}' is not a count", cols[idx[i]], f[idx[i]]),
                )
            })
        };
        let scheme = match Scheme::by_name(f[idx[6]]) {
            Some(s) => s,
            None => {
                return Err(err(
                    ln,
                    format!("scheme '{}' ({})", f[idx[6]], Scheme::NAMES),
                ))
            }
        };
        rows.push(Row {
            preset: f[idx[0]].to_string(),
            kind: f[idx[1]].to_string(),
            v: num(2)?,
            dt_ms: num(3)?,
            nx: count(4)?,
            ny: count(5)?,
            scheme,
            fx_max_pct: num(7)?,
            trise_max_pct: num(8)?,
            pfric_max_pct: num(9)?,
            cost: num(10)?,
            limit_unc_pct: num(11)?,
        });
    }
    if rows.is_empty() {
        return Err(err(hl, "no rows".into()));
    }
    Ok(rows)
}

/// The compiled-in table, parsed at each call (a few hundred rows; once per FMU instance).
/// Not cached in a static: an FMU's importer loads and unloads the library once per run,
/// and a static's heap is never freed at the unload (84 kB per load).
pub fn table() -> Result<Vec<Row>> {
    parse(TABLE_CSV, "data/accuracy.csv").map_err(|e| CreepError::Config {
        source_name: "creep-core accuracy table".into(),
        message: e.to_string(),
    })
}

/// The comment lines of the compiled-in table (what, units, commit and date measured on).
pub fn table_notes() -> Vec<&'static str> {
    TABLE_CSV
        .lines()
        .filter_map(|l| l.strip_prefix('#'))
        .map(str::trim)
        .collect()
}

/// What the user fixed explicitly: only (grid, scheme) pairs that agree with it are
/// candidates; and the preset whose rows are the scope (rule 2).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Filter {
    /// The tabulated preset whose rows alone count ([`scope_of`]); None: the worst over all.
    pub preset: Option<&'static str>,
    /// Cells per strip, if given.
    pub nx: Option<usize>,
    /// Strips, if given.
    pub ny: Option<usize>,
    /// Scheme, if given.
    pub scheme: Option<Scheme>,
    /// For a steady computation (`ecf curve`, `field`): the continuous rows are left out.
    /// Its steady state is the cell scheme's march, and its rows measure how it steps; the
    /// higher-order rules (`cells-ho`) change the march too, so their rows count.
    pub steady: bool,
}

impl Filter {
    fn allows(&self, nx: usize, ny: usize, s: Scheme) -> bool {
        self.nx.is_none_or(|n| n == nx)
            && self.ny.is_none_or(|n| n == ny)
            && self.scheme.is_none_or(|f| f == s)
            && !(self.steady && s == Scheme::Continuous)
    }
}

/// The chosen grid and scheme, with the tabulated error it has.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    /// The tolerance asked for (fraction, 0.01 = 1 %).
    pub tol: f64,
    /// Cells per strip.
    pub nx: usize,
    /// Strips.
    pub ny: usize,
    /// Scheme.
    pub scheme: Scheme,
    /// Tabulated largest F_x error (%), the worst over the cases in scope at `v_tab`.
    pub fx_err_pct: f64,
    /// Tabulated largest error of the T_max rise (%), worst over the same rows (shown, not used).
    pub trise_err_pct: f64,
    /// Tabulated cost, wall time / simulated time on one thread (-), see the rule.
    pub cost: f64,
    /// The tabulated speed used, m/s.
    pub v_tab: f64,
    /// The tabulated steps at `v_tab`, ms (the cost is of the one nearest the given step, if any).
    pub dt_tab_ms: Vec<f64>,
    /// Largest uncertainty of the reference limit itself at `v_tab`, F_x, %.
    pub limit_unc_pct: f64,
    /// True if `fx_err_pct` <= 100 `tol`.
    pub met: bool,
    /// The presets whose rows count, as words (`table4.1`, or `dry, table4.1, wet`).
    pub scope: String,
    /// Not met: the smallest tabulated error in scope (%), from which the choice is within
    /// `limit_unc_pct` (rule 5); equal to `fx_err_pct` where the most accurate row is chosen.
    pub best_err_pct: f64,
}

impl Choice {
    /// One line for the user: the grid and scheme, the tabulated error, and whether the
    /// tolerance is met.
    pub fn message(&self) -> String {
        let dts: Vec<String> = self.dt_tab_ms.iter().map(|d| format!("{d}")).collect();
        let head = format!(
            "grid {}x{}, scheme {}: tabulated largest F_x error {:.2} % (worst of {}, steps and 50 Hz sine at {} m/s, {} ms steps; T_max rise {:.2} %; reference limit uncertain by up to {:.2} %), cost {:.2}x real time on one core",
            self.nx,
            self.ny,
            self.scheme.name(),
            self.fx_err_pct,
            self.scope,
            self.v_tab,
            dts.join(" and "),
            self.trise_err_pct,
            self.limit_unc_pct,
            self.cost
        );
        if self.met {
            format!("tolerance {} % met: {head}", 100.0 * self.tol)
        } else if self.fx_err_pct > self.best_err_pct {
            format!(
                "tolerance {} % NOT met: no tabulated grid and scheme reaches it; the most accurate ones ({:.2} % at best) cannot be ranked within the reference limit's uncertainty ({:.2} %), so the cheapest of them is used: {head}",
                100.0 * self.tol,
                self.best_err_pct,
                self.limit_unc_pct
            )
        } else {
            format!(
                "tolerance {} % NOT met: no tabulated grid and scheme reaches it; the most accurate one is used: {head}",
                100.0 * self.tol
            )
        }
    }
}

/// Checks a relative tolerance: finite and > 0 (a fraction, 0.01 = 1 %); `what` names it in the error.
pub fn check_tol(tol: f64, what: &str) -> Result<()> {
    if tol.is_finite() && tol > 0.0 {
        Ok(())
    } else {
        Err(CreepError::OutOfRange {
            field: what.into(),
            value: tol,
            expected: "must be a finite relative tolerance > 0 (a fraction: 0.01 = 1 %)".into(),
        })
    }
}

/// The grid and scheme for tolerance `tol` (fraction) at speed `v` (m/s) with communication
/// step `dt` (s, if known), from the compiled-in table. See the module's rule.
pub fn choose(tol: f64, v: f64, dt: Option<f64>, filter: Filter) -> Result<Choice> {
    choose_in(&table()?, tol, v, dt, filter)
}

/// [`choose`] on a given table.
pub fn choose_in(
    rows: &[Row],
    tol: f64,
    v: f64,
    dt: Option<f64>,
    filter: Filter,
) -> Result<Choice> {
    check_tol(tol, "tolerance")?;
    if !v.is_finite() {
        return Err(CreepError::OutOfRange {
            field: "v".into(),
            value: v,
            expected: "must be finite m/s".into(),
        });
    }
    if let Some(dt) = dt {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(CreepError::OutOfRange {
                field: "step size".into(),
                value: dt,
                expected: "must be finite and > 0 s".into(),
            });
        }
    }
    let none = |m: String| CreepError::Config {
        source_name: "accuracy table".into(),
        message: m,
    };
    // 1. the speed
    let mut speeds: Vec<f64> = rows.iter().map(|r| r.v).collect();
    speeds.sort_by(f64::total_cmp);
    speeds.dedup();
    let speed = v.abs();
    let v_tab = speeds
        .iter()
        .copied()
        .find(|s| *s >= speed)
        .or(speeds.last().copied())
        .ok_or_else(|| none("the table is empty".into()))?;
    let at_all: Vec<&Row> = rows.iter().filter(|r| r.v == v_tab).collect();
    // the scope: the preset's own rows, if it has any at that speed
    let own: Vec<&Row> = match filter.preset {
        Some(p) => at_all.iter().copied().filter(|r| r.preset == p).collect(),
        None => Vec::new(),
    };
    let at = if own.is_empty() { at_all } else { own };
    let scope = {
        let mut p: Vec<&str> = at.iter().map(|r| r.preset.as_str()).collect();
        p.sort();
        p.dedup();
        p.join(", ")
    };
    // the cases at that speed: every candidate must have all of them
    let case_of = |r: &Row| (r.preset.clone(), r.kind.clone(), r.dt_ms.to_bits());
    let mut cases: Vec<_> = at.iter().map(|r| case_of(r)).collect();
    cases.sort();
    cases.dedup();
    let mut dts: Vec<f64> = at.iter().map(|r| r.dt_ms).collect();
    dts.sort_by(f64::total_cmp);
    dts.dedup();
    // 3. the step whose rows give the cost: the nearest tabulated one in ratio, ties to the smaller
    let dt_cost = dt.map(|dt| {
        let ms = dt * 1e3;
        dts.iter()
            .copied()
            .fold(None::<(f64, f64)>, |best, d| {
                let dist = (ms / d).ln().abs();
                match best {
                    Some((_, b)) if b <= dist => best,
                    _ => Some((d, dist)),
                }
            })
            .map_or(ms, |b| b.0)
    });
    // 2. the candidates: (grid, scheme) with every case at v_tab
    let mut keys: Vec<(usize, usize, &'static str)> = at
        .iter()
        .filter(|r| filter.allows(r.nx, r.ny, r.scheme))
        .map(|r| (r.nx, r.ny, r.scheme.name()))
        .collect();
    keys.sort();
    keys.dedup();
    let limit_unc_pct = at.iter().map(|r| r.limit_unc_pct).fold(0.0, f64::max);
    let mut cands: Vec<Choice> = Vec::new();
    for (nx, ny, sn) in keys {
        let mine: Vec<&&Row> = at
            .iter()
            .filter(|r| r.nx == nx && r.ny == ny && r.scheme.name() == sn)
            .collect();
        let mut covered: Vec<_> = mine.iter().map(|r| case_of(r)).collect();
        covered.sort();
        covered.dedup();
        if covered != cases {
            continue;
        }
        let fx = mine.iter().map(|r| r.fx_max_pct).fold(0.0, f64::max);
        let tr = mine.iter().map(|r| r.trise_max_pct).fold(0.0, f64::max);
        let cost = mine
            .iter()
            .filter(|r| dt_cost.is_none_or(|d| r.dt_ms == d))
            .map(|r| r.cost)
            .fold(0.0, f64::max);
        cands.push(Choice {
            tol,
            nx,
            ny,
            scheme: mine[0].scheme,
            fx_err_pct: fx,
            trise_err_pct: tr,
            cost,
            v_tab,
            dt_tab_ms: dts.clone(),
            limit_unc_pct,
            met: fx <= 100.0 * tol,
            scope: scope.clone(),
            best_err_pct: fx,
        });
    }
    let grid_size = |c: &Choice| c.nx * c.ny;
    let cheapest = |a: &&Choice, b: &&Choice| {
        a.cost
            .total_cmp(&b.cost)
            .then(a.fx_err_pct.total_cmp(&b.fx_err_pct))
            .then(grid_size(a).cmp(&grid_size(b)))
    };
    // 4. the cheapest that meets the tolerance
    let best_met = cands.iter().filter(|c| c.met).min_by(cheapest).cloned();
    // 5. else the cheapest within the limit's uncertainty of the most accurate
    let best = best_met.or_else(|| {
        let smallest = cands
            .iter()
            .map(|c| c.fx_err_pct)
            .fold(f64::INFINITY, f64::min);
        cands
            .iter()
            .filter(|c| c.fx_err_pct <= smallest + limit_unc_pct)
            .min_by(cheapest)
            .map(|c| Choice {
                best_err_pct: smallest,
                ..c.clone()
            })
    });
    best.ok_or_else(|| {
        none(format!(
            "no tabulated grid and scheme at {v_tab} m/s matches the explicit {}",
            describe(filter)
        ))
    })
}

/// The explicit settings of a filter, as words.
fn describe(f: Filter) -> String {
    let mut v = Vec::new();
    if let Some(n) = f.nx {
        v.push(format!("nx = {n}"));
    }
    if let Some(n) = f.ny {
        v.push(format!("ny = {n}"));
    }
    if let Some(s) = f.scheme {
        v.push(format!("scheme {}", s.name()));
    }
    if v.is_empty() {
        "settings".into()
    } else {
        v.join(", ")
    }
}

/// The scheme of `cfg` that restricts a tolerance's choice to its rows as an explicit one
/// does (the CLI's --tol, the FMU's rel_tol): any scheme but its model's default
/// ([`ModelKind::default_scheme`](crate::ModelKind::default_scheme): `cells-ho` for ECF), `continuous` only for time steps (`steady`
/// false; continuous's steady state is the cells march). The default restricts nothing: a
/// file that names it is not told from one that does not.
pub fn restricting_scheme(cfg: &crate::Config, steady: bool) -> Option<Scheme> {
    Some(cfg.scheme)
        .filter(|s| *s != cfg.model.default_scheme() && !(steady && *s == Scheme::Continuous))
}

/// The tabulated preset that `cfg` is, unchanged (rule 2): its name if the table has rows of
/// it and `cfg` has that preset's model, effects (`transient` may be off), parameters,
/// Coulomb bound and modifiers (grid and geometry may differ); None otherwise (the choice
/// then takes the worst over all presets).
pub fn scope_of(cfg: &crate::Config) -> Option<&'static str> {
    scope_in(&table().ok()?, cfg)
}

/// [`scope_of`] in a given table.
pub fn scope_in(rows: &[Row], cfg: &crate::Config) -> Option<&'static str> {
    use crate::effects::Effect;
    let row = rows.iter().find(|r| r.preset == cfg.preset)?;
    let p = crate::Config::preset(&row.preset).ok()?;
    // `transient` off makes every step the steady state of the same model (quasi-steady),
    // whose error is the settled error the table's responses end with: the same preset
    let mut effects = cfg.effects;
    if p.effects.has(Effect::Transient) {
        effects.insert(Effect::Transient);
    }
    let same = p.model == cfg.model
        && p.effects == effects
        && p.params == cfg.params
        && p.bound == cfg.bound
        && p.modifiers == cfg.modifiers;
    if !same {
        return None;
    }
    // the preset's name as the compiled-in list of presets holds it
    crate::config::PRESETS
        .iter()
        .map(|(name, _)| *name)
        .find(|name| *name == row.preset)
}

/// The tabulated grids and schemes (distinct, sorted by grid size then scheme name).
pub fn tabulated() -> Result<Vec<(usize, usize, Scheme)>> {
    let mut v: Vec<(usize, usize, Scheme)> =
        table()?.iter().map(|r| (r.nx, r.ny, r.scheme)).collect();
    v.sort_by_key(|k| (k.0 * k.1, k.0, k.2.name()));
    v.dedup_by_key(|k| (k.0, k.1, k.2.name()));
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_compiled_in_table_parses_and_covers_three_presets_at_each_speed() {
        let t = table().expect("the table parses");
        let mut speeds: Vec<f64> = t.iter().map(|r| r.v).collect();
        speeds.sort_by(f64::total_cmp);
        speeds.dedup();
        assert!(speeds.len() >= 2, "speeds {speeds:?}");
        for s in speeds {
            for p in ["dry", "table4.1", "wet"] {
                assert!(
                    t.iter().any(|r| r.v == s && r.preset == p),
                    "no {p} rows at {s} m/s"
                );
            }
        }
        assert!(table_notes().iter().any(|n| n.contains("measured on")));
    }

    /// Independent of `choose_in`: every (grid, scheme) at a speed with its worst error and cost.
    fn brute(rows: &[Row], v_tab: f64) -> Vec<(usize, usize, &'static str, f64, f64)> {
        let mut out: Vec<(usize, usize, &'static str, f64, f64)> = Vec::new();
        for r in rows.iter().filter(|r| r.v == v_tab) {
            let k = (r.nx, r.ny, r.scheme.name());
            match out.iter_mut().find(|o| (o.0, o.1, o.2) == k) {
                Some(o) => {
                    o.3 = o.3.max(r.fx_max_pct);
                    o.4 = o.4.max(r.cost);
                }
                None => out.push((k.0, k.1, k.2, r.fx_max_pct, r.cost)),
            }
        }
        out
    }

    #[test]
    fn the_choice_meets_the_tolerance_and_no_cheaper_row_does() {
        let t = table().expect("table");
        let mut speeds: Vec<f64> = t.iter().map(|r| r.v).collect();
        speeds.sort_by(f64::total_cmp);
        speeds.dedup();
        let mut met_some = 0;
        for &s in &speeds {
            let all = brute(&t, s);
            // tolerances around every tabulated error at this speed, and a loose one
            let mut tols: Vec<f64> = all.iter().map(|o| o.3 / 100.0).collect();
            tols.extend(all.iter().map(|o| o.3 / 100.0 * 1.001));
            tols.push(0.5);
            for tol in tols {
                // a speed just below the tabulated one uses it
                let c = choose(tol, s - 0.5, None, Filter::default()).expect("choice");
                assert_eq!(c.v_tab, s);
                let mine = all
                    .iter()
                    .find(|o| (o.0, o.1, o.2) == (c.nx, c.ny, c.scheme.name()))
                    .expect("the choice is a tabulated row");
                assert_eq!(c.fx_err_pct, mine.3, "error of the chosen row");
                if c.met {
                    met_some += 1;
                    assert!(mine.3 <= 100.0 * tol, "{c:?} does not meet {tol}");
                    for o in &all {
                        assert!(
                            !(o.3 <= 100.0 * tol && o.4 < mine.4),
                            "{o:?} meets {tol} and is cheaper than the choice {c:?}"
                        );
                    }
                } else {
                    assert!(all.iter().all(|o| o.3 > 100.0 * tol), "{tol}: {c:?}");
                }
            }
        }
        assert!(met_some > 0);
    }

    #[test]
    fn a_too_tight_tolerance_gives_the_cheapest_row_that_cannot_be_ranked_below_the_best() {
        let t = table().expect("table");
        let fastest = t.iter().map(|r| r.v).fold(0.0, f64::max);
        let mut speeds: Vec<f64> = t.iter().map(|r| r.v).collect();
        speeds.sort_by(f64::total_cmp);
        speeds.dedup();
        let mut cheaper_than_best = 0;
        for s in speeds {
            // above the fastest tabulated speed: the fastest one
            let v = if s == fastest { s + 100.0 } else { s };
            let c = choose(1e-6, v, None, Filter::default()).expect("choice");
            assert_eq!(c.v_tab, s);
            assert!(!c.met);
            let all = brute(&t, s);
            let best = all.iter().map(|o| o.3).fold(f64::INFINITY, f64::min);
            let unc = t
                .iter()
                .filter(|r| r.v == s)
                .map(|r| r.limit_unc_pct)
                .fold(0.0, f64::max);
            assert_eq!(c.best_err_pct, best);
            assert!(c.fx_err_pct <= best + unc, "{c:?}");
            for o in &all {
                assert!(
                    !(o.3 <= best + unc && o.4 < c.cost),
                    "{o:?} is within {unc} % of the best {best} % and cheaper than {c:?}"
                );
            }
            let m = c.message();
            assert!(
                m.contains("NOT met") && m.contains(&format!("{:.2} %", c.fx_err_pct)),
                "{m}"
            );
            if c.fx_err_pct > best {
                cheaper_than_best += 1;
                assert!(m.contains("cannot be ranked"), "{m}");
            } else {
                assert!(m.contains("the most accurate one is used"), "{m}");
            }
        }
        // the table has a speed where the limit's uncertainty exceeds the gap between the
        // most accurate rows, so that rule 5 is exercised
        assert!(cheaper_than_best > 0);
    }

    #[test]
    fn a_tabulated_preset_unchanged_is_judged_on_its_own_rows_and_anything_else_on_all() {
        use crate::Config;
        let t = table().expect("table");
        for p in ["dry", "table4.1", "wet"] {
            let cfg = Config::preset(p).expect("preset");
            assert_eq!(scope_of(&cfg), Some(p));
            // grid and geometry do not change the scope
            let mut g = cfg.clone();
            g.grid = crate::config::Grid { nx: 17, ny: 3 };
            assert_eq!(scope_of(&g), Some(p));
            // nor does the quasi-steady switch; another effect does
            g.effects.remove(crate::effects::Effect::Transient);
            assert_eq!(scope_of(&g), Some(p));
            g.effects.insert(crate::effects::Effect::ElasticUnloading);
            assert_eq!(scope_of(&g), None);
            // a changed parameter does
            let mut q = cfg.clone();
            let tc2 = q.params.get(crate::params::P::Tc20);
            q.params
                .set(crate::params::P::Tc20, 1.01 * tc2)
                .expect("set");
            assert_eq!(scope_of(&q), None, "{p} with tau_c2 changed");
            let own: Vec<Row> = t.iter().filter(|r| r.preset == p).cloned().collect();
            for tol in [0.005, 0.01, 0.02, 0.05] {
                for v in [5.0, 20.0, 30.0] {
                    let f = Filter {
                        preset: Some(p),
                        ..Filter::default()
                    };
                    let c = choose(tol, v, None, f).expect("choice");
                    let on_own = choose_in(&own, tol, v, None, Filter::default())
                        .expect("choice on the preset's rows");
                    assert_eq!(on_own.scope, p);
                    assert_eq!(c, on_own, "{p} {tol} {v}");
                }
            }
        }
        assert_eq!(scope_of(&Config::preset("fastsim").expect("preset")), None);
        assert_eq!(
            scope_of(&Config::preset("wet_sanded").expect("preset")),
            None
        );
        let all = choose(0.01, 20.0, None, Filter::default()).expect("choice");
        assert_eq!(all.scope, "dry, table4.1, wet");
    }

    #[test]
    fn the_speed_is_the_nearest_tabulated_one_not_below_v_in_either_direction() {
        let t = table().expect("table");
        let mut speeds: Vec<f64> = t.iter().map(|r| r.v).collect();
        speeds.sort_by(f64::total_cmp);
        speeds.dedup();
        for w in speeds.windows(2) {
            let mid = 0.5 * (w[0] + w[1]);
            assert_eq!(
                choose(0.01, mid, None, Filter::default()).unwrap().v_tab,
                w[1]
            );
            assert_eq!(
                choose(0.01, -mid, None, Filter::default()).unwrap().v_tab,
                w[1]
            );
            assert_eq!(
                choose(0.01, w[0], None, Filter::default()).unwrap().v_tab,
                w[0]
            );
        }
    }

    #[test]
    fn a_filter_restricts_the_candidates() {
        let c = choose(
            0.01,
            20.0,
            Some(1e-4),
            Filter {
                scheme: Some(Scheme::Continuous),
                ..Filter::default()
            },
        )
        .expect("choice");
        assert_eq!(c.scheme, Scheme::Continuous);
        let c = choose(
            1e-6,
            20.0,
            None,
            Filter {
                nx: Some(20),
                ny: Some(5),
                ..Filter::default()
            },
        )
        .expect("choice");
        assert_eq!((c.nx, c.ny), (20, 5));
        let e = choose(
            0.01,
            20.0,
            None,
            Filter {
                nx: Some(33),
                ..Filter::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("nx = 33"), "{e}");
    }

    #[test]
    fn bad_tolerances_and_speeds_are_refused_with_a_message() {
        for tol in [0.0, -0.01, f64::NAN, f64::INFINITY] {
            let e = choose(tol, 20.0, None, Filter::default())
                .unwrap_err()
                .to_string();
            assert!(e.contains("relative tolerance > 0"), "{tol}: {e}");
        }
        assert!(choose(0.01, f64::NAN, None, Filter::default()).is_err());
        assert!(choose(0.01, 20.0, Some(0.0), Filter::default()).is_err());
    }

    #[test]
    fn a_malformed_table_is_an_error_naming_the_line() {
        let good = "# c\npreset,kind,v_m_s,dt_ms,nx,ny,scheme,fx_max_pct,trise_max_pct,pfric_max_pct,wall_per_sim,fx_limit_unc_pct\ndry,step,5,1,20,5,cells,1,1,1,0.2,0.1\n";
        assert_eq!(parse(good, "t").expect("parses").len(), 1);
        let bad = good.replace("0.2,0.1", "x,0.1");
        let e = parse(&bad, "t").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("wall_per_sim"), "{e}");
        let bad = good.replace(",cells,", ",fast,");
        assert!(parse(&bad, "t").is_err());
    }
}
