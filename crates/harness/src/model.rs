//! The plain harness model the KBL reader fills: SI units (metres, m², kg/m), indices into
//! the model's own lists, and every KBL `id` kept for tracing back.

use glam::DVec3;
use serde::Serialize;

/// A wire harness: topology (nodes, segments), geometry (centre curves), wires and their
/// routing, fixings, protections and connectors.
#[derive(Debug, Clone, Serialize)]
pub struct Harness {
    /// The file it was read from (file name only).
    pub source: String,
    /// The KBL version as written in `version_id` (e.g. "2.4 SR-1").
    pub kbl_version: String,
    pub nodes: Vec<Node>,
    pub segments: Vec<Segment>,
    pub wire_parts: Vec<WirePart>,
    pub wires: Vec<Wire>,
    pub fixings: Vec<Fixing>,
    pub protections: Vec<Protection>,
    pub connectors: Vec<Connector>,
    /// Items not imported, with the reason: `(kbl_id, reason)`.
    pub skipped: Vec<(String, String)>,
    /// Things imported with an assumption worth knowing.
    pub warnings: Vec<String>,
}

/// A KBL `Node`: a point where segments end (branch point, connector, end).
impl Harness {
    /// A harness with nothing in it yet, read from `source` (format version `version`).
    pub fn empty(source: &str, version: String) -> Self {
        Harness {
            source: source.to_string(),
            kbl_version: version,
            nodes: Vec::new(),
            segments: Vec::new(),
            wire_parts: Vec::new(),
            wires: Vec::new(),
            fixings: Vec::new(),
            protections: Vec::new(),
            connectors: Vec::new(),
            skipped: Vec::new(),
            warnings: Vec::new(),
        }
    }

    /// The source format and version for people: "KBL 2.4", "VEC 2.0.2".
    pub fn format_version(&self) -> String {
        format_version(&self.kbl_version)
    }
}

/// "KBL 2.4" for a KBL `version_id`; a VEC reader's "VEC 2.0.2" as it is.
pub fn format_version(version: &str) -> String {
    if version.starts_with("VEC") {
        version.to_string()
    } else {
        format!("KBL {version}")
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct Node {
    pub kbl_id: String,
    /// The node's `<Id>` text, if any.
    pub name: Option<String>,
    /// Position \[m\] in the vehicle frame.
    pub position: DVec3,
}

/// One B-spline of a segment's centre curve, as written in KBL: a degree and control
/// points \[m\]; no knot vector (see `bspline.rs`).
#[derive(Debug, Clone, Serialize)]
pub struct CurveData {
    pub kbl_id: String,
    pub degree: usize,
    pub control_points: Vec<DVec3>,
}

/// A KBL `Segment`: a stretch of the bundle between two nodes.
#[derive(Debug, Clone, Serialize)]
pub struct Segment {
    pub kbl_id: String,
    /// The segment's `<Id>` text, if any.
    pub name: Option<String>,
    /// Index into `Harness::nodes`.
    pub start_node: usize,
    /// Index into `Harness::nodes`.
    pub end_node: usize,
    /// `Virtual_length` \[m\].
    pub virtual_length: Option<f64>,
    /// The centre curve: one or more B-splines, in order.
    pub curves: Vec<CurveData>,
    /// `Cross_section_area_information/Area` \[m²\].
    pub cross_section_area: Option<f64>,
    /// Indices into `Harness::wires` routed through this segment.
    pub wires: Vec<usize>,
    /// 1-based line of the element in the file.
    pub line: u32,
}

/// A conductor with its insulation: a single wire, or one core of a multi-core cable.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Conductor {
    /// Outer diameter of the insulation \[m\].
    pub outer_diameter: Option<f64>,
    /// Conductor cross-section \[m²\].
    pub cross_section: Option<f64>,
    /// Minimum bend radius \[m\].
    pub bend_radius: Option<f64>,
}

/// A KBL `General_wire`: a wire (or cable) part.
#[derive(Debug, Clone, Serialize)]
pub struct WirePart {
    pub kbl_id: String,
    pub part_number: Option<String>,
    pub description: Option<String>,
    /// The part's own diameter, cross-section and bend radius (a cable: its sheath).
    pub own: Conductor,
    /// Mass per length \[kg/m\] (`Mass_information` in a mass-per-length unit).
    pub mass_per_length: Option<f64>,
    /// Cores of a multi-core cable (empty for a single wire).
    pub cores: Vec<Conductor>,
}

/// A wire occurrence (`Wire_occurrence` or `Special_wire_occurrence`, i.e. a cable):
/// one physical wire or cable of this harness.
#[derive(Debug, Clone, Serialize)]
pub struct Wire {
    pub kbl_id: String,
    /// `Wire_number` or `Special_wire_id`.
    pub name: Option<String>,
    /// Index into `Harness::wire_parts`.
    pub part: usize,
    /// Indices into `Harness::segments` it runs through (from its `Routing`s).
    pub segments: Vec<usize>,
}

/// A `Fixing_assignment`: a fixing (clip, cable tie, …) on a segment.
#[derive(Debug, Clone, Serialize)]
pub struct Fixing {
    pub kbl_id: String,
    /// The `Fixing_occurrence` id and its `<Id>` text.
    pub occurrence: String,
    pub name: Option<String>,
    pub part_number: Option<String>,
    pub description: Option<String>,
    /// `Fixing_type` of the part (e.g. "SPT", "CABLE_DUCT").
    pub fixing_type: Option<String>,
    /// Index into `Harness::segments`.
    pub segment: usize,
    /// Location along the segment in [0, 1] from its start node.
    pub location: f64,
    /// Orientation vector as given (unit-less), if any.
    pub orientation: Option<DVec3>,
}

/// What a protection is, from its part's `Protection_type` or description.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ProtectionKind {
    /// Adhesive tape of film (PVC, …), wound over the bundle.
    Tape,
    /// Fleece (textile) tape: softer coupling than film tape.
    FleeceTape,
    /// Corrugated tube (German "Wellrohr"/"Wellschlauch").
    CorrugatedTube,
    /// Braided or woven sleeve, or a smooth tube ("Schlauch").
    Sleeve,
    /// Anything else.
    Other,
}

impl ProtectionKind {
    /// Every kind, in the order of the bundle-factor table.
    pub const ALL: [ProtectionKind; 5] = [
        ProtectionKind::Tape,
        ProtectionKind::FleeceTape,
        ProtectionKind::CorrugatedTube,
        ProtectionKind::Sleeve,
        ProtectionKind::Other,
    ];

    /// The kind of a bundle-factor key (`"none"`: unprotected, `Some(None)`); `None` for
    /// an unknown key.
    pub fn from_key(key: &str) -> Option<Option<ProtectionKind>> {
        if key == "none" {
            return Some(None);
        }
        Self::ALL.into_iter().find(|k| k.key() == key).map(Some)
    }

    /// The key of this kind in the bundle-factor table (`data/bundle.toml`).
    pub fn key(self) -> &'static str {
        match self {
            ProtectionKind::Tape => "tape",
            ProtectionKind::FleeceTape => "fleece_tape",
            ProtectionKind::CorrugatedTube => "corrugated_tube",
            ProtectionKind::Sleeve => "sleeve",
            ProtectionKind::Other => "other",
        }
    }
}

/// A `Protection_area`: a protection over part of a segment.
#[derive(Debug, Clone, Serialize)]
pub struct Protection {
    pub kbl_id: String,
    /// The `Wire_protection_occurrence` id.
    pub occurrence: String,
    pub part_number: Option<String>,
    pub description: Option<String>,
    /// `Protection_type` of the part as written.
    pub protection_type: Option<String>,
    pub kind: ProtectionKind,
    /// Index into `Harness::segments`.
    pub segment: usize,
    /// Start and end location along the segment, in [0, 1].
    pub from: f64,
    pub to: f64,
    /// Mass per length of the protection \[kg/m\], if given.
    pub mass_per_length: Option<f64>,
    /// Outer diameter \[m\] when the description states one (`D(a)=13.4`).
    pub outer_diameter: Option<f64>,
}

/// A `Connector_occurrence` and the node it sits on.
#[derive(Debug, Clone, Serialize)]
pub struct Connector {
    pub kbl_id: String,
    pub name: Option<String>,
    pub description: Option<String>,
    /// Index into `Harness::nodes`, if a node refers to it.
    pub node: Option<usize>,
    /// Positions of its housing: the cavities of its `Slots`, else its `Contact_points`
    /// (0 when the file gives neither).
    pub positions: usize,
}

impl Harness {
    /// Segments meeting at each node (indices), in segment order.
    pub fn segments_at_nodes(&self) -> Vec<Vec<usize>> {
        let mut at = vec![Vec::new(); self.nodes.len()];
        for (i, s) in self.segments.iter().enumerate() {
            at[s.start_node].push(i);
            if s.end_node != s.start_node {
                at[s.end_node].push(i);
            }
        }
        at
    }

    /// Sum of the segments' virtual lengths \[m\].
    pub fn total_virtual_length(&self) -> f64 {
        self.segments.iter().filter_map(|s| s.virtual_length).sum()
    }
}
