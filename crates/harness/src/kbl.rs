//! Reader of KBL 2.3, 2.4 and 2.5 (VDA 4964, "Kabelbaumliste") into [`Harness`].
//!
//! Schema: prostep ivip, `prostep-ivip-e-V/vec`, `wiki/content/specifications/kbl/`.
//! What is read:
//!
//! - `Cartesian_point` (mm) → positions \[m\]; `Node` → its point;
//! - `Segment`: start/end node, `Virtual_length`, `Center_curve`s (degree + control points),
//!   `Cross_section_area_information/Area` (the files write plain millimetres as its unit
//!   although the value is mm²: a length unit there is read as that unit squared, with a
//!   warning), and inside it `Fixing_assignment`s and `Protection_area`s;
//! - `General_wire` (wire and cable parts, with `Core`s), wire occurrences
//!   (`Wire_occurrence`, `Special_wire_occurrence` with `Core_occurrence`s) and `Routing`
//!   (a `Connection`, or a wire directly, and the segments it passes); the cores of a cable
//!   count as the cable;
//! - `Fixing_occurrence` → `Fixing` part, `Wire_protection_occurrence` →
//!   `Wire_protection` part, `Connector_occurrence` and the `Node` that refers to it.
//!
//! Values carry a unit by id (`Unit_component` → `Unit`), converted with `units.rs`.
//! Malformed structure (a segment without a node, a curve without points) is an error
//! naming the element; items that can be left out (a routing of an unknown wire, a fixing
//! whose part is missing) are listed in `Harness::skipped` with the reason.

use std::collections::HashMap;

use glam::DVec3;
use roxmltree::{Document, Node as XNode};

use crate::error::HarnessError;
use crate::model::*;
use crate::units::{self, Dimension, Unit};

/// KBL versions this reader accepts (major.minor of `version_id`).
pub const SUPPORTED_VERSIONS: [&str; 3] = ["2.3", "2.4", "2.5"];

/// Parse KBL text. `file` names the source in errors and in the model.
pub fn parse_kbl(file: &str, text: &str) -> Result<Harness, HarnessError> {
    let doc = parse_xml(file, text)?;
    let root = doc.root_element();
    let version = check_version(file, root)?;
    let mut r = Reader::new(file, &doc);
    r.read_units();
    let mut h = Harness::empty(file, version);
    let node_index = r.read_nodes(&mut h)?;
    r.read_wires(&mut h);
    let segment_index = r.read_segments(&mut h, &node_index)?;
    r.read_routings(&mut h, &segment_index);
    r.read_connectors(&mut h, &node_index);
    h.skipped.append(&mut r.skipped);
    h.warnings.append(&mut r.warnings);
    Ok(h)
}

/// Parse XML text; an error names the file, line and column (a truncated file: where it
/// ends).
pub(crate) fn parse_xml<'i>(file: &str, text: &'i str) -> Result<Document<'i>, HarnessError> {
    Document::parse(text).map_err(|e| {
        let pos = e.pos();
        let (mut line, mut column, mut reason) = (pos.row, pos.col, e.to_string());
        if matches!(
            e,
            roxmltree::Error::UnclosedRootNode | roxmltree::Error::UnexpectedEndOfStream
        ) {
            // The parser reports these at 1:1; the place that matters is where the file ends.
            line = text.lines().count().max(1) as u32;
            column = text
                .lines()
                .last()
                .map_or(1, |l| l.chars().count() as u32 + 1);
            reason = format!("{reason}: the file ends here, inside an element (truncated?)");
        }
        HarnessError::Xml {
            file: file.to_string(),
            line,
            column,
            reason,
        }
    })
}

/// The unit a KBL `<Unit>` element defines.
pub(crate) fn unit_of(n: XNode) -> Result<Unit, String> {
    if let Some(name) = text(n, "Si_unit_name") {
        units::si_unit(name, text(n, "Si_prefix"), text(n, "Si_dimension"))
            .ok_or_else(|| format!("SI unit \"{name}\" with an unknown prefix or dimension"))
    } else if let Some(name) = text(n, "Unit_name") {
        units::named_unit(name).ok_or_else(|| format!("unknown unit name \"{name}\""))
    } else {
        Err("unit without a name".to_string())
    }
}

/// Check the root element and version; return the version text.
pub(crate) fn check_version(file: &str, root: XNode) -> Result<String, HarnessError> {
    let unsupported = |reason: String| HarnessError::Unsupported {
        file: file.to_string(),
        reason,
    };
    if root.tag_name().name() != "KBL_container" {
        return Err(unsupported(format!(
            "not a KBL file: the root element is <{}>, expected <KBL_container>",
            root.tag_name().name()
        )));
    }
    let ns = root.tag_name().namespace().unwrap_or("");
    if !ns.contains("KBL") {
        return Err(unsupported(format!(
            "not a KBL file: namespace \"{ns}\" is not a KBL schema namespace"
        )));
    }
    // The namespace stays ".../KBL2.3/KBLSchema" in 2.4 files; `version_id` tells.
    let version = match root.attribute("version_id") {
        Some(v) => v.trim().to_string(),
        None => ns
            .split('/')
            .find_map(|p| p.strip_prefix("KBL"))
            .filter(|v| !v.is_empty() && v.chars().next().is_some_and(|c| c.is_ascii_digit()))
            .map(str::to_string)
            .ok_or_else(|| {
                unsupported(
                    "KBL file without version_id and without a version in its namespace".into(),
                )
            })?,
    };
    let major_minor: String = version
        .split_whitespace()
        .next()
        .unwrap_or("")
        .chars()
        .take(3)
        .collect();
    if !SUPPORTED_VERSIONS.contains(&major_minor.as_str()) {
        return Err(unsupported(format!(
            "KBL version \"{version}\" is not supported; this importer reads KBL {}",
            SUPPORTED_VERSIONS.join(", ")
        )));
    }
    Ok(version)
}

/// The first element child with this local name.
pub(crate) fn child<'a, 'i>(n: XNode<'a, 'i>, name: &str) -> Option<XNode<'a, 'i>> {
    n.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// All element children with this local name.
pub(crate) fn children<'a, 'i: 'a>(
    n: XNode<'a, 'i>,
    name: &'a str,
) -> impl Iterator<Item = XNode<'a, 'i>> + 'a {
    n.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// The trimmed text of a child; `None` when absent, empty or KBL's "/NULL".
pub(crate) fn text<'a>(n: XNode<'a, '_>, name: &str) -> Option<&'a str> {
    child(n, name)
        .and_then(|c| c.text())
        .map(str::trim)
        .filter(|t| !t.is_empty() && *t != "/NULL")
}

fn text_string(n: XNode, name: &str) -> Option<String> {
    text(n, name).map(str::to_string)
}

/// Element of this name with an `id` attribute (a definition, not a reference).
fn is_def(n: &XNode, name: &str) -> bool {
    n.is_element() && n.tag_name().name() == name && n.attribute("id").is_some()
}

struct Reader<'a, 'i> {
    file: String,
    doc: &'a Document<'i>,
    ids: HashMap<&'a str, XNode<'a, 'i>>,
    units: HashMap<String, Result<Unit, String>>,
    skipped: Vec<(String, String)>,
    warnings: Vec<String>,
    area_unit_warned: bool,
}

impl<'a, 'i> Reader<'a, 'i> {
    fn new(file: &str, doc: &'a Document<'i>) -> Self {
        let mut ids = HashMap::new();
        for n in doc.descendants().filter(|n| n.is_element()) {
            if let Some(id) = n.attribute("id") {
                ids.entry(id).or_insert(n);
            }
        }
        Reader {
            file: file.to_string(),
            doc,
            ids,
            units: HashMap::new(),
            skipped: Vec::new(),
            warnings: Vec::new(),
            area_unit_warned: false,
        }
    }

    fn pos(&self, n: XNode) -> (u32, u32) {
        let p = self.doc.text_pos_at(n.range().start);
        (p.row, p.col)
    }

    fn err(&self, n: XNode, reason: impl Into<String>) -> HarnessError {
        let (line, column) = self.pos(n);
        HarnessError::Element {
            file: self.file.clone(),
            element: n.tag_name().name().to_string(),
            kbl_id: n.attribute("id").unwrap_or("(no id)").to_string(),
            line,
            column,
            reason: reason.into(),
        }
    }

    fn id_of(n: XNode) -> String {
        n.attribute("id").unwrap_or("(no id)").to_string()
    }

    fn skip(&mut self, id: impl Into<String>, reason: impl Into<String>) {
        self.skipped.push((id.into(), reason.into()));
    }

    /// The element with this id, if it has the expected tag name.
    fn lookup(&self, id: &str, names: &[&str]) -> Option<XNode<'a, 'i>> {
        self.ids
            .get(id)
            .copied()
            .filter(|n| names.contains(&n.tag_name().name()))
    }

    fn read_units(&mut self) {
        for n in self.doc.descendants().filter(|n| is_def(n, "Unit")) {
            let id = Self::id_of(n);
            let unit = unit_of(n);
            self.units.insert(id, unit);
        }
    }

    /// A `Value_component` with a `Unit_component`, converted to SI. `Ok(None)` if the
    /// child is absent; `Err(reason)` if present but unusable.
    fn quantity(&mut self, n: XNode, name: &str, want: Dimension) -> Result<Option<f64>, String> {
        let Some(q) = child(n, name) else {
            return Ok(None);
        };
        let value: f64 = text(q, "Value_component")
            .ok_or_else(|| format!("{name} without Value_component"))?
            .parse()
            .map_err(|_| format!("{name}: Value_component is not a number"))?;
        if !value.is_finite() {
            return Err(format!("{name}: value is not finite"));
        }
        let unit_id =
            text(q, "Unit_component").ok_or_else(|| format!("{name} without Unit_component"))?;
        let unit = match self.units.get(unit_id) {
            Some(Ok(u)) => *u,
            Some(Err(e)) => return Err(format!("{name}: unit {unit_id}: {e}")),
            None => return Err(format!("{name}: unit {unit_id} is not defined")),
        };
        if unit.dimension == want {
            return Ok(Some(value * unit.to_si));
        }
        // KBL writers put a plain length unit on areas whose value is in that unit squared.
        if want == Dimension::Area && unit.dimension == Dimension::Length {
            if !self.area_unit_warned {
                self.area_unit_warned = true;
                self.warnings.push(format!(
                    "{name} values refer to a length unit ({unit_id}); read as that unit squared (e.g. mm²)"
                ));
            }
            return Ok(Some(value * unit.to_si * unit.to_si));
        }
        Err(format!(
            "{name}: unit {unit_id} is a {:?}, expected a {:?}",
            unit.dimension, want
        ))
    }

    /// Quantity or, on error, `None` with the reason listed as skipped for `owner`.
    fn quantity_or_skip(&mut self, n: XNode, name: &str, want: Dimension) -> Option<f64> {
        match self.quantity(n, name, want) {
            Ok(v) => v,
            Err(reason) => {
                self.skip(format!("{}/{name}", Self::id_of(n)), reason);
                None
            }
        }
    }

    /// A `Cartesian_point` by id, in metres.
    fn point(&self, id: &str, referrer: XNode) -> Result<DVec3, HarnessError> {
        let p = self.lookup(id, &["Cartesian_point"]).ok_or_else(|| {
            self.err(
                referrer,
                format!("refers to Cartesian_point \"{id}\", which does not exist"),
            )
        })?;
        let c: Vec<f64> = children(p, "Coordinates")
            .map(|c| c.text().unwrap_or("").trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| self.err(p, "a coordinate is not a number"))?;
        if c.len() != 3 || c.iter().any(|v| !v.is_finite()) {
            return Err(self.err(p, format!("needs 3 finite coordinates, has {}", c.len())));
        }
        // Coordinates are millimetres in the vehicle frame.
        Ok(DVec3::new(c[0], c[1], c[2]) * 1e-3)
    }

    fn read_nodes(&mut self, h: &mut Harness) -> Result<HashMap<String, usize>, HarnessError> {
        let mut index = HashMap::new();
        for n in self.doc.descendants().filter(|n| is_def(n, "Node")) {
            let id = Self::id_of(n);
            let pid = text(n, "Cartesian_point")
                .ok_or_else(|| self.err(n, "node without Cartesian_point"))?;
            let position = self.point(pid, n)?;
            index.insert(id.clone(), h.nodes.len());
            h.nodes.push(Node {
                kbl_id: id,
                name: text_string(n, "Id"),
                position,
            });
        }
        Ok(index)
    }

    fn conductor(&mut self, n: XNode) -> Conductor {
        Conductor {
            outer_diameter: self.quantity_or_skip(n, "Outside_diameter", Dimension::Length),
            cross_section: self.quantity_or_skip(n, "Cross_section_area", Dimension::Area),
            bend_radius: self.quantity_or_skip(n, "Bend_radius", Dimension::Length),
        }
    }

    /// Wire parts and wire occurrences (with the cores of cables).
    fn read_wires(&mut self, h: &mut Harness) {
        let mut part_index = HashMap::new();
        for n in self.doc.descendants().filter(|n| is_def(n, "General_wire")) {
            let own = self.conductor(n);
            let cores = children(n, "Core").map(|c| self.conductor(c)).collect();
            let mass = match self.quantity(n, "Mass_information", Dimension::MassPerLength) {
                Ok(m) => m,
                Err(reason) => {
                    self.warnings
                        .push(format!("{}: mass not used: {reason}", Self::id_of(n)));
                    None
                }
            };
            part_index.insert(Self::id_of(n), h.wire_parts.len());
            h.wire_parts.push(WirePart {
                kbl_id: Self::id_of(n),
                part_number: text_string(n, "Part_number"),
                description: text_string(n, "Description"),
                own,
                mass_per_length: mass,
                cores,
            });
        }
        let names = [
            "General_wire_occurrence",
            "Wire_occurrence",
            "Special_wire_occurrence",
        ];
        let occurrences: Vec<XNode> = self
            .doc
            .descendants()
            .filter(|n| names.iter().any(|name| is_def(n, name)))
            .collect();
        for n in occurrences {
            let id = Self::id_of(n);
            let Some(part) = text(n, "Part").and_then(|p| part_index.get(p).copied()) else {
                self.skip(id, "wire occurrence without a known General_wire part");
                continue;
            };
            let name = text_string(n, "Wire_number").or_else(|| text_string(n, "Special_wire_id"));
            h.wires.push(Wire {
                kbl_id: id,
                name,
                part,
                segments: Vec::new(),
            });
        }
    }

    fn read_segments(
        &mut self,
        h: &mut Harness,
        node_index: &HashMap<String, usize>,
    ) -> Result<HashMap<String, usize>, HarnessError> {
        let mut index = HashMap::new();
        let segs: Vec<XNode> = self
            .doc
            .descendants()
            .filter(|n| is_def(n, "Segment"))
            .collect();
        for n in segs {
            let id = Self::id_of(n);
            let node = |field: &str| -> Result<usize, HarnessError> {
                let nid = text(n, field)
                    .ok_or_else(|| self.err(n, format!("segment without {field}")))?;
                node_index.get(nid).copied().ok_or_else(|| {
                    self.err(
                        n,
                        format!("{field} refers to node \"{nid}\", which does not exist"),
                    )
                })
            };
            let start_node = node("Start_node")?;
            let end_node = node("End_node")?;
            let virtual_length = self
                .quantity(n, "Virtual_length", Dimension::Length)
                .map_err(|r| self.err(n, r))?;
            let mut curves = Vec::new();
            for c in children(n, "Center_curve") {
                let degree: usize = text(c, "Degree")
                    .and_then(|d| d.parse().ok())
                    .ok_or_else(|| self.err(c, "Degree missing or not a whole number"))?;
                let ids = text(c, "Control_points").unwrap_or("");
                let control_points = ids
                    .split_whitespace()
                    .map(|pid| self.point(pid, c))
                    .collect::<Result<Vec<_>, _>>()?;
                if degree == 0 || control_points.len() <= degree {
                    return Err(self.err(
                        c,
                        format!(
                            "a B-spline of degree {degree} needs more than {degree} control points, has {}",
                            control_points.len()
                        ),
                    ));
                }
                curves.push(CurveData {
                    kbl_id: Self::id_of(c),
                    degree,
                    control_points,
                });
            }
            if curves.is_empty() {
                self.warnings.push(format!(
                    "{id}: no centre curve; a straight line between its nodes is used"
                ));
            }
            let cross_section_area = match child(n, "Cross_section_area_information") {
                Some(info) => self.quantity_or_skip(info, "Area", Dimension::Area),
                None => None,
            };
            let seg_idx = h.segments.len();
            index.insert(id.clone(), seg_idx);
            let (line, _) = self.pos(n);
            h.segments.push(Segment {
                kbl_id: id.clone(),
                name: text_string(n, "Id"),
                start_node,
                end_node,
                virtual_length,
                curves,
                cross_section_area,
                wires: Vec::new(),
                line,
            });
            for (k, f) in children(n, "Fixing_assignment").enumerate() {
                let fid = f
                    .attribute("id")
                    .map(str::to_string)
                    .unwrap_or_else(|| format!("{id}/Fixing_assignment[{k}]"));
                self.read_fixing(h, f, fid, seg_idx);
            }
            for (k, p) in children(n, "Protection_area").enumerate() {
                let pid = p
                    .attribute("id")
                    .map(str::to_string)
                    .unwrap_or_else(|| format!("{id}/Protection_area[{k}]"));
                self.read_protection(h, p, pid, seg_idx);
            }
        }
        Ok(index)
    }

    fn location(n: XNode, name: &str) -> Result<f64, String> {
        let v: f64 = text(n, name)
            .ok_or_else(|| format!("{name} missing"))?
            .parse()
            .map_err(|_| format!("{name} is not a number"))?;
        if !(-1e-9..=1.0 + 1e-9).contains(&v) {
            return Err(format!("{name} = {v} is outside [0, 1]"));
        }
        Ok(v.clamp(0.0, 1.0))
    }

    fn read_fixing(&mut self, h: &mut Harness, f: XNode, fid: String, segment: usize) {
        let location = match Self::location(f, "Location") {
            Ok(l) => l,
            Err(r) => return self.skip(fid, r),
        };
        let o: Vec<f64> = children(f, "Orientation")
            .filter_map(|c| c.text()?.trim().parse().ok())
            .collect();
        let orientation = (o.len() == 3)
            .then(|| DVec3::new(o[0], o[1], o[2]))
            .filter(|v| v.is_finite() && v.length() > 1e-9);
        let Some(occ_id) = text(f, "Fixing") else {
            return self.skip(fid, "Fixing_assignment without Fixing");
        };
        let Some(occ) = self.lookup(occ_id, &["Fixing_occurrence"]) else {
            return self.skip(
                fid,
                format!("refers to fixing occurrence \"{occ_id}\", which does not exist"),
            );
        };
        let part = text(occ, "Part").and_then(|p| self.lookup(p, &["Fixing"]));
        h.fixings.push(Fixing {
            kbl_id: fid,
            occurrence: occ_id.to_string(),
            name: text_string(occ, "Id"),
            part_number: part.and_then(|p| text_string(p, "Part_number")),
            description: part.and_then(|p| text_string(p, "Description")),
            fixing_type: part.and_then(|p| text_string(p, "Fixing_type")),
            segment,
            location,
            orientation,
        });
    }

    fn read_protection(&mut self, h: &mut Harness, p: XNode, pid: String, segment: usize) {
        let (from, to) = match (
            Self::location(p, "Start_location"),
            Self::location(p, "End_location"),
        ) {
            (Ok(a), Ok(b)) => (a.min(b), a.max(b)),
            (Err(r), _) | (_, Err(r)) => return self.skip(pid, r),
        };
        let Some(occ_id) = text(p, "Associated_protection") else {
            return self.skip(pid, "Protection_area without Associated_protection");
        };
        let Some(occ) = self.lookup(occ_id, &["Wire_protection_occurrence"]) else {
            return self.skip(
                pid,
                format!("refers to protection occurrence \"{occ_id}\", which does not exist"),
            );
        };
        let Some(part) = text(occ, "Part").and_then(|p| self.lookup(p, &["Wire_protection"]))
        else {
            return self.skip(
                pid,
                format!("protection occurrence \"{occ_id}\" has no known Wire_protection part"),
            );
        };
        let description = text_string(part, "Description");
        let protection_type = text_string(part, "Protection_type");
        let kind = classify_protection(protection_type.as_deref(), description.as_deref());
        let mass_per_length =
            match self.quantity(part, "Mass_information", Dimension::MassPerLength) {
                Ok(m) => m,
                Err(reason) => {
                    self.warnings
                        .push(format!("{pid}: protection mass not used: {reason}"));
                    None
                }
            };
        let outer_diameter = description
            .as_deref()
            .and_then(outer_diameter_from_description);
        h.protections.push(Protection {
            kbl_id: pid,
            occurrence: occ_id.to_string(),
            part_number: text_string(part, "Part_number"),
            description,
            protection_type,
            kind,
            segment,
            from,
            to,
            mass_per_length,
            outer_diameter,
        });
    }

    /// Routings: which wire (through a `Connection`, or directly) passes which segments.
    /// The cores of a cable resolve to the cable.
    fn read_routings(&mut self, h: &mut Harness, segment_index: &HashMap<String, usize>) {
        let wire_index: HashMap<String, usize> = h
            .wires
            .iter()
            .enumerate()
            .map(|(i, w)| (w.kbl_id.clone(), i))
            .collect();
        let routings: Vec<XNode> = self
            .doc
            .descendants()
            .filter(|n| is_def(n, "Routing"))
            .collect();
        for r in routings {
            let rid = Self::id_of(r);
            let Some(target) = text(r, "Routed_wire") else {
                self.skip(rid, "Routing without Routed_wire");
                continue;
            };
            let Some(wire) = self.resolve_wire(target, &wire_index) else {
                self.skip(
                    rid,
                    format!("routed wire \"{target}\" does not lead to a known wire occurrence"),
                );
                continue;
            };
            for sid in text(r, "Segments").unwrap_or("").split_whitespace() {
                match segment_index.get(sid) {
                    Some(&s) => {
                        if !h.wires[wire].segments.contains(&s) {
                            h.wires[wire].segments.push(s);
                        }
                    }
                    None => self.skip(
                        rid.clone(),
                        format!("refers to segment \"{sid}\", which does not exist"),
                    ),
                }
            }
        }
        for (i, w) in h.wires.iter().enumerate() {
            for &s in &w.segments {
                h.segments[s].wires.push(i);
            }
        }
        let unrouted: Vec<String> = h
            .wires
            .iter()
            .filter(|w| w.segments.is_empty())
            .map(|w| w.kbl_id.clone())
            .collect();
        for id in unrouted {
            self.skip(
                id,
                "wire occurrence has no Routing: not part of any segment's bundle",
            );
        }
    }

    /// A `Connection`, wire occurrence or core occurrence id → the wire (cable) index.
    fn resolve_wire(&self, id: &str, wire_index: &HashMap<String, usize>) -> Option<usize> {
        if let Some(&w) = wire_index.get(id) {
            return Some(w);
        }
        let n = self.ids.get(id)?;
        match n.tag_name().name() {
            "Connection" => {
                let w = text(*n, "Wire")?;
                if w == id {
                    return None;
                }
                self.resolve_wire(w, wire_index)
            }
            "Core_occurrence" => {
                let parent = n
                    .ancestors()
                    .skip(1)
                    .find(|a| a.attribute("id").is_some())?;
                wire_index.get(parent.attribute("id")?).copied()
            }
            _ => None,
        }
    }

    fn read_connectors(&mut self, h: &mut Harness, node_index: &HashMap<String, usize>) {
        let mut on_node: HashMap<&str, usize> = HashMap::new();
        for n in self.doc.descendants().filter(|n| is_def(n, "Node")) {
            let Some(&ni) = n.attribute("id").and_then(|id| node_index.get(id)) else {
                continue;
            };
            for c in children(n, "Referenced_components") {
                for cid in c.text().unwrap_or("").split_whitespace() {
                    on_node.entry(cid).or_insert(ni);
                }
            }
        }
        for n in self
            .doc
            .descendants()
            .filter(|n| is_def(n, "Connector_occurrence"))
        {
            let id = Self::id_of(n);
            // The node refers to the connector itself, or to a part plugged into it (a
            // terminal listed in the connector's `Contact_points/Associated_parts`).
            let associated = children(n, "Contact_points")
                .flat_map(|c| children(c, "Associated_parts"))
                .flat_map(|a| a.text().unwrap_or("").split_whitespace());
            let node = std::iter::once(id.as_str())
                .chain(associated)
                .find_map(|c| on_node.get(c).copied());
            // the housing's positions: its cavities (a cavity may stay empty), else the
            // contact points written
            let cavities = children(n, "Slots")
                .map(|s| children(s, "Cavities").count())
                .sum::<usize>();
            let contacts = children(n, "Contact_points").count();
            h.connectors.push(Connector {
                name: text_string(n, "Id"),
                description: text_string(n, "Description"),
                node,
                positions: if cavities > 0 { cavities } else { contacts },
                kbl_id: id,
            });
        }
    }
}

/// Protection kind from `Protection_type` and description (German or English terms as
/// found in KBL files: "WELLROHR" corrugated tube, "PET-Vlies" fleece tape, "PVC-Folie"
/// film tape, "Schlauch" tube/sleeve).
pub fn classify_protection(
    protection_type: Option<&str>,
    description: Option<&str>,
) -> ProtectionKind {
    let t = format!(
        "{} {}",
        protection_type.unwrap_or(""),
        description.unwrap_or("")
    )
    .to_uppercase();
    let has = |words: &[&str]| words.iter().any(|w| t.contains(w));
    if has(&["WELLROHR", "WELLSCHLAUCH", "CORRUGATED", "CONVOLUTED"]) {
        ProtectionKind::CorrugatedTube
    } else if has(&["VLIES", "FLEECE", "GEWEBEBAND", "TEXTILBAND", "CLOTH"]) {
        ProtectionKind::FleeceTape
    } else if has(&["TAPE", "FOLIE", "KLEBEBAND", "BAND"]) {
        ProtectionKind::Tape
    } else if has(&["SLEEVE", "SCHLAUCH", "GEFLECHT", "BRAID", "TUBE", "HUELSE"]) {
        ProtectionKind::Sleeve
    } else {
        ProtectionKind::Other
    }
}

/// Outer diameter \[m\] from a description such as "PP-Wellschlauch Gr. 10.0 D(i)=8.3
/// D(a)=13.4" (millimetres).
pub fn outer_diameter_from_description(d: &str) -> Option<f64> {
    let upper = d.to_uppercase();
    let at = upper.find("D(A)=")? + 5;
    let num: String = upper[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.' || *c == ',')
        .collect();
    let v: f64 = num.replace(',', ".").parse().ok()?;
    (v > 0.0 && v.is_finite()).then_some(v * 1e-3)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn protection_kinds() {
        assert_eq!(
            classify_protection(Some("TAPE"), Some("PVC-Folie")),
            ProtectionKind::Tape
        );
        assert_eq!(
            classify_protection(Some("TAPE"), Some("PET-Vlies")),
            ProtectionKind::FleeceTape
        );
        assert_eq!(
            classify_protection(Some("WELLROHR"), Some("PP-Wellschlauch Gr. 10.0")),
            ProtectionKind::CorrugatedTube
        );
        assert_eq!(
            classify_protection(None, Some("Gewebeband")),
            ProtectionKind::FleeceTape
        );
        assert_eq!(
            classify_protection(None, Some("Gewebeschlauch")),
            ProtectionKind::Sleeve
        );
        assert_eq!(
            classify_protection(None, Some("Schrumpfschlauch")),
            ProtectionKind::Sleeve
        );
        assert_eq!(classify_protection(None, None), ProtectionKind::Other);
    }

    #[test]
    fn diameter_in_description() {
        let d =
            outer_diameter_from_description("PP-Wellschlauch Gr. 10.0 D(i)=8.3 D(a)=13.4").unwrap();
        assert!((d - 0.0134).abs() < 1e-12);
        assert!(outer_diameter_from_description("PVC-Folie").is_none());
    }
}
