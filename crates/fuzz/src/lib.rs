//! Fuzz targets for everything Pliant reads from outside:
//! scene files in TOML and JSON, the OBJ, STL and glTF mesh readers, the
//! WebSocket protocol's message parser, session logs, calibration specs and curves and
//! KBL harness files ([`readers`]), and study files ([`study`], read by the Python
//! package in a worker process). Inputs are seeds (the example scenes, small meshes, protocol
//! messages) changed by a few [`mutate::Op`]s — byte flips, inserted tokens ("1e300",
//! "nan", "[[", …), deleted ranges, repeated lines, numbers swapped for extreme ones,
//! splices from other seeds — so most inputs get past the parsers into validation.
//!
//! Each target returns `Err` when a property breaks (a loaded scene with a non-finite
//! node, a mesh with an index out of range, a message that does not survive a
//! round trip); a panic is a find too. The tests run a bounded number of inputs per
//! target (proptest, deterministic); `pliant-fuzz --inputs N` runs the long job.

pub mod mutate;
pub mod readers;
pub mod seeds;
pub mod study;
pub mod targets;
