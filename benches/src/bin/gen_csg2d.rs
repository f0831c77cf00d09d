//! Writes the generated 2D CSG benchmark expression (see `benches::csg2d`) in the `.vm`
//! format.
//!
//! ```text
//! cargo run -p benches --bin gen_csg2d                 # data/models/csg2d.vm, seed csg2d::SEED
//! cargo run -p benches --bin gen_csg2d -- out.vm 42    # another file and seed
//! ```
//!
//! The file is written whole or not at all (a temporary file next to it, then a rename).

use std::path::PathBuf;
use std::process::ExitCode;

use benches::csg2d;
use benches::vmgen::op_count;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let path = args.next().map(PathBuf::from).unwrap_or_else(|| {
        PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../data/models/csg2d.vm"
        ))
    });
    let seed = match args.next().map(|s| parse_seed(&s)) {
        None => csg2d::SEED,
        Some(Ok(s)) => s,
        Some(Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let text = csg2d::generate(seed);
    let tmp = path.with_extension("vm.tmp");
    let written = std::fs::write(&tmp, &text).and_then(|()| std::fs::rename(&tmp, &path));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        eprintln!("error: cannot write {}: {e}", path.display());
        return ExitCode::FAILURE;
    }
    println!(
        "wrote {} ({} operations, {} lines, seed {seed:#x})",
        path.display(),
        op_count(&text),
        text.lines().count()
    );
    ExitCode::SUCCESS
}

/// A seed in decimal or `0x` hexadecimal.
fn parse_seed(s: &str) -> Result<u64, String> {
    let parsed = match s.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => s.parse(),
    };
    parsed.map_err(|e| format!("bad seed '{s}': {e}"))
}
