//! Puts this crate's memory.x (the MPS2 boards' map) where cortex-m-rt's link.x finds it, and
//! tells the bench which target it was built for (printed in its header line).
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap());
    fs::copy("memory.x", out.join("memory.x")).unwrap();
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!(
        "cargo:rustc-env=BENCH_TARGET={}",
        env::var("TARGET").unwrap()
    );
}
