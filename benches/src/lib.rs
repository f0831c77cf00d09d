//! Support code for the criterion benchmarks (see `benches/`).
