//! Modal intervals (filled in below).
