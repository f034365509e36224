//! Temporal coherence for rigid contact: each beam's nearby triangles are found
//! once, with a margin, and kept from step to step until the beam has moved by the margin — the idea of Verlet neighbour lists (L. Verlet, Phys.
//! Rev. 159, 98, 1967) and of the "enlarged bounding volumes" of collision detection
//! (Ericson, "Real-Time Collision Detection", §6.6 / §9.6).
//!
//! A slot's query is a segment [a, b] (a beam; a = b would be a point) with a contact
//! reach ρ. On a
//! refresh every triangle whose box meets the segment's box grown by ρ + m is examined,
//! and those whose distance to the segment is at most ρ + m are kept, in the environment's
//! own order (parts in order, each part's BVH depth-first). The distance from a segment to
//! a fixed set is 1-Lipschitz in the largest end-point displacement (each point
//! (1−t)a + tb moves by at most max(|Δa|, |Δb|)), so while both end points stay within m
//! of where they were, no triangle that was dropped can come within ρ: the kept list
//! holds every triangle that can touch, in the same order as a fresh query, and the
//! contact found from it is the same to the last bit. Most slots keep an empty list (the
//! hose is clear of the parts) and cost one distance check per step; such a slot asks
//! the BVH, best first, for the nearest triangle box within [`FAR`] reaches and may move
//! until that box could come within reach. A node searches the list of one of its beams:
//! a point of the segment is no nearer to any triangle than the segment, and it moves no
//! more than the segment's end points, so the beam's list, bounds and margin serve it.
//!
//! Where they are now: each kept triangle carries its `Planes` (unit normal and the
//! three in-plane edge normals, made at the refresh), whose lower bound on the distance
//! from the searcher's current point or segment rejects most candidates for ≈ 40 flops
//! before the exact test. That lets the margin be small (ρ/16): the Lipschitz slack
//! between refreshes stays tight, and the refreshes stay cheap.
//!
//! Nearest first, and only as far as needed: a refresh keeps the slot's candidates sorted
//! by their distance at the refresh, each with its rank in the environment's own order.
//! A search (`Nearest`) offered them in that order can stop as soon as the next one's
//! lower bound (its recorded distance minus the displacement since) exceeds the best it
//! has, since no later one can beat it; ties are broken by rank, so the contact chosen is
//! the one a fresh query — which offers every triangle in rank order, first found winning
//! ties — would choose, to the last bit. On a fine mesh (a cylinder of 512 facets under a
//! beam) that examines a handful of triangles instead of a hundred.
//!
//! Quiet searchers: a searcher whose last look found nothing and left every candidate's
//! bound beyond its reach (`Quiet`) need not look again while its slot's end points
//! stay within the room those bounds leave (`Settled`) — one displacement test instead
//! of setting up a search, for the beams and nodes that lie near a part without touching
//! it (most of a hose lying on a floor).
//!
//! Storage is allocated once: a fixed number of candidates per slot. A slot that finds
//! more keeps the nearest ones and the distance of the nearest it dropped (its cutoff);
//! while the search's bound stays below the cutoff less the displacement, the dropped
//! ones cannot matter, else the slot is searched by a fresh query (still exact, slower).

use super::closest_segment_triangle;
use super::environment::RigidEnvironment;
use super::planes::Planes;
use super::triangle_set::TriangleSet;
use glam::DVec3;
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::Triangle;

/// Candidates kept per slot.
pub const SLOT_CAPACITY: usize = 48;
/// Margin m as a fraction of the reach ρ: a slot is refreshed after moving ρ/16 (a
/// truncated list sooner, an empty one later, see `CandidateCache::refresh`): the margin
/// of fewest instructions on the bench's floor among ρ/4 … ρ/32 (measurements in
/// docs/performance.md).
pub const MARGIN: f64 = 0.0625;
/// How far (in reaches) a slot with no candidates looks for the nearest triangle, to
/// know how far it may move before its next refresh.
pub const FAR: f64 = 4.0;
/// Relative slack on distances for rounding (the kept test errs towards keeping).
pub(crate) const SLACK: f64 = 1e-9;

/// One triangle of one part, its rank in the environment's order, and its distance from
/// the slot's segment at the refresh. (The planes' lower bound would do in its place and
/// save the refresh its exact tests, but the looser first bounds send more triangles to
/// the searches' exact tests every step.)
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Candidate {
    part: u32,
    triangle: u32,
    rank: u32,
    distance: f64,
}

impl Candidate {
    /// Nearer first, then earlier in the environment's order.
    fn before(&self, other: &Candidate) -> bool {
        self.distance < other.distance
            || (self.distance == other.distance && self.rank < other.rank)
    }
}

/// A search for the nearest triangle that passes the searcher's own test, offered
/// candidate triangles by [`CandidateCache::scan`] or [`scan_fresh`].
pub(crate) trait Nearest {
    /// Considers triangle `tri` of part `part`; `rank` orders the triangles as the
    /// environment does (equal distances: the lower rank wins); `edges` are the edges the
    /// triangle owns (bit k: vertex k to k + 1), the ones a search whose hits lie on
    /// edges measures ([`super::owned_edges`]). Returns a lower bound on the distance at
    /// which the search could accept this triangle, 1-Lipschitz in the searcher's
    /// end-point displacement while the probe stays clear of the triangle (see
    /// [`CandidateCache::scan`]); 0 if nothing is known.
    fn offer(&mut self, part: usize, tri: &Triangle, rank: u32, edges: u8) -> f64;
    /// The distance beyond which no triangle can change the result any more (the best
    /// found so far, or the reach).
    fn bound(&self) -> f64;
    /// Forgets what was found (the search starts over on a fresh query).
    fn reset(&mut self);
    /// Whether a triangle was accepted.
    fn found(&self) -> bool;
}

/// Offers `search` every triangle whose box meets `query`, ranked in the environment's
/// order.
pub(crate) fn scan_fresh(env: &impl TriangleSet, query: &Aabb, search: &mut impl Nearest) {
    let mut rank = 0u32;
    env.for_each_index_near(query, |part, triangle| {
        let (tri, edges) = env.triangle_and_edges(part, triangle);
        search.offer(part, &tri, rank, edges);
        rank += 1;
    });
}

/// The searches that share a slot's list: the beam's interior, and the node at its start
/// or its end. Each keeps its own bounds on the list's candidates
/// ([`CandidateCache::scan`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Searcher {
    Interior = 0,
    StartNode = 1,
    EndNode = 2,
}

/// Searchers per slot.
const SEARCHERS: usize = 3;

/// What [`CandidateCache::clear_slack`] reads of a slot, kept together (one bounds check
/// and one cache line per beam and step): its anchors and reach, and the square of the
/// margin if the slot keeps nothing and dropped nothing (−∞ otherwise, so that no
/// displacement is below it). Written with the slot's fields in
/// [`CandidateCache::anchor`] and [`CandidateCache::clear`].
#[derive(Clone, Copy, Debug)]
struct ClearTest {
    anchor_a: DVec3,
    anchor_b: DVec3,
    reach: f64,
    margin_squared: f64,
}

impl ClearTest {
    const NEVER: ClearTest = ClearTest {
        anchor_a: DVec3::INFINITY,
        anchor_b: DVec3::INFINITY,
        reach: 0.0,
        margin_squared: f64::NEG_INFINITY,
    };
}

/// What one searcher's last look at its slot's list leaves certain: the least of the
/// candidates' face bounds, the least of their larger bounds (face or edge), each plus the
/// travel when found as in [`CandidateCache::scan`], and the refresh distance of the first
/// candidate it did not reach (∞: it saw them all). While these, less the travel since,
/// pass every candidate over, a search that starts from the same bound offers nothing —
/// one test instead of the list (a beam lying near a part but clear of it, most beams
/// near one).
#[derive(Clone, Copy, Debug)]
struct Quiet {
    face: f64,
    either: f64,
    unseen: f64,
}

impl Quiet {
    /// Not known: the list must be looked at.
    const UNKNOWN: Quiet = Quiet {
        face: f64::NEG_INFINITY,
        either: f64::NEG_INFINITY,
        unseen: f64::NEG_INFINITY,
    };

    /// How much farther than `travel` the searcher may travel, and its slot's end points
    /// move from their anchors beyond `moved`, before [`CandidateCache::scan`]'s loop,
    /// started with the search's bound `bound`, could offer a candidate (negative: it
    /// may now). The loop passes candidate k over while its face bound less the travel is
    /// positive (beyond the slack) and one of its bounds lies beyond the limit — true of
    /// all while it is of the least ones — and stops at the first candidate whose refresh
    /// distance less `moved` lies beyond the bound (see `reaches` there).
    fn slack(&self, travel: f64, moved: f64, bound: f64) -> f64 {
        let limit = bound * (1.0 + SLACK);
        (self.face - travel - SLACK * limit)
            .min(self.either - travel - limit)
            .min(self.unseen / (1.0 + SLACK) - bound - moved)
    }
}

/// A searcher whose last search found nothing and proved that a search from the same
/// bound finds nothing while the slot's end points stay within `slack` of where they
/// were (its anchor margin, cutoff and candidates' bounds all allow for it): it need not
/// be searched, nor even set up ([`CandidateCache::settled`]). A Verlet skin per
/// searcher, as [`super::ClearSkin`] is for beams without candidates.
#[derive(Clone, Copy, Debug)]
struct Settled {
    a: DVec3,
    b: DVec3,
    /// The search's bound when it started (its reach).
    bound: f64,
    /// Square of the displacement allowed (−∞: not settled).
    slack_squared: f64,
}

impl Settled {
    const NOT: Settled = Settled {
        a: DVec3::INFINITY,
        b: DVec3::INFINITY,
        bound: 0.0,
        slack_squared: f64::NEG_INFINITY,
    };
}

/// Candidate triangles per slot (one slot per beam), allocated once.
#[derive(Clone, Debug, Default)]
pub struct CandidateCache {
    /// Whether the lists are used; off, every query goes to the environment's BVH
    /// (the reference the coherent path is tested against).
    pub enabled: bool,
    /// End points and reach of each slot's last refresh (∞: never refreshed).
    anchor_a: Vec<DVec3>,
    anchor_b: Vec<DVec3>,
    reach: Vec<f64>,
    /// How far each slot's end points may move before its next refresh.
    margin: Vec<f64>,
    /// Number of candidates of each slot.
    len: Vec<u32>,
    /// Refresh distance of the nearest triangle each slot dropped for want of room
    /// (∞: none dropped).
    cutoff: Vec<f64>,
    /// Each slot's [`ClearTest`] (derived from the fields above).
    clear_test: Vec<ClearTest>,
    /// Counts the changes of any slot's anchors (refreshes and clears), so that a
    /// [`super::ClearSkin`] knows the lists it saw.
    generation: u64,
    /// `SLOT_CAPACITY` entries per slot.
    items: Vec<Candidate>,
    /// The bounding planes of each entry's triangle (same places as `items`).
    planes: Vec<Planes>,
    /// Per searcher of each slot (`SEARCHERS` per slot): the slot's end points when it
    /// last searched, and the path its end points travelled since the slot's refresh
    /// (the sum of the larger end-point displacement of each search).
    seen_a: Vec<DVec3>,
    seen_b: Vec<DVec3>,
    travel: Vec<f64>,
    /// Per searcher and candidate (`SLOT_CAPACITY` per searcher of each slot): lower
    /// bounds [edge, face] (see [`CandidateCache::scan`]), each plus the searcher's
    /// travel when it was found, so that subtracting the travel now keeps it valid.
    lower: Vec<[f64; 2]>,
    /// Per searcher of each slot: what its last look at the list leaves certain
    /// ([`Quiet`]).
    quiet: Vec<Quiet>,
    /// Per searcher of each slot: whether it may skip its search ([`Settled`]).
    settled: Vec<Settled>,
    /// Parts and triangles of the environment the lists were made for.
    environment_key: (usize, usize),
    /// Refreshes made (a counter for benchmarks and tests).
    pub refreshes: u64,
    /// Refreshes that found more triangles than a slot keeps (a counter).
    pub truncations: u64,
    /// Searches a truncated list could not decide, so a fresh query did (a counter).
    pub fresh_fallbacks: u64,
}

/// Distance from segment [a, b] (a point if a = b) to `tri`.
fn segment_distance(a: DVec3, b: DVec3, tri: &Triangle) -> f64 {
    if a == b {
        (tri.project_local_point(a, false).point - a).length()
    } else {
        closest_segment_triangle(a, b, tri).distance
    }
}

/// The box of segment [a, b] grown by `grow` on every side.
fn grown_box(a: DVec3, b: DVec3, grow: f64) -> Aabb {
    let grow = DVec3::splat(grow);
    Aabb::new(a.min(b) - grow, a.max(b) + grow)
}

impl CandidateCache {
    /// A cache of `slots` slots, enabled; empty (and unused) without an environment.
    pub fn new(slots: usize, env: &RigidEnvironment) -> Self {
        Self::for_set(if env.is_empty() { 0 } else { slots }, env)
    }

    /// A cache of `slots` slots for the triangles of `set`, enabled.
    pub(crate) fn for_set(slots: usize, set: &impl TriangleSet) -> Self {
        CandidateCache {
            enabled: true,
            anchor_a: vec![DVec3::INFINITY; slots],
            anchor_b: vec![DVec3::INFINITY; slots],
            reach: vec![0.0; slots],
            margin: vec![0.0; slots],
            len: vec![0; slots],
            cutoff: vec![f64::INFINITY; slots],
            clear_test: vec![ClearTest::NEVER; slots],
            generation: 0,
            items: vec![Candidate::default(); slots * SLOT_CAPACITY],
            planes: vec![Planes::default(); slots * SLOT_CAPACITY],
            seen_a: vec![DVec3::ZERO; slots * SEARCHERS],
            seen_b: vec![DVec3::ZERO; slots * SEARCHERS],
            travel: vec![0.0; slots * SEARCHERS],
            lower: vec![[0.0; 2]; slots * SEARCHERS * SLOT_CAPACITY],
            quiet: vec![Quiet::UNKNOWN; slots * SEARCHERS],
            settled: vec![Settled::NOT; slots * SEARCHERS],
            environment_key: set.key(),
            refreshes: 0,
            truncations: 0,
            fresh_fallbacks: 0,
        }
    }

    /// Forgets every list (the next query of each slot refreshes it).
    pub fn clear(&mut self) {
        self.anchor_a.fill(DVec3::INFINITY);
        self.anchor_b.fill(DVec3::INFINITY);
        for t in &mut self.clear_test {
            (t.anchor_a, t.anchor_b) = (DVec3::INFINITY, DVec3::INFINITY);
        }
        self.settled.fill(Settled::NOT);
        self.generation += 1;
    }

    /// The reach `slot`'s list was last made for (0: never).
    pub(crate) fn slot_reach(&self, slot: usize) -> f64 {
        self.reach.get(slot).copied().unwrap_or(0.0)
    }

    /// Bytes a slot takes ([`Self::for_set`] allocates this per slot).
    pub(crate) const BYTES_PER_SLOT: usize = SLOT_CAPACITY
        * (std::mem::size_of::<Candidate>()
            + std::mem::size_of::<Planes>()
            + SEARCHERS * std::mem::size_of::<[f64; 2]>())
        + SEARCHERS * (2 * std::mem::size_of::<DVec3>() + std::mem::size_of::<f64>())
        + SEARCHERS * (std::mem::size_of::<Quiet>() + std::mem::size_of::<Settled>())
        + std::mem::size_of::<ClearTest>()
        + 2 * std::mem::size_of::<DVec3>()
        + 4 * std::mem::size_of::<f64>();

    /// Changes whenever any slot's anchors change ([`Self::clear`], refreshes).
    pub(crate) fn generation(&self) -> u64 {
        self.generation
    }

    /// Finds the slot's candidates anew around [a, b] (see the module doc), with their
    /// [`Planes`] (which also reject most triangles beyond the kept distance before the
    /// exact distance is taken). A slot that finds none looks up to [`FAR`] reaches out
    /// for the nearest triangle's box, and may move until that could come within reach.
    fn refresh(&mut self, env: &impl TriangleSet, slot: usize, a: DVec3, b: DVec3, reach: f64) {
        let keep = (reach * (1.0 + MARGIN)) * (1.0 + SLACK);
        let base = slot * SLOT_CAPACITY;
        // A slot that found nothing last time likely finds nothing again: the nearest
        // box first, and if it lies beyond `keep` (with room for rounding) no triangle
        // can be kept, and the box query is skipped.
        let mut nearest_box = None;
        if self.len[slot] == 0 && self.anchor_a[slot].is_finite() {
            let nearest = env.nearest_box(a, b, FAR * reach);
            nearest_box = Some(nearest); // the same if the list stays empty below
            if nearest > keep * (1.0 + SLACK) {
                self.len[slot] = 0;
                self.cutoff[slot] = f64::INFINITY;
                self.margin[slot] = Self::empty_margin(nearest, keep, reach);
                self.anchor(slot, a, b, reach);
                return;
            }
        }
        let query = grown_box(a, b, keep);
        let exact_within = reach * (1.0 + SLACK);
        let (mut n, mut cutoff, mut rank) = (0usize, f64::INFINITY, 0u32);
        let items = &mut self.items[base..base + SLOT_CAPACITY];
        env.for_each_index_near(&query, |part, triangle| {
            let this_rank = rank;
            rank += 1;
            let planes = env.planes(part, triangle);
            let bound_squared = planes.lower_bound_squared(a, b);
            if bound_squared > keep * keep {
                return;
            }
            let distance = if bound_squared > exact_within * exact_within {
                bound_squared.sqrt()
            } else {
                let (tri, _) = env.triangle_and_edges(part, triangle);
                let distance = segment_distance(a, b, &tri);
                if distance > keep {
                    return;
                }
                distance
            };
            let c = Candidate {
                part: part as u32,
                triangle,
                rank: this_rank,
                distance,
            };
            // insertion into the sorted list of the nearest SLOT_CAPACITY
            if n == SLOT_CAPACITY {
                if !c.before(&items[n - 1]) {
                    cutoff = cutoff.min(c.distance);
                    return;
                }
                cutoff = cutoff.min(items[n - 1].distance);
                n -= 1;
            }
            let mut k = n;
            while k > 0 && c.before(&items[k - 1]) {
                items[k] = items[k - 1];
                k -= 1;
            }
            items[k] = c;
            n += 1;
        });
        for k in 0..n {
            let c = &self.items[base + k];
            self.planes[base + k] = *env.planes(c.part as usize, c.triangle);
        }
        self.len[slot] = n as u32;
        self.cutoff[slot] = cutoff;
        // A truncated list decides a search while the best stays below the cutoff less
        // the displacement; the best is at most the nearest's distance plus it, so a
        // refresh after half the spread keeps most searches on the list.
        self.margin[slot] = if n > 0 && cutoff.is_finite() {
            (MARGIN * reach).min(0.5 * (cutoff - self.items[base].distance))
        } else if n == 0 {
            // every triangle lies beyond `keep`, and beyond its box's distance
            let nearest = nearest_box.unwrap_or_else(|| env.nearest_box(a, b, FAR * reach));
            Self::empty_margin(nearest, keep, reach)
        } else {
            MARGIN * reach
        };
        self.anchor(slot, a, b, reach);
        self.truncations += u64::from(cutoff.is_finite());
    }

    /// Records a refresh of `slot` at [a, b]: every searcher starts from there, with the
    /// refresh distances (a lower bound for any probe on the segment) as its bounds.
    fn anchor(&mut self, slot: usize, a: DVec3, b: DVec3, reach: f64) {
        self.anchor_a[slot] = a;
        self.anchor_b[slot] = b;
        self.reach[slot] = reach;
        self.refreshes += 1;
        self.generation += 1;
        let base = slot * SLOT_CAPACITY;
        let n = self.len[slot] as usize;
        let m = self.margin[slot];
        self.clear_test[slot] = ClearTest {
            anchor_a: a,
            anchor_b: b,
            reach,
            margin_squared: if n == 0 && self.cutoff[slot] == f64::INFINITY {
                m * m
            } else {
                f64::NEG_INFINITY
            },
        };
        // every bound is the refresh distance, the nearest's the least
        let nearest = if n > 0 {
            self.items[base].distance
        } else {
            f64::INFINITY
        };
        for s in slot * SEARCHERS..(slot + 1) * SEARCHERS {
            self.seen_a[s] = a;
            self.seen_b[s] = b;
            self.travel[s] = 0.0;
            for k in 0..n {
                let d = self.items[base + k].distance;
                self.lower[s * SLOT_CAPACITY + k] = [d, d];
            }
            self.quiet[s] = Quiet {
                face: nearest,
                either: nearest,
                unseen: f64::INFINITY,
            };
        }
    }

    /// How far a slot that keeps no triangle may move: until the nearest triangle box
    /// (at `nearest`, or beyond `keep`) could come within `reach`.
    fn empty_margin(nearest: f64, keep: f64, reach: f64) -> f64 {
        (nearest.max(keep) / (1.0 + SLACK) - reach).max(MARGIN * reach)
    }

    /// Forgets every list if the environment is not the one they were made for; once a
    /// step, before [`Self::clear_slack`] and [`Self::scan`].
    pub(crate) fn follow(&mut self, env: &impl TriangleSet) {
        if self.environment_key != env.key() {
            self.environment_key = env.key();
            self.clear();
        }
    }

    /// `Some` if [`Self::scan`] of `slot` at [a, b] would offer nothing without a look at
    /// the list: the list is empty, nothing was dropped, and the slot has not moved past
    /// its margin (no triangle can be within reach) — most slots, checked once a step per
    /// beam (after [`Self::follow`]) before a search is set up. The value is how much
    /// farther (less relative slack for rounding) both end points may move before the
    /// answer could change: the slot's margin less the larger end-point displacement
    /// (for [`super::ClearSkin`]).
    pub(crate) fn clear_slack(&self, slot: usize, a: DVec3, b: DVec3, reach: f64) -> Option<f64> {
        let t = self.clear_test.get(slot).filter(|_| self.enabled)?;
        if t.margin_squared == f64::NEG_INFINITY {
            return None; // the slot keeps or dropped triangles
        }
        let moved = (a - t.anchor_a)
            .length_squared()
            .max((b - t.anchor_b).length_squared());
        (moved < t.margin_squared && t.reach == reach)
            .then(|| t.margin_squared.sqrt() * (1.0 - SLACK) - moved.sqrt() * (1.0 + SLACK))
    }

    /// Offers `search` the triangles whose box meets `query` and which may lie within its
    /// bound of `probe` — a point or segment on segment [a, b] of the slot (a = b for a
    /// point) — nearest first, until no later one can matter; the result is that of
    /// [`scan_fresh`] (see the module doc), if [`Self::follow`] was asked this step.
    /// `query` must contain the probe's box grown by `search.bound()`, which must not
    /// exceed `reach`. A probe on the slot's segment is
    /// no nearer to any triangle than the segment, so the slot's list serves it (a node
    /// uses its beam's list).
    ///
    /// Each `searcher` of the slot keeps, per candidate, two lower bounds from its last
    /// look at it, less the path `D` its end points travelled since (the distance to a
    /// fixed set is 1-Lipschitz in the end points' displacement, and the displacements
    /// of successive steps add up to at most their path): `face` bounds the probe's
    /// distance to the triangle (the [`Planes`] bound, or the refresh distance), `edge`
    /// what [`Nearest::offer`] returned (for a beam's interior, the distance from the
    /// segment to the edges the triangle owns, which bounds any hit of it that does not
    /// pierce the face; a shared edge's other triangles leave it to its owner, so a
    /// beam lying across it revisits one triangle, not two). A candidate is passed over, without its planes, while
    /// `face − D` exceeds the search's bound, or is positive (the probe cannot have
    /// reached the face) with `edge − D` beyond the bound: a hose at rest on a surface
    /// revisits its touching triangles, not all it lies near (a persistent contact
    /// manifold, re-validated by the Lipschitz bound instead of re-searched).
    ///
    /// A search that finds nothing leaves its searcher [`Settled`] for as long as those
    /// bounds, the slot's margin and its cutoff allow: [`Self::settled`] then answers
    /// for it without a search.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn scan(
        &mut self,
        env: &impl TriangleSet,
        slot: usize,
        a: DVec3,
        b: DVec3,
        reach: f64,
        searcher: Searcher,
        probe: [DVec3; 2],
        query: &Aabb,
        search: &mut impl Nearest,
    ) {
        if !self.enabled || slot >= self.len.len() {
            return scan_fresh(env, query, search);
        }
        let s = slot * SEARCHERS + searcher as usize;
        self.settled[s] = Settled::NOT;
        let mut moved = (a - self.anchor_a[slot])
            .length_squared()
            .max((b - self.anchor_b[slot]).length_squared());
        let m = self.margin[slot];
        if !(moved < m * m) || self.reach[slot] != reach {
            self.refresh(env, slot, a, b, reach);
            moved = 0.0;
        }
        let len = self.len[slot] as usize;
        if len == 0 && self.cutoff[slot] == f64::INFINITY {
            return; // nothing kept, nothing dropped: no triangle within reach (most slots)
        }
        // a candidate that was d away can be no nearer than d − moved now
        let moved = moved.sqrt();
        let reaches = |distance: f64, bound: f64| distance <= (bound + moved) * (1.0 + SLACK);
        let step = (a - self.seen_a[s])
            .length_squared()
            .max((b - self.seen_b[s]).length_squared())
            .sqrt();
        (self.seen_a[s], self.seen_b[s]) = (a, b);
        self.travel[s] += step;
        let travel = self.travel[s];
        let start = search.bound();
        let mut room = self.quiet[s].slack(travel, moved, start);
        if room.is_nan() || room <= 0.0 {
            // not quiet (or NaN): walk the list, which records what it leaves certain
            self.search_list(env, slot, s, probe, query, moved, search);
            room = self.quiet[s].slack(travel, moved, start);
        }
        let cutoff = self.cutoff[slot];
        if reaches(cutoff, search.bound()) {
            // a dropped triangle might still matter: ask the environment
            search.reset();
            self.fresh_fallbacks += 1;
            return scan_fresh(env, query, search);
        }
        if !search.found() {
            let slack = room
                .min(cutoff / (1.0 + SLACK) - start - moved)
                .min(self.margin[slot] - moved)
                - SLACK * start;
            if slack > 0.0 {
                self.settled[s] = Settled {
                    a,
                    b,
                    bound: start,
                    slack_squared: slack * slack,
                };
            }
        }
    }

    /// Whether `searcher` of `slot`, its end points now at [a, b] and its search starting
    /// from `bound`, would find nothing ([`Settled`]): its last search found nothing and
    /// they moved less than that search allowed. Then [`Self::scan`] need not be asked.
    pub(crate) fn settled(
        &self,
        slot: usize,
        searcher: Searcher,
        a: DVec3,
        b: DVec3,
        bound: f64,
    ) -> bool {
        let Some(q) = self.settled.get(slot * SEARCHERS + searcher as usize) else {
            return false;
        };
        if q.slack_squared == f64::NEG_INFINITY {
            return false;
        }
        let moved = (a - q.a).length_squared().max((b - q.b).length_squared());
        // a search from a smaller bound accepts less: it finds nothing too
        self.enabled && moved < q.slack_squared && bound <= q.bound
    }

    /// [`Self::scan`]'s walk through the list of `slot` for searcher `s` (see there),
    /// nearest first; records what it leaves certain ([`Quiet`]).
    #[allow(clippy::too_many_arguments)]
    fn search_list(
        &mut self,
        env: &impl TriangleSet,
        slot: usize,
        s: usize,
        probe: [DVec3; 2],
        query: &Aabb,
        moved: f64,
        search: &mut impl Nearest,
    ) {
        let reaches = |distance: f64, bound: f64| distance <= (bound + moved) * (1.0 + SLACK);
        let travel = self.travel[s];
        let (base, len) = (slot * SLOT_CAPACITY, self.len[slot] as usize);
        // the slot's candidates, their planes and the searcher's bounds, side by side
        // (iterated together: no index is checked per candidate)
        let items = &self.items[base..base + len];
        let planes = &self.planes[base..base + len];
        let bounds = &mut self.lower[s * SLOT_CAPACITY..s * SLOT_CAPACITY + len];
        // accumulated in registers and written once: a store per candidate would make
        // each iteration wait for the last one's
        let (mut least_face, mut least_either) = (f64::INFINITY, f64::INFINITY);
        let mut unseen = f64::INFINITY;
        for ((r, planes), lower) in items.iter().zip(planes).zip(bounds) {
            let bound = search.bound();
            if !reaches(r.distance, bound) {
                unseen = r.distance;
                break; // sorted: no later candidate can reach either
            }
            let limit = bound * (1.0 + SLACK);
            let [mut edge, mut face] = *lower;
            if !(face - travel > limit || (face - travel > SLACK * limit && edge - travel > limit))
            {
                let bound_squared = planes.lower_bound_squared(probe[0], probe[1]);
                if bound_squared > limit * limit {
                    // where it is now, it cannot
                    face = bound_squared.sqrt() + travel;
                    lower[1] = face;
                } else {
                    let (tri, edges) = env.triangle_and_edges(r.part as usize, r.triangle);
                    if triangle_box_meets(&tri, query) {
                        let offered = search.offer(r.part as usize, &tri, r.rank, edges);
                        [edge, face] = [offered + travel, bound_squared.sqrt() + travel];
                        *lower = [edge, face];
                    }
                }
            } // else: as last seen, less the way travelled since, it cannot
            least_face = lesser(face, least_face);
            least_either = lesser(greater(face, edge), least_either);
        }
        self.quiet[s] = Quiet {
            face: least_face,
            either: least_either,
            unseen,
        };
    }
}

/// The lesser of `a` and `b` (`b` if they are unordered): one `minsd`, where `f64::min`'s
/// NaN rule costs several instructions. (A NaN bound can only come from NaN positions,
/// whose travel is NaN too: the searcher is then never quiet.)
#[inline(always)]
fn lesser(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// The greater of `a` and `b` (`b` if they are unordered), as [`lesser`].
#[inline(always)]
fn greater(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// Whether the box of `tri` meets `query`, inclusively: the answer of parry's
/// `tri.local_aabb()` and box test, as the BVH applies it to its leaves, for finite
/// vertices, without the NaN rules of its minima and maxima.
#[inline(always)]
fn triangle_box_meets(tri: &Triangle, query: &Aabb) -> bool {
    // axis by axis, written out: a loop over indexed axes costs ≈ 5× as much
    let meets = |a: f64, b: f64, c: f64, low: f64, high: f64| {
        lesser(lesser(a, b), c) <= high && greater(greater(a, b), c) >= low
    };
    let (a, b, c, low, high) = (tri.a, tri.b, tri.c, query.mins, query.maxs);
    meets(a.x, b.x, c.x, low.x, high.x)
        && meets(a.y, b.y, c.y, low.y, high.y)
        && meets(a.z, b.z, c.z, low.z, high.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::RigidPartSpec;

    /// A prism of `n` facets around the y axis, radius 50 mm, 0.4 m long.
    fn fine_cylinder(n: usize) -> RigidEnvironment {
        let mut vertices = Vec::new();
        for y in [-0.2, 0.2] {
            for k in 0..n {
                let phi = std::f64::consts::TAU * k as f64 / n as f64;
                vertices.push(DVec3::new(0.05 * phi.cos(), y, 0.05 * phi.sin()));
            }
        }
        let triangles = (0..n as u32)
            .flat_map(|a| {
                let b = (a + 1) % n as u32;
                let (c, d) = (a + n as u32, b + n as u32);
                [[a, b, d], [a, d, c]]
            })
            .collect();
        RigidEnvironment::build(&[RigidPartSpec {
            name: "cylinder".into(),
            vertices,
            triangles,
            friction_static: 0.5,
            friction_sliding: 0.5,
            ..Default::default()
        }])
        .unwrap()
    }

    /// The nearest triangle to a point whose centroid lies at x ≥ `x_min`: a test the
    /// triangles nearest the point fail, so a truncated list cannot decide it.
    struct NearestBeyond {
        x: DVec3,
        x_min: f64,
        reach: f64,
        /// Distance, rank, closest point, and the triangle's first vertex (its identity).
        best: Option<(f64, u32, DVec3, DVec3)>,
    }

    impl Nearest for NearestBeyond {
        fn offer(&mut self, _part: usize, tri: &Triangle, rank: u32, _edges: u8) -> f64 {
            if (tri.a.x + tri.b.x + tri.c.x) / 3.0 < self.x_min {
                return 0.0;
            }
            let q = tri.project_local_point(self.x, false).point;
            let d = (q - self.x).length();
            let better = |b: &(f64, u32, DVec3, DVec3)| d < b.0 || (d == b.0 && rank < b.1);
            if d <= self.reach && self.best.as_ref().is_none_or(better) {
                self.best = Some((d, rank, q, tri.a));
            }
            d
        }
        fn bound(&self) -> f64 {
            self.best.map_or(self.reach, |b| b.0)
        }
        fn reset(&mut self) {
            self.best = None;
        }
        fn found(&self) -> bool {
            self.best.is_some()
        }
    }

    /// A point that wanders in and out of reach of a fine cylinder, with jitter, searched
    /// as [`super::super::rigid`] does: whenever its slot is clear or its searcher settled,
    /// a fresh query finds nothing; otherwise the kept list finds what the fresh query
    /// finds.
    #[test]
    fn a_settled_searcher_would_find_nothing() {
        let env = fine_cylinder(256);
        let mut cache = CandidateCache::new(1, &env);
        let reach = 0.0101;
        let mut uniform = super::super::test_random::uniform(0x9e37_79b9_7f4a_7c15);
        let mut jitter = || uniform() * 2e-6;
        let (mut settled, mut searched, mut touching) = (0, 0, 0);
        for step in 0..6000 {
            let t = step as f64;
            let radius = 0.0605 + 0.0025 * (t / 1000.0).sin();
            let phi = 1.0 + 0.2 * (t / 1700.0).sin();
            let x = DVec3::new(
                radius * phi.cos(),
                0.01 * (t / 900.0).cos(),
                radius * phi.sin(),
            ) + DVec3::new(jitter(), jitter(), jitter());
            let query = Aabb::new(x - DVec3::splat(reach), x + DVec3::splat(reach));
            let search = || NearestBeyond {
                x,
                x_min: -1.0,
                reach,
                best: None,
            };
            let mut fresh = search();
            scan_fresh(&env, &query, &mut fresh);
            let found = |s: &NearestBeyond| s.best.map(|(d, _, q, a)| (d, q, a));
            touching += usize::from(fresh.found());
            if cache.clear_slack(0, x, x, reach).is_some() {
                assert!(
                    !fresh.found(),
                    "step {step}: clear, but a triangle is within reach"
                );
            } else if cache.settled(0, Searcher::StartNode, x, x, reach) {
                assert!(
                    !fresh.found(),
                    "step {step}: settled, but a triangle is within reach"
                );
                settled += 1;
            } else {
                let mut kept = search();
                let searcher = Searcher::StartNode;
                cache.scan(&env, 0, x, x, reach, searcher, [x, x], &query, &mut kept);
                assert_eq!(found(&kept), found(&fresh), "step {step}");
                searched += 1;
            }
        }
        assert!(
            touching > 1000 && touching < 5000,
            "{touching} steps in reach"
        );
        // the band between reach and the kept distance is crossed twice, ≈ 250 steps each
        assert!(settled > 200, "{settled} settled, {searched} searched");
    }

    /// A search the kept nearest triangles cannot answer falls back to a fresh query and
    /// finds what the fresh query finds; one they answer stays on the list.
    #[test]
    fn truncated_lists_fall_back_to_fresh_queries_when_they_cannot_decide() {
        let env = fine_cylinder(1024);
        let mut cache = CandidateCache::new(1, &env);
        let reach = 0.0101;
        for (k, x_min) in [(0, -1.0), (1, 0.006), (2, -1.0)] {
            let x = DVec3::new(0.0005 * k as f64, 0.0, 0.056);
            let query = Aabb::new(x - DVec3::splat(reach), x + DVec3::splat(reach));
            let search = |x_min| NearestBeyond {
                x,
                x_min,
                reach,
                best: None,
            };
            let (mut kept, mut fresh) = (search(x_min), search(x_min));
            let before = cache.fresh_fallbacks;
            let searcher = Searcher::StartNode;
            cache.scan(&env, 0, x, x, reach, searcher, [x, x], &query, &mut kept);
            scan_fresh(&env, &query, &mut fresh);
            assert!(fresh.best.is_some(), "search {k} finds nothing");
            // the same triangle and point (ranks count in different queries)
            let found = |s: &NearestBeyond| s.best.map(|(d, _, q, a)| (d, q, a));
            assert_eq!(found(&kept), found(&fresh), "search {k}");
            let fell_back = cache.fresh_fallbacks > before;
            assert_eq!(fell_back, x_min > 0.0, "search {k}");
        }
        assert!(cache.truncations > 0);
    }
}
