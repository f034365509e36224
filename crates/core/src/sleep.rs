//! Sleeping hoses (SPEC I6, dissertation §5.2.2: "only hoses near the action need
//! simulating"): in an interactive session a hose that has come to rest and that nothing
//! moves is frozen — its elements are not evaluated and its nodes are held where they are
//! — until something touches it again. Off by default (scripted runs and the validation
//! suite simulate everything); `pliant serve` switches it on.
//!
//! A hose falls asleep when, for [`SLEEP_AFTER_STEPS`] steps in a row, every node is
//! slower than [`SLEEP_SPEED`], no kinematic load case moves any of its nodes and no other
//! hose touches it. It wakes when a kinematic load case on one of its nodes moves, when a
//! load case on it is added or removed ([`Sleep::wake`], called by whoever changes them),
//! or when an awake hose comes into contact with it, or when a hose tied to it by a cable
//! tie ([`crate::loads::Tie`]) moves. Hoses joined by junctions ([`crate::junction`])
//! sleep and wake together, as one network: a network falls asleep when all its hoses
//! are calm, and wakes whole.
//!
//! A network lying on one moving part is calm when its nodes are at rest *relative to the
//! part*; it then sleeps carried by the part ([`carried`]), and wakes besides when the
//! part's motion would make it slip, lift off or sag, or carries it into something.

pub mod carried;

use crate::{Model, State};
use glam::DVec3;

/// Node speed below which a hose counts as at rest \[m/s\].
pub const SLEEP_SPEED: f64 = 1e-4;
/// Consecutive calm steps before a hose sleeps.
pub const SLEEP_AFTER_STEPS: u32 = 2000;

/// Sleep state of the hoses of a [`State`].
#[derive(Clone, Debug, Default)]
pub struct Sleep {
    /// Whether hoses may sleep at all.
    pub enabled: bool,
    /// Per hose: asleep now.
    pub hose_asleep: Vec<bool>,
    /// Per node: its hose is asleep (for the step's inner loops).
    pub node_asleep: Vec<bool>,
    /// Per hose: calm steps in a row.
    calm: Vec<u32>,
    /// Per node: the hose–hose contact force when its hose fell asleep.
    contact_at_sleep: Vec<DVec3>,
    /// The hoses asleep on a moving part, carried by it.
    pub carried: carried::Carriage,
}

impl Sleep {
    pub fn new(model: &Model) -> Self {
        Sleep {
            enabled: false,
            hose_asleep: vec![false; model.hoses.len()],
            node_asleep: vec![false; model.node_count()],
            calm: vec![0; model.hoses.len()],
            contact_at_sleep: vec![DVec3::ZERO; model.node_count()],
            carried: carried::Carriage::new(model),
        }
    }

    /// Wakes hose `h` and the hoses of its network (e.g. a hand grabbed it or a load
    /// case on it changed).
    pub fn wake(&mut self, model: &Model, h: usize) {
        let Some(&network) = model.hose_network.get(h) else {
            return;
        };
        for (k, info) in model.hoses.iter().enumerate() {
            if k != h && model.hose_network[k] != network {
                continue;
            }
            self.hose_asleep[k] = false;
            self.calm[k] = 0;
            self.carried.release(model, k);
            for i in info.nodes() {
                self.node_asleep[i] = false;
            }
        }
    }

    /// Wakes every hose.
    pub fn wake_all(&mut self, model: &Model) {
        for h in 0..model.hoses.len() {
            self.wake(model, h);
        }
    }

    /// How many hoses sleep.
    pub fn sleeping(&self) -> usize {
        self.hose_asleep.iter().filter(|a| **a).count()
    }
}

/// Change of contact force that wakes a sleeping node \[N\] (plus 1 % of the force it slept
/// with).
const WAKE_FORCE: f64 = 1e-6;

/// After a step: wakes sleeping hoses that were touched or moved, puts calm ones to sleep.
/// `moved(i)` tells whether a kinematic load case moved node i in this step (the explicit
/// step wakes those hoses itself and passes none).
pub fn update(model: &Model, state: &mut State, moved: impl Fn(usize) -> bool) {
    if !state.sleep.enabled {
        return;
    }
    carried::survey(model, state);
    for (h, info) in model.hoses.iter().enumerate() {
        let driven = info.nodes().any(&moved);
        if state.sleep.hose_asleep[h] {
            let touched = info.nodes().any(|i| {
                let (now, then) = (state.hose_contact_force[i], state.sleep.contact_at_sleep[i]);
                (now - then).length() > WAKE_FORCE + 0.01 * then.length()
            });
            if driven || touched {
                state.sleep.wake(model, h);
            }
            continue;
        }
        // at rest, or at rest relative to the moving part its network lies on
        let calm = !driven
            && info.nodes().all(|i| {
                let (v, w) = carried::relative_motion(state, h, i);
                v.length() < SLEEP_SPEED && w.length() * model.radius[i] < SLEEP_SPEED
            });
        let s = &mut state.sleep;
        s.calm[h] = if calm { s.calm[h] + 1 } else { 0 };
    }
    // calm hoses fall asleep when every hose of their network is calm (or asleep)
    for (h, info) in model.hoses.iter().enumerate() {
        let s = &mut state.sleep;
        if s.hose_asleep[h] || s.calm[h] < SLEEP_AFTER_STEPS {
            continue;
        }
        let network = model.hose_network[h];
        let all_calm = (0..model.hoses.len()).all(|k| {
            model.hose_network[k] != network || s.hose_asleep[k] || s.calm[k] >= SLEEP_AFTER_STEPS
        });
        if !all_calm {
            continue;
        }
        let Ok(carrier) = carried::carrier(model, state, h) else {
            continue; // on a moving part that would not carry it at rest
        };
        let s = &mut state.sleep;
        s.hose_asleep[h] = true;
        for i in info.nodes() {
            s.node_asleep[i] = true;
            s.contact_at_sleep[i] = state.hose_contact_force[i];
            state.v[i] = DVec3::ZERO;
            state.w[i] = DVec3::ZERO;
        }
        if let Some(k) = carrier {
            carried::begin(model, state, h, k);
        }
    }
    // a moving hose wakes the hoses tied to it (one that is merely awake but calm does
    // not, or two tied hoses falling asleep a step apart would wake each other forever)
    let hose_of = |i: usize| model.hoses.iter().position(|h| h.nodes().contains(&i));
    for (_, case) in state.loads.iter() {
        let crate::loads::LoadCase::Tie(t) = case else {
            continue;
        };
        let (Some(a), Some(b)) = (hose_of(t.nodes[0]), hose_of(t.nodes[1])) else {
            continue;
        };
        let s = &mut state.sleep;
        for (from, to) in [(a, b), (b, a)] {
            if !s.hose_asleep[from] && s.calm[from] == 0 && s.hose_asleep[to] {
                s.wake(model, to);
            }
        }
    }
}
