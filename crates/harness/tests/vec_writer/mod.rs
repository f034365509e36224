//! A harness model written as VEC 2.0.2, for tests that import a KBL file, write what
//! they read as VEC and import that: topology (nodes, segments with their lengths and
//! cross-section areas), 3-D geometry (centre curves as NURBS without knots, the
//! convention KBL's centre curves follow), wires (parts with conductor, insulation and
//! cores; roles; routings), fixings (point placements with an orientation), protections
//! (way placements) and connector housings (cavities, node placements). Units:
//! millimetres, mm² (an `SIUnit` with exponent 2) and g/m (a `CompositeUnit`).
#![allow(dead_code)] // each test file uses part of it

use std::fmt::Write as _;

use glam::DVec3;
use pliant_harness::geometry::SegmentCurve;
use pliant_harness::model::{Conductor, ProtectionKind};
use pliant_harness::Harness;

/// A `NumericalValue` element `tag` of `value` in unit `unit`.
fn value(tag: &str, unit: &str, value: f64) -> String {
    format!("<{tag}><UnitComponent>{unit}</UnitComponent><ValueComponent>{value}</ValueComponent></{tag}>")
}

fn localized(tag: &str, text: &Option<String>) -> String {
    match text {
        Some(t) => format!(
            "<{tag} xsi:type=\"vec:LocalizedString\"><LanguageCode>de</LanguageCode><Value>{}</Value></{tag}>",
            escape(t)
        ),
        None => String::new(),
    }
}

fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn opt(tag: &str, text: &Option<String>) -> String {
    text.as_ref()
        .map(|t| format!("<{tag}>{}</{tag}>", escape(t)))
        .unwrap_or_default()
}

/// The length \[m\] the VEC reader measures a segment location against.
fn length(h: &Harness, s: usize) -> f64 {
    let seg = &h.segments[s];
    seg.virtual_length
        .unwrap_or_else(|| SegmentCurve::of(h, seg).length)
}

/// A `SegmentLocation` element `tag` at fraction `at` of segment `s`, anchored at its
/// start node or (`from_end`) its end node.
fn segment_location(h: &Harness, tag: &str, s: usize, at: f64, from_end: bool) -> String {
    let l = length(h, s) * 1e3;
    let (offset, anchor) = if from_end {
        ((1.0 - at) * l, "FromEndNode")
    } else {
        (at * l, "FromStartNode")
    };
    format!(
        "<{tag} xsi:type=\"vec:SegmentLocation\"><Identification>{tag}</Identification>{}<Anchor>{anchor}</Anchor><ReferencedSegment>T_{}</ReferencedSegment></{tag}>",
        value("Offset", "mm", offset),
        h.segments[s].kbl_id
    )
}

/// A `WireElementSpecification` `id` (with its `CoreSpecification`) of a conductor.
fn wire_element_specification(out: &mut String, id: &str, c: &Conductor) {
    let mut core = format!("<Specification xsi:type=\"vec:CoreSpecification\" id=\"CS_{id}\"><Identification>{id}</Identification>");
    if let Some(a) = c.cross_section {
        core += &value("CrossSectionArea", "mm2", a * 1e6);
    }
    core += "</Specification>\n";
    out.push_str(&core);
    let _ = write!(
        out,
        "<Specification xsi:type=\"vec:WireElementSpecification\" id=\"{id}\"><Identification>{id}</Identification>"
    );
    if let Some(r) = c.bend_radius {
        out.push_str(&value("MinBendRadiusStatic", "mm", r * 1e3));
    }
    if let Some(d) = c.outer_diameter {
        out.push_str(&value("OutsideDiameter", "mm", d * 1e3));
    }
    let _ = writeln!(
        out,
        "<ConductorSpecification>CS_{id}</ConductorSpecification></Specification>"
    );
}

/// A `PartVersion` and, with a mass per length, its `GeneralTechnicalPartSpecification`.
fn part(
    parts: &mut String,
    specs: &mut String,
    id: &str,
    number: &Option<String>,
    description: &Option<String>,
    mass: Option<f64>,
) {
    let _ = writeln!(
        parts,
        "<PartVersion id=\"{id}\"><CompanyName>test</CompanyName>{}<PartNumber>{}</PartNumber><PartVersion>1</PartVersion><PrimaryPartType>Other</PrimaryPartType></PartVersion>",
        localized("Description", description),
        escape(number.as_deref().unwrap_or(id))
    );
    if let Some(m) = mass {
        let _ = writeln!(
            specs,
            "<Specification xsi:type=\"vec:GeneralTechnicalPartSpecification\" id=\"GTPS_{id}\"><Identification>{id}</Identification><DescribedPart>{id}</DescribedPart><MassInformation>{}</MassInformation></Specification>",
            value("Value", "g_per_m", m * 1e3)
        );
    }
}

/// A part occurrence with one role, its specification and its part.
struct Occurrence<'h> {
    id: &'h str,
    name: &'h Option<String>,
    part_number: &'h Option<String>,
    description: &'h Option<String>,
    mass_per_length: Option<f64>,
    /// The specification's `xsi:type` (without `vec:`) and its content after the part.
    specification: (&'h str, String),
    /// Its content before the part (`SpecialPartType`).
    special: String,
    /// The role's `xsi:type`, and its id prefix.
    role: (&'h str, &'h str),
    /// The role's reference to the specification.
    field: &'h str,
}

/// Write an occurrence: its `PartVersion` `PV_<id>` (to `parts`), its specification
/// `S_<id>` (to `specs`) and its `Component` with the role `<prefix>_<id>`.
fn occurrence(parts: &mut String, specs: &mut String, components: &mut String, o: Occurrence) {
    let pv = format!("PV_{}", o.id);
    part(
        parts,
        specs,
        &pv,
        o.part_number,
        o.description,
        o.mass_per_length,
    );
    let _ = writeln!(
        specs,
        "<Specification xsi:type=\"vec:{1}\" id=\"S_{0}\"><Identification>{0}</Identification>{2}<DescribedPart>{pv}</DescribedPart>{3}</Specification>",
        o.id, o.specification.0, o.special, o.specification.1
    );
    let _ = writeln!(
        components,
        "<Component id=\"{0}\">{1}<Role xsi:type=\"vec:{2}\" id=\"{3}_{0}\"><{4}>S_{0}</{4}></Role><Part>{pv}</Part></Component>",
        o.id,
        opt("Identification", o.name),
        o.role.0,
        o.role.1,
        o.field
    );
}

/// The harness written as VEC 2.0.2.
pub fn as_vec(h: &Harness) -> String {
    let mut points = String::new();
    let mut point = |id: &str, p: DVec3| {
        let mm = p * 1e3;
        let _ = writeln!(
            points,
            "<CartesianPoint id=\"{id}\"><X>{}</X><Y>{}</Y><Z>{}</Z></CartesianPoint>",
            mm.x, mm.y, mm.z
        );
    };
    let mut topology = String::new();
    let mut block = String::new();
    for n in &h.nodes {
        point(&format!("P_{}", n.kbl_id), n.position);
        let _ = writeln!(
            topology,
            "<TopologyNode id=\"T_{0}\"><Identification>{1}</Identification></TopologyNode>",
            n.kbl_id,
            escape(n.name.as_deref().unwrap_or(&n.kbl_id))
        );
        let _ = writeln!(
            block,
            "<GeometryNode id=\"{0}\"><Identification>{0}</Identification><ReferenceNode>T_{0}</ReferenceNode><CartesianPoint>P_{0}</CartesianPoint></GeometryNode>",
            n.kbl_id
        );
    }
    for s in &h.segments {
        let (a, b) = (&h.nodes[s.start_node].kbl_id, &h.nodes[s.end_node].kbl_id);
        let _ = write!(
            topology,
            "<TopologySegment id=\"T_{}\"><Identification>{}</Identification><EndNode>T_{b}</EndNode><StartNode>T_{a}</StartNode>",
            s.kbl_id,
            escape(s.name.as_deref().unwrap_or(&s.kbl_id))
        );
        if let Some(area) = s.cross_section_area {
            let _ = write!(
                topology,
                "<CrossSectionAreaInformation>{}<ValueDetermination>Calculated</ValueDetermination></CrossSectionAreaInformation>",
                value("Area", "mm2", area * 1e6)
            );
        }
        if let Some(l) = s.virtual_length {
            let _ = write!(
                topology,
                "<LengthInformation>{}<Classification>Nominal</Classification></LengthInformation>",
                value("Length", "mm", l * 1e3)
            );
        }
        topology.push_str("</TopologySegment>\n");
        let _ = write!(
            block,
            "<GeometrySegment id=\"{0}\"><Identification>{0}</Identification><ReferenceSegment>T_{0}</ReferenceSegment><EndNode>{b}</EndNode><StartNode>{a}</StartNode>",
            s.kbl_id
        );
        for c in &s.curves {
            let _ = write!(
                block,
                "<Curve xsi:type=\"vec:NURBSCurve\" id=\"C_{}\"><Degree>{}</Degree>",
                c.kbl_id, c.degree
            );
            for (k, p) in c.control_points.iter().enumerate() {
                let id = format!("P_{}_{k}", c.kbl_id);
                point(&id, *p);
                let _ = write!(
                    block,
                    "<ControlPoint id=\"CP_{}_{k}\"><Weight>1</Weight><CartesianPoint3D>{id}</CartesianPoint3D></ControlPoint>",
                    c.kbl_id
                );
            }
            block.push_str("</Curve>");
        }
        block.push_str("</GeometrySegment>\n");
    }
    let (mut parts, mut specs, mut components, mut placements, mut routings) = (
        String::new(),
        String::new(),
        String::new(),
        String::new(),
        String::new(),
    );
    for (i, p) in h.wire_parts.iter().enumerate() {
        let pv = format!("PV_wire_{i}");
        part(
            &mut parts,
            &mut specs,
            &pv,
            &p.part_number,
            &p.description,
            p.mass_per_length,
        );
        wire_element_specification(&mut specs, &format!("WES_{i}"), &p.own);
        let mut subs = String::new();
        for (k, c) in p.cores.iter().enumerate() {
            wire_element_specification(&mut specs, &format!("WES_{i}_{k}"), c);
            let _ = write!(
                subs,
                "<SubWireElement id=\"WE_{i}_{k}\"><Identification>{k}</Identification><WireElementSpecification>WES_{i}_{k}</WireElementSpecification></SubWireElement>"
            );
        }
        let _ = writeln!(
            specs,
            "<Specification xsi:type=\"vec:WireSpecification\" id=\"{}\"><Identification>{i}</Identification><DescribedPart>{pv}</DescribedPart><WireElementSpecification>WES_{i}</WireElementSpecification><WireElement id=\"WE_{i}\"><Identification>{i}</Identification><WireElementSpecification>WES_{i}</WireElementSpecification>{subs}</WireElement></Specification>",
            p.kbl_id
        );
    }
    for (i, w) in h.wires.iter().enumerate() {
        let _ = writeln!(
            components,
            "<Component id=\"PO_wire_{i}\"><Identification>occurrence {i}</Identification><Role xsi:type=\"vec:WireRole\" id=\"{}\">{}<WireSpecification>{}</WireSpecification><WireElementReference id=\"WER_{i}\"><Connection>Connection_{i}</Connection><ReferencedWireElement>WE_{}</ReferencedWireElement></WireElementReference></Role><Part>PV_wire_{}</Part></Component>",
            w.kbl_id,
            opt("Identification", &w.name),
            h.wire_parts[w.part].kbl_id,
            w.part,
            w.part
        );
        if w.segments.is_empty() {
            continue;
        }
        let path: Vec<String> = w
            .segments
            .iter()
            .map(|s| format!("T_{}", h.segments[*s].kbl_id))
            .collect();
        // Odd wires are routed through their connection, even ones directly.
        let routed = if i % 2 == 1 {
            format!("Connection_{i}")
        } else {
            format!("WER_{i}")
        };
        let _ = writeln!(
            routings,
            "<Routing id=\"R_{i}\"><RoutedElement>{routed}</RoutedElement><Path><Segment>{}</Segment></Path></Routing>",
            path.join(" ")
        );
    }
    let connections: String = (0..h.wires.len())
        .map(|i| {
            format!(
                "<Connection id=\"Connection_{i}\"><Identification>{i}</Identification></Connection>"
            )
        })
        .collect();
    let mut views = String::new();
    let mut done = std::collections::HashSet::new();
    for (k, f) in h.fixings.iter().enumerate() {
        if done.insert(f.occurrence.clone()) {
            occurrence(
                &mut parts,
                &mut specs,
                &mut components,
                Occurrence {
                    id: &f.occurrence,
                    name: &f.name,
                    part_number: &f.part_number,
                    description: &f.description,
                    mass_per_length: None,
                    specification: ("FixingSpecification", String::new()),
                    special: opt("SpecialPartType", &f.fixing_type),
                    role: ("FixingRole", "FR"),
                    field: "FixingSpecification",
                },
            );
            if let Some(o) = f.orientation {
                // A rotation whose local z axis is the orientation.
                let z = o.normalize();
                let x = z.any_orthonormal_vector();
                let y = z.cross(x);
                let origin = format!("P_view_{}", f.occurrence);
                point(&origin, DVec3::ZERO);
                let _ = writeln!(
                    views,
                    "<PlacedElementViewItem3D id=\"View_{0}\"><Identification>{0}</Identification><OccurrenceOrUsage>{0}</OccurrenceOrUsage><Orientation><A11>{1}</A11><A12>{2}</A12><A13>{3}</A13><A21>{4}</A21><A22>{5}</A22><A23>{6}</A23><A31>{7}</A31><A32>{8}</A32><A33>{9}</A33><Origin>{origin}</Origin></Orientation></PlacedElementViewItem3D>",
                    f.occurrence, x.x, y.x, z.x, x.y, y.y, z.y, x.z, y.z, z.z
                );
            }
        }
        // Odd fixings anchored at the segment's end node, even ones at its start.
        let _ = writeln!(
            placements,
            "<Placement xsi:type=\"vec:OnPointPlacement\" id=\"{}\"><Identification>fixing</Identification><PlacedElement>FR_{}</PlacedElement>{}</Placement>",
            f.kbl_id,
            f.occurrence,
            segment_location(h, "Location", f.segment, f.location, k % 2 == 1)
        );
    }
    done.clear();
    for p in &h.protections {
        if done.insert(p.occurrence.clone()) {
            let specification = match p.kind {
                ProtectionKind::Tape | ProtectionKind::FleeceTape => {
                    ("TapeSpecification", String::new())
                }
                _ => (
                    "TubeSpecification",
                    p.outer_diameter
                        .map(|d| value("OuterDiameter", "mm", d * 1e3))
                        .unwrap_or_default(),
                ),
            };
            occurrence(
                &mut parts,
                &mut specs,
                &mut components,
                Occurrence {
                    id: &p.occurrence,
                    name: &Some(p.occurrence.clone()),
                    part_number: &p.part_number,
                    description: &p.description,
                    mass_per_length: p.mass_per_length,
                    specification,
                    special: opt("SpecialPartType", &p.protection_type),
                    role: ("WireProtectionRole", "WPR"),
                    field: "WireProtectionSpecification",
                },
            );
        }
        let _ = writeln!(
            placements,
            "<Placement xsi:type=\"vec:OnWayPlacement\" id=\"{}\"><Identification>protection</Identification><PlacedElement>WPR_{}</PlacedElement>{}<Path><Segment>T_{}</Segment></Path>{}</Placement>",
            p.kbl_id,
            p.occurrence,
            segment_location(h, "EndLocation", p.segment, p.to, true),
            h.segments[p.segment].kbl_id,
            segment_location(h, "StartLocation", p.segment, p.from, false)
        );
    }
    for c in &h.connectors {
        let cavities: String = (0..c.positions)
            .map(|k| {
                format!(
                    "<Cavity id=\"Cavity_{}_{k}\"><CavityNumber>{k}</CavityNumber></Cavity>",
                    c.kbl_id
                )
            })
            .collect();
        let _ = writeln!(
            specs,
            "<Specification xsi:type=\"vec:ConnectorHousingSpecification\" id=\"CHS_{0}\"><Identification>{0}</Identification><Slot xsi:type=\"vec:Slot\" id=\"Slot_{0}\"><SlotNumber>A</SlotNumber>{cavities}</Slot></Specification>",
            c.kbl_id
        );
        let _ = writeln!(
            components,
            "<Component id=\"{0}\"><Identification>{1}</Identification>{2}<Role xsi:type=\"vec:PlaceableElementRole\" id=\"PER_{0}\"><PlaceableElementSpecification>PES</PlaceableElementSpecification></Role><Role xsi:type=\"vec:ConnectorHousingRole\" id=\"CHR_{0}\"><ConnectorHousingSpecification>CHS_{0}</ConnectorHousingSpecification></Role></Component>",
            c.kbl_id,
            escape(c.name.as_deref().unwrap_or(&c.kbl_id)),
            localized("Description", &c.description)
        );
        if let Some(n) = c.node {
            let _ = writeln!(
                placements,
                "<Placement xsi:type=\"vec:OnPointPlacement\" id=\"Place_{0}\"><Identification>{0}</Identification><PlacedElement>PER_{0}</PlacedElement><Location xsi:type=\"vec:NodeLocation\" id=\"At_{0}\"><Identification>at</Identification><ReferencedNode>T_{1}</ReferencedNode></Location></Placement>",
                c.kbl_id, h.nodes[n].kbl_id
            );
        }
    }
    format!(
        "<?xml version=\"1.0\"?>\n<vec:VecContent xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" xmlns:vec=\"http://www.prostep.org/ecad-if/2011/vec\" id=\"c\">\n\
         <VecVersion>2.0.2</VecVersion>\n<DocumentVersion id=\"d\"><CompanyName>test</CompanyName><DocumentNumber>1</DocumentNumber><DocumentVersion>1</DocumentVersion>\n\
         <Specification xsi:type=\"vec:PlaceableElementSpecification\" id=\"PES\"><Identification>placeable</Identification><ValidPlacementTypes>OnPoint</ValidPlacementTypes></Specification>\n\
         {specs}\
         <Specification xsi:type=\"vec:TopologySpecification\" id=\"topology\"><Identification>topology</Identification>\n{topology}</Specification>\n\
         <Specification xsi:type=\"vec:BuildingBlockSpecification3D\" id=\"b\"><Identification>b</Identification><BaseUnit>mm</BaseUnit>\n{points}{block}{views}</Specification>\n\
         <Specification xsi:type=\"vec:ConnectionSpecification\" id=\"connections\"><Identification>connections</Identification>{connections}</Specification>\n\
         <Specification xsi:type=\"vec:RoutingSpecification\" id=\"routings\"><Identification>routings</Identification>\n{routings}</Specification>\n\
         <Specification xsi:type=\"vec:PlacementSpecification\" id=\"placements\"><Identification>placements</Identification>\n{placements}</Specification>\n\
         <Specification xsi:type=\"vec:CompositionSpecification\" id=\"composition\"><Identification>composition</Identification>\n{components}</Specification>\n\
         </DocumentVersion>\n{parts}\
         <Unit xsi:type=\"vec:SIUnit\" id=\"mm\"><SiUnitName>Metre</SiUnitName><SiPrefix>Milli</SiPrefix></Unit>\n\
         <Unit xsi:type=\"vec:SIUnit\" id=\"mm2\"><Exponent>2</Exponent><SiUnitName>Metre</SiUnitName><SiPrefix>Milli</SiPrefix></Unit>\n\
         <Unit xsi:type=\"vec:SIUnit\" id=\"g\"><SiUnitName>Gram</SiUnitName></Unit>\n\
         <Unit xsi:type=\"vec:SIUnit\" id=\"per_m\"><Exponent>-1</Exponent><SiUnitName>Metre</SiUnitName></Unit>\n\
         <Unit xsi:type=\"vec:CompositeUnit\" id=\"g_per_m\"><Factors>g per_m</Factors></Unit>\n\
         </vec:VecContent>\n"
    )
}
