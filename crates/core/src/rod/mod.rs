//! The rod: the co-rotational 3-D Euler–Bernoulli beam element (SPEC P1, P2) and what
//! computes with it — the element in scalar form ([`element`]) and four at a time
//! ([`element_block`], [`lanes`], [`lane_arith`]), its consistent tangent ([`tangent`],
//! [`tangent_kernel`]), the assembly of element and body loads over a model ([`forces`],
//! [`body_loads`]) over the node arrays ([`node_view`], and as lanes for the kernel, [`node_lanes`]), lumped masses ([`mass`]), rest frames ([`frames`]), stiffened
//! sections ([`stiffened`]) and a body's own mass ([`attached`]) and the stable explicit time step ([`timestep`]); elements
//! with a history ([`inelastic`]): yielding ones (SPEC X1: the fibre law
//! [`fibre_law`], the fibre section [`fibre_section`], the yielding hinge of an element
//! [`plastic_hinges`] and the closed forms of the elastic–plastic tube
//! [`plastic_moment`]), relaxing ones (SPEC X2, [`relaxation`]) and rubbing ones (SPEC
//! X2, [`hysteresis`]); what an element's section carries, for output ([`section_loads`]).
//!
//! The kernels read the plain data of the crate (model, sections, materials) and nothing
//! above it: no loads, contact or solvers.

pub mod attached;
pub mod body_loads;
pub mod element;
pub mod element_block;
pub mod fibre_law;
pub mod fibre_section;
pub mod forces;
pub mod frames;
pub mod hysteresis;
pub mod inelastic;
pub mod lane_arith;
pub mod lanes;
pub mod mass;
pub mod node_lanes;
pub mod node_view;
pub mod plastic_hinges;
pub mod plastic_moment;
pub mod relaxation;
pub mod section_loads;
pub mod stiffened;
pub mod tangent;
pub mod tangent_kernel;
#[cfg(test)]
mod test_elements;
pub mod timestep;
