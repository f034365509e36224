//! Reader of VEC 2.x files (VDA 4968, "Vehicle Electric Container") that carry 3-D
//! geometry, into the same [`Harness`] the KBL reader fills.
//!
//! Schema: prostep ivip, `prostep-ivip-e-V/vec`, `wiki/content/specifications/vec/v202/
//! vec_2.0.2.xsd` and the 2.1.0 pages *3D-Geometry* and *3D Curves*. What is read:
//!
//! - every `Specification` of `xsi:type` `BuildingBlockSpecification3D`: its `BaseUnit`
//!   (a `Unit` of length, by id), its `CartesianPoint`s (X, Y, Z), `GeometryNode`s
//!   (`GeometryNode3D`: a `CartesianPoint` by id) → nodes, and `GeometrySegment`s
//!   (`GeometrySegment3D`: `StartNode`, `EndNode`, `Curve`s) → segments;
//! - a `HarnessGeometrySpecification3D`'s `BuildingBlockPositionings`: a block's
//!   `Positioning` (`Transformation3D`: the rotation A11 … A33 and an `Origin` point)
//!   places it, p ↦ A p + o;
//! - `Curve`s of `xsi:type` `NURBSCurve` (`Degree`, `Knots`, `ControlPoint`s with a
//!   `CartesianPoint3D` by id and a `Weight`). Without knots, or with equally spaced knots,
//!   and unit weights, a curve is the unclamped uniform B-spline the KBL reader reads
//!   (`bspline.rs`), control points as given. Any other knot vector (clamped, non-uniform)
//!   or weights: the rational curve is evaluated by de Boor's algorithm on homogeneous
//!   points (Piegl & Tiller, *The NURBS Book*, §4.2) at [`SAMPLES_PER_SPAN`] points per
//!   knot span and kept as the polyline through them (a degree-1 B-spline);
//! - names: a node's or segment's `ReferenceNode` / `ReferenceSegment` (its
//!   `TopologyNode` / `TopologySegment`) gives its `Identification` as the name, else its
//!   own; a `TopologySegment`'s first `LengthInformation` gives the virtual length.
//!
//! - a `TopologySegment`'s `CrossSectionAreaInformation/Area` (the stand-in bundle's
//!   size where no wire runs); a `PlacedElementViewItem3D`'s `Orientation`: its local z
//!   axis (A13, A23, A33), placed with its block, is the orientation of the part
//!   occurrences it shows (a fixing's orientation, as KBL's `Fixing_assignment`);
//! - values: a `NumericalValue` (`ValueComponent` in its `UnitComponent`: an `SIUnit`,
//!   `ImperialUnit` or `CompositeUnit`, each with an `Exponent`) converted to SI.
//!
//! Wires, routings, fixings, protections and connectors: `vec_parts.rs`.
//!
//! A VEC without 3-D geometry (topology only) is refused saying so.

use std::collections::{HashMap, HashSet};

use glam::{DMat3, DVec3};
use roxmltree::{Document, Node as XNode};

use crate::error::HarnessError;
use crate::kbl::{child, children, parse_xml, text};
use crate::model::*;
use crate::units::{self, Dimension, Unit};

/// Points per knot span of a NURBS curve kept as a polyline.
pub const SAMPLES_PER_SPAN: usize = 32;

/// Most knot spans of one curve (a cost bound before sampling).
const MAX_SPANS: usize = 100_000;

/// The XML Schema instance namespace (`xsi:type`).
const XSI: &str = "http://www.w3.org/2001/XMLSchema-instance";

/// Whether the text (or file name) looks like VEC: a `.vec` extension or a `VecContent`
/// root element.
pub fn looks_like_vec(file: &str, text: &str) -> bool {
    let head: String = text.chars().take(4096).collect();
    file.to_ascii_lowercase().ends_with(".vec") || head.contains("VecContent")
}

/// The refusal for a VEC file without 3-D geometry.
fn topology_only(file: &str) -> HarnessError {
    HarnessError::Unsupported {
        file: file.to_string(),
        reason: "VEC file (VDA 4968) without 3-D geometry (no BuildingBlockSpecification3D with GeometryNode3D/GeometrySegment3D): it describes topology only, so there is no centre line to simulate; export the harness with its 3-D geometry (VEC 2.x with a BuildingBlockSpecification3D, or KBL 2.3–2.5)".to_string(),
    }
}

/// The local name of an element's `xsi:type` (`vec:NURBSCurve` → `NURBSCurve`).
pub(crate) fn xsi_type<'a>(n: XNode<'a, '_>) -> Option<&'a str> {
    n.attribute((XSI, "type"))
        .map(|t| t.rsplit(':').next().unwrap_or(t))
}

/// A unit as SI factor and powers of length and mass (`other`: some other quantity).
#[derive(Clone, Copy)]
struct UnitPowers {
    to_si: f64,
    length: i32,
    mass: i32,
    other: bool,
}

impl UnitPowers {
    const ONE: UnitPowers = UnitPowers {
        to_si: 1.0,
        length: 0,
        mass: 0,
        other: false,
    };

    const OTHER: UnitPowers = UnitPowers {
        to_si: 1.0,
        length: 0,
        mass: 0,
        other: true,
    };

    fn length(to_si: f64) -> Self {
        UnitPowers {
            to_si,
            length: 1,
            mass: 0,
            other: false,
        }
    }

    fn mass(to_si: f64) -> Self {
        UnitPowers {
            to_si,
            length: 0,
            mass: 1,
            other: false,
        }
    }

    fn times(self, o: UnitPowers) -> Self {
        UnitPowers {
            to_si: self.to_si * o.to_si,
            length: self.length + o.length,
            mass: self.mass + o.mass,
            other: self.other || o.other,
        }
    }

    fn power(self, e: i32) -> Self {
        UnitPowers {
            to_si: self.to_si.powi(e),
            length: self.length * e,
            mass: self.mass * e,
            other: self.other,
        }
    }
}

/// The reader's state: the document, its ids, and what the geometry pass found for the
/// parts pass (`vec_parts.rs`).
pub(crate) struct Reader<'a, 'i> {
    pub(crate) file: String,
    pub(crate) doc: &'a Document<'i>,
    pub(crate) ids: HashMap<&'a str, XNode<'a, 'i>>,
    sampled_curves: usize,
    /// A `GeometryNode`'s id, and the `TopologyNode` id it refers to → index into
    /// `Harness::nodes`.
    pub(crate) node_of: HashMap<&'a str, usize>,
    /// A `GeometrySegment`'s id, and the `TopologySegment` id it refers to → index into
    /// `Harness::segments`.
    pub(crate) segment_of: HashMap<&'a str, usize>,
    /// `TopologySegment`s whose geometry segment runs from their end node to their start
    /// node (a location anchored at the topology's start is then at the geometry's end).
    pub(crate) reversed: HashSet<&'a str>,
    /// A part occurrence's id → its orientation (the local z axis of its
    /// `PlacedElementViewItem3D`, placed with its building block).
    pub(crate) orientation_of: HashMap<&'a str, DVec3>,
    pub(crate) skipped: Vec<(String, String)>,
    pub(crate) warnings: Vec<String>,
}

impl<'a, 'i> Reader<'a, 'i> {
    pub(crate) fn error(&self, n: XNode, reason: impl Into<String>) -> HarnessError {
        let pos = self.doc.text_pos_at(n.range().start);
        HarnessError::Element {
            file: self.file.clone(),
            element: n.tag_name().name().to_string(),
            kbl_id: n.attribute("id").unwrap_or("").to_string(),
            line: pos.row,
            column: pos.col,
            reason: reason.into(),
        }
    }

    /// The element a child's IDREF text points to.
    pub(crate) fn reference(
        &self,
        n: XNode<'a, 'i>,
        field: &str,
    ) -> Result<XNode<'a, 'i>, HarnessError> {
        let id = text(n, field).ok_or_else(|| self.error(n, format!("{field} is missing")))?;
        self.ids
            .get(id)
            .copied()
            .ok_or_else(|| self.error(n, format!("{field} \"{id}\" refers to no element")))
    }

    /// A finite number in child `field`.
    pub(crate) fn number(&self, n: XNode, field: &str) -> Result<f64, HarnessError> {
        let t = text(n, field).ok_or_else(|| self.error(n, format!("{field} is missing")))?;
        t.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| self.error(n, format!("{field} \"{t}\" is not a finite number")))
    }

    fn vector(&self, n: XNode) -> Result<DVec3, HarnessError> {
        Ok(DVec3::new(
            self.number(n, "X")?,
            self.number(n, "Y")?,
            self.number(n, "Z")?,
        ))
    }

    /// A `NumericalValue` child `field` in SI units, if present: its `ValueComponent` in
    /// its `UnitComponent`, which must measure `want`.
    pub(crate) fn quantity(
        &self,
        n: XNode<'a, 'i>,
        field: &str,
        want: Dimension,
    ) -> Result<Option<f64>, HarnessError> {
        let Some((value, dimension, q)) = self.measured(n, field)? else {
            return Ok(None);
        };
        if dimension != want {
            return Err(self.error(
                q,
                format!(
                    "its unit {} measures {dimension:?}, expected {want:?}",
                    text(q, "UnitComponent").unwrap_or("")
                ),
            ));
        }
        Ok(Some(value))
    }

    /// A `NumericalValue` child `field` in SI units with what its unit measures, and the
    /// value's element.
    pub(crate) fn measured(
        &self,
        n: XNode<'a, 'i>,
        field: &str,
    ) -> Result<Option<(f64, Dimension, XNode<'a, 'i>)>, HarnessError> {
        let Some(q) = child(n, field) else {
            return Ok(None);
        };
        let value = self.number(q, "ValueComponent")?;
        let u = self.reference(q, "UnitComponent")?;
        let unit = self
            .unit(u)
            .map_err(|reason| self.error(q, format!("UnitComponent: {reason}")))?;
        let si = value * unit.to_si;
        if !si.is_finite() {
            return Err(self.error(q, format!("{value} in its unit is not finite in SI units")));
        }
        Ok(Some((si, unit.dimension, q)))
    }

    /// Whether geometry segment `g` runs from the end node of its topology segment to the
    /// start node.
    fn runs_against(&self, g: XNode<'a, 'i>, topology: XNode<'a, 'i>) -> bool {
        let start = text(g, "StartNode")
            .and_then(|id| self.ids.get(id))
            .and_then(|n| text(*n, "ReferenceNode"));
        start.is_some()
            && start == text(topology, "EndNode")
            && start != text(topology, "StartNode")
    }

    /// Metres per unit of the `Unit` element `u` (a length).
    fn length_unit(&self, u: XNode<'a, 'i>) -> Result<f64, HarnessError> {
        match self.unit(u) {
            Ok(unit) if unit.dimension == Dimension::Length => Ok(unit.to_si),
            _ => Err(self.error(
                u,
                format!(
                    "the base unit of 3-D geometry must be a length (e.g. SIUnit Metre with SiPrefix Milli); this is {} with exponent {}",
                    xsi_type(u).unwrap_or(""),
                    text(u, "Exponent").unwrap_or("1")
                ),
            )),
        }
    }

    /// The unit a VEC `Unit` element defines (`SIUnit`, `ImperialUnit`, `OtherUnit`, or a
    /// `CompositeUnit`: the product of its `Factors`), raised to its `Exponent`.
    pub(crate) fn unit(&self, u: XNode<'a, 'i>) -> Result<Unit, String> {
        let p = self.unit_powers(u, 0)?;
        let dimension = match (p.length, p.mass, p.other) {
            (1, 0, false) => Dimension::Length,
            (2, 0, false) => Dimension::Area,
            (3, 0, false) => Dimension::Volume,
            (0, 1, false) => Dimension::Mass,
            (-1, 1, false) => Dimension::MassPerLength,
            _ => Dimension::Other,
        };
        Ok(Unit {
            dimension,
            to_si: p.to_si,
        })
    }

    fn unit_powers(&self, u: XNode<'a, 'i>, depth: usize) -> Result<UnitPowers, String> {
        let id = u.attribute("id").unwrap_or("");
        if u.tag_name().name() != "Unit" {
            return Err(format!("\"{id}\" is a {}, not a Unit", u.tag_name().name()));
        }
        let exponent: i32 = match text(u, "Exponent") {
            Some(e) => e
                .parse()
                .ok()
                .filter(|e: &i32| e.abs() <= 4)
                .ok_or_else(|| {
                    format!("unit {id}: Exponent \"{e}\" is not an integer in -4 … 4")
                })?,
            None => 1,
        };
        let kind = xsi_type(u).unwrap_or("");
        let base = match kind {
            "SIUnit" => {
                let name = text(u, "SiUnitName").unwrap_or("");
                let prefix = text(u, "SiPrefix").unwrap_or("");
                let f = units::si_prefix(prefix)
                    .ok_or_else(|| format!("unit {id}: unknown SiPrefix \"{prefix}\""))?;
                match name {
                    "Metre" => UnitPowers::length(f),
                    // The SI base unit of mass is the kilogram; VEC names the gram.
                    "Gram" => UnitPowers::mass(1e-3 * f),
                    _ => UnitPowers::OTHER,
                }
            }
            "ImperialUnit" => match text(u, "ImperialUnitName").unwrap_or("") {
                // International yard and pound (1959): exact by definition.
                "Thou" => UnitPowers::length(2.54e-5),
                "Inch" => UnitPowers::length(0.0254),
                "Foot" => UnitPowers::length(0.3048),
                "Yard" => UnitPowers::length(0.9144),
                "Mile" => UnitPowers::length(1609.344),
                "Grain" => UnitPowers::mass(6.479891e-5),
                "Ounce" => UnitPowers::mass(0.028349523125),
                "Pound" => UnitPowers::mass(0.45359237),
                _ => UnitPowers::OTHER,
            },
            "CompositeUnit" => {
                if depth >= 4 {
                    return Err(format!("unit {id}: CompositeUnit nested more than 4 deep"));
                }
                let factors = text(u, "Factors").unwrap_or("");
                let mut p = UnitPowers::ONE;
                for f in factors.split_whitespace() {
                    let n =
                        self.ids.get(f).copied().ok_or_else(|| {
                            format!("unit {id}: factor \"{f}\" refers to no element")
                        })?;
                    p = p.times(self.unit_powers(n, depth + 1)?);
                }
                p
            }
            _ => UnitPowers::OTHER,
        };
        Ok(base.power(exponent))
    }

    /// The `Identification` of the topology element `field` refers to, else `n`'s own.
    fn name(&self, n: XNode<'a, 'i>, field: &str) -> Option<String> {
        child(n, field)
            .and_then(|_| self.reference(n, field).ok())
            .and_then(|t| text(t, "Identification"))
            .or_else(|| text(n, "Identification"))
            .map(str::to_string)
    }

    /// A topology segment's first length \[m\], if it has one in a length unit.
    fn virtual_length(&self, geometry_segment: XNode<'a, 'i>) -> Option<f64> {
        let topology = child(geometry_segment, "ReferenceSegment")
            .and_then(|_| self.reference(geometry_segment, "ReferenceSegment").ok())?;
        let length = child(child(topology, "LengthInformation")?, "Length")?;
        let value: f64 = text(length, "ValueComponent")?.parse().ok()?;
        let unit = self.reference(length, "UnitComponent").ok()?;
        let scale = self.length_unit(unit).ok()?;
        Some(value * scale).filter(|v| v.is_finite() && *v > 0.0)
    }

    /// The placements of building blocks: block id → (rotation, origin point element).
    fn positionings(&self) -> Result<HashMap<&'a str, (DMat3, XNode<'a, 'i>)>, HarnessError> {
        let mut out = HashMap::new();
        let specs = self.doc.descendants().filter(|n| {
            n.tag_name().name() == "Specification"
                && xsi_type(*n) == Some("HarnessGeometrySpecification3D")
        });
        for spec in specs {
            for p in children(spec, "BuildingBlockPositionings") {
                let block = text(p, "Referenced3DBuildingBlock")
                    .ok_or_else(|| self.error(p, "Referenced3DBuildingBlock is missing"))?;
                let Some(t) = child(p, "Positioning") else {
                    continue;
                };
                let mut a = [0.0; 9];
                for (k, v) in a.iter_mut().enumerate() {
                    *v = self.number(t, &format!("A{}{}", k / 3 + 1, k % 3 + 1))?;
                }
                // DMat3 is column-major: column j holds A1j, A2j, A3j.
                let m =
                    DMat3::from_cols_array(&[a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]]);
                let origin = self.reference(t, "Origin")?;
                out.insert(block, (m, origin));
            }
        }
        Ok(out)
    }

    /// A NURBS curve as the model's curve data (positions in metres, placed).
    fn curve(
        &mut self,
        c: XNode<'a, 'i>,
        place: &dyn Fn(DVec3) -> DVec3,
    ) -> Result<CurveData, HarnessError> {
        if xsi_type(c) != Some("NURBSCurve") {
            return Err(self.error(
                c,
                format!(
                    "curve of type {}: VEC 2.x centre lines are NURBSCurve",
                    xsi_type(c).unwrap_or("(none)")
                ),
            ));
        }
        let degree_text = text(c, "Degree").unwrap_or("");
        let degree: usize = degree_text
            .parse()
            .ok()
            .filter(|d| (1..=10).contains(d))
            .ok_or_else(|| {
                self.error(
                    c,
                    format!("Degree \"{degree_text}\" is not an integer in 1 … 10"),
                )
            })?;
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for cp in children(c, "ControlPoint") {
            let p = self.reference(cp, "CartesianPoint3D")?;
            let placed = place(self.vector(p)?);
            if !placed.is_finite() {
                return Err(self.error(
                    p,
                    "the placed point is not finite (coordinates or unit too large)",
                ));
            }
            points.push(placed);
            weights.push(match child(cp, "Weight") {
                Some(_) => self.number(cp, "Weight")?,
                None => 1.0,
            });
        }
        if points.len() <= degree {
            return Err(self.error(
                c,
                format!(
                    "{} control points: a curve of degree {degree} needs at least {}",
                    points.len(),
                    degree + 1
                ),
            ));
        }
        if let Some(w) = weights.iter().find(|w| **w <= 0.0) {
            return Err(self.error(c, format!("control point weight {w}: must be positive")));
        }
        let mut knots = Vec::new();
        for k in children(c, "Knots") {
            let t = k.text().unwrap_or("").trim();
            knots.push(
                t.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| self.error(c, format!("knot \"{t}\" is not a finite number")))?,
            );
        }
        let rational = weights.iter().any(|w| *w != 1.0);
        let id = c.attribute("id").unwrap_or("").to_string();
        if knots.is_empty() && !rational {
            return Ok(CurveData {
                kbl_id: id,
                degree,
                control_points: points,
            });
        }
        let n = points.len();
        if knots.is_empty() {
            // Rational without knots: the unclamped uniform knot vector.
            knots = (0..n + degree + 1).map(|i| i as f64).collect();
        }
        if knots.len() != n + degree + 1 {
            return Err(self.error(
                c,
                format!(
                    "{} knots for {n} control points of degree {degree}: need n + degree + 1 = {}",
                    knots.len(),
                    n + degree + 1
                ),
            ));
        }
        if knots.windows(2).any(|w| w[1] < w[0]) {
            return Err(self.error(c, "the knots decrease: a knot vector must not"));
        }
        let steps: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
        let uniform = steps
            .iter()
            .all(|s| (s - steps[0]).abs() <= 1e-12 * steps[0].abs().max(1e-300));
        if uniform && steps[0] > 0.0 && !rational {
            return Ok(CurveData {
                kbl_id: id,
                degree,
                control_points: points,
            });
        }
        let spans = (degree..n).filter(|&i| knots[i + 1] > knots[i]).count();
        if spans == 0 || spans > MAX_SPANS {
            return Err(self.error(
                c,
                format!("{spans} non-empty knot spans in the curve's domain: need 1 … {MAX_SPANS}"),
            ));
        }
        self.sampled_curves += 1;
        Ok(CurveData {
            kbl_id: id,
            degree: 1,
            control_points: sample_nurbs(degree, &knots, &points, &weights),
        })
    }
}

/// The point of a NURBS curve at parameter `t` in span `span` (knots[span] ≤ t ≤
/// knots[span + 1]): de Boor's algorithm on the homogeneous points (w P, w).
fn nurbs_point(p: usize, knots: &[f64], ctrl: &[DVec3], w: &[f64], span: usize, t: f64) -> DVec3 {
    let mut d: Vec<(DVec3, f64)> = (0..=p)
        .map(|j| {
            let i = span + j - p;
            (ctrl[i] * w[i], w[i])
        })
        .collect();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = span + j - p;
            let denom = knots[i + p + 1 - r] - knots[i];
            let a = if denom > 0.0 {
                (t - knots[i]) / denom
            } else {
                0.0
            };
            d[j] = (
                d[j - 1].0 * (1.0 - a) + d[j].0 * a,
                d[j - 1].1 * (1.0 - a) + d[j].1 * a,
            );
        }
    }
    d[p].0 / d[p].1
}

/// Points along a NURBS curve over its domain [knots[p], knots[n]]: the start, then
/// [`SAMPLES_PER_SPAN`] points per non-empty knot span (its end included).
fn sample_nurbs(p: usize, knots: &[f64], ctrl: &[DVec3], w: &[f64]) -> Vec<DVec3> {
    let n = ctrl.len();
    let mut out = vec![nurbs_point(
        p,
        knots,
        ctrl,
        w,
        first_span(p, knots, n),
        knots[p],
    )];
    for span in p..n {
        let (a, b) = (knots[span], knots[span + 1]);
        if b <= a {
            continue;
        }
        for k in 1..=SAMPLES_PER_SPAN {
            let t = a + (b - a) * k as f64 / SAMPLES_PER_SPAN as f64;
            out.push(nurbs_point(p, knots, ctrl, w, span, t));
        }
    }
    out
}

fn first_span(p: usize, knots: &[f64], n: usize) -> usize {
    (p..n).find(|&i| knots[i + 1] > knots[i]).unwrap_or(p)
}

/// Parse VEC text with 3-D geometry. `file` names the source in errors and in the model.
pub fn parse_vec(file: &str, text_in: &str) -> Result<Harness, HarnessError> {
    let doc = parse_xml(file, text_in)?;
    let root = doc.root_element();
    if root.tag_name().name() != "VecContent" {
        return Err(HarnessError::Unsupported {
            file: file.to_string(),
            reason: format!(
                "not a VEC file: the root element is <{}>, expected <VecContent>",
                root.tag_name().name()
            ),
        });
    }
    let mut ids = HashMap::new();
    for n in doc.descendants().filter(|n| n.is_element()) {
        if let Some(id) = n.attribute("id") {
            ids.entry(id).or_insert(n);
        }
    }
    let mut r = Reader {
        file: file.to_string(),
        doc: &doc,
        ids,
        sampled_curves: 0,
        node_of: HashMap::new(),
        segment_of: HashMap::new(),
        reversed: HashSet::new(),
        orientation_of: HashMap::new(),
        skipped: Vec::new(),
        warnings: Vec::new(),
    };
    let blocks: Vec<XNode> = doc
        .descendants()
        .filter(|n| {
            n.tag_name().name() == "Specification"
                && xsi_type(*n) == Some("BuildingBlockSpecification3D")
        })
        .collect();
    if blocks
        .iter()
        .all(|b| children(*b, "GeometrySegment").next().is_none())
    {
        return Err(topology_only(file));
    }
    let version = text(root, "VecVersion").unwrap_or("").to_string();
    if !version.starts_with("2.") {
        return Err(HarnessError::Unsupported {
            file: file.to_string(),
            reason: format!(
                "VEC version \"{version}\": this importer reads VEC 2.x (VecVersion 2.0.0 … 2.2.x)"
            ),
        });
    }
    let positionings = r.positionings()?;
    let mut h = Harness::empty(file, format!("VEC {version}"));
    for block in blocks {
        let unit = r.reference(block, "BaseUnit")?;
        let scale = r.length_unit(unit)?;
        let (rotation, origin) = match block.attribute("id").and_then(|id| positionings.get(id)) {
            Some((m, o)) => (*m, r.vector(*o)? * scale),
            None => (DMat3::IDENTITY, DVec3::ZERO),
        };
        let place = move |p: DVec3| rotation * (p * scale) + origin;
        for g in children(block, "GeometryNode") {
            let id = g
                .attribute("id")
                .ok_or_else(|| r.error(g, "GeometryNode without id"))?;
            let point = r.reference(g, "CartesianPoint")?;
            let position = place(r.vector(point)?);
            if !position.is_finite() {
                return Err(r.error(
                    point,
                    "the placed point is not finite (coordinates or unit too large)",
                ));
            }
            r.node_of.insert(id, h.nodes.len());
            if let Some(t) = text(g, "ReferenceNode") {
                r.node_of.entry(t).or_insert(h.nodes.len());
            }
            h.nodes.push(Node {
                kbl_id: id.to_string(),
                name: r.name(g, "ReferenceNode"),
                position,
            });
        }
        for g in children(block, "GeometrySegment") {
            let id = g
                .attribute("id")
                .ok_or_else(|| r.error(g, "GeometrySegment without id"))?;
            let end = |field: &str| -> Result<usize, HarnessError> {
                let target = text(g, field).unwrap_or("");
                r.node_of.get(target).copied().ok_or_else(|| {
                    r.error(
                        g,
                        format!("{field} \"{target}\" is no GeometryNode of this building block"),
                    )
                })
            };
            let (start_node, end_node) = (end("StartNode")?, end("EndNode")?);
            let mut curves = Vec::new();
            for c in children(g, "Curve") {
                curves.push(r.curve(c, &place)?);
            }
            let line = doc.text_pos_at(g.range().start).row;
            let topology = match child(g, "ReferenceSegment") {
                Some(_) => Some(r.reference(g, "ReferenceSegment")?),
                None => None,
            };
            r.segment_of.insert(id, h.segments.len());
            if let Some(t) = topology.and_then(|t| t.attribute("id")) {
                r.segment_of.entry(t).or_insert(h.segments.len());
            }
            if let Some(t) = topology {
                if r.runs_against(g, t) {
                    r.reversed.insert(t.attribute("id").unwrap_or(""));
                }
            }
            let cross_section_area =
                match topology.and_then(|t| child(t, "CrossSectionAreaInformation")) {
                    Some(info) => r.quantity(info, "Area", Dimension::Area)?,
                    None => None,
                };
            h.segments.push(Segment {
                kbl_id: id.to_string(),
                name: r.name(g, "ReferenceSegment"),
                start_node,
                end_node,
                virtual_length: r.virtual_length(g),
                curves,
                cross_section_area,
                wires: Vec::new(),
                line,
            });
        }
        for v in children(block, "PlacedElementViewItem3D") {
            let Some(t) = child(v, "Orientation") else {
                continue;
            };
            let z = DVec3::new(
                r.number(t, "A13")?,
                r.number(t, "A23")?,
                r.number(t, "A33")?,
            );
            let axis = rotation * z;
            if !(axis.is_finite() && axis.length() > 1e-9) {
                return Err(r.error(t, "the local z axis (A13, A23, A33) is zero or not finite"));
            }
            for o in text(v, "OccurrenceOrUsage")
                .unwrap_or("")
                .split_whitespace()
            {
                r.orientation_of.insert(o, axis);
            }
        }
    }
    if r.sampled_curves > 0 {
        h.warnings.push(format!(
            "{} NURBS curves with a knot vector other than uniform or with weights are kept as polylines of {SAMPLES_PER_SPAN} points per knot span",
            r.sampled_curves
        ));
    }
    r.read_parts(&mut h)?;
    h.skipped.append(&mut r.skipped);
    h.warnings.append(&mut r.warnings);
    Ok(h)
}
