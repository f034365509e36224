//! Writing `install.toml`: the harness installed by a worker, step by step, into a simple
//! body — connectors plugged against their mating force, fixings pressed into their clips
//! — under the quasi-static solver.
//!
//! The body is made of primitives around the KBL route: at every fixing its clip, the seat
//! on the route; behind every connector end a counterpart housing (a box) whose mouth lies
//! `push` before the route's end (the route is the installed shape: a plug pushed in sits
//! on it). The clips have no panel behind them: the harness hangs before its fixings are
//! pressed in, and would fall onto panels placed without the vehicle's real surfaces
//! around them (the body it lies on is not modelled).
//!
//! The harness is drawn on its route, every segment [`InstallData`]'s slack longer (1 %,
//! bowed between its nodes: a route from CAD is the shortest the bundle may be, and a
//! taut straight stretch leaves a plug or fixing no room to be brought in from beside its
//! place — the copper would have to stretch), in elements of [`INSTALL_ELEMENT_LENGTH`].
//! What holds it before the worker starts: for a branch (`--branch`), the node where it
//! was cut off (the rest of the harness, installed); otherwise the left hand (1), at the
//! end of the last connector (loosely, a ball grip: the plug turns as the harness hangs),
//! which that hand takes firmly and plugs last. The clips are `by_hand`: the
//! route passes through their seats, but a fixing is only taken when the worker presses
//! it in. So the harness first hangs under gravity from what holds it, as a harness does
//! before it is fixed (where a cable simulation's installation sequence starts in the
//! industrial tools).
//!
//! The worker's sequence (hand 0, the right hand, unless said otherwise):
//!
//! 1. every connector: take the plug (the hose's end node, wherever it hangs), carry it
//!    `IN_FRONT` before the counterpart's mouth on the mating axis, turning it to face the
//!    counterpart on the way, and push it `push` in, past the latch; let go (the latched
//!    plug is carried to its seat);
//! 2. every fixing, nearest (along the bundle) to what held the harness at the start
//!    first: take the bundle at the fixing (the beam crossing the fixing's place, wherever
//!    it hangs; a firm grip), carry it in front of the clip, `LIFT_CLEAR` beyond its first
//!    touch of the jaws, turning it onto the route's direction there on the way; press it
//!    in past the seat (the click; `PRESS_PAST` of the way to the jaws' back edge) and ease
//!    off onto the seat; let go;
//! 3. the connector the left hand holds, as in 1; settle.
//!
//! Connectors first: a plug's travel (8 mm, and 2 mm in front of the mouth) must be taken
//! up by the bundle behind it, which hanging free gives way; with the fixings in first, a
//! stub of a few centimetres between a fixing and its plug would have to buckle by the
//! whole travel. A fixing's press-in moves the bundle a few millimetres across itself,
//! which the slack takes up.
//!
//! The hand is displacement-controlled: it holds the plug and moves it at walking pace, so
//! the mating force's drop where the latch clicks is felt as a drop of the hand's force,
//! not a limit point of the load path (the plug cannot run ahead of a hand that holds it).
//! A bundle that buckles or snaps through on the way is followed by the static solver's
//! snap relaxation (crates/core/src/integrators/snap.rs).
//!
//! The verdict then names the connector or fixing whose force the hand could not give
//! ("— plugging connector 'X'", "— pressing the hose into clip 'Y'"), any connector not
//! latched or fixing not seated, and every segment bent below its bend radius. KBL carries
//! no mating forces: each connector gets the curve of `data/installation.toml`
//! ([`crate::install_data`]) for its number of positions.

use std::collections::{BinaryHeap, HashSet};
use std::fmt::Write as _;

use glam::DVec3;

use crate::install_data::InstallData;
use crate::model::Harness;
use crate::scene::{
    clip_places, clip_toml, mm, network_toml_with_slack, quote, sanitise, unit_vec, vec_mm,
    ClipPlace, SegmentOut, STATIC_ITERATIONS,
};

/// How far beyond its first touch of the clip's jaws the hand brings a bundle before
/// pressing it in \[m\]: clear of the jaws.
pub const LIFT_CLEAR: f64 = 0.002;
/// How far past the seat the hand presses a bundle into its clip, as a share of the way
/// from the seat to the jaws' back edge (|n|, where a bundle pressed further leaves the
/// clip through its back).
pub const PRESS_PAST: f64 = 0.5;
/// How far short of home the hand's push ends \[m\]: past the latch, short of the stop.
pub const SHORT_OF_HOME: f64 = 0.0005;
/// Where the hand brings a connector end before pushing: this far before the mouth \[m\].
pub const IN_FRONT: f64 = 0.002;
/// Duration of a hand's move to a clip's seat or before a connector's mouth \[s\].
pub const MOVE_S: f64 = 0.5;
/// Duration of easing off from past the seat back onto it before letting go \[s\].
pub const EASE_S: f64 = 0.2;
/// Duration of a connector's push \[s\]: ≈ 13 mm/s, a slow push at which the hand feels
/// the mating force (quasi-static).
pub const PUSH_S: f64 = 0.75;
/// Target element length of `install.toml` \[m\]: a stub of bundle between a fixing and a
/// plug, a few centimetres long, bends smoothly over several elements as the plug is
/// carried to its counterpart and pushed (at the installed state's 25 mm, three elements
/// of a 7 cm stub kink where it buckles and hold hundreds of newtons).
pub const INSTALL_ELEMENT_LENGTH: f64 = 0.010;
/// Fewest elements per segment in `install.toml`.
pub const INSTALL_MIN_ELEMENTS: usize = 6;

/// Elements of a segment of length `len` \[m\] in `install.toml`.
pub fn install_elements(len: f64) -> usize {
    ((len / INSTALL_ELEMENT_LENGTH).round() as usize).max(INSTALL_MIN_ELEMENTS)
}

/// Farthest a point of the bundle may lie from every support, measured along the bundle
/// \[m\], for `install.toml` to be written. Farther, the bundle hangs like a rope between
/// supports that in the vehicle are the body's surfaces it lies on (not modelled by the
/// body of primitives), and its plugs dangle far below their counterparts: import a branch
/// with its fixings instead (`--branch`).
pub const MAX_FREE_LENGTH: f64 = 0.6;

/// A connector on a leaf end of the network.
struct ConnectorEnd {
    name: String,
    hose: String,
    at_start: bool,
    /// The counterpart's mouth \[m\]: `push` before the route's end, so that the plug
    /// pushed in sits on the route.
    mouth: DVec3,
    /// Out of the bundle along its end: the mating axis.
    axis: DVec3,
    d_outer: f64,
    /// Positions of the housing (0: not known).
    positions: usize,
    /// The harness node it sits on.
    node: usize,
}

fn connector_ends(h: &Harness, segs: &[SegmentOut], push: f64) -> Vec<ConnectorEnd> {
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
        let outward = (h.nodes[node].position - inner).normalize_or(DVec3::X);
        let name = sanitise(c.name.as_deref().unwrap_or(&c.kbl_id));
        if names.contains(&name) {
            continue;
        }
        names.push(name.clone());
        ends.push(ConnectorEnd {
            name,
            hose: segs[s].hose.clone(),
            at_start,
            mouth: h.nodes[node].position - outward * push,
            axis: outward,
            d_outer: segs[s].d_outer_at(if at_start { 0.0 } else { 1.0 }),
            positions: c.positions,
            node,
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

fn step(t: &mut String, fields: &str) {
    let _ = writeln!(t, "[[timeline]]\n{fields}\n");
}

/// `hand` takes the end of connector `c` where it is, firmly or, `ball`, loosely (the plug
/// free to turn in the hand: held while the rest is done, it hangs as it will).
fn grab_end(t: &mut String, c: &ConnectorEnd, hand: usize, ball: bool) {
    step(
        t,
        &format!(
            "action = \"grab\"\nhand = {hand}\nhose = {}\nnode = {}{}",
            quote(&c.hose),
            if c.at_start { 0 } else { -1 },
            if ball { "\ngrip = \"ball\"" } else { "" }
        ),
    );
}

/// `hand` takes the end of connector `c` firmly (a loose hold on it becomes firm) and
/// plugs it.
fn plug(t: &mut String, c: &ConnectorEnd, hand: usize, push: f64) {
    let _ = writeln!(t, "# connector {}", c.name);
    grab_end(t, c, hand, false);
    // carried and turned to face the counterpart at once, then pushed in
    step(
        t,
        &format!(
            "action = \"align_hand\"\nhand = {hand}\ndirection = {}\nto = {}\nduration_s = {MOVE_S}",
            unit_vec(c.axis),
            vec_mm(c.mouth - c.axis * IN_FRONT)
        ),
    );
    step(
        t,
        &format!(
            "action = \"move_hand\"\nhand = {hand}\nto = {}\nduration_s = {PUSH_S}",
            vec_mm(c.mouth + c.axis * push)
        ),
    );
    step(t, &format!("action = \"release_hand\"\nhand = {hand}"));
}

/// Why no `install.toml` is written for a harness.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub enum NotInstalled {
    /// No connector sits on a free end: nothing to start the sequence from.
    NoConnector,
    /// Part of the bundle lies farther than [`MAX_FREE_LENGTH`] from every support.
    Unsupported {
        /// How far, along the bundle \[m\], and the node farthest out.
        length_m: f64,
        node: String,
        fixings: usize,
        connectors: usize,
    },
}

impl std::fmt::Display for NotInstalled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NotInstalled::NoConnector => write!(f, "no connector on a free end to plug"),
            NotInstalled::Unsupported {
                length_m,
                node,
                fixings,
                connectors,
            } => write!(
                f,
                "{connectors} connectors and {fixings} fixings, but the bundle reaches {:.2} m from every fixing (at {node}); \
                 held only at its fixings it would hang like a rope (the body it lies on is not modelled, more than {MAX_FREE_LENGTH} m is not installed). \
                 Install a branch with its fixings: pliant import FILE --branch NODE_OR_SEGMENT",
                length_m
            ),
        }
    }
}

/// Distance along the bundle \[m\] of every node from the nearest of `sources`: (node,
/// distance along the bundle to reach it) pairs.
fn distances(h: &Harness, sources: &[(usize, f64)]) -> Vec<f64> {
    #[derive(PartialEq)]
    struct Item(f64, usize);
    impl Eq for Item {}
    impl PartialOrd for Item {
        fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
            Some(self.cmp(o))
        }
    }
    impl Ord for Item {
        fn cmp(&self, o: &Self) -> std::cmp::Ordering {
            o.0.total_cmp(&self.0)
        }
    }
    let at = h.segments_at_nodes();
    let mut heap: BinaryHeap<Item> = sources.iter().map(|&(n, d)| Item(d, n)).collect();
    let mut dist = vec![f64::INFINITY; h.nodes.len()];
    let mut done = HashSet::new();
    while let Some(Item(d, n)) = heap.pop() {
        if !done.insert(n) {
            continue;
        }
        dist[n] = d;
        for &s in &at[n] {
            let seg = &h.segments[s];
            let other = if seg.start_node == n {
                seg.end_node
            } else {
                seg.start_node
            };
            if !done.contains(&other) {
                heap.push(Item(d + segment_length(h, s), other));
            }
        }
    }
    dist
}

fn segment_length(h: &Harness, s: usize) -> f64 {
    h.segments[s].virtual_length.unwrap_or(0.0)
}

/// Farthest distance along the bundle from any support (the fixings' places and the
/// `held` nodes), and the node where it is reached.
fn farthest_from_support(h: &Harness, held: &[usize]) -> (f64, usize) {
    let mut sources: Vec<(usize, f64)> = held.iter().map(|&n| (n, 0.0)).collect();
    for f in &h.fixings {
        let (s, l) = (&h.segments[f.segment], segment_length(h, f.segment));
        sources.push((s.start_node, f.location * l));
        sources.push((s.end_node, (1.0 - f.location) * l));
    }
    let dist = distances(h, &sources);
    let at = h.segments_at_nodes();
    // nodes no segment reaches are not part of the bundle
    (0..h.nodes.len())
        .filter(|&n| !at[n].is_empty())
        .map(|n| (dist[n], n))
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
}

/// A fixing as the worker presses it in: the clip placed on the route as the model draws
/// it (its seat where the beam crossing the fixing's place passes), the beam the hand
/// takes and where that beam lies on the route.
struct Press {
    clip: ClipPlace,
    /// The hose node the taken beam starts at (it runs to the next node).
    node: usize,
    /// That node's place on the route \[m\].
    at: DVec3,
    /// The taken beam's direction on the route, pointing towards the nearer end of its
    /// hose (what `align_hand` turns it onto).
    towards_end: DVec3,
    /// Distance along the bundle from what holds the harness at the start \[m\].
    reach: f64,
}

/// The fixings in the order the worker presses them: nearest (along the bundle) to the
/// `held` nodes first.
fn presses(h: &Harness, segs: &[SegmentOut], held: &[usize]) -> Vec<Press> {
    let dist = distances(h, &held.iter().map(|&n| (n, 0.0)).collect::<Vec<_>>());
    let mut out: Vec<Press> = h
        .fixings
        .iter()
        .zip(clip_places(h, segs))
        .map(|(f, mut clip)| {
            let out = &segs[f.segment];
            let n = out.elements.max(1);
            let x = f.location.clamp(0.0, 1.0) * n as f64;
            let k = (x.floor() as usize).min(n - 1);
            let (a, _) = out.curve.at_fraction(k as f64 / n as f64);
            let (b, _) = out.curve.at_fraction((k + 1) as f64 / n as f64);
            let chord = (b - a).normalize_or(clip.tangent);
            // the seat where the drawn beam crosses the fixing's place, the clip turned
            // onto the beam: a bundle brought back onto its route lies in the seat
            clip.point = a.lerp(b, x - k as f64);
            clip.tangent = chord;
            let o = clip.opening - chord * clip.opening.dot(chord);
            if o.length() > 1e-6 {
                clip.opening = o.normalize();
            }
            // the runner's rule (crates/assembly/src/runner.rs, held_beam_direction): the
            // beam k → k + 1 of a hose of n + 1 nodes points to its end when
            // n − (k + 1) <= k
            let towards_end = if n - (k + 1) <= k { chord } else { -chord };
            let seg = &h.segments[f.segment];
            let l = segment_length(h, f.segment);
            let reach = (dist[seg.start_node] + f.location * l)
                .min(dist[seg.end_node] + (1.0 - f.location) * l);
            Press {
                clip,
                node: k,
                at: a,
                towards_end,
                reach,
            }
        })
        .collect();
    out.sort_by(|a, b| a.reach.total_cmp(&b.reach));
    out
}

/// The text of `install.toml` (see the module's sequence), or why there is none. `cut`:
/// the node a branch was cut off at (held fixed), if the harness is a branch.
pub fn install_toml(
    h: &Harness,
    segs: &[SegmentOut],
    licence_note: &str,
    cut: Option<usize>,
    data: &InstallData,
) -> Result<String, NotInstalled> {
    // finer elements than the installed state's: the short stubs behind the connectors
    // bend as the plugs are carried and pushed
    let fine: Vec<SegmentOut> = segs
        .iter()
        .map(|s| SegmentOut {
            hose: s.hose.clone(),
            curve: s.curve,
            section: s.section,
            bare: s.bare,
            stretches: s.stretches,
            elements: install_elements(s.curve.length),
            friction: s.friction,
        })
        .collect();
    let segs = &fine[..];
    let travel = data.shape.travel_mm.value * 1e-3;
    let push = travel - SHORT_OF_HOME;
    let connectors = connector_ends(h, segs, push);
    if connectors.is_empty() {
        return Err(NotInstalled::NoConnector);
    }
    // without a cut, the left hand holds the last connector's end throughout
    let hand_holds = cut.is_none();
    let mut held: Vec<usize> = cut.into_iter().collect();
    if hand_holds {
        held.push(connectors[connectors.len() - 1].node);
    }
    let mut supports = held.clone();
    if hand_holds && h.fixings.is_empty() && connectors.len() > 1 {
        // the right hand takes the first end at once (both grabs come before the first
        // step): a cable held at both ends
        supports.push(connectors[0].node);
    }
    let (far, node) = farthest_from_support(h, &supports);
    if far > MAX_FREE_LENGTH {
        return Err(NotInstalled::Unsupported {
            length_m: far,
            node: h.nodes[node].kbl_id.clone(),
            fixings: h.fixings.len(),
            connectors: connectors.len(),
        });
    }
    let presses = presses(h, segs, &held);
    let slack = data.slack.share.value;
    let mut t = network_toml_with_slack(
        h,
        segs,
        licence_note,
        &format!("solver = \"static\"\nstatic_max_iterations = {STATIC_ITERATIONS}"),
        slack,
    );
    let _ = writeln!(
        t,
        "# Assembly slack: every segment is drawn {} % longer than its route, bowed between its\n# nodes ({}).\n",
        round2(slack * 100.0),
        data.slack.share.source
    );
    let _ = writeln!(
        t,
        "# The body: a clip at every fixing, its seat on the route; a counterpart housing behind\n# every connector end, its mouth {} mm before the route's end.\n",
        mm(push)
    );
    // the clips take the bundle when the worker presses it in, not as it hangs by
    for p in &presses {
        clip_toml(&mut t, &p.clip, p.clip.point, true);
    }
    for c in &connectors {
        let law = data.law(c.positions);
        let size = (2.0 * c.d_outer).max(0.015);
        let depth = 0.020;
        let face = travel + 0.5 * c.d_outer + 0.002;
        box_part(
            &mut t,
            &format!("housing {}", c.name),
            c.mouth + c.axis * (face + 0.5 * depth),
            [size, size, depth],
            c.axis,
        );
        let curve: Vec<String> = law
            .curve
            .iter()
            .map(|(s, f)| format!("[{s}, {}]", round2(*f)))
            .collect();
        let positions = if c.positions > 0 {
            format!("{} positions", c.positions)
        } else {
            "positions not given".into()
        };
        let _ = writeln!(
            t,
            "[[connectors]]\nname = {}\norigin = {}\naxis = {}\ntravel = {}\n\
             # KBL gives no mating force: peak {} N for {positions} — {}; the curve's shape,\n\
             # travel and latch are assumptions (crates/harness/data/installation.toml). Put the\n\
             # connector's datasheet curve here where it is known.\n\
             mating_force = [{}]\nlatch_at = {}\nretention_force_n = {}\nsize = {}\nhose = {}\nend = \"{}\"\n",
            quote(&c.name),
            vec_mm(c.mouth),
            unit_vec(c.axis),
            mm(travel),
            round2(law.peak_n),
            law.source.split(';').next().unwrap_or(""),
            curve.join(", "),
            law.latch_at_mm,
            round2(law.retention_n),
            mm(size),
            quote(&c.hose),
            if c.at_start { "start" } else { "end" }
        );
    }
    let _ = writeln!(
        t,
        "# The worker: the harness hangs from {}; the right hand (0) plugs every connector{},\n\
         # then presses every fixing in, nearest to what holds the harness first{}.\n",
        if cut.is_some() {
            "the node where the branch was cut off (the rest of the harness, installed)"
        } else {
            "the left hand (1), which holds the last connector's end"
        },
        if hand_holds { " but that one" } else { "" },
        if hand_holds {
            "; the left hand plugs the one it holds last"
        } else {
            ""
        }
    );
    if let Some(n) = cut {
        let at = h.segments_at_nodes();
        if let Some(&s) = at[n].first() {
            let node = if h.segments[s].start_node == n { 0 } else { -1 };
            let _ = writeln!(t, "# the cut: {}", h.nodes[n].kbl_id);
            step(
                &mut t,
                &format!(
                    "action = \"fix\"\nhose = {}\nnode = {node}",
                    quote(&segs[s].hose)
                ),
            );
        }
    }
    let last = &connectors[connectors.len() - 1];
    if hand_holds {
        // loosely: the plug hangs from the hand as it will, not bent where it is held
        grab_end(&mut t, last, 1, true);
    }
    let by_right = if hand_holds {
        &connectors[..connectors.len() - 1]
    } else {
        &connectors[..]
    };
    for c in by_right {
        plug(&mut t, c, 0, push);
    }
    for p in &presses {
        press_in(&mut t, p);
    }
    if hand_holds {
        plug(&mut t, last, 1, push);
    }
    step(&mut t, "action = \"settle\"\nmax_duration_s = 5");
    Ok(t)
}

/// The right hand takes the bundle at fixing `p` where it hangs, turns it onto the route,
/// brings it in front of the clip and presses it in past the seat, eases off onto the seat
/// and lets go.
fn press_in(t: &mut String, p: &Press) {
    let c = &p.clip;
    let _ = writeln!(t, "# fixing {}", c.name);
    step(
        t,
        &format!(
            "action = \"grab\"\nhand = 0\nhose = {}\nnode = {}",
            quote(&c.hose),
            p.node
        ),
    );
    // carried out of where it hangs and turned onto the route at once, in front of the clip
    step(
        t,
        &format!(
            "action = \"align_hand\"\nhand = 0\ndirection = {}\nto = {}\nduration_s = {MOVE_S}",
            unit_vec(p.towards_end),
            vec_mm(p.at + c.opening * (first_touch(c) + LIFT_CLEAR))
        ),
    );
    for (target, duration) in [
        (
            p.at - c.opening * (PRESS_PAST * opening_distance(c)),
            MOVE_S,
        ),
        (p.at, EASE_S),
    ] {
        step(
            t,
            &format!(
                "action = \"move_hand\"\nhand = 0\nto = {}\nduration_s = {duration}",
                vec_mm(target)
            ),
        );
    }
    step(t, "action = \"release_hand\"\nhand = 0");
}

/// Distance |n| of clip `c`'s opening from its seat (seat diameter D, opening w =
/// [`crate::scene::OPENING_SHARE`] D): √((D/2)² − (w/2)²), as
/// `pliant_assembly::clip::ClipSpec::opening_distance` has it.
fn opening_distance(c: &ClipPlace) -> f64 {
    let (r, w) = (
        0.5 * c.d_outer,
        0.5 * crate::scene::OPENING_SHARE * c.d_outer,
    );
    (r * r - w * w).max(0.0).sqrt()
}

/// Distance of the bundle's centre from the seat when it first touches the jaws of clip
/// `c`: |n| + h, h = √(r² − (w/2)²) = |n| for a bundle of the seat's diameter
/// (`ClipSpec::first_touch`).
fn first_touch(c: &ClipPlace) -> f64 {
    2.0 * opening_distance(c)
}

/// A force with two decimals, without trailing zeros.
fn round2(v: f64) -> String {
    let s = format!("{v:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
