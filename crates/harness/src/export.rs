//! KBL out (SPEC N3, "back to CAD"): the original KBL file with each
//! settled segment's centre curve, lengths and end vectors replaced and its nodes moved.
//!
//! **How the file is edited.** The document is parsed with roxmltree (which keeps each
//! node's byte range in the text) and only the changed pieces of text are replaced, so
//! everything else — element order, comments, processing instructions, indentation,
//! ids, number formats, the vendor's extensions — stays byte for byte as it was. A
//! re-serialising writer would have rewritten every line of a 1.8 MB file (attribute
//! quoting, whitespace, number formats) to change a few hundred; the text edits are also
//! what a reviewer can diff.
//!
//! **What changes, for each segment in the [`SettledHarness`]:**
//!
//! - its `Center_curve` elements become one `Center_curve` (the first one's id) of degree
//!   1 whose control points are the polyline's points. KBL gives no knot vector; read as
//!   the unclamped uniform B-spline (knots t_i = i, domain [1, n + 1], `bspline.rs`) a
//!   degree-1 curve passes through every control point, C(i + 1) = P_i, so it is the
//!   polyline itself, first point on the start node and last on the end node;
//! - one new `Cartesian_point` per polyline point (millimetres, 6 decimals as in the
//!   sample files), with fresh ids `Cartesian_point_<k>` after the highest existing one,
//!   inserted after the last `Cartesian_point` of the container (the schema's order);
//!   the old control points that nothing else refers to any more are removed;
//! - `Virtual_length` and, if present, `Physical_length`: the polyline length in the
//!   unit their `Unit_component` names;
//! - `Start_vector` / `End_vector` (the sample files write the unit tangent along the
//!   segment, start node → end node, at each end): the first and last polyline piece;
//! - its start and end nodes move to the settled ends (the mean of all settled segment
//!   ends meeting at the node; they must agree within [`NODE_SPREAD_LIMIT_M`]): the
//!   node's `Cartesian_point` is edited in place when only the node refers to it, else
//!   the node gets a new point.
//!
//! Segments not in the settled route keep their curves; if one of their nodes moved, the
//! report warns that their curve no longer ends on it. Fixing and protection locations
//! are fractions of the segment's length and stay as written.

use std::collections::{HashMap, HashSet};
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use glam::DVec3;
use roxmltree::{Document, Node as XNode};
use serde::Serialize;

use crate::error::HarnessError;
use crate::geometry::SegmentCurve;
use crate::kbl::{self, child, children, text};
use crate::model::Harness;
use crate::settled::{clean, polyline_length, SettledHarness, DUPLICATE_M};
use crate::units::Dimension;

/// Largest distance \[m\] between settled segment ends meeting at one node (0.1 mm, the
/// harness round trip's tolerance): Pliant welds the ends at a junction, so a larger
/// spread means a wrong route (e.g. a polyline given from its end node to its start).
pub const NODE_SPREAD_LIMIT_M: f64 = 1e-4;

/// What [`export_kbl`] did.
#[derive(Debug, Clone, Serialize)]
pub struct ExportReport {
    /// The original file (name only) and the written file.
    pub source: String,
    pub out: PathBuf,
    /// Segments whose centre curve was replaced, and those kept.
    pub segments_replaced: usize,
    pub segments_kept: usize,
    /// Nodes moved, and the largest move \[m\].
    pub nodes_moved: usize,
    pub max_node_move_m: f64,
    /// Largest distance \[m\] between settled segment ends at one node (before they were
    /// joined at their mean).
    pub max_node_spread_m: f64,
    /// `Cartesian_point` elements added and removed.
    pub points_added: usize,
    pub points_removed: usize,
    /// Sum of the replaced segments' lengths \[m\], before (their `Virtual_length`) and after.
    pub length_before_m: f64,
    pub length_after_m: f64,
    pub warnings: Vec<String>,
}

impl fmt::Display for ExportReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "KBL export of {} → {}", self.source, self.out.display())?;
        writeln!(
            f,
            "  segments: {} with the settled route, {} kept as they were",
            self.segments_replaced, self.segments_kept
        )?;
        writeln!(
            f,
            "  nodes moved: {} (largest move {:.3} mm; segment ends at a node within {:.2e} mm)",
            self.nodes_moved,
            self.max_node_move_m * 1e3,
            self.max_node_spread_m * 1e3
        )?;
        writeln!(
            f,
            "  Cartesian_point: {} added, {} removed",
            self.points_added, self.points_removed
        )?;
        writeln!(
            f,
            "  length of the settled segments: {:.1} mm (file: {:.1} mm)",
            self.length_after_m * 1e3,
            self.length_before_m * 1e3
        )?;
        for w in &self.warnings {
            writeln!(f, "  warning: {w}")?;
        }
        Ok(())
    }
}

/// A segment's route as it will be written: its index and the polyline with its ends on
/// the (moved) nodes.
struct Route {
    segment: usize,
    points: Vec<DVec3>,
}

/// Where the settled route puts things: routes and new node positions.
struct Plan {
    routes: Vec<Route>,
    nodes: HashMap<usize, DVec3>,
    max_spread: f64,
}

fn settled_error(kbl_id: &str, reason: impl Into<String>) -> HarnessError {
    HarnessError::Settled {
        kbl_id: kbl_id.to_string(),
        reason: reason.into(),
    }
}

/// Check the settled route against the harness and place the nodes.
fn plan(file: &str, h: &Harness, settled: &SettledHarness) -> Result<Plan, HarnessError> {
    settled
        .check()
        .map_err(|(id, reason)| settled_error(&id, reason))?;
    let index: HashMap<&str, usize> = h
        .segments
        .iter()
        .enumerate()
        .map(|(i, s)| (s.kbl_id.as_str(), i))
        .collect();
    // Settled segment ends at each node: (segment id, point).
    let mut ends: HashMap<usize, Vec<(&str, DVec3)>> = HashMap::new();
    let mut routes = Vec::new();
    for (id, pts) in settled.iter() {
        let &segment = index
            .get(id)
            .ok_or_else(|| settled_error(id, format!("{file} has no Segment with this id")))?;
        let s = &h.segments[segment];
        let pts = clean(pts);
        ends.entry(s.start_node).or_default().push((id, pts[0]));
        ends.entry(s.end_node)
            .or_default()
            .push((id, pts[pts.len() - 1]));
        routes.push(Route {
            segment,
            points: pts,
        });
    }
    let mut nodes = HashMap::new();
    let mut max_spread: f64 = 0.0;
    for (&node, list) in &ends {
        for (i, (ida, a)) in list.iter().enumerate() {
            for (idb, b) in &list[i + 1..] {
                let d = a.distance(*b);
                max_spread = max_spread.max(d);
                if d > NODE_SPREAD_LIMIT_M {
                    return Err(settled_error(
                        ida,
                        format!(
                            "its end at node {} is {:.3} mm from the end of {idb} there; \
                             settled segment ends meeting at a node must agree within {} mm \
                             (is a polyline given from its end node to its start node?)",
                            h.nodes[node].kbl_id,
                            d * 1e3,
                            NODE_SPREAD_LIMIT_M * 1e3
                        ),
                    ));
                }
            }
        }
        let mean = list.iter().map(|(_, p)| *p).sum::<DVec3>() / list.len() as f64;
        // A node that stays (within 10⁻⁹ m) keeps its position and its text.
        let old = h.nodes[node].position;
        nodes.insert(
            node,
            if mean.distance(old) <= DUPLICATE_M {
                old
            } else {
                mean
            },
        );
    }
    for r in &mut routes {
        let s = &h.segments[r.segment];
        let n = r.points.len();
        r.points[0] = nodes[&s.start_node];
        r.points[n - 1] = nodes[&s.end_node];
        r.points = clean(&r.points);
        if r.points.len() < 2 {
            return Err(settled_error(
                &s.kbl_id,
                "its start and end node coincide and no point lies between them",
            ));
        }
    }
    Ok(Plan {
        routes,
        nodes,
        max_spread,
    })
}

/// The text of `doc` with ranges replaced.
struct Edits {
    list: Vec<(Range<usize>, String)>,
}

impl Edits {
    fn replace(&mut self, range: Range<usize>, with: String) {
        self.list.push((range, with));
    }

    /// Apply to `text`; the ranges must not overlap (an internal error otherwise).
    fn apply(mut self, file: &str, text: &str) -> Result<String, HarnessError> {
        self.list.sort_by_key(|(r, _)| (r.start, r.end));
        let mut out = String::with_capacity(text.len() + 64 * self.list.len());
        let mut at = 0;
        for (r, with) in &self.list {
            if r.start < at {
                return Err(HarnessError::Unsupported {
                    file: file.to_string(),
                    reason: format!("internal error: overlapping edits at byte {}", r.start),
                });
            }
            out.push_str(&text[at..r.start]);
            out.push_str(with);
            at = r.end;
        }
        out.push_str(&text[at..]);
        Ok(out)
    }
}

/// The byte range of an element's text, without surrounding whitespace.
fn text_range(text: &str, n: XNode) -> Option<Range<usize>> {
    let t = n.children().find(|c| c.is_text())?;
    let r = t.range();
    let raw = &text[r.clone()];
    let start = r.start + (raw.len() - raw.trim_start().len());
    let end = r.end - (raw.len() - raw.trim_end().len());
    (start < end).then_some(start..end)
}

/// The whitespace from the start of the line to `pos`, if only whitespace precedes it.
fn indent_at(text: &str, pos: usize) -> &str {
    let line = text[..pos].rfind('\n').map_or(0, |i| i + 1);
    let lead = &text[line..pos];
    if lead.chars().all(char::is_whitespace) {
        lead
    } else {
        ""
    }
}

/// An element's range widened to its line: from the newline before it when only
/// whitespace stands between (so removing it leaves no blank line).
fn line_range(text: &str, n: XNode) -> Range<usize> {
    let r = n.range();
    let ws = indent_at(text, r.start);
    let mut start = r.start - ws.len();
    if start > 0 && text[..start].ends_with('\n') {
        start -= 1;
        if text[..start].ends_with('\r') {
            start -= 1;
        }
    }
    start..r.end
}

/// The tag name as written (with its namespace prefix, if any).
fn raw_name<'t>(text: &'t str, n: XNode) -> &'t str {
    let s = &text[n.range().start + 1..];
    let end = s
        .find(|c: char| c.is_whitespace() || c == '>' || c == '/')
        .unwrap_or(s.len());
    &s[..end]
}

/// `prefix:name` with the prefix of `like` (e.g. `kbl:Center_curve` → `kbl:Degree`).
fn same_prefix(like: &str, name: &str) -> String {
    match like.split_once(':') {
        Some((p, _)) => format!("{p}:{name}"),
        None => name.to_string(),
    }
}

/// Millimetres with 6 decimals, as the sample files write them.
fn mm(v: f64) -> String {
    format!("{:.6}", v * 1e3)
}

/// Fresh ids `<prefix><k>` after the highest k in use.
struct IdMaker<'a> {
    prefix: &'static str,
    next: u64,
    taken: &'a HashSet<&'a str>,
}

impl<'a> IdMaker<'a> {
    fn new(prefix: &'static str, taken: &'a HashSet<&'a str>) -> Self {
        let next = taken
            .iter()
            .filter_map(|id| id.strip_prefix(prefix)?.parse::<u64>().ok())
            .max()
            .map_or(1, |k| k + 1);
        IdMaker {
            prefix,
            next,
            taken,
        }
    }

    fn make(&mut self) -> String {
        loop {
            let id = format!("{}{}", self.prefix, self.next);
            self.next += 1;
            if !self.taken.contains(id.as_str()) {
                return id;
            }
        }
    }
}

/// Write `out`: a copy of the KBL file `original_kbl` in which every segment of `settled`
/// has its settled centre line (see the module documentation). Returns what was changed.
pub fn export_kbl(
    original_kbl: &Path,
    settled: &SettledHarness,
    out: &Path,
) -> Result<ExportReport, HarnessError> {
    let h = crate::read_kbl(original_kbl)?;
    let (file, text) = crate::read_text(original_kbl)?;
    let doc = kbl::parse_xml(&file, &text)?;
    let plan = plan(&file, &h, settled)?;
    let mut report = ExportReport {
        source: file.clone(),
        out: out.to_path_buf(),
        segments_replaced: plan.routes.len(),
        segments_kept: h.segments.len() - plan.routes.len(),
        nodes_moved: plan
            .nodes
            .iter()
            .filter(|(&n, p)| h.nodes[n].position != **p)
            .count(),
        max_node_move_m: plan
            .nodes
            .iter()
            .map(|(&n, p)| h.nodes[n].position.distance(*p))
            .fold(0.0, f64::max),
        max_node_spread_m: plan.max_spread,
        points_added: 0,
        points_removed: 0,
        length_before_m: 0.0,
        length_after_m: 0.0,
        warnings: Vec::new(),
    };
    let new_text = Writer::new(&file, &text, &doc)?.write(&h, &plan, &mut report)?;
    warn_kept_segments(&h, settled, &plan, &mut report.warnings);
    warn_checksums(&doc, &mut report.warnings);
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| HarnessError::Write {
            path: dir.to_path_buf(),
            source,
        })?;
    }
    std::fs::write(out, new_text).map_err(|source| HarnessError::Write {
        path: out.to_path_buf(),
        source,
    })?;
    Ok(report)
}

/// Segments kept as they were whose curve no longer ends on a moved node.
fn warn_kept_segments(h: &Harness, settled: &SettledHarness, plan: &Plan, w: &mut Vec<String>) {
    for s in &h.segments {
        if settled.get(&s.kbl_id).is_some() {
            continue;
        }
        for (node, at_start) in [(s.start_node, true), (s.end_node, false)] {
            let Some(p) = plan.nodes.get(&node) else {
                continue;
            };
            let c = SegmentCurve::of(h, s);
            let end = c.chain.point(if at_start { c.u_start } else { c.u_end });
            let d = end.distance(*p);
            if d > crate::geometry::END_TOLERANCE_M {
                w.push(format!(
                    "{}: not in the settled route; its centre curve now ends {:.3} mm from its moved node {}",
                    s.kbl_id,
                    d * 1e3,
                    h.nodes[node].kbl_id
                ));
            }
        }
    }
}

/// Processing instructions with a checksum describe the original bytes.
fn warn_checksums(doc: &Document, w: &mut Vec<String>) {
    for n in doc.root().children() {
        if let Some(pi) = n.pi() {
            if pi.value.is_some_and(|v| v.contains("checksum")) {
                w.push(format!(
                    "the processing instruction <?{} {}?> is kept as it was; it describes the original file's content",
                    pi.target,
                    pi.value.unwrap_or("")
                ));
            }
        }
    }
}

/// The edits of one export.
struct Writer<'a, 'i> {
    file: &'a str,
    text: &'i str,
    doc: &'a Document<'i>,
    /// Elements with an id.
    ids: HashMap<&'a str, XNode<'a, 'i>>,
    /// How often each id is named in element text (references).
    refs: HashMap<&'a str, usize>,
    edits: Edits,
}

impl<'a, 'i: 'a> Writer<'a, 'i> {
    fn new(file: &'a str, text: &'i str, doc: &'a Document<'i>) -> Result<Self, HarnessError> {
        let mut ids = HashMap::new();
        for n in doc.descendants().filter(|n| n.is_element()) {
            if let Some(id) = n.attribute("id") {
                ids.entry(id).or_insert(n);
            }
        }
        let mut refs: HashMap<&str, usize> = HashMap::new();
        for t in doc.descendants().filter(|n| n.is_text()) {
            for token in t.text().unwrap_or("").split_whitespace() {
                if let Some((&id, _)) = ids.get_key_value(token) {
                    *refs.entry(id).or_default() += 1;
                }
            }
        }
        Ok(Writer {
            file,
            text,
            doc,
            ids,
            refs,
            edits: Edits { list: Vec::new() },
        })
    }

    fn element_error(&self, n: XNode, reason: impl Into<String>) -> HarnessError {
        let p = self.doc.text_pos_at(n.range().start);
        HarnessError::Element {
            file: self.file.to_string(),
            element: n.tag_name().name().to_string(),
            kbl_id: n.attribute("id").unwrap_or("(no id)").to_string(),
            line: p.row,
            column: p.col,
            reason: reason.into(),
        }
    }

    /// The element `name` with this id.
    fn find(&self, id: &str, name: &str) -> Option<XNode<'a, 'i>> {
        self.ids
            .get(id)
            .copied()
            .filter(|n| n.tag_name().name() == name)
    }

    fn newline(&self) -> &'static str {
        if self.text.contains("\r\n") {
            "\r\n"
        } else {
            "\n"
        }
    }

    /// All edits; the new text.
    fn write(
        mut self,
        h: &Harness,
        plan: &Plan,
        report: &mut ExportReport,
    ) -> Result<String, HarnessError> {
        let taken: HashSet<&str> = self.ids.keys().copied().collect();
        let mut point_ids = IdMaker::new("Cartesian_point_", &taken);
        let mut curve_ids = IdMaker::new("Center_curve_", &taken);
        // New points (id, position) in the order they are made.
        let mut new_points: Vec<(String, DVec3)> = Vec::new();
        // Points whose last reference went away.
        let mut released: Vec<&'a str> = Vec::new();

        // Routes in document order, so fresh ids follow the file.
        let mut routes: Vec<&Route> = plan.routes.iter().collect();
        routes.sort_by_key(|r| h.segments[r.segment].line);
        for r in routes {
            let s = &h.segments[r.segment];
            let seg = self
                .find(&s.kbl_id, "Segment")
                .ok_or_else(|| settled_error(&s.kbl_id, "segment element not found"))?;
            let ids: Vec<String> = r
                .points
                .iter()
                .map(|p| {
                    let id = point_ids.make();
                    new_points.push((id.clone(), *p));
                    id
                })
                .collect();
            self.replace_curves(seg, &ids, &mut curve_ids, &mut released)?;
            let length = polyline_length(&r.points);
            report.length_before_m += s.virtual_length.unwrap_or(0.0);
            report.length_after_m += length;
            for name in ["Virtual_length", "Physical_length"] {
                self.set_length(seg, name, length, &mut report.warnings)?;
            }
            let n = r.points.len();
            let t0 = (r.points[1] - r.points[0]).normalize_or_zero();
            let t1 = (r.points[n - 1] - r.points[n - 2]).normalize_or_zero();
            self.set_vector(seg, "Start_vector", t0);
            self.set_vector(seg, "End_vector", t1);
        }

        // Nodes: their point edited in place when only the node names it.
        let mut moved: Vec<(usize, DVec3)> = plan.nodes.iter().map(|(&n, &p)| (n, p)).collect();
        moved.sort_by_key(|&(n, _)| n);
        for (ni, p) in moved {
            if h.nodes[ni].position == p {
                continue;
            }
            let node = self
                .find(&h.nodes[ni].kbl_id, "Node")
                .ok_or_else(|| settled_error(&h.nodes[ni].kbl_id, "node element not found"))?;
            let cp = child(node, "Cartesian_point")
                .ok_or_else(|| self.element_error(node, "node without Cartesian_point"))?;
            let pid = text(node, "Cartesian_point").unwrap_or("");
            let point = self.find(pid, "Cartesian_point");
            let coords: Vec<XNode> = point
                .map(|pt| children(pt, "Coordinates").collect())
                .unwrap_or_default();
            let alone = self.refs.get(pid).copied() == Some(1);
            if alone && coords.len() == 3 {
                for (c, v) in coords.iter().zip([p.x, p.y, p.z]) {
                    let r = text_range(self.text, *c)
                        .ok_or_else(|| self.element_error(*c, "empty Coordinates"))?;
                    self.edits.replace(r, mm(v));
                }
            } else {
                let id = point_ids.make();
                new_points.push((id.clone(), p));
                let r = text_range(self.text, cp)
                    .ok_or_else(|| self.element_error(cp, "empty Cartesian_point reference"))?;
                self.edits.replace(r, id);
                self.release(pid, &mut released);
            }
        }

        // Old points nothing refers to any more.
        for pid in released {
            if let Some(pt) = self.find(pid, "Cartesian_point") {
                self.edits.replace(line_range(self.text, pt), String::new());
                report.points_removed += 1;
            }
        }
        report.points_added = new_points.len();
        self.insert_points(&new_points)?;
        self.edits.apply(self.file, self.text)
    }

    /// One reference to `id` fewer; note it when none is left.
    fn release(&mut self, id: &str, released: &mut Vec<&'a str>) {
        if let Some((&key, count)) = self.refs.get_key_value(id) {
            let c = count.saturating_sub(1);
            self.refs.insert(key, c);
            if c == 0 {
                released.push(key);
            }
        }
    }

    /// Replace the segment's `Center_curve`s by one degree-1 curve through `points`.
    fn replace_curves(
        &mut self,
        seg: XNode<'a, 'i>,
        points: &[String],
        curve_ids: &mut IdMaker,
        released: &mut Vec<&'a str>,
    ) -> Result<(), HarnessError> {
        let nl = self.newline();
        let curves: Vec<XNode> = children(seg, "Center_curve").collect();
        for c in &curves {
            for pid in text(*c, "Control_points").unwrap_or("").split_whitespace() {
                self.release(pid, released);
            }
        }
        let write = |name: &str, id: &str, indent: &str, inner: &str| {
            format!(
                "<{name} id=\"{id}\">{nl}{inner}<{d}>1</{d}>{nl}{inner}<{cp}>{}</{cp}>{nl}{indent}</{name}>",
                points.join(" "),
                d = same_prefix(name, "Degree"),
                cp = same_prefix(name, "Control_points"),
            )
        };
        match curves.first() {
            Some(first) => {
                let name = raw_name(self.text, *first);
                let indent = indent_at(self.text, first.range().start);
                let inner = first
                    .children()
                    .find(|c| c.is_element())
                    .map(|c| indent_at(self.text, c.range().start).to_string())
                    .unwrap_or_else(|| format!("{indent}\t"));
                let id = first.attribute("id").unwrap_or("Center_curve_1");
                self.edits
                    .replace(first.range(), write(name, id, indent, &inner));
                for c in &curves[1..] {
                    self.edits.replace(line_range(self.text, *c), String::new());
                }
            }
            None => {
                // After Start_node / End_node (the schema's order: … End_node, Start_node,
                // Center_curve …).
                let after = ["Start_node", "End_node"]
                    .iter()
                    .filter_map(|n| child(seg, n))
                    .max_by_key(|n| n.range().end)
                    .ok_or_else(|| self.element_error(seg, "segment without nodes"))?;
                let indent = indent_at(self.text, after.range().start);
                let name = same_prefix(raw_name(self.text, after), "Center_curve");
                let inner = format!("{indent}\t");
                let at = after.range().end;
                let id = curve_ids.make();
                self.edits.replace(
                    at..at,
                    format!("{nl}{indent}{}", write(&name, &id, indent, &inner)),
                );
            }
        }
        Ok(())
    }

    /// Set a length quantity of the segment to `length` \[m\] in its own unit.
    fn set_length(
        &mut self,
        seg: XNode,
        name: &str,
        length: f64,
        warnings: &mut Vec<String>,
    ) -> Result<(), HarnessError> {
        let Some(q) = child(seg, name) else {
            if name == "Virtual_length" {
                warnings.push(format!(
                    "{}: has no Virtual_length; none written",
                    seg.attribute("id").unwrap_or("(no id)")
                ));
            }
            return Ok(());
        };
        let unit = text(q, "Unit_component")
            .and_then(|u| self.find(u, "Unit"))
            .ok_or_else(|| self.element_error(q, format!("{name}: unit missing or not defined")))?;
        let unit = kbl::unit_of(unit).map_err(|e| self.element_error(q, e))?;
        if unit.dimension != Dimension::Length {
            return Err(self.element_error(q, format!("{name}: its unit is not a length")));
        }
        let value = child(q, "Value_component")
            .and_then(|v| text_range(self.text, v))
            .ok_or_else(|| self.element_error(q, format!("{name} without Value_component")))?;
        self.edits
            .replace(value, format!("{:.6}", length / unit.to_si));
        Ok(())
    }

    /// Set a three-component vector (`Start_vector`, `End_vector`) if the segment has one.
    fn set_vector(&mut self, seg: XNode, name: &str, v: DVec3) {
        let parts: Vec<Range<usize>> = children(seg, name)
            .filter_map(|c| text_range(self.text, c))
            .collect();
        if parts.len() == 3 && v != DVec3::ZERO {
            for (r, x) in parts.into_iter().zip([v.x, v.y, v.z]) {
                self.edits.replace(r, format!("{x:.6}"));
            }
        }
    }

    /// New `Cartesian_point`s after the container's last one (or as its first children).
    fn insert_points(&mut self, points: &[(String, DVec3)]) -> Result<(), HarnessError> {
        if points.is_empty() {
            return Ok(());
        }
        let nl = self.newline();
        let root = self.doc.root_element();
        let last = children(root, "Cartesian_point").last();
        let (at, indent, inner, name) = match last {
            Some(p) => {
                let indent = indent_at(self.text, p.range().start).to_string();
                let inner = p
                    .children()
                    .find(|c| c.is_element())
                    .map(|c| indent_at(self.text, c.range().start).to_string())
                    .unwrap_or_else(|| format!("{indent}\t"));
                (
                    p.range().end,
                    indent,
                    inner,
                    raw_name(self.text, p).to_string(),
                )
            }
            None => {
                let first = root.children().find(|c| c.is_element()).ok_or_else(|| {
                    self.element_error(root, "the container is empty: nowhere to add points")
                })?;
                let indent = indent_at(self.text, first.range().start).to_string();
                let name = same_prefix(raw_name(self.text, first), "Cartesian_point");
                // Before the first child: the points are written ahead of it.
                let at = first.range().start - indent.len();
                (at, indent.clone(), format!("{indent}\t"), name)
            }
        };
        let coords = same_prefix(&name, "Coordinates");
        let element = |id: &str, p: &DVec3| {
            let mut e = format!("<{name} id=\"{id}\">");
            for v in [p.x, p.y, p.z] {
                e.push_str(&format!("{nl}{inner}<{coords}>{}</{coords}>", mm(v)));
            }
            e.push_str(&format!("{nl}{indent}</{name}>"));
            e
        };
        let mut s = String::with_capacity(points.len() * 200);
        for (id, p) in points {
            if last.is_some() {
                // After the last point: a line break, the indentation, the element.
                s.push_str(&format!("{nl}{indent}{}", element(id, p)));
            } else {
                // Before the first child, whose indentation is already there.
                s.push_str(&format!("{}{nl}{indent}", element(id, p)));
            }
        }
        self.edits.replace(at..at, s);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_helpers() {
        let t = "<r xmlns:k=\"u\">\n\t<k:a id=\"x\"> 1.5 </k:a>\n\t<b/>\n</r>";
        let doc = Document::parse(t).unwrap();
        let a = doc
            .descendants()
            .find(|n| n.tag_name().name() == "a")
            .unwrap();
        assert_eq!(&t[text_range(t, a).unwrap()], "1.5");
        assert_eq!(raw_name(t, a), "k:a");
        assert_eq!(same_prefix(raw_name(t, a), "Degree"), "k:Degree");
        assert_eq!(indent_at(t, a.range().start), "\t");
        let r = line_range(t, a);
        assert_eq!(&t[r], "\n\t<k:a id=\"x\"> 1.5 </k:a>");
        let b = doc
            .descendants()
            .find(|n| n.tag_name().name() == "b")
            .unwrap();
        assert!(text_range(t, b).is_none());
    }

    #[test]
    fn fresh_ids_follow_the_highest() {
        let taken: HashSet<&str> = ["Cartesian_point_7", "Cartesian_point_9", "Node_12"]
            .into_iter()
            .collect();
        let mut m = IdMaker::new("Cartesian_point_", &taken);
        assert_eq!(m.make(), "Cartesian_point_10");
        assert_eq!(m.make(), "Cartesian_point_11");
        let mut c = IdMaker::new("Center_curve_", &taken);
        assert_eq!(c.make(), "Center_curve_1");
    }
}
