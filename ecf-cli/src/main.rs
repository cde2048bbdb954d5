//! The `ecf` binary: [`ecf_cli::main`] (the library holds the command line, so that a build with a user's effect crate can link the same program).

fn main() -> std::process::ExitCode {
    ecf_cli::main()
}
