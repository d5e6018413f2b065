//! Writes a torus of about `TRIANGLES` triangles as an OFF model, for measuring the simulator
//! and the converter at scale without committing large files:
//!
//! ```text
//! cargo run --release -p zrow-sim --example torus -- 200000 torus-200k.off
//! ```
//!
//! `nu × nv` vertices on a ring of radius 1 and tube radius 0.35, `2·nu·nv` triangles facing
//! outwards, with `nv = ⌈√(TRIANGLES / 2)⌉` and `nu = ⌈TRIANGLES / (2·nv)⌉`.

use std::io::Write;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(triangles), Some(out)) = (
        args.first().and_then(|t| t.parse::<u64>().ok()),
        args.get(1),
    ) else {
        eprintln!("usage: torus TRIANGLES OUT.off");
        return ExitCode::from(2);
    };
    let triangles = triangles.clamp(8, 100_000_000);
    let nv = ((triangles as f64 / 2.0).sqrt().ceil() as u64).max(2);
    let nu = triangles.div_ceil(2 * nv).max(2);
    let write = || -> std::io::Result<()> {
        let mut f = std::io::BufWriter::new(std::fs::File::create(out)?);
        writeln!(f, "OFF\n{} {} 0", nu * nv, 2 * nu * nv)?;
        for i in 0..nu {
            let a = std::f64::consts::TAU * i as f64 / nu as f64;
            for j in 0..nv {
                let b = std::f64::consts::TAU * j as f64 / nv as f64;
                let r = 1.0 + 0.35 * b.cos();
                writeln!(
                    f,
                    "{:.6} {:.6} {:.6}",
                    r * a.cos(),
                    0.35 * b.sin(),
                    r * a.sin()
                )?;
            }
        }
        for i in 0..nu {
            for j in 0..nv {
                let (i1, j1) = ((i + 1) % nu, (j + 1) % nv);
                let (p, q, p1, q1) = (i * nv + j, i1 * nv + j, i * nv + j1, i1 * nv + j1);
                writeln!(f, "3 {p} {p1} {q}\n3 {q} {p1} {q1}")?;
            }
        }
        f.flush()
    };
    match write() {
        Ok(()) => {
            println!("{out}: {} vertices, {} triangles", nu * nv, 2 * nu * nv);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {out}: cannot write: {e}");
            ExitCode::FAILURE
        }
    }
}
