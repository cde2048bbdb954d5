//! Criterion benches: FASTSIM, Polach, steady ECF and one transient ECF step at several grid sizes.
use creep_core::{Config, Grid, Inputs, Model};
use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};

fn cfg(name: &str, nx: usize, ny: usize) -> Config {
    let mut c = Config::preset(name).expect("preset");
    c.grid = Grid { nx, ny };
    c
}

fn inputs(cx: f64) -> Inputs {
    Inputs {
        cx,
        v: 20.0,
        fn_n: 110e3,
        ..Inputs::default()
    }
}

fn steady(c: &mut Criterion) {
    let mut g = c.benchmark_group("steady");
    for (nx, ny) in [(20, 11), (40, 21), (80, 21)] {
        for name in ["fastsim", "table4.1"] {
            let mut m = Model::new(&cfg(name, nx, ny)).expect("model");
            g.bench_with_input(BenchmarkId::new(name, format!("{nx}x{ny}")), &(), |b, _| {
                b.iter(|| m.steady(black_box(&inputs(0.05))).expect("steady"))
            });
        }
    }
    let mut p = Model::new(&Config::preset("polach").expect("preset")).expect("model");
    g.bench_function("polach", |b| {
        b.iter(|| p.steady(black_box(&inputs(0.05))).expect("steady"))
    });
    g.finish();
}

fn transient(c: &mut Criterion) {
    let mut g = c.benchmark_group("transient_step_1ms_v5");
    for (nx, ny) in [(20, 11), (40, 21), (80, 21)] {
        let mut m = Model::new(&cfg("table4.1", nx, ny)).expect("model");
        let i = Inputs {
            cx: 0.15,
            v: 5.0,
            fn_n: 110e3,
            ..Inputs::default()
        };
        m.steady(&i).expect("steady");
        g.bench_with_input(
            BenchmarkId::new("table4.1", format!("{nx}x{ny}")),
            &(),
            |b, _| b.iter(|| m.step(1e-3, black_box(&i)).expect("step")),
        );
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(2));
    targets = steady, transient
}
criterion_main!(benches);
