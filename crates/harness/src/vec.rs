//! VEC (VDA 4968, "Vehicle Electric Container") files: recognised, not yet imported.
//!
//! Most published VEC samples describe topology only (no 3-D placement of the
//! harness); those are refused saying so. A VEC file with 3-D geometry is refused too,
//! for now, with a message saying that only KBL is read.

use crate::error::HarnessError;

/// Whether the text (or file name) looks like VEC: a `.vec` extension or a `VecContent`
/// root element.
pub fn looks_like_vec(file: &str, text: &str) -> bool {
    let head: String = text.chars().take(4096).collect();
    file.to_ascii_lowercase().ends_with(".vec") || head.contains("VecContent")
}

/// The refusal for a VEC file: says whether it carries 3-D geometry.
pub fn refuse_vec(file: &str, text: &str) -> HarnessError {
    // VEC 3-D geometry lives in GeometryNode3D / GeometrySegment3D / CartesianPoint3D
    // (VEC 1.2+ placement specifications).
    let has_3d = [
        "GeometryNode3D",
        "GeometrySegment3D",
        "CartesianPoint3D",
        "Geometry3D",
    ]
    .iter()
    .any(|t| text.contains(t));
    let reason = if has_3d {
        "VEC file (VDA 4968) with 3-D geometry: reading VEC geometry is not implemented yet; export the harness as KBL 2.3–2.5 (VDA 4964) instead".to_string()
    } else {
        "VEC file (VDA 4968) without 3-D geometry (no GeometryNode3D/GeometrySegment3D/CartesianPoint3D): it describes topology only, so there is no centre line to simulate; export the harness with its 3-D geometry, e.g. as KBL 2.3–2.5".to_string()
    };
    HarnessError::Unsupported {
        file: file.to_string(),
        reason,
    }
}
