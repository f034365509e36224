//! Errors of the harness import: every one names the file and, where the problem sits in
//! the XML, the KBL element, its `id` and its line and column.

use std::path::PathBuf;

/// What went wrong while importing a harness file or writing the scene.
#[derive(Debug, thiserror::Error)]
pub enum HarnessError {
    /// The input file could not be read.
    #[error("{file}: cannot read: {source}")]
    Read {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// The input is not well-formed XML (e.g. truncated).
    #[error("{file}:{line}:{column}: not well-formed XML: {reason}")]
    Xml {
        file: String,
        line: u32,
        column: u32,
        reason: String,
    },
    /// The file is not a format (or version) this importer reads.
    #[error("{file}: {reason}")]
    Unsupported { file: String, reason: String },
    /// A KBL element is malformed or refers to something missing.
    #[error("{file}:{line}:{column}: {element} id=\"{kbl_id}\": {reason}")]
    Element {
        file: String,
        element: String,
        kbl_id: String,
        line: u32,
        column: u32,
        reason: String,
    },
    /// A settled route handed to an exporter does not fit the harness (unknown segment,
    /// too few points, segment ends that disagree at a node, …).
    #[error("settled route of {kbl_id}: {reason}")]
    Settled { kbl_id: String, reason: String },
    /// A segment named by the user is not in the harness.
    #[error("{file}: no segment \"{id}\" (give a Segment's KBL id, e.g. \"{example}\", or its <Id> text)")]
    UnknownSegment {
        file: String,
        id: String,
        example: String,
    },
    /// `--branch ID` names nothing that can be cut off as a branch.
    #[error("--branch {id}: {reason}")]
    Branch { id: String, reason: String },
    /// An output file could not be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}
