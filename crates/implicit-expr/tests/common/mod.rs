//! What the property-test files share.

use proptest::test_runner::Config;

/// The test configuration: `cases` cases, times `INTERVAL_CORE_TEST_SCALE` (a positive
/// integer; 1 when unset).
pub fn config(cases: u32) -> Config {
    let scale = std::env::var("INTERVAL_CORE_TEST_SCALE")
        .ok()
        .and_then(|v| v.parse::<u32>().ok())
        .filter(|&v| v > 0)
        .unwrap_or(1);
    Config {
        cases: cases.saturating_mul(scale),
        failure_persistence: None,
        ..Config::default()
    }
}
