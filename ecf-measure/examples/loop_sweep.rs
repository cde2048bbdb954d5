//! The search of formula forms on files it was never tuned on: every hidden-effect case and files with nothing missing over noise seeds, with the held-out error against the true noise, the variable named, and the time.
//!
//! `cargo run --release -p ecf-measure --example loop_sweep -- [--seeds N] [--nulls N] [--only NAME] [--threads N] [--layout standard|other|sparse|precise|one-load] [--presets dry,table4.1,wet] [--write DIR]`
//! (`--write`: each case's file and truth, and each file with nothing missing, into DIR; `--layout other`: the files of another
//! rig, 4 speeds x 2 loads x 16 creepages with another noise; `--layout sparse`: 3 speeds x
//! 3 loads x 7 creepages of 0.5-15 %, noise 3 % of |f|; `--layout precise`: 4 speeds x 3
//! loads x 12 creepages of 0.2-20 %, noise 0.4 % of |f| + 0.001; `--layout one-load`: 7
//! speeds x 12 creepages at 110 kN; `--presets`: the presets of the files
//! with nothing missing)
//! (`LOOP_SWEEP_VERBOSE=1`: each file's verdict and the search's best forms on stderr)
//! (`bash scripts/loop-sweep.sh` runs it with the defaults: 2 seeds per case, 20 seeds of
//! files with nothing missing per preset). The files come from `tests/measurement/hidden.rs`:
//! seeds and truths the search never reads.

#[path = "../tests/measurement/hidden.rs"]
mod hidden;

use ecf_measure::diagnose::{diagnose_opts, Options};

/// What one file's diagnosis gave.
struct Outcome {
    proposed: Option<String>,
    variable: Option<String>,
    heldout: f64,
    true_noise: f64,
    est_noise: f64,
    /// The search's first finalist: (its gain over the configuration's held-out error in
    /// noise levels, its per-row evidence in standard errors); `None` without a search.
    margin: Option<(f64, f64)>,
    seconds: f64,
    /// CPU seconds over the threads: the wall time alone on an idle machine, about.
    cpu_per_thread: f64,
}

/// CPU seconds of this process so far (user + system, from /proc/self/stat; NaN elsewhere):
/// on a machine shared with other jobs, CPU time over the threads bounds the wall time the
/// diagnosis would take alone.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            let rest = s.rsplit_once(')')?.1;
            let f: Vec<&str> = rest.split_whitespace().collect();
            let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
            Some(ticks / 100.0)
        })
        .unwrap_or(f64::NAN)
}

/// [`hidden::file_in`], also written as `name` into `write` when given (the file made once).
#[allow(clippy::too_many_arguments)]
fn file(
    layout: &hidden::Layout,
    truth: &creep_core::Config,
    column: Option<(&str, f64, f64)>,
    distractor: bool,
    seed: u64,
    write: &Option<String>,
    name: &str,
) -> (ecf_measure::measure::Dataset, Vec<f64>) {
    let (csv, clean) = hidden::csv_text_in(layout, truth, column, distractor, seed);
    if let Some(dir) = write {
        std::fs::write(std::path::Path::new(dir).join(name), &csv).expect("write");
    }
    (hidden::dataset(&csv), clean)
}

fn run(
    cfg: &creep_core::Config,
    data: &ecf_measure::measure::Dataset,
    clean: &[f64],
    threads: usize,
) -> Outcome {
    let (t, c0) = (std::time::Instant::now(), cpu_seconds());
    let d = diagnose_opts(cfg, data, &Options::new(threads), &|_| {}).expect("diagnose");
    let seconds = t.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - c0;
    if std::env::var_os("LOOP_SWEEP_VERBOSE").is_some() {
        // the verdict and the search's best forms, for a file that misses
        eprintln!("folds by {} ({} folds): {}", d.folds_by, d.folds, d.verdict);
        if let Some(s) = &d.search {
            let c = &s.cost;
            eprintln!(
                "  search {:.1} s; evaluations: fold fits {}, needed factors {}, shortlist {}, finalists {}",
                s.seconds,
                c.fold_fit_evaluations,
                c.inverse_evaluations,
                c.shortlist_evaluations,
                c.final_evaluations
            );
        }
        for f in d.search.iter().flat_map(|s| s.forms.iter().take(8)) {
            eprintln!(
                "  {} x {} in {}: screened {:.2} %, shortlist {:.2} %, held-out {:.2} %, z {:.1}",
                f.target,
                f.shape,
                f.variable,
                f.screen_cv_rmse_pct,
                f.shortlist_cv_rmse_pct,
                f.heldout_cv_rmse_pct,
                f.evidence_z
            );
        }
    }
    let p = d.search.as_ref().and_then(|s| s.proposed.clone());
    let est_noise = d.noise.as_ref().map(|n| n.cv_rmse_pct).unwrap_or(f64::NAN);
    let margin = d.search.as_ref().and_then(|s| s.forms.first()).map(|f| {
        (
            (d.baseline_heldout_cv_rmse_pct - f.heldout_cv_rmse_pct) / est_noise,
            f.evidence_z,
        )
    });
    Outcome {
        proposed: p
            .as_ref()
            .map(|f| format!("{} x {} in {}", f.target, f.shape, f.variable)),
        variable: p.as_ref().map(|f| f.variable.clone()),
        heldout: p
            .as_ref()
            .map(|f| f.heldout_cv_rmse_pct)
            .unwrap_or(d.best_heldout_cv_rmse_pct),
        true_noise: hidden::true_noise_cv(data, clean),
        est_noise,
        margin,
        seconds,
        cpu_per_thread: cpu / threads as f64,
    }
}

fn arg(args: &[String], name: &str) -> Option<String> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1).cloned())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = arg(&args, "--seeds")
        .and_then(|s| s.parse().ok())
        .unwrap_or(2);
    let nulls: u64 = arg(&args, "--nulls")
        .and_then(|s| s.parse().ok())
        .unwrap_or(20);
    let only = arg(&args, "--only");
    let write = arg(&args, "--write");
    let layout_name = arg(&args, "--layout").unwrap_or_else(|| "standard".into());
    let Some(layout) = hidden::Layout::by_name(&layout_name) else {
        eprintln!("--layout: standard, other, sparse, precise or one-load, not '{layout_name}'");
        std::process::exit(2);
    };
    let threads: usize = arg(&args, "--threads")
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1)
        });
    println!("| case | seed | proposed | held-out % | true noise % | x true noise | estimated noise % | variable right | gain / noise | evidence | wall s | CPU s / thread |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let (mut hits, mut runs, mut worst_time, mut worst_cpu) = (0, 0, 0.0f64, 0.0f64);
    for c in hidden::cases() {
        if only.as_deref().is_some_and(|o| o != c.name) {
            continue;
        }
        for seed in 1..=seeds {
            let truth = hidden::truth(c.preset, c.target, Some(c.factor));
            let name = format!("{}-{seed}.csv", c.name);
            let (data, clean) = file(
                &layout,
                &truth,
                c.column,
                c.distractor,
                1000 + seed,
                &write,
                &name,
            );
            if let Some(dir) = &write {
                let path = std::path::Path::new(dir).join(&name);
                std::fs::write(
                    path.with_extension("truth.json"),
                    truth.to_json().to_string(),
                )
                .expect("write");
            }
            let cfg = creep_core::Config::preset(c.preset).expect("preset");
            let o = run(&cfg, &data, &clean, threads);
            let right = o
                .variable
                .as_deref()
                .is_some_and(|v| c.variables.contains(&v));
            let ratio = o.heldout / o.true_noise;
            // a factor of the load on a file of one load (or of the speed at one speed) is a
            // constant the fitted parameters take up: nothing to find, and nothing to propose
            let constant = (c.variables.contains(&"fn_kN") && layout.loads.len() < 2)
                || (c.variables.contains(&"v_mps") && layout.speeds.len() < 2);
            let ok = if constant {
                o.proposed.is_none()
            } else {
                right && ratio <= 1.3
            };
            hits += ok as usize;
            runs += 1;
            worst_time = worst_time.max(o.seconds);
            worst_cpu = worst_cpu.max(o.cpu_per_thread);
            let (gain, z) = o.margin.unwrap_or((f64::NAN, f64::NAN));
            println!(
                "| {} | {seed} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {gain:.2} | {z:.1} | {:.0} | {:.0} |",
                c.name,
                o.proposed.as_deref().unwrap_or("none"),
                o.heldout,
                o.true_noise,
                ratio,
                o.est_noise,
                match (constant, right) {
                    (true, _) => "constant here",
                    (false, true) => "yes",
                    (false, false) => "no",
                },
                o.seconds,
                o.cpu_per_thread
            );
        }
    }
    println!("\nhidden effects: {hits} of {runs} files proposed the true variable within 1.3 times the true noise (or, where the effect's variable is constant, nothing); longest diagnosis {worst_time:.0} s wall, {worst_cpu:.0} CPU s per thread");
    if only.is_some() {
        return;
    }
    println!("\n| preset | seeds | searched | proposals | largest gain / noise | largest evidence | longest wall s | longest CPU s / thread |");
    println!("|---|---|---|---|---|---|---|---|");
    let presets = arg(&args, "--presets").unwrap_or_else(|| "dry,table4.1,wet".into());
    for preset in presets.split(',') {
        let (mut proposals, mut longest, mut searched, mut cpu) = (0, 0.0f64, 0, 0.0f64);
        let (mut gain, mut z) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for seed in 1..=nulls {
            let truth = hidden::truth(preset, "tau_c1", None);
            let column = (seed % 2 == 0).then_some(("humidity", 20.0, 80.0));
            let name = format!("null-{preset}-{seed}.csv");
            let (data, clean) = file(
                &layout,
                &truth,
                column,
                seed % 3 == 0,
                2000 + seed,
                &write,
                &name,
            );
            let cfg = creep_core::Config::preset(preset).expect("preset");
            let o = run(&cfg, &data, &clean, threads);
            if let Some(p) = &o.proposed {
                eprintln!("false proposal: {preset} seed {seed}: {p}");
                proposals += 1;
            }
            longest = longest.max(o.seconds);
            cpu = cpu.max(o.cpu_per_thread);
            if let Some((g, e)) = o.margin {
                searched += 1;
                gain = gain.max(g);
                z = z.max(e);
                eprintln!(
                    "{preset} seed {seed}: gain {g:.3} noise, evidence {e:.2}, {:.0} s wall, {:.0} CPU s per thread",
                    o.seconds, o.cpu_per_thread
                );
            }
        }
        let (gain, z) = if searched > 0 {
            (format!("{gain:.3}"), format!("{z:.1}"))
        } else {
            ("-".into(), "-".into())
        };
        println!("| {preset} | {nulls} | {searched} | {proposals} | {gain} | {z} | {longest:.0} | {cpu:.0} |");
    }
}
