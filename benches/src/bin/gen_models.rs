//! Writes the generated benchmark models of `data/models/` (see `benches::models`), or one
//! model of any seed or size elsewhere.
//!
//! ```text
//! cargo run -p benches --bin gen_models                    # rewrite every committed model
//! cargo run -p benches --bin gen_models -- --check         # only check they are up to date
//! cargo run -p benches --bin gen_models -- --list          # the models, seeds and sizes
//! cargo run -p benches --bin gen_models -- csg2d --seed 42 --out other.vm
//! cargo run -p benches --bin gen_models -- city:5000 --seed 7 --out city.vm
//! ```
//!
//! A model is the name of a committed model (`csg2d`, `text2d`, `csg3d-660`, `csg3d-2k`)
//! or `FLAVOUR:OPS`, a 3D CSG model (`city` or `molecule`, see `benches::csg3d`) of about
//! `OPS` operations. Files are written whole or not at all (a temporary file next to each,
//! then a rename).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use benches::csg3d::{self, Flavour};
use benches::models::{self, MODELS};
use benches::vmgen::op_count;

fn main() -> ExitCode {
    benches::exit(run())
}

const USAGE: &str = "usage: gen_models [--check | --list] | gen_models MODEL [--seed S] --out FILE
  MODEL: a committed model (csg2d, text2d, csg3d-660, csg3d-2k) or FLAVOUR:OPS (city or molecule)";

fn run() -> Result<(), String> {
    let mut model = None;
    let mut seed = None;
    let mut out = None;
    let mut check = false;
    let mut list = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value\n{USAGE}"));
        match a.as_str() {
            "--check" => check = true,
            "--list" => list = true,
            "--seed" => seed = Some(parse_seed(&value("--seed")?)?),
            "--out" => out = Some(PathBuf::from(value("--out")?)),
            "-h" | "--help" => {
                println!("{USAGE}");
                return Ok(());
            }
            s if s.starts_with('-') => return Err(format!("unknown option '{s}'\n{USAGE}")),
            s if model.is_none() => model = Some(s.to_string()),
            s => return Err(format!("unexpected argument '{s}'\n{USAGE}")),
        }
    }
    if list {
        for m in &MODELS {
            let text = m.committed();
            println!(
                "{:<10} seed {:#x}, {} operations, {} lines: {}",
                m.name,
                m.seed,
                op_count(text),
                text.lines().count(),
                m.description
            );
        }
        return Ok(());
    }
    match model {
        None => {
            if seed.is_some() || out.is_some() {
                return Err(format!("--seed and --out need a MODEL\n{USAGE}"));
            }
            if check { check_all() } else { write_all() }
        }
        Some(name) => {
            if check {
                return Err(format!("--check takes no MODEL\n{USAGE}"));
            }
            let out = out.ok_or(format!("a MODEL needs --out FILE\n{USAGE}"))?;
            let (text, seed) = one(&name, seed)?;
            write(&out, &text)?;
            println!(
                "wrote {} ({} operations, {} lines, seed {seed:#x})",
                out.display(),
                op_count(&text),
                text.lines().count()
            );
            Ok(())
        }
    }
}

/// The text of the model `name` with `seed` (its own by default), and the seed used.
fn one(name: &str, seed: Option<u64>) -> Result<(String, u64), String> {
    if let Some(m) = models::get(name) {
        let seed = seed.unwrap_or(m.seed);
        return Ok((m.generate(seed), seed));
    }
    let Some((flavour, ops)) = name.split_once(':') else {
        return Err(format!("unknown model '{name}'\n{USAGE}"));
    };
    let flavour: Flavour = flavour.parse()?;
    let ops: usize = ops
        .parse()
        .map_err(|e| format!("bad operation count '{ops}': {e}"))?;
    if !(csg3d::MIN_TARGET..=csg3d::MAX_TARGET).contains(&ops) {
        return Err(format!(
            "the operation count must lie in {}..={}, got {ops}",
            csg3d::MIN_TARGET,
            csg3d::MAX_TARGET
        ));
    }
    let seed = seed.unwrap_or(1);
    Ok((csg3d::generate(flavour, ops, seed), seed))
}

/// Rewrites every committed model.
fn write_all() -> Result<(), String> {
    for m in &MODELS {
        let text = m.generate(m.seed);
        let path = m.path();
        write(&path, &text)?;
        println!(
            "wrote {} ({} operations, {} lines, seed {:#x})",
            path.display(),
            op_count(&text),
            text.lines().count(),
            m.seed
        );
    }
    Ok(())
}

/// Checks that every committed file is what its generator writes.
fn check_all() -> Result<(), String> {
    let mut stale = Vec::new();
    for m in &MODELS {
        let path = m.path();
        let on_disk = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        if on_disk == m.generate(m.seed) {
            println!("{}: up to date", path.display());
        } else {
            stale.push(m.name);
        }
    }
    if stale.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "out of date: {} (rewrite with `cargo run -p benches --bin gen_models`)",
            stale.join(", ")
        ))
    }
}

/// Writes `text` to `path` through a temporary file and a rename.
fn write(path: &Path, text: &str) -> Result<(), String> {
    let tmp = path.with_extension("vm.tmp");
    let written = std::fs::write(&tmp, text).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(format!("cannot write {}: {e}", path.display()));
    }
    Ok(())
}

/// A seed in decimal or `0x` hexadecimal.
fn parse_seed(s: &str) -> Result<u64, String> {
    let parsed = match s.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => s.parse(),
    };
    parsed.map_err(|e| format!("bad seed '{s}': {e}"))
}
