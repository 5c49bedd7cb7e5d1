//! Placeholder until the stage benchmarks land.
fn main() {}
