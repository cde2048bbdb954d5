//! Compiles the plain C FASTSIM reference (c/fastsim.c) with gcc -O2.
fn main() {
    println!("cargo:rerun-if-changed=c/fastsim.c");
    cc::Build::new()
        .file("c/fastsim.c")
        .opt_level(2)
        .compile("fastsim_ref");
}
