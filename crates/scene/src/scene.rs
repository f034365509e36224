//! The result of loading a scene: everything the physics core and the assembly layer
//! need, in SI units, plus a few facts for reports.

use crate::units::LengthUnit;
use pliant_assembly::clip::ClipSpec;
use pliant_assembly::ergonomics::ErgonomicProfile;
use pliant_assembly::stub::StubSpec;
use pliant_assembly::Timeline;
use pliant_core::WorldSpec;

/// One end of a hose: the hose's index and which end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HoseEnd {
    /// Hose index (as in `LoadedScene::world.hoses`).
    pub hose: usize,
    /// `true`: the last node; `false`: the first node.
    pub at_end: bool,
}

impl HoseEnd {
    /// The node index of this end on a hose of `nodes` nodes.
    pub fn node(&self, nodes: usize) -> usize {
        if self.at_end {
            nodes.saturating_sub(1)
        } else {
            0
        }
    }
}

/// A connector stub of the scene (SPEC L6).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneStub {
    /// The stub's name.
    pub name: String,
    /// Geometry and friction, SI, axis normalised.
    pub spec: StubSpec,
    /// The hose end meant to go onto it (named, or the end of the scene's only hose).
    pub hose_end: HoseEnd,
    /// Its profile (SPEC V4): beads or barbs from the mouth inwards, SI (empty: a plain
    /// cylinder).
    pub profile: Vec<pliant_assembly::stub::Bead>,
    /// The part it sits on (index into the world's parts), if any.
    pub part: Option<usize>,
}

/// A connector of the scene: the plug on a hose end and its counterpart.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneConnector {
    /// The connector's name.
    pub name: String,
    /// The counterpart's geometry and the mating force law, SI.
    pub mating: pliant_assembly::stub::Mating,
    /// The hose end carrying the plug.
    pub hose_end: HoseEnd,
    /// The part the counterpart sits on (index into the world's parts), if any.
    pub part: Option<usize>,
}

/// A clip of the scene (SPEC L7).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneClip {
    /// The clip's name.
    pub name: String,
    /// Geometry and snap force, SI, directions normalised and perpendicular.
    pub spec: ClipSpec,
    /// Index of the hose meant to be snapped into it (named, or the scene's only hose).
    pub hose: usize,
    /// The part it sits on (index into the world's parts), if any.
    pub part: Option<usize>,
    /// It takes the hose only when a hand presses it in.
    pub by_hand: bool,
}

/// How one hose was discretised.
#[derive(Clone, Debug, PartialEq)]
pub struct HoseDiscretisation {
    /// The hose's name.
    pub name: String,
    /// Arc length of its centre line (m) (before imperfections).
    pub length: f64,
    /// Number of beam elements (nodes − 1).
    pub elements: usize,
    /// Number of elements the file asked for (directly or via `element_length`).
    pub requested_elements: usize,
    /// Whether arcs forced more elements than requested (≥ 4 per quarter circle).
    pub raised_for_arcs: bool,
    /// Arc length between neighbouring nodes (m).
    pub element_length: f64,
    /// Stiffened spans (first, last node, inclusive) (SPEC M6).
    pub stiffened: Vec<(usize, usize)>,
    /// Smallest bend radius of the centre line (m): the material's, else the rule
    /// [`crate::materials::min_bend_radius_rule`] for the hose's first section.
    pub min_bend_radius: f64,
    /// Minimum bend radius of every element (m) where spans give their own; empty when
    /// `min_bend_radius` holds throughout.
    pub bend_radii: Vec<f64>,
    /// Protections over stretches of the hose.
    pub protections: Vec<crate::protections::ProtectionSpan>,
    /// Outer diameter of the hose's first section (m).
    pub d_outer: f64,
    /// The nodes of its delivered, stress-free shape (m), if it is not the routed one.
    pub delivered: Option<Vec<glam::DVec3>>,
}

/// How one rigid part was built.
#[derive(Clone, Debug, PartialEq)]
pub struct PartInfo {
    /// The part's name.
    pub name: String,
    /// Where its triangles came from: the mesh file as resolved, or `box`, `cylinder`,
    /// `sphere`.
    pub source: String,
    /// Number of triangles kept.
    pub triangles: usize,
    /// Number of degenerate (zero-area) triangles of the file that were dropped.
    pub dropped_degenerate: usize,
    /// World-frame bounding box (m): minimum and maximum corner.
    pub bounds: (glam::DVec3, glam::DVec3),
}

/// A scene, fully checked and converted to SI. Hoses in `world.hoses`, `hose_names` and
/// `hoses` share indices, which are also the `hose` indices of the timeline's node
/// references.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedScene {
    /// Scene name (the file's `name`, else the file name without extension).
    pub name: String,
    /// Hoses, rigid parts and global settings for the physics core.
    pub world: WorldSpec,
    /// Junctions joining hose ends (SPEC N1), for [`pliant_core::Model::with_junctions`].
    pub junctions: Vec<pliant_core::JunctionSpec>,
    /// Which of `junctions` are junction bodies (moulded pieces; the others are welded
    /// branch points), as indices into `junctions`.
    pub junction_bodies: Vec<usize>,
    /// Scripted actions, node references resolved to indices.
    pub timeline: Timeline,
    /// Interval between recorded states (s); 0 = every step.
    pub record_interval: f64,
    /// Hose names by index.
    pub hose_names: Vec<String>,
    /// Discretisation facts per hose, by index.
    pub hoses: Vec<HoseDiscretisation>,
    /// Facts per rigid part, by index (same order as `world.rigid_parts`).
    pub parts: Vec<PartInfo>,
    /// Connector stubs, in file order.
    pub stubs: Vec<SceneStub>,
    /// Connectors, in file order.
    pub connectors: Vec<SceneConnector>,
    /// Clips, in file order.
    pub clips: Vec<SceneClip>,
    /// The rows and columns of the ergonomic tables hand loads are judged against
    /// (`[ergonomics]`, else the default profile).
    pub ergonomics: ErgonomicProfile,
    /// The installation checks and their limits (`[checks]`, SPEC V3).
    pub checks: pliant_assembly::checks::CheckSettings,
    /// The worker (`[worker]`, SPEC E1–E2), if the scene has one.
    pub worker: Option<pliant_assembly::worker::WorkerSettings>,
    /// The length unit the file was written in.
    pub length_unit: LengthUnit,
    /// Where the scene came from (a path, or a description such as the built-in demo).
    pub source: String,
    /// The scene file's text as loaded, for reports that embed their input.
    pub text: String,
    /// The folder relative mesh paths were read from.
    pub base_dir: std::path::PathBuf,
    /// Its size: elements, triangles and the memory a run needs ([`crate::budget`]).
    pub estimate: crate::budget::Estimate,
    /// The limits it was loaded under (its memory limit also bounds what a run records,
    /// [`LoadedScene::check_planned_steps`]).
    pub limits: crate::budget::Limits,
    /// What loading left out or doubts, for the user (e.g. solids of a STEP assembly
    /// that could not be read); empty when nothing was.
    pub warnings: Vec<String>,
}

impl LoadedScene {
    /// Whether the scene was written as JSON (else TOML).
    pub fn is_json(&self) -> bool {
        self.text.trim_start().starts_with('{')
    }

    /// All stiffened spans, for [`pliant_core::Model::with_stiffened_spans`].
    pub fn stiffened_spans(&self) -> Vec<pliant_core::rod::stiffened::StiffenedSpan> {
        self.hoses
            .iter()
            .enumerate()
            .flat_map(|(hose, info)| {
                info.stiffened.iter().map(move |&(first, last)| {
                    pliant_core::rod::stiffened::StiffenedSpan { hose, first, last }
                })
            })
            .collect()
    }

    /// The hoses delivered in a shape of their own, for
    /// [`pliant_core::Model::with_delivered_shapes`].
    pub fn delivered_shapes(&self) -> Vec<pliant_core::DeliveredShape> {
        self.hoses
            .iter()
            .enumerate()
            .filter_map(|(hose, info)| {
                let nodes = info.delivered.clone()?;
                Some(pliant_core::DeliveredShape {
                    hose,
                    nodes,
                    normal_hint: self.world.hoses[hose].normal_hint,
                })
            })
            .collect()
    }

    /// Index of the hose with this name.
    pub fn hose_index(&self, name: &str) -> Option<usize> {
        self.hose_names.iter().position(|n| n == name)
    }

    /// The stub with this name.
    pub fn stub(&self, name: &str) -> Option<&SceneStub> {
        self.stubs.iter().find(|s| s.name == name)
    }

    /// The clip with this name.
    pub fn clip(&self, name: &str) -> Option<&SceneClip> {
        self.clips.iter().find(|c| c.name == name)
    }
}
