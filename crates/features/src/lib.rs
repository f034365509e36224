//! No code: the crate's manifest turns on one set of features of shared third-party
//! crates, so that every build containing pliant-core resolves them alike (see its
//! Cargo.toml).
