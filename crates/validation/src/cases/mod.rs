//! The validation cases, one file each.

mod axial;
mod buckling;
mod contact;
mod convergence;
mod curved_reactions;
mod energy;
mod fasteners;
mod frames;
mod friction;
mod helix;
pub mod hose_contact;
mod hysteresis;
mod invariance;
mod junction_body;
mod junction_shape;
mod large_frames;
mod mass_scaling;
mod moving_parts;
mod plastic_bending;
mod postbuckling;
mod relaxation;
mod rollup;
mod scale;
mod sections;
mod solvers;
mod stiffened;
mod thesis;
pub(crate) mod tip_load;
mod torsion;

use crate::CaseFn;

/// All cases in report order.
pub const ALL: &[(&str, CaseFn)] = &[
    ("rollup", rollup::run),
    ("helix", helix::run),
    ("tip_load", tip_load::run),
    ("buckling", buckling::run),
    ("postbuckling", postbuckling::run),
    ("axial", axial::run),
    ("torsion", torsion::run),
    ("invariance", invariance::run),
    ("energy", energy::run),
    ("mass_scaling", mass_scaling::run),
    ("convergence", convergence::run),
    ("scale", scale::run),
    ("contact_rest", contact::run_rest),
    ("contact_incline", contact::run_incline),
    ("friction_newton", friction::run),
    ("tunnelling", contact::run_tunnelling),
    ("hose_contact", hose_contact::run),
    ("stiffened", stiffened::run),
    ("sections", sections::run),
    ("frames", frames::run),
    ("large_frames", large_frames::run),
    ("junction_body", junction_body::run_static),
    ("junction_body_torsion", junction_body::run_torsion),
    ("junction_shape_rest", junction_shape::run_rest),
    ("junction_shape_impact", junction_shape::run_impact),
    ("curved_reactions", curved_reactions::run),
    ("stub", fasteners::run_stub),
    ("clip", fasteners::run_clip),
    ("thesis_1", thesis::run_1),
    ("thesis_2", thesis::run_2),
    ("thesis_3", thesis::run_3),
    ("thesis_4", thesis::run_4),
    ("solvers", solvers::run),
    ("plastic_section", plastic_bending::run_section),
    ("springback", plastic_bending::run_springback),
    ("relaxing_bar", relaxation::run_bar),
    ("relaxing_beam", relaxation::run_beam),
    ("hysteresis_torsion", hysteresis::run_torsion),
    ("hysteresis_bending", hysteresis::run_bending),
    ("moving_carry", moving_parts::run_carry),
    ("moving_lift", moving_parts::run_lift),
    ("moving_drag", moving_parts::run_drag),
    ("moving_hinge", moving_parts::run_hinge),
    ("moving_fast", moving_parts::run_fast),
];
