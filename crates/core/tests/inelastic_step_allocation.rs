//! No allocation in the step from the inelastic laws (SPEC X1–X3): a steel line bent
//! past yield along a mandrel's arc, a rubber hose that relaxes and a bundle with Dahl
//! friction, stepped by each solver while the line's end keeps bending it. Once a
//! solver's buffers exist (its first steps), a step allocates nothing at all, under
//! every solver, in the inelastic world as in its elastic twin — the plastic strains,
//! the Prony stresses and the friction moments live in the state's own arrays, and the
//! Newton solvers save and restore the contact friction's memory into buffers they keep.
//! The allocator counts every allocation of the process; this file holds one test so
//! that nothing else runs beside it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::{DQuat, DVec3};
use pliant_core::loads::{Fix, LoadCase, LoadCaseId};
use pliant_core::material::{DahlLaw, Hysteresis, PronyTerm, YieldLaw};
use pliant_core::{
    HoseSpec, Material, Model, Section, SimSettings, Solver, SolverKind, SolverSettings, State,
    WorldSpec,
};

/// Counts allocations while `COUNTING` is set.
struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is passed on to the system allocator unchanged; only a counter is
// added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: the caller's layout, as GlobalAlloc::alloc requires
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: ptr came from System.alloc with this layout
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: ptr came from System.alloc with this layout
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

const N: usize = 12;
const L: f64 = 0.1;

fn nodes(y: f64) -> Vec<DVec3> {
    (0..=N)
        .map(|i| DVec3::new(L * i as f64 / N as f64, y, 0.0))
        .collect()
}

fn hose(name: &str, material: Material, y: f64, section: Section) -> HoseSpec {
    HoseSpec {
        name: name.into(),
        material,
        nodes: nodes(y),
        sections: vec![section],
        normal_hint: Some(DVec3::Z),
    }
}

/// The three hoses, each clamped at its start; the steel line's end held too. `elastic`:
/// the same materials without their inelastic laws.
fn world(elastic: bool) -> (Model, State, LoadCaseId) {
    let mut steel = Material::isotropic(200e9, 0.3, 7850.0);
    steel.plasticity = Some(YieldLaw {
        yield_stress: 250e6,
        hardening_modulus: 2e9,
    });
    let mut rubber = Material::isotropic(10e6, 0.49, 1100.0);
    rubber.relaxation = vec![
        PronyTerm {
            weight: 0.3,
            time: 0.5,
        },
        PronyTerm {
            weight: 0.2,
            time: 2.0,
        },
    ];
    let mut wires = Material::isotropic(50e6, 0.4, 2000.0);
    wires.hysteresis = Some(Hysteresis {
        bending: DahlLaw {
            moment: 0.01,
            curvature: 1.0,
        },
        torsion: Some(DahlLaw {
            moment: 0.02,
            curvature: 0.5,
        }),
    });
    if elastic {
        steel.plasticity = None;
        rubber.relaxation.clear();
        wires.hysteresis = None;
    }
    let model = Model::build(&WorldSpec {
        hoses: vec![
            hose("line", steel, 0.0, Section::new(0.006, 0.008)),
            hose("rubber", rubber, 0.1, Section::new(0.010, 0.016)),
            hose("bundle", wires, 0.2, Section::new(0.0, 0.010)),
        ],
        rigid_parts: vec![],
        settings: SimSettings::default(),
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    for h in 0..3 {
        let node = h * (N + 1);
        state.loads.add(LoadCase::Fix(Fix {
            node,
            position: model.rest_x[node],
            orientation: model.rest_q[node],
        }));
    }
    let tip = state.loads.add(LoadCase::Fix(Fix {
        node: N,
        position: model.rest_x[N],
        orientation: model.rest_q[N],
    }));
    (model, state, tip)
}

/// Holds the line's end on the arc of curvature `kappa` from its clamp (bending about
/// z, the mandrel's curvature).
fn bend(model: &Model, state: &mut State, tip: LoadCaseId, kappa: f64) {
    let phi = kappa * L;
    let x = DVec3::new(phi.sin() / kappa, (1.0 - phi.cos()) / kappa, 0.0);
    if let Some(LoadCase::Fix(f)) = state.loads.get_mut(tip) {
        f.position = x;
        f.orientation = DQuat::from_rotation_z(phi) * model.rest_q[N];
    }
}

/// Allocations of `steps` steps of `kind` after `warm_up` steps, the line bent a little
/// further each step from curvature `kappa` (1/m) by `dkappa`.
fn allocations(
    kind: SolverKind,
    (warm_up, steps): (usize, usize),
    (kappa, dkappa): (f64, f64),
    model: &Model,
    state: &mut State,
    tip: LoadCaseId,
) -> usize {
    let mut solver = Solver::new(
        model,
        SolverSettings {
            kind,
            ..Default::default()
        },
    )
    .unwrap();
    let mut counted = 0;
    for k in 0..warm_up + steps {
        bend(model, state, tip, kappa + dkappa * k as f64);
        ALLOCATIONS.store(0, Ordering::SeqCst);
        COUNTING.store(k >= warm_up, Ordering::SeqCst);
        let result = solver.step(model, state);
        COUNTING.store(false, Ordering::SeqCst);
        counted += ALLOCATIONS.load(Ordering::SeqCst);
        result.unwrap_or_else(|e| panic!("{} step {k}: {e:?}", kind.name()));
    }
    counted
}

#[test]
fn the_inelastic_laws_allocate_nothing_in_the_step() {
    // the line's first yield is at κ_e = σ_y/(E r_o) = 0.31 1/m: bent to 5 1/m and on
    let runs = [
        (SolverKind::Static, (3, 10), (0.5, 0.5)),
        (SolverKind::Implicit, (3, 10), (5.5, 0.05)),
        (SolverKind::Explicit, (5, 200), (6.0, 1e-5)),
    ];
    let mut counts = Vec::new();
    for elastic in [false, true] {
        let (model, mut state, tip) = world(elastic);
        let n: Vec<usize> = runs
            .iter()
            .map(|(kind, steps, bending)| {
                allocations(*kind, *steps, *bending, &model, &mut state, tip)
            })
            .collect();
        if !elastic {
            // the histories were active
            assert!(
                state.inelastic_history.iter().any(|v| *v != 0.0),
                "no inelastic history"
            );
        }
        counts.push(n);
    }
    for (i, (kind, steps, _)) in runs.iter().enumerate() {
        println!(
            "{}: {} allocations in {} steps (elastic twin: {})",
            kind.name(),
            counts[0][i],
            steps.1,
            counts[1][i]
        );
        assert_eq!(
            counts[0][i],
            0,
            "{}: the inelastic world's step allocated",
            kind.name()
        );
        assert_eq!(
            counts[1][i],
            0,
            "{}: the elastic twin's step allocated",
            kind.name()
        );
    }
}
