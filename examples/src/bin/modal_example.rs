//! Placeholder until the modal module lands.
fn main() {}
