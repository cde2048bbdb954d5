//! The search of formula forms on files it was never tuned on: every hidden-effect case and files with nothing missing over noise seeds, with the held-out error against the true noise, the variable named, and the time.
//!
//! `cargo run --release -p ecf-measure --example loop_sweep -- [--seeds N] [--nulls N] [--only NAME] [--threads N] [--write DIR]`
//! (`--write`: each case's file and truth into DIR)
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
    seconds: f64,
}

fn run(
    cfg: &creep_core::Config,
    data: &ecf_measure::measure::Dataset,
    clean: &[f64],
    threads: usize,
) -> Outcome {
    let t = std::time::Instant::now();
    let d = diagnose_opts(cfg, data, &Options::new(threads), &|_| {}).expect("diagnose");
    let seconds = t.elapsed().as_secs_f64();
    let p = d.search.as_ref().and_then(|s| s.proposed.clone());
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
        est_noise: d.noise.as_ref().map(|n| n.cv_rmse_pct).unwrap_or(f64::NAN),
        seconds,
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
    let threads: usize = arg(&args, "--threads")
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1)
        });
    println!("| case | seed | proposed | held-out % | true noise % | x true noise | estimated noise % | variable right | s |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let (mut hits, mut runs, mut worst_time) = (0, 0, 0.0f64);
    for c in hidden::cases() {
        if only.as_deref().is_some_and(|o| o != c.name) {
            continue;
        }
        for seed in 1..=seeds {
            let truth = hidden::truth(c.preset, c.target, Some(c.factor));
            let (data, clean) = hidden::file(&truth, c.column, c.distractor, 1000 + seed);
            if let Some(dir) = &write {
                let (csv, _) = hidden::csv_text(&truth, c.column, c.distractor, 1000 + seed);
                let path = std::path::Path::new(dir).join(format!("{}-{seed}.csv", c.name));
                std::fs::write(&path, csv).expect("write");
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
            let ok = right && ratio <= 1.3;
            hits += ok as usize;
            runs += 1;
            worst_time = worst_time.max(o.seconds);
            println!(
                "| {} | {seed} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {:.0} |",
                c.name,
                o.proposed.as_deref().unwrap_or("none"),
                o.heldout,
                o.true_noise,
                ratio,
                o.est_noise,
                if right { "yes" } else { "no" },
                o.seconds
            );
        }
    }
    println!("\nhidden effects: {hits} of {runs} files proposed the true variable within 1.3 times the true noise; longest diagnosis {worst_time:.0} s");
    if only.is_some() {
        return;
    }
    println!("\n| preset | seeds | proposals | longest s |");
    println!("|---|---|---|---|");
    for preset in ["dry", "table4.1", "wet"] {
        let (mut proposals, mut longest) = (0, 0.0f64);
        for seed in 1..=nulls {
            let truth = hidden::truth(preset, "tau_c1", None);
            let column = (seed % 2 == 0).then_some(("humidity", 20.0, 80.0));
            let (data, clean) = hidden::file(&truth, column, seed % 3 == 0, 2000 + seed);
            let cfg = creep_core::Config::preset(preset).expect("preset");
            let o = run(&cfg, &data, &clean, threads);
            if let Some(p) = &o.proposed {
                eprintln!("false proposal: {preset} seed {seed}: {p}");
                proposals += 1;
            }
            longest = longest.max(o.seconds);
        }
        println!("| {preset} | {nulls} | {proposals} | {longest:.0} |");
    }
}
