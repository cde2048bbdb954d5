# Debian 12 packages of the win64 and darwin64 builds (sourced by scripts/setup.sh and scripts/build-fmu.sh; setup.sh says what each is for).
CROSS_PACKAGES=(rustc-web cargo-web rust-web-src gcc-mingw-w64-x86-64 lld-22 llvm-22)
