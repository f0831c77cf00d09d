//! The `render2d` example as a user runs it: errors are messages with a nonzero status, the
//! output file is written whole or not at all, and `--check` finds no differing pixel.

use std::path::PathBuf;
use std::process::{Command, Output};

fn render2d(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render2d"))
        .args(args)
        .output()
        .expect("the example runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("render2d-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn bad_formula_is_an_error_with_its_span() {
    let out_path = scratch("bad.png");
    let out = render2d(&[
        "--formula",
        "x^2 + sine(y)",
        "--out",
        out_path.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("unknown function 'sine' at 6..10"), "{err}");
    assert!(err.contains("did you mean 'sin'"), "{err}");
    assert!(err.contains("      ^^^^"), "{err}");
    assert!(!out_path.exists());
}

#[test]
fn bad_vm_file_is_an_error_with_its_line() {
    let vm = scratch("bad.vm");
    std::fs::write(&vm, "_0 var-x\n_1 sqaure _0\n").unwrap();
    let out = render2d(&[
        "--vm",
        vm.to_str().unwrap(),
        "--out",
        scratch("vm.png").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("line 2: unknown op 'sqaure'"), "{err}");
    std::fs::remove_file(&vm).unwrap();
    let missing = render2d(&["--vm", scratch("missing.vm").to_str().unwrap()]);
    assert_eq!(missing.status.code(), Some(1));
}

#[test]
fn unwritable_output_leaves_nothing_behind() {
    let dir = scratch("no-such-dir");
    let out_path = dir.join("x.png");
    let out = render2d(&[
        "--formula",
        "x^2 + y^2 - 0.5",
        "--size",
        "32",
        "--out",
        out_path.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot write"));
    assert!(!dir.exists());
}

#[test]
fn check_finds_no_difference_and_the_png_is_complete() {
    let out_path = scratch("disc.png");
    let out = render2d(&[
        "--formula",
        "min(x^2 + y^2 - 0.5, max(abs(x - 0.5) - 0.2, abs(y) - 0.7))",
        "--size",
        "100",
        "--tiles",
        "32,8,2",
        "--check",
        "--stats",
        "--threads",
        "2",
        "--out",
        out_path.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("0 differing pixels"), "{stdout}");
    let bytes = std::fs::read(&out_path).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    assert!(
        bytes.ends_with(&[0xae, 0x42, 0x60, 0x82]),
        "ends with the IEND chunk"
    );
    let mut tmp = out_path.clone().into_os_string();
    tmp.push(".tmp");
    assert!(!PathBuf::from(tmp).exists());
    std::fs::remove_file(&out_path).unwrap();
}

#[test]
fn bad_options_are_errors() {
    for args in [
        &["--formula", "x", "--region", "1,0,0,1"][..],
        &["--formula", "x", "--tiles", "16,5"],
        &["--formula", "x", "--size", "0"],
        &["--formula", "x", "--size", "100000"],
    ] {
        let out = render2d(args);
        assert!(!out.status.success(), "{args:?}");
        assert!(
            !String::from_utf8_lossy(&out.stderr).contains("panicked"),
            "{args:?}"
        );
    }
}
