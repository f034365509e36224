//! VEC 2.x content besides the 3-D geometry — wires and their routing, fixings,
//! protections and connectors — read into the same [`Harness`] lists the KBL reader
//! fills, so one bundle-section, scene and installation code serves both formats.
//!
//! Schema: prostep ivip, `vec_2.0.2.xsd` (`prostep-ivip-e-V/vec`,
//! `wiki/content/specifications/vec/v202/`). A part occurrence (`Component`, a
//! `PartOccurrence`) carries `Role`s; a role refers to its part's specification:
//!
//! - `WireRole` → `WireSpecification` → its `WireElement`'s `WireElementSpecification`
//!   (`OutsideDiameter`, `MinBendRadiusStatic`, else `MinBendRadiusDynamic`, and the
//!   `ConductorSpecification`/`CoreSpecification`'s `CrossSectionArea`); the element's
//!   `SubWireElement`s are the cores of a cable. Mass per length: the `MassInformation`
//!   of the `GeneralTechnicalPartSpecification` describing the same `PartVersion`, in a
//!   mass-per-length unit (a `CompositeUnit` such as gram × metre⁻¹);
//! - a `Routing` (`RoutedElement`: a `WireElementReference` of a wire role, or a
//!   `Connection` such a reference lists) runs its wire through the `Path`'s segments;
//! - `FixingRole` → `FixingSpecification` (`SpecialPartType` as the fixing type), placed
//!   by an `OnPointPlacement` at a `SegmentLocation`;
//! - `WireProtectionRole` → a `WireProtectionSpecification` or its `TapeSpecification`,
//!   `TubeSpecification`, … (`SpecialPartType`, else the specification type without
//!   "Specification", as the protection type; a tube's `OuterDiameter`), placed by an
//!   `OnWayPlacement` from its `StartLocation` along its `Path` to its `EndLocation`;
//! - `ConnectorHousingRole` → `ConnectorHousingSpecification` (positions: the `Cavity`s
//!   of its `Slot`s, else the slots' `NumberOfCavities`, else the role's
//!   `CavityReference`s), on the node of an `OnPointPlacement` at a `NodeLocation`.
//!
//! A placement's `PlacedElement` is the occurrence or any of its roles. A
//! `SegmentLocation` is `Offset` (a length) from the `Anchor` node of its segment, as a
//! fraction of the segment's topology length (else its centre-curve length). Part number
//! and description come from the occurrence's `Part` (`PartVersion`), else the
//! specification's `DescribedPart`. A dangling reference or a missing or malformed value
//! is an error naming the element, id and line; content not mapped (other roles, a fixing
//! at a node, a protection at a point) is listed in `Harness::skipped` with its id.

use std::collections::HashMap;

use roxmltree::Node as XNode;

use crate::error::HarnessError;
use crate::geometry::SegmentCurve;
use crate::kbl::{child, children, classify_protection, outer_diameter_from_description, text};
use crate::model::*;
use crate::units::Dimension;
use crate::vec::{xsi_type, Reader};

/// A stretch of a segment a placement covers: (segment, from, to) as shares of its length.
type WaySpan = (usize, f64, f64);

/// Specification types a `WireProtectionRole` may refer to.
const PROTECTION_SPECIFICATIONS: [&str; 5] = [
    "WireProtectionSpecification",
    "TapeSpecification",
    "TubeSpecification",
    "FittingSpecification",
    "StripeSpecification",
];

/// Roles whose occurrence this reader turns into model content.
const READ_ROLES: [&str; 4] = [
    "WireRole",
    "FixingRole",
    "WireProtectionRole",
    "ConnectorHousingRole",
];

/// Where a location lies: on a segment at a fraction of it, or not usable (the reason).
type Place = Result<(usize, f64), String>;

impl<'a, 'i> Reader<'a, 'i> {
    /// Read wires, routings, fixings, protections and connectors into `h` (its nodes and
    /// segments already read).
    pub(crate) fn read_parts(&mut self, h: &mut Harness) -> Result<(), HarnessError> {
        let technical = self.technical_specifications()?;
        let routable = self.read_wires(h, &technical)?;
        self.read_routings(h, &routable)?;
        let placed = self.placements()?;
        let occurrences: Vec<XNode<'a, 'i>> = self
            .doc
            .descendants()
            .filter(|n| {
                n.is_element()
                    && (n.tag_name().name() == "Component" || child(*n, "Role").is_some())
            })
            .collect();
        for occ in occurrences {
            let is_placed = occ
                .attribute("id")
                .is_some_and(|id| placed.contains_key(id));
            let mut read = false;
            for role in children(occ, "Role") {
                let ty = xsi_type(role).unwrap_or("");
                if ty == "ConnectorHousingRole" {
                    self.read_connector(
                        h,
                        occ,
                        role,
                        placed.get(occ.attribute("id").unwrap_or("")),
                    )?;
                }
                if (ty == "FixingRole" || ty == "WireProtectionRole") && !is_placed {
                    self.skipped
                        .push((id_of(occ), format!("{ty} without a Placement")));
                }
                read |= READ_ROLES.contains(&ty);
            }
            if !read {
                let roles: Vec<&str> = children(occ, "Role")
                    .map(|r| xsi_type(r).unwrap_or("Role"))
                    .collect();
                self.skipped.push((
                    id_of(occ),
                    format!(
                        "part occurrence with {}: not simulated (read are wire, fixing, wire-protection and connector-housing roles)",
                        if roles.is_empty() {
                            "no role".to_string()
                        } else {
                            format!("roles {}", roles.join(", "))
                        }
                    ),
                ));
            }
        }
        // Fixings and protections in the order of their placements, by segment (as KBL
        // lists them inside its segments).
        for p in self.elements("Placement") {
            for occ in self.placed_occurrences(p)? {
                for role in children(occ, "Role") {
                    match xsi_type(role).unwrap_or("") {
                        "FixingRole" => self.read_fixing(h, occ, role, p)?,
                        "WireProtectionRole" => {
                            self.read_protection(h, occ, role, p, &technical)?
                        }
                        _ => {}
                    }
                }
            }
        }
        h.fixings.sort_by_key(|f| f.segment);
        h.protections.sort_by_key(|p| p.segment);
        Ok(())
    }

    /// The element field `field` refers to, which must be one of the specification types
    /// `types`.
    fn specification(
        &self,
        n: XNode<'a, 'i>,
        field: &str,
        types: &[&str],
    ) -> Result<XNode<'a, 'i>, HarnessError> {
        let s = self.reference(n, field)?;
        let ty = xsi_type(s).unwrap_or(s.tag_name().name());
        if !types.contains(&ty) {
            return Err(self.error(
                n,
                format!(
                    "{field} \"{}\" is a {ty}, expected a {}",
                    s.attribute("id").unwrap_or(""),
                    types.join(" or ")
                ),
            ));
        }
        Ok(s)
    }

    /// The elements the IDREFS in child `field` point to (none when it is absent).
    fn references(
        &self,
        n: XNode<'a, 'i>,
        field: &str,
    ) -> Result<Vec<XNode<'a, 'i>>, HarnessError> {
        text(n, field)
            .unwrap_or("")
            .split_whitespace()
            .map(|id| {
                self.ids
                    .get(id)
                    .copied()
                    .ok_or_else(|| self.error(n, format!("{field} \"{id}\" refers to no element")))
            })
            .collect()
    }

    /// `PartVersion` id → the `GeneralTechnicalPartSpecification` describing it.
    fn technical_specifications(&self) -> Result<HashMap<&'a str, XNode<'a, 'i>>, HarnessError> {
        let mut out = HashMap::new();
        for s in self.specifications("GeneralTechnicalPartSpecification") {
            for p in self.references(s, "DescribedPart")? {
                out.entry(p.attribute("id").unwrap_or("")).or_insert(s);
            }
        }
        Ok(out)
    }

    /// Every element with this tag name, in document order.
    fn elements(&self, tag: &str) -> Vec<XNode<'a, 'i>> {
        self.doc
            .descendants()
            .filter(|n| n.tag_name().name() == tag)
            .collect()
    }

    fn specifications(&self, ty: &'static str) -> impl Iterator<Item = XNode<'a, 'i>> + 'a {
        self.doc
            .descendants()
            .filter(move |n| n.tag_name().name() == "Specification" && xsi_type(*n) == Some(ty))
    }

    /// The part (`PartVersion`) of occurrence `occ`, else the first part `spec` describes.
    fn part(
        &self,
        occ: Option<XNode<'a, 'i>>,
        spec: XNode<'a, 'i>,
    ) -> Result<Option<XNode<'a, 'i>>, HarnessError> {
        if let Some(o) = occ.filter(|o| child(*o, "Part").is_some()) {
            return Ok(Some(self.reference(o, "Part")?));
        }
        Ok(self.references(spec, "DescribedPart")?.into_iter().next())
    }

    /// A part's mass per length \[kg/m\] from its technical specification's
    /// `MassInformation`; a mass per piece is noted in the warnings and not used.
    fn mass_per_length(
        &mut self,
        part: Option<XNode<'a, 'i>>,
        owner: &str,
        technical: &HashMap<&'a str, XNode<'a, 'i>>,
    ) -> Result<Option<f64>, HarnessError> {
        let Some(t) = part
            .and_then(|p| p.attribute("id"))
            .and_then(|id| technical.get(id))
        else {
            return Ok(None);
        };
        for m in children(*t, "MassInformation") {
            let value = self
                .measured(m, "Value")?
                .ok_or_else(|| self.error(m, "Value is missing"))?;
            match value {
                (v, Dimension::MassPerLength, _) => return Ok(Some(v)),
                (_, d, _) => self.warnings.push(format!(
                    "{owner}: mass not used: its MassInformation is a {d:?}, not a mass per length"
                )),
            }
        }
        Ok(None)
    }

    /// A wire element specification's conductor and insulation data.
    fn conductor(&self, element: XNode<'a, 'i>) -> Result<Conductor, HarnessError> {
        let spec = self.specification(
            element,
            "WireElementSpecification",
            &["WireElementSpecification"],
        )?;
        let core = match child(spec, "ConductorSpecification") {
            Some(_) => Some(self.specification(
                spec,
                "ConductorSpecification",
                &["ConductorSpecification", "CoreSpecification"],
            )?),
            None => None,
        };
        let outer_diameter = match self.quantity(spec, "OutsideDiameter", Dimension::Length)? {
            Some(d) => Some(d),
            None => match core {
                Some(c) => self.quantity(c, "OutsideDiameter", Dimension::Length)?,
                None => None,
            },
        };
        let cross_section = match core {
            Some(c) => self.quantity(c, "CrossSectionArea", Dimension::Area)?,
            None => None,
        };
        let bend_radius = match self.quantity(spec, "MinBendRadiusStatic", Dimension::Length)? {
            Some(r) => Some(r),
            None => self.quantity(spec, "MinBendRadiusDynamic", Dimension::Length)?,
        };
        Ok(Conductor {
            outer_diameter,
            cross_section,
            bend_radius,
        })
    }

    /// Wire parts (`WireSpecification`s) and wires (`WireRole`s); returns the routable
    /// elements (wire element references, and the connections they list) → wire index.
    fn read_wires(
        &mut self,
        h: &mut Harness,
        technical: &HashMap<&'a str, XNode<'a, 'i>>,
    ) -> Result<HashMap<&'a str, usize>, HarnessError> {
        let mut part_index = HashMap::new();
        let specs: Vec<XNode<'a, 'i>> = self.specifications("WireSpecification").collect();
        for spec in specs {
            let id = id_of(spec);
            let element = child(spec, "WireElement")
                .ok_or_else(|| self.error(spec, "WireElement is missing"))?;
            let own = self.conductor(element)?;
            let cores = children(element, "SubWireElement")
                .map(|c| self.conductor(c))
                .collect::<Result<Vec<_>, _>>()?;
            let part = self.part(None, spec)?;
            let mass_per_length = self.mass_per_length(part, &id, technical)?;
            part_index.insert(spec.attribute("id").unwrap_or(""), h.wire_parts.len());
            h.wire_parts.push(WirePart {
                kbl_id: id,
                part_number: part.and_then(|p| text(p, "PartNumber")).map(str::to_string),
                description: description(part, spec),
                own,
                mass_per_length,
                cores,
            });
        }
        let mut routable = HashMap::new();
        let roles = self.elements("Role");
        for role in roles
            .into_iter()
            .filter(|r| xsi_type(*r) == Some("WireRole"))
        {
            let spec = self.specification(role, "WireSpecification", &["WireSpecification"])?;
            let part = part_index[spec.attribute("id").unwrap_or("")];
            let wire = h.wires.len();
            for r in role
                .descendants()
                .filter(|n| n.tag_name().name() == "WireElementReference")
            {
                if let Some(id) = r.attribute("id") {
                    routable.insert(id, wire);
                }
                for c in self.references(r, "Connection")? {
                    routable.insert(c.attribute("id").unwrap_or(""), wire);
                }
            }
            let occ = role.parent_element();
            h.wires.push(Wire {
                kbl_id: id_of(role),
                name: text(role, "Identification")
                    .or_else(|| occ.and_then(|o| text(o, "Identification")))
                    .map(str::to_string),
                part,
                segments: Vec::new(),
            });
        }
        Ok(routable)
    }

    /// `Routing`s: each runs its wire through the segments of its `Path`.
    fn read_routings(
        &mut self,
        h: &mut Harness,
        routable: &HashMap<&'a str, usize>,
    ) -> Result<(), HarnessError> {
        for r in self.elements("Routing") {
            let rid = id_of(r);
            let target = self.reference(r, "RoutedElement")?;
            let Some(&wire) = routable.get(target.attribute("id").unwrap_or("")) else {
                self.skipped.push((
                    rid,
                    format!(
                        "routes {} \"{}\", which no WireRole's WireElementReference is or lists",
                        target.tag_name().name(),
                        target.attribute("id").unwrap_or("")
                    ),
                ));
                continue;
            };
            let path = child(r, "Path").ok_or_else(|| self.error(r, "Path is missing"))?;
            for s in self.path(path)? {
                match s {
                    Ok(s) if !h.wires[wire].segments.contains(&s) => h.wires[wire].segments.push(s),
                    Ok(_) => {}
                    Err(reason) => self.skipped.push((rid.clone(), reason)),
                }
            }
        }
        for (i, w) in h.wires.iter().enumerate() {
            for &s in &w.segments {
                h.segments[s].wires.push(i);
            }
        }
        for w in h.wires.iter().filter(|w| w.segments.is_empty()) {
            self.skipped.push((
                w.kbl_id.clone(),
                "wire role has no Routing: not part of any segment's bundle".to_string(),
            ));
        }
        Ok(())
    }

    /// The segments of a `Path`, in order; a topology segment without 3-D geometry is
    /// `Err(reason)`.
    fn path(&self, path: XNode<'a, 'i>) -> Result<Vec<Result<usize, String>>, HarnessError> {
        Ok(self
            .references(path, "Segment")?
            .into_iter()
            .map(|s| self.segment_index(s))
            .collect())
    }

    fn segment_index(&self, s: XNode<'a, 'i>) -> Result<usize, String> {
        let id = s.attribute("id").unwrap_or("");
        self.segment_of.get(id).copied().ok_or_else(|| {
            format!(
                "segment \"{id}\" ({}) has no GeometrySegment in a building block",
                s.tag_name().name()
            )
        })
    }

    /// The occurrences a placement places: its `PlacedElement`s, a role standing for the
    /// occurrence that has it.
    fn placed_occurrences(&self, p: XNode<'a, 'i>) -> Result<Vec<XNode<'a, 'i>>, HarnessError> {
        let mut out: Vec<XNode<'a, 'i>> = Vec::new();
        for e in self.references(p, "PlacedElement")? {
            let occ = if e.tag_name().name() == "Role" {
                e.parent_element().unwrap_or(e)
            } else {
                e
            };
            if !out.contains(&occ) {
                out.push(occ);
            }
        }
        Ok(out)
    }

    /// Occurrence id → the placements that place it or one of its roles.
    fn placements(&self) -> Result<HashMap<&'a str, Vec<XNode<'a, 'i>>>, HarnessError> {
        let mut out: HashMap<&str, Vec<XNode>> = HashMap::new();
        for p in self.elements("Placement") {
            for occ in self.placed_occurrences(p)? {
                out.entry(occ.attribute("id").unwrap_or(""))
                    .or_default()
                    .push(p);
            }
        }
        Ok(out)
    }

    /// Where a `Location` lies: a `SegmentLocation` as (segment, fraction from the
    /// geometry segment's start node), a `NodeLocation` on `segment` as 0 or 1.
    fn place(
        &self,
        h: &Harness,
        loc: XNode<'a, 'i>,
        segment: Option<usize>,
    ) -> Result<Place, HarnessError> {
        match xsi_type(loc).unwrap_or("") {
            "SegmentLocation" => {
                let target = self.reference(loc, "ReferencedSegment")?;
                let s = match self.segment_index(target) {
                    Ok(s) => s,
                    Err(reason) => return Ok(Err(reason)),
                };
                let offset = self
                    .quantity(loc, "Offset", Dimension::Length)?
                    .ok_or_else(|| self.error(loc, "Offset is missing"))?;
                let from_start = match text(loc, "Anchor") {
                    Some("FromStartNode") => true,
                    Some("FromEndNode") => false,
                    other => {
                        return Err(self.error(
                            loc,
                            format!(
                                "Anchor \"{}\": expected FromStartNode or FromEndNode",
                                other.unwrap_or("")
                            ),
                        ))
                    }
                };
                let against = self.reversed.contains(target.attribute("id").unwrap_or(""));
                let seg = &h.segments[s];
                let length = seg
                    .virtual_length
                    .unwrap_or_else(|| SegmentCurve::of(h, seg).length);
                if length <= 0.0 {
                    return Ok(Err(format!("segment {} has no length", seg.kbl_id)));
                }
                let f = offset / length;
                Ok(Ok((s, if from_start != against { f } else { 1.0 - f })))
            }
            "NodeLocation" => {
                let node = self.reference(loc, "ReferencedNode")?;
                let id = node.attribute("id").unwrap_or("");
                let Some(&n) = self.node_of.get(id) else {
                    return Ok(Err(format!(
                        "node \"{id}\" has no GeometryNode in a building block"
                    )));
                };
                let Some(s) = segment else {
                    return Ok(Err(format!("placed at node \"{id}\", not on a segment")));
                };
                let seg = &h.segments[s];
                Ok(match n {
                    n if n == seg.start_node => Ok((s, 0.0)),
                    n if n == seg.end_node => Ok((s, 1.0)),
                    _ => Err(format!("node \"{id}\" is no end of segment {}", seg.kbl_id)),
                })
            }
            other => Err(self.error(
                loc,
                format!("location of type \"{other}\": expected SegmentLocation or NodeLocation"),
            )),
        }
    }

    /// The fixing `role` of occurrence `occ` at the point(s) of placement `p`.
    fn read_fixing(
        &mut self,
        h: &mut Harness,
        occ: XNode<'a, 'i>,
        role: XNode<'a, 'i>,
        p: XNode<'a, 'i>,
    ) -> Result<(), HarnessError> {
        let spec = self.specification(role, "FixingSpecification", &["FixingSpecification"])?;
        let part = self.part(Some(occ), spec)?;
        let pid = id_of(p);
        if xsi_type(p) != Some("OnPointPlacement") {
            self.skipped.push((
                pid,
                format!(
                    "fixing placed by a {}: read are fixings at a point (OnPointPlacement)",
                    xsi_type(p).unwrap_or("Placement")
                ),
            ));
            return Ok(());
        }
        let locations: Vec<XNode> = children(p, "Location").collect();
        for (k, loc) in locations.iter().enumerate() {
            let id = if locations.len() == 1 {
                pid.clone()
            } else {
                format!("{pid}/Location[{k}]")
            };
            let (segment, location) = match self.place(h, *loc, None)?.and_then(in_segment) {
                Ok(at) => at,
                Err(reason) => {
                    self.skipped.push((id, format!("fixing {reason}")));
                    continue;
                }
            };
            h.fixings.push(Fixing {
                kbl_id: id,
                occurrence: id_of(occ),
                name: text(occ, "Identification").map(str::to_string),
                part_number: part.and_then(|p| text(p, "PartNumber")).map(str::to_string),
                description: description(part, spec),
                fixing_type: text(spec, "SpecialPartType").map(str::to_string),
                segment,
                location,
                orientation: occ
                    .attribute("id")
                    .and_then(|o| self.orientation_of.get(o))
                    .copied(),
            });
        }
        Ok(())
    }

    /// The protection `role` of occurrence `occ` along the way of placement `p`.
    fn read_protection(
        &mut self,
        h: &mut Harness,
        occ: XNode<'a, 'i>,
        role: XNode<'a, 'i>,
        p: XNode<'a, 'i>,
        technical: &HashMap<&'a str, XNode<'a, 'i>>,
    ) -> Result<(), HarnessError> {
        let spec = self.specification(
            role,
            "WireProtectionSpecification",
            &PROTECTION_SPECIFICATIONS,
        )?;
        let part = self.part(Some(occ), spec)?;
        let occurrence = id_of(occ);
        let pid = id_of(p);
        let spans = match xsi_type(p) {
            Some("OnWayPlacement") => self.way(h, p)?,
            other => Err(format!(
                "wire protection placed by a {}: read are protections along a way (OnWayPlacement)",
                other.unwrap_or("Placement")
            )),
        };
        let spans = match spans {
            Ok(spans) => spans,
            Err(reason) => {
                self.skipped.push((pid, reason));
                return Ok(());
            }
        };
        let desc = description(part, spec);
        let protection_type = text(spec, "SpecialPartType")
            .or_else(|| xsi_type(spec).map(|t| t.trim_end_matches("Specification")))
            .map(str::to_string);
        let kind = classify_protection(protection_type.as_deref(), desc.as_deref());
        let mass_per_length = self.mass_per_length(part, &occurrence, technical)?;
        let outer_diameter = match self.quantity(spec, "OuterDiameter", Dimension::Length)? {
            Some(d) => Some(d),
            None => desc.as_deref().and_then(outer_diameter_from_description),
        };
        for (k, (segment, from, to)) in spans.iter().enumerate() {
            h.protections.push(Protection {
                kbl_id: if spans.len() == 1 {
                    pid.clone()
                } else {
                    format!("{pid}/{k}")
                },
                occurrence: occurrence.clone(),
                part_number: part.and_then(|p| text(p, "PartNumber")).map(str::to_string),
                description: desc.clone(),
                protection_type: protection_type.clone(),
                kind,
                segment: *segment,
                from: *from,
                to: *to,
                mass_per_length,
                outer_diameter,
            });
        }
        Ok(())
    }

    /// The spans an `OnWayPlacement` covers: from its
    /// `StartLocation` along the segments of its `Path` (just the start location's segment
    /// without one) to its `EndLocation`.
    fn way(
        &self,
        h: &Harness,
        p: XNode<'a, 'i>,
    ) -> Result<Result<Vec<WaySpan>, String>, HarnessError> {
        let start =
            child(p, "StartLocation").ok_or_else(|| self.error(p, "StartLocation is missing"))?;
        let end = child(p, "EndLocation").ok_or_else(|| self.error(p, "EndLocation is missing"))?;
        let path: Vec<usize> = match child(p, "Path") {
            Some(path) => match self.path(path)?.into_iter().collect() {
                Ok(path) => path,
                Err(reason) => return Ok(Err(reason)),
            },
            None => match self.place(h, start, None)? {
                Ok((s, _)) => vec![s],
                Err(reason) => return Ok(Err(format!("no Path, and the start is {reason}"))),
            },
        };
        let (Some(&first), Some(&last)) = (path.first(), path.last()) else {
            return Err(self.error(p, "the Path has no segment"));
        };
        let on = |loc: XNode<'a, 'i>, s: usize| -> Result<Result<f64, String>, HarnessError> {
            Ok(match self.place(h, loc, Some(s))?.and_then(in_segment) {
                Ok((t, f)) if t == s => Ok(f),
                Ok((t, _)) => Err(format!(
                    "{} lies on segment {}, but the path has {} there",
                    loc.tag_name().name(),
                    h.segments[t].kbl_id,
                    h.segments[s].kbl_id
                )),
                Err(reason) => Err(reason),
            })
        };
        let (a, b) = match (on(start, first)?, on(end, last)?) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(r), _) | (_, Err(r)) => return Ok(Err(r)),
        };
        if path.len() == 1 {
            return Ok(Ok(vec![(first, a.min(b), a.max(b))]));
        }
        let mut spans = Vec::with_capacity(path.len());
        for (k, &s) in path.iter().enumerate() {
            let seg = &h.segments[s];
            // The node this segment shares with the next one (or the previous one).
            let shared = |o: usize| {
                let other = &h.segments[o];
                [seg.start_node, seg.end_node]
                    .into_iter()
                    .find(|n| *n == other.start_node || *n == other.end_node)
            };
            let span = if k == 0 {
                shared(path[1]).map(|n| {
                    if n == seg.end_node {
                        (a, 1.0)
                    } else {
                        (0.0, a)
                    }
                })
            } else if k + 1 == path.len() {
                shared(path[k - 1]).map(|n| {
                    if n == seg.start_node {
                        (0.0, b)
                    } else {
                        (b, 1.0)
                    }
                })
            } else {
                shared(path[k - 1]).map(|_| (0.0, 1.0))
            };
            let Some((from, to)) = span else {
                return Err(self.error(
                    p,
                    format!(
                        "the Path's segments {} and {} share no node",
                        seg.kbl_id,
                        h.segments[path[if k == 0 { 1 } else { k - 1 }]].kbl_id
                    ),
                ));
            };
            spans.push((s, from, to));
        }
        Ok(Ok(spans))
    }

    fn read_connector(
        &mut self,
        h: &mut Harness,
        occ: XNode<'a, 'i>,
        role: XNode<'a, 'i>,
        places: Option<&Vec<XNode<'a, 'i>>>,
    ) -> Result<(), HarnessError> {
        let spec = self.specification(
            role,
            "ConnectorHousingSpecification",
            &["ConnectorHousingSpecification"],
        )?;
        let mut cavities = 0;
        let mut by_number = 0;
        for slot in children(spec, "Slot") {
            cavities += children(slot, "Cavity").count();
            if child(slot, "SlotSpecification").is_some() {
                let s = self.specification(slot, "SlotSpecification", &["SlotSpecification"])?;
                let n = self.number(s, "NumberOfCavities")?;
                if !(0.0..=1e6).contains(&n) || n.fract() != 0.0 {
                    return Err(self.error(
                        s,
                        format!("NumberOfCavities {n} is not a whole number in 0 … 10⁶"),
                    ));
                }
                by_number += n as usize;
            }
        }
        let referenced = role
            .descendants()
            .filter(|n| n.tag_name().name() == "CavityReference")
            .count();
        let positions = [cavities, by_number, referenced]
            .into_iter()
            .find(|n| *n > 0)
            .unwrap_or(0);
        let mut node = None;
        for p in places
            .into_iter()
            .flatten()
            .filter(|p| xsi_type(**p) == Some("OnPointPlacement"))
        {
            for loc in children(*p, "Location") {
                if xsi_type(loc) != Some("NodeLocation") {
                    self.skipped.push((
                        id_of(*p),
                        format!(
                            "connector placed at a {}: its held end is read from a NodeLocation",
                            xsi_type(loc).unwrap_or("Location")
                        ),
                    ));
                    continue;
                }
                let target = self.reference(loc, "ReferencedNode")?;
                match self.node_of.get(target.attribute("id").unwrap_or("")) {
                    Some(&n) => node = node.or(Some(n)),
                    None => self.skipped.push((
                        id_of(*p),
                        format!(
                            "connector placed at node \"{}\", which has no GeometryNode",
                            target.attribute("id").unwrap_or("")
                        ),
                    )),
                }
            }
        }
        h.connectors.push(Connector {
            kbl_id: id_of(occ),
            name: text(occ, "Identification").map(str::to_string),
            description: description(None, occ),
            node,
            positions,
        });
        Ok(())
    }
}

/// A place within its segment (fraction in [0, 1], rounding allowed), else why not.
fn in_segment((s, f): (usize, f64)) -> Place {
    if (-1e-9..=1.0 + 1e-9).contains(&f) {
        Ok((s, f.clamp(0.0, 1.0)))
    } else {
        Err(format!(
            "location at {f} of its segment's length: outside the segment"
        ))
    }
}

fn id_of(n: XNode) -> String {
    n.attribute("id").unwrap_or("(no id)").to_string()
}

/// The first `Description` (its `Value`) of the part, else of the element.
fn description(part: Option<XNode>, n: XNode) -> Option<String> {
    fn of<'a>(e: XNode<'a, '_>) -> Option<&'a str> {
        child(e, "Description").and_then(|d| text(d, "Value"))
    }
    part.and_then(of).or_else(|| of(n)).map(str::to_string)
}
