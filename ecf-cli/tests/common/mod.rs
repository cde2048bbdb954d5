//! What the `ecf` binary's integration tests share: running it and capturing its output.
use std::process::Command;

/// Runs `ecf` with `args`: (exit code, -1 if killed by a signal; stdout; stderr).
pub fn ecf(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_ecf"))
        .args(args)
        .output()
        .expect("run ecf");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}
