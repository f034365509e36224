//! The `pliant` command's helpers that its tests use: the peak table printed after a
//! run. The output writers themselves are `pliant_assembly::report`, shared with
//! `pliant serve` and the Python API.

pub mod table;
