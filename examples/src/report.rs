//! What every example program does at its end: print a markdown report and save it where
//! asked, and turn its result into an exit status with the error on standard error; and
//! the median its repeated timings report.

use std::cmp::Ordering;
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

/// The median of `values` (the upper one of an even count) in the order `compare`, which
/// sorts them; `None` when there are none.
pub fn median<T: Copy>(values: &mut [T], compare: impl FnMut(&T, &T) -> Ordering) -> Option<T> {
    values.sort_by(compare);
    values.get(values.len() / 2).copied()
}

#[cfg(test)]
mod tests {
    use super::median;

    #[test]
    fn the_median_is_the_middle_value_in_order() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0], f64::total_cmp), Some(2.0));
        assert_eq!(median(&mut [4, 1, 3, 2], Ord::cmp), Some(3));
        assert_eq!(median(&mut [] as &mut [u8], Ord::cmp), None);
    }
}
