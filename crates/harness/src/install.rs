//! Writing `install.toml`: the harness installed by a worker, step by step, into a simple
//! body — connectors plugged against a mating force, fixings pressed into their clips.
//!
//! The body is made of primitives around the KBL route: behind every fixing a panel
//! with the fixing's clip, its seat on the route, behind every connector end a
//! counterpart housing whose mouth lies [`PUSH`] before the route's end (the route is the
//! installed shape: a plug pushed in sits on it). The harness is drawn on its route, its
//! plugs home; the counterparts take a plug only through the mouth.
//!
//! The worker's sequence, two hands:
//!
//! 0. the left hand (1) holds the harness at its first fixing, on the route (without
//!    fixings: at its second connector's end, which it plugs in step 3);
//! 1. the right hand (0) plugs the first connector: take the end, bring it [`IN_FRONT`] before the mouth on
//!    the mating axis and push it [`PUSH`] in, past the latch; let go (the latched
//!    connector now carries the harness);
//! 2. every fixing in KBL order: take the bundle at the fixing (the first: the left hand
//!    holds it already), lift it out of the clip (the harness is drawn installed, in its
//!    clips) and press it in, [`PRESS_PAST`] past the seat; let go;
//! 3. every other connector as the first;
//! 4. settle.
//!
//! The verdict then names the connector or fixing whose force the hand could not give and
//! every segment bent below its bend radius. KBL carries no mating forces: every connector
//! gets [`MATING_CURVE`], an assumption to be replaced by the connector's datasheet curve.

use std::fmt::Write as _;

use glam::DVec3;

use crate::model::Harness;
use crate::scene::{clip_places, clip_toml, mm, network_toml, quote, sanitise, unit_vec, vec_mm};
use crate::scene::{ClipPlace, SegmentOut};

/// How far beyond the bundle's diameter the hand lifts a bundle out of its clip before
/// pressing it in \[m\]: clear of the jaws.
pub const LIFT_CLEAR: f64 = 0.003;
/// How far past the seat the hand presses a bundle into its clip \[m\].
pub const PRESS_PAST: f64 = 0.002;
/// Mating travel of every connector \[m\] (assumption, typical of small automotive
/// connectors).
pub const TRAVEL: f64 = 0.008;
/// How far the hand pushes a connector in from its mouth \[m\]: past the latch, short of
/// home.
pub const PUSH: f64 = 0.0075;
/// Where the hand brings a connector end before pushing: this far before the mouth \[m\].
pub const IN_FRONT: f64 = 0.002;
/// The mating force curve of every connector, (travel mm, force N): rising to its peak
/// just before the latch clicks at 6.5 mm. An assumption of the usual shape and size for a
/// small sealed connector; KBL gives none.
pub const MATING_CURVE: [(f64, f64); 5] = [
    (0.0, 5.0),
    (5.0, 35.0),
    (6.0, 40.0),
    (6.5, 12.0),
    (8.0, 15.0),
];
/// Where the latch clicks \[mm\].
pub const LATCH_AT_MM: f64 = 6.5;
/// Force a latched connector holds against pulling \[N\] (assumption of the usual order).
pub const RETENTION_N: f64 = 110.0;
/// Duration of a hand's move to a clip's seat or before a connector's mouth \[s\].
pub const MOVE_S: f64 = 0.5;
/// Duration of a connector's push \[s\]: ≈ 10 mm/s, slow enough that the hand feels the
/// mating force, not the bundle's inertia.
pub const PUSH_S: f64 = 0.75;
/// Gap between a bundle in its clip's seat and the panel behind \[m\]: wider than
/// [`PRESS_PAST`], so that the hand pressing past the seat does not press the bundle into
/// the panel.
pub const PANEL_GAP: f64 = 0.005;
/// Edge of a fixing's panel in bundle diameters (a small boss around the clip's hole:
/// branches that leave a junction beside the fixing pass clear of it), and its thickness
/// \[m\].
const PANEL: (f64, f64) = (2.5, 0.003);

/// A connector on a leaf end of the network.
struct ConnectorEnd {
    name: String,
    hose: String,
    at_start: bool,
    /// The counterpart's mouth \[m\]: [`PUSH`] before the route's end, so that the plug
    /// pushed in sits on the route.
    mouth: DVec3,
    /// Out of the bundle along its end: the mating axis.
    axis: DVec3,
    d_outer: f64,
}

fn connector_ends(h: &Harness, segs: &[SegmentOut]) -> Vec<ConnectorEnd> {
    let at = h.segments_at_nodes();
    let mut names = Vec::new();
    let mut ends = Vec::new();
    for c in &h.connectors {
        let Some(node) = c.node else { continue };
        let [s] = at[node][..] else { continue };
        let seg = &h.segments[s];
        let at_start = seg.start_node == node;
        // the end element's direction (the chord over one element), which the plug's
        // direction follows in the model, rather than the curve's tangent at the node
        let one = 1.0 / segs[s].elements.max(1) as f64;
        let (inner, _) = segs[s]
            .curve
            .at_fraction(if at_start { one } else { 1.0 - one });
        let outward = h.nodes[node].position - inner;
        let name = sanitise(c.name.as_deref().unwrap_or(&c.kbl_id));
        if names.contains(&name) {
            continue;
        }
        names.push(name.clone());
        ends.push(ConnectorEnd {
            name,
            hose: segs[s].hose.clone(),
            at_start,
            mouth: h.nodes[node].position - outward.normalize_or(DVec3::X) * PUSH,
            axis: outward.normalize_or(DVec3::X),
            d_outer: segs[s].section.d_outer,
        });
    }
    ends
}

/// `rotation = { axis, angle_deg }` turning the local z axis onto `dir`.
fn rotation_onto(dir: DVec3) -> String {
    let axis = DVec3::Z.cross(dir);
    let angle = DVec3::Z.dot(dir).clamp(-1.0, 1.0).acos().to_degrees();
    let axis = if axis.length() > 1e-9 {
        axis.normalize()
    } else {
        DVec3::X
    };
    format!("{{ axis = {}, angle_deg = {angle:.4} }}", unit_vec(axis))
}

fn box_part(t: &mut String, name: &str, centre: DVec3, size: [f64; 3], normal: DVec3) {
    let _ = writeln!(
        t,
        "[[parts]]\nname = {}\nbox = {{ size = [{}, {}, {}] }}\nposition = {}\nrotation = {}\n",
        quote(name),
        mm(size[0]),
        mm(size[1]),
        mm(size[2]),
        vec_mm(centre),
        rotation_onto(normal)
    );
}

/// The clip's seat: on the route (the route is the installed shape).
fn seat(c: &ClipPlace) -> DVec3 {
    c.point
}

fn step(t: &mut String, fields: &str) {
    let _ = writeln!(t, "[[timeline]]\n{fields}\n");
}

/// `hand` plugs connector `c`; `holding`: the hand holds its end already (else it takes it).
fn plug(t: &mut String, c: &ConnectorEnd, hand: usize, holding: bool) {
    let _ = writeln!(t, "# connector {}", c.name);
    if !holding {
        step(
            t,
            &format!(
                "action = \"grab\"\nhand = {hand}\nat = {}",
                vec_mm(c.mouth + c.axis * PUSH)
            ),
        );
    }
    for (target, duration) in [
        (c.mouth - c.axis * IN_FRONT, MOVE_S),
        (c.mouth + c.axis * PUSH, PUSH_S),
    ] {
        step(
            t,
            &format!(
                "action = \"move_hand\"\nhand = {hand}\nto = {}\nduration_s = {duration}",
                vec_mm(target)
            ),
        );
    }
    step(t, &format!("action = \"release_hand\"\nhand = {hand}"));
}

/// Most connectors, and most fixings, of a harness `install.toml` is written for: the
/// sequence runs under the explicit solver, whose step thin wires make microseconds long,
/// and every connector and fixing adds a second or more (a branch, a small harness; the
/// generator cable's takes 2.3 million steps).
pub const MAX_INSTALLED: usize = 8;

/// Why no `install.toml` is written for a harness.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub enum NotInstalled {
    /// No connector sits on a free end: nothing to start the sequence from.
    NoConnector,
    /// More connectors or fixings than [`MAX_INSTALLED`].
    TooLarge { connectors: usize, fixings: usize },
}

impl std::fmt::Display for NotInstalled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NotInstalled::NoConnector => write!(f, "no connector on a free end to start from"),
            NotInstalled::TooLarge {
                connectors,
                fixings,
            } => write!(
                f,
                "{connectors} connectors and {fixings} fixings: the worker's sequence is written for up to {MAX_INSTALLED} of each (a branch or a small harness)"
            ),
        }
    }
}

/// The text of `install.toml` (see the module's sequence), or why there is none.
pub fn install_toml(
    h: &Harness,
    segs: &[SegmentOut],
    licence_note: &str,
) -> Result<String, NotInstalled> {
    let connectors = connector_ends(h, segs);
    let clips = clip_places(h, segs);
    if connectors.len() > MAX_INSTALLED || clips.len() > MAX_INSTALLED {
        return Err(NotInstalled::TooLarge {
            connectors: connectors.len(),
            fixings: clips.len(),
        });
    }
    let first = connectors.first().ok_or(NotInstalled::NoConnector)?;
    // the explicit solver: hands, connectors and clips act through their dynamics (thin
    // wires make its step a few microseconds; the sequence lasts a few seconds)
    let mut t = network_toml(h, segs, licence_note, "solver = \"explicit\"");
    let _ = writeln!(
        t,
        "# The body: a panel behind every fixing, its clip's seat on the route; a counterpart\n# housing behind every connector end, its mouth {} mm before the route's end.\n",
        mm(PUSH)
    );
    for c in &clips {
        let s = seat(c);
        let centre = s - c.opening * (0.5 * c.d_outer + PANEL_GAP + 0.5 * PANEL.1);
        box_part(
            &mut t,
            &format!("panel {}", c.name),
            centre,
            [PANEL.0 * c.d_outer, PANEL.0 * c.d_outer, PANEL.1],
            c.opening,
        );
        clip_toml(&mut t, c, s);
    }
    let curve: Vec<String> = MATING_CURVE
        .iter()
        .map(|(s, f)| format!("[{s}, {f}]"))
        .collect();
    for c in &connectors {
        let size = (2.0 * c.d_outer).max(0.015);
        let depth = 0.020;
        let face = TRAVEL + 0.5 * c.d_outer + 0.002;
        box_part(
            &mut t,
            &format!("housing {}", c.name),
            c.mouth + c.axis * (face + 0.5 * depth),
            [size, size, depth],
            c.axis,
        );
        let _ = writeln!(
            t,
            "[[connectors]]\nname = {}\norigin = {}\naxis = {}\ntravel = {}\n# assumption: KBL gives no mating force; take the connector's datasheet curve\nmating_force = [{}]\nlatch_at = {LATCH_AT_MM}\nretention_force_n = {RETENTION_N}\nsize = {}\nhose = {}\nend = \"{}\"\n",
            quote(&c.name),
            vec_mm(c.mouth),
            unit_vec(c.axis),
            mm(TRAVEL),
            curve.join(", "),
            mm(size),
            quote(&c.hose),
            if c.at_start { "start" } else { "end" }
        );
    }
    // the left hand (1) holds the harness at its first fixing, or, without fixings, at its
    // second connector's end, while the right hand (0) plugs the first connector
    let _ = writeln!(
        t,
        "# The worker: the left hand (1) holds the harness at its first fixing (or its second\n# connector's end), the right hand (0) plugs the first connector; the fixings are pressed\n# in, the other connectors plugged.\n"
    );
    let held_connector = clips.is_empty() && connectors.len() > 1;
    if let Some(c) = clips.first() {
        step(
            &mut t,
            &format!(
                "action = \"grab\"\nhand = 1\nat = {}\ngrip = \"ball\"",
                vec_mm(c.point)
            ),
        );
    } else if held_connector {
        step(
            &mut t,
            &format!(
                "action = \"grab\"\nhand = 1\nat = {}",
                vec_mm(connectors[1].mouth + connectors[1].axis * PUSH)
            ),
        );
    }
    plug(&mut t, first, 0, false);
    for (k, c) in clips.iter().enumerate() {
        // the first fixing is pressed in by the hand that has held the harness there
        let hand = if k == 0 { 1 } else { 0 };
        let _ = writeln!(t, "# fixing {}", c.name);
        if k > 0 {
            step(
                &mut t,
                &format!(
                    "action = \"grab\"\nhand = 0\nat = {}\ngrip = \"ball\"",
                    vec_mm(c.point)
                ),
            );
        }
        for target in [
            c.point + c.opening * (c.d_outer + LIFT_CLEAR),
            seat(c) - c.opening * PRESS_PAST,
        ] {
            step(
                &mut t,
                &format!(
                    "action = \"move_hand\"\nhand = {hand}\nto = {}\nduration_s = {MOVE_S}",
                    vec_mm(target)
                ),
            );
        }
        step(&mut t, &format!("action = \"release_hand\"\nhand = {hand}"));
    }
    for (k, c) in connectors.iter().enumerate().skip(1) {
        if k == 1 && held_connector {
            plug(&mut t, c, 1, true);
        } else {
            plug(&mut t, c, 0, false);
        }
    }
    step(&mut t, "action = \"settle\"\nmax_duration_s = 5");
    Ok(t)
}
