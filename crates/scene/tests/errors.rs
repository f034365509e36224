//! Bad scene files: each kind of mistake gives an error that names the field and the
//! reason, and loading never panics.

use pliant_scene::{load_scene_json_str, load_scene_str, SceneError};
use pliant_testkit::bad_inputs::{check_bad_inputs, BadInput};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A valid scene exercising every section; the cases below break one thing each.
const BASE: &str = r#"
format = "pliant-scene"
version = 1
name = "errors"
length_unit = "mm"

[simulation]
gravity = [0, 0, -9.81]
time_step_safety = 0.5

[output]
record_interval_s = 0.01

[materials.rub]
e_tension_mpa = 10
e_compression_mpa = 12
poisson = 0.49
density_kg_m3 = 1000

[[hoses]]
name = "a"
material = "hose3"
section = { d_inner = 27, d_outer = 35 }
elements = 4
start = [0, 0, 0]
path = [
  { line = { to = [300, 0, 0] } },
  { arc = { via = [400, 50, 0], to = [450, 150, 0] } },
]
imperfection = [{ node = 5, offset = [0, 0, 1] }]

[[hoses]]
name = "b"
material = "rub"
section = { d_inner = 10, d_outer = 16 }
start = [0, 100, 0]
path = [{ line = { to = [200, 100, 0] } }]

[[timeline]]
action = "fix"
hose = "a"
node = 0

[[timeline]]
action = "move"
hose = "a"
node = -1
to = [[500, 0, 0], [600, 100, 0]]
rotate = { axis = [1, 0, 0], angle_deg = 90 }
duration_s = 2.0

[[timeline]]
action = "load"
hose = "b"
node = -1
force_n = [0, 0, -5]

[[timeline]]
action = "settle"
"#;

/// The bad inputs: each breaks one thing in [`BASE`].
const CASES: &[BadInput] = &[
    BadInput { what: "missing format", edits: &[("format = \"pliant-scene\"\n", "")], field: Some("format"), message: &["missing"] },
    BadInput { what: "wrong format", edits: &[("\"pliant-scene\"", "\"pliant-scen\"")], field: Some("format"), message: &["expected \"pliant-scene\", found \"pliant-scen\""] },
    BadInput { what: "unsupported version", edits: &[("version = 1", "version = 2")], field: Some("version"), message: &["unsupported scene format version 2", "reads version 1"] },
    BadInput { what: "missing version", edits: &[("version = 1\n", "")], field: Some("version"), message: &["missing"] },
    BadInput { what: "version not an integer", edits: &[("version = 1", "version = \"1\"")], field: Some("version"), message: &["expected the integer 1"] },
    BadInput { what: "unknown length unit cm", edits: &[("\"mm\"", "\"cm\"")], field: Some("length_unit"), message: &["unknown variant `cm`", "`mm` or `m`"] },
    BadInput { what: "length unit wrong case", edits: &[("\"mm\"", "\"MM\"")], field: Some("length_unit"), message: &["`MM`", "`mm` or `m`"] },
    BadInput { what: "missing length unit", edits: &[("length_unit = \"mm\"\n", "")], field: Some("length_unit"), message: &["missing field"] },
    BadInput { what: "missing required hose field", edits: &[("material = \"hose3\"\n", "")], field: Some("hoses[0].material"), message: &["missing field `material`"] },
    BadInput { what: "unknown field (typo)", edits: &[("section = { d_inner = 27", "sectoin = { d_inner = 27")], field: Some("hoses[0].sectoin"), message: &["unknown field `sectoin`"] },
    BadInput { what: "unknown field in a section table", edits: &[("d_inner = 27,", "d_innr = 27,")], field: Some("hoses[0].section.d_innr"), message: &["unknown field `d_innr`"] },
    BadInput { what: "wrong type", edits: &[("elements = 4", "elements = \"ten\"")], field: Some("hoses[0].elements"), message: &["invalid type"] },
    BadInput { what: "negative element count", edits: &[("elements = 4", "elements = -3")], field: Some("hoses[0].elements"), message: &["-3"] },
    BadInput { what: "vector of two components", edits: &[("start = [0, 0, 0]", "start = [0, 0]")], field: Some("hoses[0].start"), message: &["invalid length 2"] },
    BadInput { what: "negative outer diameter", edits: &[("d_outer = 35", "d_outer = -35")], field: Some("hoses[0].section.d_outer"), message: &["= -35 mm: must be greater than 0"] },
    BadInput { what: "zero outer diameter", edits: &[("d_outer = 35", "d_outer = 0")], field: Some("hoses[0].section.d_outer"), message: &["= 0 mm: must be greater than 0"] },
    BadInput { what: "negative inner diameter", edits: &[("d_inner = 27", "d_inner = -1")], field: Some("hoses[0].section.d_inner"), message: &["= -1 mm: must not be negative"] },
    BadInput { what: "inner not smaller than outer", edits: &[("d_inner = 10, d_outer = 16", "d_inner = 40, d_outer = 35")], field: Some("hoses[1].section.d_inner"), message: &["hoses[1].section.d_inner = 40 mm: must be smaller than d_outer (35 mm)"] },
    BadInput { what: "unknown material", edits: &[("material = \"hose3\"", "material = \"hose9\"")], field: Some("hoses[0].material"), message: &["\"hose9\": unknown material", "hose1, hose2, hose3, hose4, hose5", "rub"] },
    BadInput { what: "material shadows the library", edits: &[("[materials.rub]", "[materials.hose1]")], field: Some("materials.hose1"), message: &["taken by the built-in library"] },
    BadInput { what: "user material without section", edits: &[("section = { d_inner = 10, d_outer = 16 }\n", "")], field: Some("hoses[1].section"), message: &["required because material \"rub\" is not a library hose"] },
    BadInput { what: "zero modulus", edits: &[("e_tension_mpa = 10", "e_tension_mpa = 0")], field: Some("materials.rub.e_tension_mpa"), message: &["= 0 MPa: must be greater than 0"] },
    BadInput { what: "negative compression modulus", edits: &[("e_compression_mpa = 12", "e_compression_mpa = -12")], field: Some("materials.rub.e_compression_mpa"), message: &["must be greater than 0"] },
    BadInput { what: "negative density", edits: &[("density_kg_m3 = 1000", "density_kg_m3 = -1000")], field: Some("materials.rub.density_kg_m3"), message: &["= -1000 kg/m³: must be greater than 0"] },
    BadInput { what: "poisson 0.5", edits: &[("poisson = 0.49", "poisson = 0.5")], field: Some("materials.rub.poisson"), message: &["= 0.5: must lie in (−1, 0.5)"] },
    BadInput { what: "poisson -1", edits: &[("poisson = 0.49", "poisson = -1")], field: Some("materials.rub.poisson"), message: &["= -1: must lie in (−1, 0.5)"] },
    BadInput { what: "nan position", edits: &[("start = [0, 0, 0]", "start = [nan, 0, 0]")], field: Some("hoses[0].start[0]"), message: &["= nan mm: must be a finite number"] },
    BadInput { what: "inf gravity", edits: &[("gravity = [0, 0, -9.81]", "gravity = [0, 0, -inf]")], field: Some("simulation.gravity[2]"), message: &["= -inf m/s²: must be a finite number"] },
    BadInput { what: "nan modulus", edits: &[("e_tension_mpa = 10", "e_tension_mpa = nan")], field: Some("materials.rub.e_tension_mpa"), message: &["must be a finite number"] },
    BadInput { what: "zero yield stress", edits: &[("density_kg_m3 = 1000", "density_kg_m3 = 1000\nyield_stress_mpa = 0")], field: Some("materials.rub.yield_stress_mpa"), message: &["= 0 MPa: must be greater than 0"] },
    BadInput { what: "negative hardening", edits: &[("density_kg_m3 = 1000", "density_kg_m3 = 1000\nyield_stress_mpa = 250\nhardening_modulus_mpa = -1")], field: Some("materials.rub.hardening_modulus_mpa"), message: &["= -1 MPa: must be ≥ 0"] },
    BadInput { what: "hardening without yield", edits: &[("density_kg_m3 = 1000", "density_kg_m3 = 1000\nhardening_modulus_mpa = 2000")], field: Some("materials.rub.hardening_modulus_mpa"), message: &["needs `yield_stress_mpa`"] },
    BadInput { what: "inf waypoint", edits: &[("[600, 100, 0]", "[600, inf, 0]")], field: Some("timeline[1].to[1][1]"), message: &["= inf mm: must be a finite number"] },
    BadInput { what: "nan angle", edits: &[("angle_deg = 90", "angle_deg = nan")], field: Some("timeline[1].rotate.angle_deg"), message: &["must be a finite number"] },
    BadInput { what: "zero-length segment", edits: &[("{ line = { to = [300, 0, 0] } }", "{ line = { to = [0, 0, 0] } }")], field: Some("hoses[0].path[0].line.to"), message: &["= [0, 0, 0] mm", "zero length"] },
    BadInput { what: "zero-length hose", edits: &[("to = [200, 100, 0]", "to = [0, 100, 0]")], field: Some("hoses[1].path[0].line.to"), message: &["zero length"] },
    BadInput { what: "collinear arc", edits: &[("via = [400, 50, 0], to = [450, 150, 0]", "via = [400, 0, 0], to = [450, 0, 0]")], field: Some("hoses[0].path[1].arc"), message: &["collinear"] },
    BadInput { what: "arc via on its start", edits: &[("via = [400, 50, 0]", "via = [300, 0, 0]")], field: Some("hoses[0].path[1].arc.via"), message: &["coincides with the arc's start point"] },
    BadInput { what: "empty path", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = []")], field: Some("hoses[1].path"), message: &["at least one segment"] },
    BadInput { what: "segment of two kinds", edits: &[("{ line = { to = [200, 100, 0] } }", "{ line = { to = [200, 100, 0] }, arc = { via = [1, 2, 3], to = [4, 5, 6] } }")], field: Some("hoses[1].path[0]"), message: &["exactly one of `line`, `arc`, `spline`"] },
    BadInput { what: "empty segment", edits: &[("{ line = { to = [200, 100, 0] } }", "{}")], field: Some("hoses[1].path[0]"), message: &["exactly one of `line`, `arc`, `spline`"] },
    BadInput { what: "zero elements", edits: &[("elements = 4", "elements = 0")], field: Some("hoses[0].elements"), message: &["= 0: must be at least 1"] },
    BadInput { what: "zero element length", edits: &[("elements = 4", "element_length = 0")], field: Some("hoses[0].element_length"), message: &["= 0 mm: must be greater than 0"] },
    BadInput { what: "negative element length", edits: &[("elements = 4", "element_length = -5")], field: Some("hoses[0].element_length"), message: &["= -5 mm: must be greater than 0"] },
    BadInput { what: "both elements and element length", edits: &[("elements = 4", "elements = 4\nelement_length = 20")], field: Some("hoses[0].elements"), message: &["either elements or element_length"] },
    BadInput { what: "absurd element count", edits: &[("elements = 4", "elements = 4000000000")], field: Some("hoses[0].path"), message: &["more than 100000 elements"] },
    BadInput { what: "duplicate hose names", edits: &[("name = \"b\"", "name = \"a\"")], field: Some("hoses[1].name"), message: &["\"a\": duplicate hose name (also hoses[0].name)"] },
    BadInput { what: "empty hose name", edits: &[("name = \"b\"", "name = \"\"")], field: Some("hoses[1].name"), message: &["must not be empty"] },
    BadInput { what: "unknown hose in an action", edits: &[("hose = \"b\"", "hose = \"c\"")], field: Some("timeline[2].hose"), message: &["\"c\": unknown hose; hoses: a, b"] },
    BadInput { what: "node index too large", edits: &[("node = 0", "node = 99")], field: Some("timeline[0].node"), message: &["= 99: out of range"] },
    BadInput { what: "negative node index too small", edits: &[("node = 0", "node = -99")], field: Some("timeline[0].node"), message: &["= -99: out of range"] },
    BadInput { what: "unknown action", edits: &[("action = \"fix\"", "action = \"fx\"")], field: Some("timeline[0].action"), message: &["unknown action `fx`, expected one of `fix`"] },
    BadInput { what: "action without its tag", edits: &[("action = \"settle\"\n", "")], field: Some("timeline[3].action"), message: &["missing field `action`"] },
    BadInput { what: "wrong type inside an action", edits: &[("duration_s = 2.0", "duration_s = \"2 s\"")], field: Some("timeline[1].duration_s"), message: &["invalid type: string \"2 s\", expected f64"] },
    BadInput { what: "unknown field inside a rotation", edits: &[("angle_deg = 90", "angle = 90")], field: Some("timeline[1].rotate.angle"), message: &["unknown field `angle`"] },
    BadInput { what: "unknown field in an action", edits: &[("force_n = [0, 0, -5]", "force = [0, 0, -5]")], field: Some("timeline[2].force"), message: &["unknown field `force`"] },
    BadInput { what: "move with nothing to do", edits: &[("to = [[500, 0, 0], [600, 100, 0]]\n", ""), ("rotate = { axis = [1, 0, 0], angle_deg = 90 }\n", "")], field: Some("timeline[1]"), message: &["a move needs `to`, `by` or `rotate`"] },
    BadInput { what: "move with both to and by", edits: &[("to = [[500, 0, 0], [600, 100, 0]]", "to = [500, 0, 0]\nby = [1, 0, 0]")], field: Some("timeline[1]"), message: &["either `to` (absolute) or `by` (relative), not both"] },
    BadInput { what: "move with no waypoints", edits: &[("to = [[500, 0, 0], [600, 100, 0]]", "to = []")], field: Some("timeline[1].to"), message: &["needs at least one waypoint"] },
    BadInput { what: "waypoint of wrong shape", edits: &[("to = [[500, 0, 0], [600, 100, 0]]", "to = [500, 0]")], field: Some("timeline[1].to"), message: &["expected a point [x, y, z] or a list of points"] },
    BadInput { what: "zero duration", edits: &[("duration_s = 2.0", "duration_s = 0")], field: Some("timeline[1].duration_s"), message: &["= 0 s: must be greater than 0"] },
    BadInput { what: "negative run duration", edits: &[("action = \"settle\"", "action = \"run\"\nduration_s = -1")], field: Some("timeline[3].duration_s"), message: &["= -1 s: must be greater than 0"] },
    BadInput { what: "zero rotation axis", edits: &[("axis = [1, 0, 0]", "axis = [0, 0, 0]")], field: Some("timeline[1].rotate.axis"), message: &["= [0, 0, 0]: must not be the zero vector"] },
    BadInput { what: "load with neither force nor moment", edits: &[("force_n = [0, 0, -5]\n", "")], field: Some("timeline[2]"), message: &["needs `force_n` and/or `moment_nm`"] },
    BadInput { what: "negative load ramp", edits: &[("force_n = [0, 0, -5]", "force_n = [0, 0, -5]\nramp_s = -1")], field: Some("timeline[2].ramp_s"), message: &["= -1 s: must not be negative"] },
    BadInput { what: "empty load name", edits: &[("force_n = [0, 0, -5]", "force_n = [0, 0, -5]\nname = \"\"")], field: Some("timeline[2].name"), message: &["must not be empty"] },
    BadInput { what: "unload of a load never named", edits: &[("action = \"settle\"", "action = \"unload\"\nhose = \"b\"\nnode = -1\nname = \"push\"")], field: Some("timeline[3].name"), message: &["\"push\"", "no earlier `load` of this name is acting"] },
    BadInput { what: "unload by name on another node", edits: &[("force_n = [0, 0, -5]", "force_n = [0, 0, -5]\nname = \"push\""), ("action = \"settle\"", "action = \"unload\"\nhose = \"b\"\nnode = 0\nname = \"push\"")], field: Some("timeline[3].name"), message: &["that load acts on another node"] },
    BadInput { what: "load name taken twice", edits: &[("force_n = [0, 0, -5]", "force_n = [0, 0, -5]\nname = \"push\""), ("action = \"settle\"", "action = \"load\"\nhose = \"a\"\nnode = 1\nforce_n = [1, 0, 0]\nname = \"push\"")], field: Some("timeline[3].name"), message: &["a load of this name is still acting"] },
    BadInput { what: "zero settle threshold", edits: &[("action = \"settle\"", "action = \"settle\"\nkinetic_energy_j = 0")], field: Some("timeline[3].kinetic_energy_j"), message: &["must be greater than 0"] },
    BadInput { what: "imperfection node out of range", edits: &[("node = 5, offset", "node = 500, offset")], field: Some("hoses[0].imperfection[0].node"), message: &["= 500: out of range: hose \"a\""] },
    BadInput { what: "imperfection collapses two nodes", edits: &[("start = [0, 100, 0]", "start = [0, 100, 0]\nelements = 10\nimperfection = [{ node = 3, offset = [0, 0, 1] }, { node = 1, offset = [-20, 0, 0] }]")], field: Some("hoses[1].imperfection[1].offset"), message: &["= [-20, 0, 0] mm: moves node 1 onto node 0"] },
    BadInput { what: "negative given bending stiffness", edits: &[("d_inner = 10, d_outer = 16 }", "d_inner = 10, d_outer = 16, ei1_n_m2 = -1 }")], field: Some("hoses[1].section.ei1_n_m2"), message: &["= -1 N·m²: must be greater than 0"] },
    BadInput { what: "ribbon without normal hint", edits: &[("d_inner = 10, d_outer = 16 }", "d_inner = 10, d_outer = 16, ei1_n_m2 = 1, ei2_n_m2 = 2 }")], field: Some("hoses[1].normal_hint"), message: &["required", "EI1 ≠ EI2"] },
    BadInput { what: "span ends before it starts", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nspans = [{ from = 150, to = 100, section = { d_inner = 10, d_outer = 20 } }]")], field: Some("hoses[1].spans[0].to"), message: &["= 100 mm: must be greater than from (150 mm)"] },
    BadInput { what: "span beyond the hose", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nspans = [{ from = 100, to = 250, section = { d_inner = 10, d_outer = 20 } }]")], field: Some("hoses[1].spans[0].to"), message: &["lies beyond the hose's end (its length is 200 mm)"] },
    BadInput { what: "overlapping spans", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nspans = [{ from = 0, to = 100, section = { d_inner = 10, d_outer = 20 } }, { from = 50, to = 150, section = { d_inner = 10, d_outer = 20 } }]")], field: Some("hoses[1].spans[1]"), message: &["overlaps the span 0 mm..100 mm"] },
    BadInput { what: "span holding no element", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nspans = [{ from = 103, to = 104, section = { d_inner = 10, d_outer = 20 } }]")], field: Some("hoses[1].spans[0]"), message: &["holds no element's middle"] },
    BadInput { what: "span section invalid", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nspans = [{ from = 0, to = 100, section = { d_inner = 30, d_outer = 20 } }]")], field: Some("hoses[1].spans[0].section.d_inner"), message: &["must be smaller than d_outer"] },
    BadInput { what: "span bend radius zero", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nspans = [{ from = 0, to = 100, min_bend_radius = 0, section = { d_inner = 10, d_outer = 20 } }]")], field: Some("hoses[1].spans[0].min_bend_radius"), message: &["= 0 mm: must be greater than 0"] },
    BadInput { what: "protection beyond the hose", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nprotections = [{ kind = \"tape\", from = 0, to = 250 }]")], field: Some("hoses[1].protections[0].to"), message: &["= 250 mm: lies beyond the hose's end (its length is 200 mm)"] },
    BadInput { what: "protection ends before it starts", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nprotections = [{ kind = \"sleeve\", from = 120, to = 80 }]")], field: Some("hoses[1].protections[0].to"), message: &["= 80 mm: must be greater than from (120 mm)"] },
    BadInput { what: "protection from negative", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nprotections = [{ kind = \"sleeve\", from = -5, to = 80 }]")], field: Some("hoses[1].protections[0].from"), message: &["= -5 mm: must not be negative"] },
    BadInput { what: "protections of one kind overlapping", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nprotections = [{ kind = \"tape\", from = 0, to = 120 }, { kind = \"corrugated_tube\", from = 10, to = 190 }, { kind = \"tape\", from = 100, to = 200 }]")], field: Some("hoses[1].protections[2]"), message: &["= 100 mm..200 mm: overlaps protections[0] (0 mm..120 mm), of the same kind \"tape\""] },
    BadInput { what: "unknown protection kind", edits: &[("path = [{ line = { to = [200, 100, 0] } }]", "path = [{ line = { to = [200, 100, 0] } }]\nprotections = [{ kind = \"bubble_wrap\", from = 0, to = 100 }]")], field: None, message: &["unknown variant `bubble_wrap`", "corrugated_tube"] },
    BadInput { what: "normal hint along the tangent", edits: &[("elements = 4", "elements = 4\nnormal_hint = [2, 0, 0]")], field: Some("hoses[0].normal_hint"), message: &["must not be parallel to the hose's first tangent"] },
    BadInput { what: "negative record interval", edits: &[("record_interval_s = 0.01", "record_interval_s = -1")], field: Some("output.record_interval_s"), message: &["= -1 s: must not be negative"] },
    BadInput { what: "time step safety above 1", edits: &[("time_step_safety = 0.5", "time_step_safety = 1.5")], field: Some("simulation.time_step_safety"), message: &["= 1.5: must lie in [0.001, 1]"] },
    BadInput { what: "time step safety 1e-300 (runs for ever)", edits: &[("time_step_safety = 0.5", "time_step_safety = 1e-300")], field: Some("simulation.time_step_safety"), message: &["must lie in [0.001, 1]"] },
    BadInput { what: "time step safety 5e-324 (a zero step)", edits: &[("time_step_safety = 0.5", "time_step_safety = 5e-324")], field: Some("simulation.time_step_safety"), message: &["must lie in [0.001, 1]"] },
    BadInput { what: "mass scaling below 1", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nmass_scaling = 0.5")], field: Some("simulation.mass_scaling"), message: &["simulation.mass_scaling = 0.5: must lie in 1 … 10000"] },
    BadInput { what: "mass scaling NaN", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nmass_scaling = nan")], field: Some("simulation.mass_scaling"), message: &["must lie in 1 … 10000"] },
    BadInput { what: "mass scaling beyond 10 000", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nmass_scaling = 1e5")], field: Some("simulation.mass_scaling"), message: &["must lie in 1 … 10000"] },
    BadInput { what: "time step safety zero", edits: &[("time_step_safety = 0.5", "time_step_safety = 0")], field: Some("simulation.time_step_safety"), message: &["= 0: must be greater than 0"] },
    BadInput { what: "unknown solver", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nsolver = \"newton\"")], field: Some("simulation.solver"), message: &["unknown solver 'newton'"] },
    BadInput { what: "implicit step above 1 s", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nimplicit_time_step_s = 2.0")], field: Some("simulation.implicit_time_step_s"), message: &["must lie in (0, 1] s"] },
    BadInput { what: "negative damping", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\ndamping_mass_per_s = -1")], field: Some("simulation.damping_mass_per_s"), message: &["must not be negative"] },
    BadInput { what: "unknown hose contact rule", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nhose_contact = \"some\"")], field: Some("simulation.hose_contact"), message: &["unknown hose contact rule 'some'", "apart_at_rest"] },
    BadInput { what: "no static iterations", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nstatic_max_iterations = 0")], field: Some("simulation.static_max_iterations"), message: &["must lie in 1 … 10000"] },
    BadInput { what: "too many static iterations", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\nstatic_max_iterations = 1000000")], field: Some("simulation.static_max_iterations"), message: &["must lie in 1 … 10000"] },
    BadInput { what: "non-positive fixed time step", edits: &[("time_step_safety = 0.5", "time_step_safety = 0.5\ntime_step_s = 0")], field: Some("simulation.time_step_s"), message: &["must be greater than 0"] },
];

#[test]
fn base_scene_is_valid() {
    let scene = load_scene_str(BASE, "base.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.hose_names, ["a", "b"]);
    // 4 elements were asked for, but the arc (R = 125 mm) needs more.
    assert!(scene.hoses[0].raised_for_arcs);
    assert!(scene.hoses[0].elements > 4);
}

#[test]
fn every_bad_input_is_named_and_explained() {
    check_bad_inputs(
        BASE,
        CASES,
        "scene.toml",
        |text| load_scene_str(text, "scene.toml"),
        |e| e.field(),
    );
    assert!(CASES.len() >= 18);
}

#[test]
fn syntax_errors_keep_line_and_column() {
    let text = BASE.replacen("elements = 4", "elements = = 10", 1);
    let err = load_scene_str(&text, "scene.toml").unwrap_err();
    assert!(matches!(err, SceneError::Syntax { .. }), "{err}");
    let line = BASE
        .lines()
        .position(|l| l.starts_with("elements = 4"))
        .unwrap()
        + 1;
    assert_eq!(err.location().map(|(l, _)| l), Some(line), "{err}");
    assert!(
        err.to_string().starts_with(&format!("scene.toml:{line}:")),
        "{err}"
    );
}

#[test]
fn shape_errors_keep_line_and_column() {
    let text = BASE.replacen("elements = 4", "elements = \"ten\"", 1);
    let err = load_scene_str(&text, "scene.toml").unwrap_err();
    let line = BASE
        .lines()
        .position(|l| l.starts_with("elements = 4"))
        .unwrap()
        + 1;
    assert_eq!(err.location(), Some((line, 12)), "{err}");
    let text = BASE.replacen("d_inner = 27,", "d_innr = 27,", 1);
    let err = load_scene_str(&text, "scene.toml").unwrap_err();
    let line = BASE
        .lines()
        .position(|l| l.contains("d_inner = 27,"))
        .unwrap()
        + 1;
    assert_eq!(err.location().map(|(l, _)| l), Some(line), "{err}");
}

#[test]
fn json_errors_name_field_and_position() {
    let err = load_scene_json_str(
        "{\"format\": \"pliant-scene\", \"version\": 1, \"length_unit\": \"mm\", \"hoses\": 3}",
        "s.json",
    )
    .unwrap_err();
    assert_eq!(err.field(), Some("hoses"), "{err}");
    assert!(err.location().is_some());
    let err = load_scene_json_str("{\"format\": ", "s.json").unwrap_err();
    assert!(matches!(err, SceneError::Syntax { .. }), "{err}");
}

#[test]
fn garbage_never_panics() {
    let inputs = [
        String::new(),
        "\u{0}".to_string(),
        "format = \"pliant-scene\"\nversion = 1".to_string(),
        "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\nhoses = []".to_string(),
        "[[[".to_string(),
        BASE.replace("0", "-"),
        BASE.replace("]", ""),
        BASE.replace("1", "1e400"),
        BASE.replace("= [", "= [[").replace("]\n", "]]\n"),
    ];
    for (i, text) in inputs.iter().enumerate() {
        let result = catch_unwind(AssertUnwindSafe(|| load_scene_str(text, "g.toml")));
        match result {
            Ok(Ok(_)) => panic!("garbage {i} loaded"),
            Ok(Err(e)) => assert!(!e.to_string().is_empty()),
            Err(_) => panic!("garbage {i} panicked"),
        }
    }
    // Every prefix of a valid scene: errors or loads, never panics.
    for cut in (0..BASE.len())
        .filter(|&c| BASE.is_char_boundary(c))
        .step_by(7)
    {
        let result = catch_unwind(AssertUnwindSafe(|| load_scene_str(&BASE[..cut], "p.toml")));
        assert!(result.is_ok(), "prefix of {cut} bytes panicked");
    }
}

#[test]
fn empty_hose_list_is_rejected() {
    let text = "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\nhoses = []\n";
    let err = load_scene_str(text, "scene.toml").unwrap_err();
    assert_eq!(err.field(), Some("hoses"), "{err}");
    assert!(err.to_string().contains("at least one hose"), "{err}");
}

#[test]
fn a_time_step_safety_too_large_for_contact_or_supports_is_warned_about() {
    let load = |safety: &str| {
        load_scene_str(
            &BASE.replace("time_step_safety = 0.5", safety),
            "safety.toml",
        )
        .expect("a valid scene")
        .warnings
    };
    assert!(load("time_step_safety = 0.5").is_empty());
    // above 0.5: hose–hose contact; above 0.65: supports as well
    let contact = load("time_step_safety = 0.64");
    assert!(
        contact.len() == 1
            && contact[0].contains("simulation.time_step_safety = 0.64")
            && contact[0].contains("hoses pressing on each other")
            && !contact[0].contains("supports"),
        "{contact:?}"
    );
    let warned = load("time_step_safety = 0.9");
    assert!(
        warned.len() == 1
            && warned[0].contains("simulation.time_step_safety = 0.9")
            && warned[0].contains("hoses pressing on each other")
            && warned[0].contains("above 0.65 so can the springs"),
        "{warned:?}"
    );
}

/// `n` hoses of `elements` elements, 500 mm long, `spacing` mm apart (0: on top of each
/// other).
fn many_hoses(n: usize, elements: usize, spacing: f64) -> String {
    let mut s = String::from("format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n");
    for i in 0..n {
        let y = i as f64 * spacing;
        s.push_str(&format!(
            "[[hoses]]\nname = \"h{i}\"\nmaterial = \"hose1\"\nstart = [0, {y}, 0]\npath = [{{ line = {{ to = [500, {y}, 0] }} }}]\nelements = {elements}\n"
        ));
    }
    s
}

/// 5 000 hoses of 4 elements laid on one line (640 KB of TOML, 20 000
/// elements, within every per-field limit) list 2·10⁸ contact pairs — several GB. The
/// estimate counts them, and the scene is refused naming them, before any is built.
#[test]
fn hoses_laid_on_each_other_are_refused_for_their_contact_pairs() {
    let options = pliant_scene::LoadOptions {
        limits: pliant_scene::Limits::with_memory(1_000_000_000),
        ..Default::default()
    };
    let load = |text: &str| {
        pliant_scene::load_scene_str_with(text, "many.toml", std::path::Path::new("."), &options)
    };
    let err = load(&many_hoses(5000, 4, 0.0)).unwrap_err().to_string();
    assert!(
        err.contains("hoses") && err.contains("contact pairs") && err.contains("1.0 GB"),
        "{err}"
    );
    let apart = load(&many_hoses(500, 4, 100.0)).unwrap();
    assert_eq!(apart.estimate.contact_pairs, 0);
    assert_eq!(apart.estimate.elements, 2000);
}

/// An error echoing a user's key of 100 000 characters clips it to its start
/// and its length.
#[test]
fn a_huge_unknown_key_is_echoed_clipped() {
    let key = "k".repeat(100_000);
    let text = BASE.replace(
        "time_step_safety = 0.5",
        &format!("time_step_safety = 0.5\n{key} = 1"),
    );
    let err = load_scene_str(&text, "huge.toml").unwrap_err().to_string();
    assert!(err.len() < 1000, "{} chars: {}", err.len(), &err[..200]);
    assert!(err.contains("…(") && err.contains("chars)"), "{err}");
    assert!(err.contains("unknown field"), "{err}");
}

/// A yielding material's fields are read in MPa and reach the core in Pa.
#[test]
fn yield_fields_are_converted_to_si() {
    let text = BASE.replace(
        "density_kg_m3 = 1000",
        "density_kg_m3 = 1000\nyield_stress_mpa = 250\nhardening_modulus_mpa = 2000",
    );
    let scene = load_scene_str(&text, "scene.toml").unwrap_or_else(|e| panic!("{e}"));
    let law = scene.world.hoses[1]
        .material
        .plasticity
        .expect("the material yields");
    assert_eq!(law.yield_stress, 250e6);
    assert_eq!(law.hardening_modulus, 2000e6);
    assert!(scene.world.hoses[0].material.plasticity.is_none());
}
