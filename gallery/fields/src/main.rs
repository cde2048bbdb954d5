//! `ecf-gallery-fields`: bristle fields along y = 0 at chosen instants of a creepage step
//! (seed Fig. 4.13, 4.15, 4.17, 4.19), through creep-core's public API only
//! (`Model::steady`, `Model::step`, `Model::field_y0`). The `ecf` CLI prints fields at steady
//! state only; this helper of the validation gallery prints them during the transient.
//!
//! Usage:
//!   ecf-gallery-fields --config FILE.json --v-mps 5 --fn-kN 110 --cx-from 0.001 --cx-to 0.01
//!                      --dt-ms 0.01 --at-ms 0,0.1,0.8,3.1
//! The model starts from the steady state of `cx-from` (t <= 0), then steps with `cx-to`
//! held constant (Eq. 4.36). Output: CSV on stdout with the header
//!   t_ms,f,x_mm,x_rail_mm,tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime
//! where x is the contact-frame position (leading edge at +a) and x_rail = x + v t the
//! position in a frame fixed on the rail that coincides with the contact frame at t = 0.
#![forbid(unsafe_code)]

use creep_core::{Config, Inputs, Model};
use std::process::ExitCode;

struct Args {
    config: String,
    v: f64,
    fn_kn: f64,
    cx_from: f64,
    cx_to: f64,
    dt_ms: f64,
    at_ms: Vec<f64>,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        config: String::new(),
        v: 5.0,
        fn_kn: 110.0,
        cx_from: f64::NAN,
        cx_to: f64::NAN,
        dt_ms: 0.01,
        at_ms: vec![],
    };
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let mut i = 0;
    while i < argv.len() {
        let key = argv[i].as_str();
        let val = argv
            .get(i + 1)
            .ok_or_else(|| format!("{key}: missing value"))?;
        let num = |s: &str| -> Result<f64, String> {
            s.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{key}: '{s}' is not a finite number"))
        };
        match key {
            "--config" => a.config = val.clone(),
            "--v-mps" => a.v = num(val)?,
            "--fn-kN" => a.fn_kn = num(val)?,
            "--cx-from" => a.cx_from = num(val)?,
            "--cx-to" => a.cx_to = num(val)?,
            "--dt-ms" => a.dt_ms = num(val)?,
            "--at-ms" => {
                a.at_ms = val
                    .split(',')
                    .map(|s| num(s.trim()))
                    .collect::<Result<Vec<_>, _>>()?
            }
            _ => return Err(format!("unknown option {key}")),
        }
        i += 2;
    }
    if a.config.is_empty() {
        return Err("--config: required".into());
    }
    if !(a.cx_from.is_finite() && a.cx_to.is_finite()) {
        return Err("--cx-from and --cx-to: required".into());
    }
    if a.dt_ms.is_nan() || a.dt_ms <= 0.0 {
        return Err("--dt-ms: must be > 0".into());
    }
    if a.at_ms.is_empty() || a.at_ms.iter().any(|&t| t < 0.0) {
        return Err("--at-ms: give one or more instants >= 0 ms".into());
    }
    Ok(a)
}

fn run(a: &Args) -> Result<String, String> {
    let cfg = Config::from_file(std::path::Path::new(&a.config)).map_err(|e| e.to_string())?;
    let mut model = Model::new(&cfg).map_err(|e| e.to_string())?;
    let inp = |cx: f64| Inputs {
        cx,
        v: a.v,
        fn_n: a.fn_kn * 1e3,
        ..Inputs::default()
    };
    let mut out =
        String::from("t_ms,f,x_mm,x_rail_mm,tau_Pa,tau_x_Pa,tau_c1_Pa,tau_c2_Pa,p_Pa,T_C,regime\n");
    let mut o = model.steady(&inp(a.cx_from)).map_err(|e| e.to_string())?;
    let dt = a.dt_ms * 1e-3;
    let mut want: Vec<(usize, f64)> = a
        .at_ms
        .iter()
        .map(|&t| ((t / a.dt_ms).round() as usize, t))
        .collect();
    want.sort_by_key(|p| p.0);
    let last = want.last().map(|w| w.0).unwrap_or(0);
    let mut k = 0usize;
    loop {
        for &(_, t_req) in want.iter().filter(|w| w.0 == k) {
            let t = k as f64 * dt;
            let field = model
                .field_y0()
                .ok_or("fields exist for the bristle models (ecf, fastsim), not for polach")?;
            for p in field {
                let c1 = if p.tau_c1.is_finite() { p.tau_c1 } else { -1.0 };
                let c2 = if p.tau_c2.is_finite() { p.tau_c2 } else { -1.0 };
                out.push_str(&format!(
                    "{},{:.8},{:.5},{:.5},{:.1},{:.1},{:.1},{:.1},{:.1},{:.3},{}\n",
                    t_req,
                    o.f,
                    p.x * 1e3,
                    (p.x + a.v * t) * 1e3,
                    p.tau,
                    p.tau_x,
                    c1,
                    c2,
                    p.p,
                    p.t,
                    p.regime
                ));
            }
        }
        if k >= last {
            break;
        }
        o = model.step(dt, &inp(a.cx_to)).map_err(|e| e.to_string())?;
        k += 1;
    }
    Ok(out)
}

fn main() -> ExitCode {
    match parse().and_then(|a| run(&a)) {
        Ok(s) => {
            print!("{s}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
