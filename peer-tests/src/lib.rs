//! Differential tests against peer interval libraries live in `tests/`.
