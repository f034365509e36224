//! The core's layering (crate docs, docs/architecture.md) checked on the source: the plain
//! data modules use no kernel, load, contact or solver module beyond the few types they
//! carry (listed here one by one), and the kernels (`rod/`) use no load, contact or
//! solver module. A new `crate::…` path in these files that breaks the rule fails here.

use std::collections::BTreeSet;
use std::path::Path;

/// The plain data modules (files under `src/`).
const DATA: &[&str] = &[
    "spec", "settings", "model", "state", "material", "section", "junction", "curve", "math",
];

/// Names the crate root re-exports from the data modules.
const DATA_ROOT: &[&str] = &[
    "GivenStiffness",
    "HoseEnd",
    "HoseInfo",
    "HoseSpec",
    "Junction",
    "JunctionSpec",
    "Material",
    "Model",
    "ModelError",
    "RigidPartSpec",
    "Section",
    "SectionProperties",
    "SimSettings",
    "SolverKind",
    "SolverSettings",
    "State",
    "WorldSpec",
];

/// Modules no data module or kernel may use.
const SOLVERS: &[&str] = &["integrators", "newton", "relax", "health"];

/// The types of higher layers a data module carries, path by path: the model holds its
/// built elements, rest frames, masses, stiffened bodies and stable step (kernels), its
/// contact environment and the junction bodies' shapes (parts posed from the bodies); the state holds the per-step scratch of contact, loads and
/// sleeping, and the parts inputs moved; a spec names the hose contact rule.
const DATA_EXCEPTIONS: &[(&str, &[&str])] = &[
    (
        "spec",
        &["contact::HoseContactRule", "kinematics::PartMotion"],
    ),
    (
        "model",
        &[
            "contact::HoseContactModel",
            "contact::RigidEnvironment",
            "junction_shape::JunctionShapes",
            "kinematics::PartKinematics",
            "parallel::available_cores",
            "rod::element::BeamElement",
            "rod::element_block::PackedElements",
            "rod::frames::curve_frames",
            "rod::frames::node_frames",
            "rod::mass::half_element_mass",
            "rod::inelastic::InelasticElements",
            "rod::stiffened::RigidBody",
            "rod::stiffened::StiffenedSpan",
            "rod::timestep::stable_time_step",
            "rod::timestep::TimeStepReport",
        ],
    ),
    (
        "state",
        &[
            "contact::ContactScratch",
            "contact::HoseContactScratch",
            "contact::friction::FrictionMemory",
            "kinematics::PartMoves",
            "loads::LoadCases",
            "sleep::Sleep",
            "rod::element::BeamElement",
            "rod::inelastic::HistoryView",
            "rod::stiffened::BodyState",
        ],
    ),
    (
        "junction",
        &[
            "contact::HoseContactModel",
            "rod::attached::check_inertia",
            "rod::stiffened::RigidBody",
        ],
    ),
    ("math", &["autodiff"]),
];

/// What the kernels may use besides the data modules and themselves.
const KERNEL_EXTRA: &[&str] = &["rod", "autodiff", "parallel"];

#[test]
fn data_modules_use_no_algorithm_module() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut broken = Vec::new();
    for module in DATA {
        let exceptions = DATA_EXCEPTIONS
            .iter()
            .find(|(m, _)| m == module)
            .map_or(&[][..], |(_, e)| *e);
        for path in crate_paths(&src.join(format!("{module}.rs"))) {
            let first = path.split("::").next().unwrap_or_default();
            let ok = if is_root_name(first) {
                DATA_ROOT.contains(&first)
            } else {
                !SOLVERS.contains(&first)
                    && (DATA.contains(&first) || exceptions.iter().any(|e| within(&path, e)))
            };
            if !ok {
                broken.push(format!("src/{module}.rs uses crate::{path}"));
            }
        }
    }
    assert!(
        broken.is_empty(),
        "plain data modules must not use kernels, loads, contact or solvers (beyond the \
         types listed in tests/layering.rs):\n{}",
        broken.join("\n")
    );
}

#[test]
fn kernels_use_no_loads_contact_or_solvers() {
    let rod = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/rod");
    let mut broken = Vec::new();
    let mut files: Vec<_> = std::fs::read_dir(&rod)
        .expect("src/rod")
        .map(|e| e.expect("entry").path())
        .collect();
    files.sort();
    assert!(files.len() > 10, "src/rod holds the element kernels");
    for file in files {
        for path in crate_paths(&file) {
            let first = path.split("::").next().unwrap_or_default();
            let ok = if is_root_name(first) {
                DATA_ROOT.contains(&first)
            } else {
                !SOLVERS.contains(&first)
                    && (DATA.contains(&first) || KERNEL_EXTRA.contains(&first))
            };
            if !ok {
                broken.push(format!("{} uses crate::{path}", file.display()));
            }
        }
    }
    assert!(
        broken.is_empty(),
        "the kernels (src/rod) must not use loads, contact or solvers:\n{}",
        broken.join("\n")
    );
}

#[test]
fn the_path_reader_expands_groups() {
    let paths = paths_in("use crate::a::{b::C, d as D};\nlet x = crate::e::f(1); // crate::g\n");
    let want: BTreeSet<String> = ["a::b::C", "a::d", "e::f"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(paths, want);
}

fn is_root_name(segment: &str) -> bool {
    segment.starts_with(|c: char| c.is_ascii_uppercase())
}

/// Whether `path` is `allowed` or inside it (`a::b::C` is within `a::b`; `a::b::new`
/// within `a::b`).
fn within(path: &str, allowed: &str) -> bool {
    path == allowed || path.starts_with(&format!("{allowed}::"))
}

/// Every `crate::…` path a source file uses outside comments, with `use` groups expanded.
fn crate_paths(file: &Path) -> BTreeSet<String> {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    paths_in(&text)
}

fn paths_in(text: &str) -> BTreeSet<String> {
    let code: String = text
        .lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n");
    let mut out = BTreeSet::new();
    let mut rest = code.as_str();
    while let Some(i) = rest.find("crate::") {
        let before = rest[..i].chars().next_back();
        rest = &rest[i + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue; // `pliant_crate::…` and the like
        }
        let used = expand("", rest, &mut out);
        rest = &rest[used..];
    }
    out
}

/// Reads one path (or group) at the start of `s` under `prefix`, adds what it names to
/// `out`, and returns the bytes read.
fn expand(prefix: &str, s: &str, out: &mut BTreeSet<String>) -> usize {
    let len = s
        .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
        .unwrap_or(s.len());
    let path = format!("{prefix}{}", &s[..len]);
    if s[len..].starts_with('{') && path.ends_with("::") {
        let mut i = len + 1;
        loop {
            let rest = &s[i..];
            let skip = rest.len() - rest.trim_start_matches([' ', '\n', ',']).len();
            i += skip;
            if s[i..].starts_with('}') || i >= s.len() {
                return (i + 1).min(s.len());
            }
            if s[i..].starts_with("as ") {
                i += s[i..].find([',', '}']).unwrap_or(s.len() - i);
                continue;
            }
            i += expand(&path, &s[i..], out);
        }
    }
    let path = path.trim_end_matches("::").to_string();
    if !path.is_empty() && path != "self" {
        out.insert(path.trim_end_matches("::self").to_string());
    }
    len
}
