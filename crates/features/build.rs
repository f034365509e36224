//! No build step: the build-dependencies only fix the host crates' features.
fn main() {}
