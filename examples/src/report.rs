//! What every example program does at its end: print a markdown report and save it where
//! asked, and turn its result into an exit status with the error on standard error.

use std::path::Path;
use std::process::ExitCode;

/// Prints `markdown` and, with a `path`, writes it there too.
///
/// # Errors
///
/// The file's name and the I/O error when it cannot be written.
pub fn print_and_save(markdown: &str, path: Option<&Path>) -> Result<(), String> {
    println!("{markdown}");
    if let Some(p) = path {
        std::fs::write(p, markdown).map_err(|e| format!("{}: {e}", p.display()))?;
        eprintln!("wrote {}", p.display());
    }
    Ok(())
}

/// The exit status of a program that returned `result`: failure with `error: …` printed
/// on standard error, or success.
pub fn exit(result: Result<(), String>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
