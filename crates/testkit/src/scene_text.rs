//! A scene file's text (docs/scene-format.md) put together from typed pieces, so a test
//! says only what its scene has of its own: `SceneText::mm()` and then tables — the
//! `[simulation]`, a `[worker]`, a straight hose, a box part, the timeline's actions —
//! each a [`Table`] whose keys a test may add to (`.number("elements", 10.0)`,
//! `.inline("motion", "{ kind = \"hinge\", … }")`).
//!
//! Numbers are written so that the reader gets back the very `f64` given (whole numbers
//! as TOML integers, so they also fill integer fields; others in Rust's shortest
//! round-trip form), so a scene built here is the scene its hand-written text was.

use crate::scenes::HEAD_MM;
use std::fmt::Write;

/// A scene's text in millimetres, built table by table in the order given (the timeline's
/// actions run in that order).
#[derive(Clone, Debug)]
pub struct SceneText {
    text: String,
}

impl SceneText {
    /// The head of a scene in millimetres (format, version, length unit), nothing else.
    pub fn mm() -> Self {
        Self {
            text: HEAD_MM.to_owned(),
        }
    }

    /// The head of a scene in millimetres and the scene's `name`.
    pub fn mm_named(name: &str) -> Self {
        let mut scene = Self::mm();
        scene.text.push_str(&format!("name = {}\n", quoted(name)));
        scene
    }

    /// No head: tables for a test that puts its own head (or other pieces) before them.
    pub fn piece() -> Self {
        Self {
            text: String::new(),
        }
    }

    /// The scene with `table` appended.
    pub fn with(mut self, table: Table) -> Self {
        self.text.push('\n');
        self.text.push_str(&table.text);
        self
    }

    /// The scene with every table of `tables` appended, in order.
    pub fn with_all(self, tables: impl IntoIterator<Item = Table>) -> Self {
        tables.into_iter().fold(self, Self::with)
    }

    /// The scene with a piece of hand-written scene text appended (for what a test writes
    /// on purpose, such as a bad field the reader must refuse).
    pub fn raw(mut self, piece: &str) -> Self {
        self.text.push('\n');
        self.text.push_str(piece);
        self.text.push('\n');
        self
    }
}

impl From<SceneText> for String {
    fn from(scene: SceneText) -> String {
        scene.text
    }
}

/// One table of a scene, `[name]` or one entry of `[[name]]`, and its `key = value`
/// lines in the order they are added.
#[derive(Clone, Debug)]
pub struct Table {
    text: String,
}

impl Table {
    /// The single table `[name]` (such as `simulation` or `worker`).
    pub fn single(name: &str) -> Self {
        Self {
            text: format!("[{name}]\n"),
        }
    }

    /// One entry of the array of tables `[[name]]` (such as `hoses` or `timeline`).
    pub fn entry(name: &str) -> Self {
        Self {
            text: format!("[[{name}]]\n"),
        }
    }

    /// `key = "value"`.
    pub fn text(self, key: &str, value: &str) -> Self {
        self.line(key, &quoted(value))
    }

    /// `key = value`, a number.
    pub fn number(self, key: &str, value: f64) -> Self {
        self.line(key, &number(value))
    }

    /// `key = [x, y, z]`, a point or vector.
    pub fn point(self, key: &str, p: [f64; 3]) -> Self {
        self.line(key, &point(p))
    }

    /// `key = true` or `key = false`.
    pub fn flag(self, key: &str, value: bool) -> Self {
        self.line(key, &value.to_string())
    }

    /// `key = value`, the value written as TOML by the test (an inline table or array).
    pub fn inline(self, key: &str, value: &str) -> Self {
        self.line(key, value)
    }

    fn line(mut self, key: &str, value: &str) -> Self {
        // writing to a String cannot fail
        let _ = writeln!(self.text, "{key} = {value}");
        self
    }
}

/// `value` as a TOML number that reads back as the same `f64`: a whole number of
/// magnitude below 2⁵³ as an integer, any other in the shortest round-trip form.
fn number(value: f64) -> String {
    if value.fract() == 0.0 && value.abs() < 9_007_199_254_740_992.0 {
        format!("{}", value as i64)
    } else {
        format!("{value:?}")
    }
}

/// `value` as a TOML string (quoted and escaped as the `toml` crate writes it).
fn quoted(value: &str) -> String {
    toml::Value::String(value.to_owned()).to_string()
}

/// `[x, y, z]` of [`number`]s.
fn point([x, y, z]: [f64; 3]) -> String {
    format!("[{}, {}, {}]", number(x), number(y), number(z))
}

/// The `[simulation]` table, empty (add `solver`, `gravity`, … to it).
pub fn simulation() -> Table {
    Table::single("simulation")
}

/// `[simulation]` with the given solver ("explicit", "implicit", "static").
pub fn solver(kind: &str) -> Table {
    simulation().text("solver", kind)
}

/// `[worker]` of the given population ("male", "female 5", "male 50", …).
pub fn worker(population: &str) -> Table {
    Table::single("worker").text("population", population)
}

/// A hose `name` of `material`, straight from `start` to `to` (mm).
pub fn hose(name: &str, material: &str, start: [f64; 3], to: [f64; 3]) -> Table {
    Table::entry("hoses")
        .text("name", name)
        .text("material", material)
        .point("start", start)
        .inline("path", &format!("[{{ line = {{ to = {} }} }}]", point(to)))
}

/// A part `name`, a box of `size` (mm) centred at `position` (mm).
pub fn box_part(name: &str, size: [f64; 3], position: [f64; 3]) -> Table {
    Table::entry("parts")
        .text("name", name)
        .inline("box", &format!("{{ size = {} }}", point(size)))
        .point("position", position)
}

/// A timeline action of kind `action`, without its fields yet.
pub fn action(action: &str) -> Table {
    Table::entry("timeline").text("action", action)
}

/// The timeline's `fix` of node `node` of hose `hose` (negative: counted from the end).
pub fn fix(hose: &str, node: i64) -> Table {
    action("fix").text("hose", hose).number("node", node as f64)
}

/// The timeline's `mount` of node `node` of hose `hose` on part `part`.
pub fn mount(hose: &str, node: i64, part: &str) -> Table {
    action("mount")
        .text("hose", hose)
        .number("node", node as f64)
        .text("part", part)
}

/// The timeline's `grab` by hand `hand` at `at` (mm).
pub fn grab(hand: usize, at: [f64; 3]) -> Table {
    action("grab").number("hand", hand as f64).point("at", at)
}

/// The timeline's `move_hand` of hand `hand` by `by` (mm) over `duration_s`.
pub fn move_hand(hand: usize, by: [f64; 3], duration_s: f64) -> Table {
    action("move_hand")
        .number("hand", hand as f64)
        .point("by", by)
        .number("duration_s", duration_s)
}

/// The timeline's `rotate_part` of part `part` about `axis` through `point` (mm), without
/// its angle (`to_deg` or `by_deg`) and duration yet.
pub fn rotate_part(part: &str, axis: [f64; 3], point: [f64; 3]) -> Table {
    action("rotate_part")
        .text("part", part)
        .point("axis", axis)
        .point("point", point)
}

/// The timeline's `move_part` of part `part`, without its `by` or `to` and duration yet.
pub fn move_part(part: &str) -> Table {
    action("move_part").text("part", part)
}

/// The timeline's `load` on node `node` of hose `hose` (negative: counted from the end),
/// without its force or moment yet.
pub fn load(hose: &str, node: i64) -> Table {
    action("load")
        .text("hose", hose)
        .number("node", node as f64)
}

/// The timeline's `settle` until the kinetic energy is below `kinetic_energy_j`, for at
/// most `max_duration_s`.
pub fn settle(kinetic_energy_j: f64, max_duration_s: f64) -> Table {
    action("settle")
        .number("kinetic_energy_j", kinetic_energy_j)
        .number("max_duration_s", max_duration_s)
}

/// The timeline's `run` for `duration_s`.
pub fn run_for(duration_s: f64) -> Table {
    action("run").number("duration_s", duration_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_as_given() {
        for v in [
            0.0,
            -200.0,
            1900.0,
            0.3,
            1e-9,
            -0.5 * 0.397 * 1e3,
            1e21,
            2.0f64.powi(53),
        ] {
            let written = number(v);
            let read: f64 = written.parse().unwrap();
            assert_eq!(read.to_bits(), v.to_bits(), "{v} written as {written}");
        }
        assert_eq!(number(10.0), "10", "a whole number fills an integer field");
        assert_eq!(number(0.3), "0.3");
    }

    #[test]
    fn strings_read_back_as_given() {
        assert_eq!(quoted("male 50"), "\"male 50\"");
        for v in ["male 50", "a \"b\" \\ c\n", "d'e"] {
            let line = format!("k = {}", quoted(v));
            let read: toml::Table = line.parse().unwrap();
            assert_eq!(read["k"].as_str(), Some(v), "{line}");
        }
    }

    #[test]
    fn a_scene_is_its_tables_in_order() {
        let text: String = SceneText::mm()
            .with(solver("static"))
            .with(hose("h", "hose3", [0.0, 0.0, 0.0], [300.0, 0.0, 0.0]).number("elements", 10.0))
            .with(fix("h", 0))
            .with(move_hand(0, [0.0, 0.0, -20.0], 0.3))
            .into();
        let expected = concat!(
            "\nformat = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n",
            "\n[simulation]\nsolver = \"static\"\n",
            "\n[[hoses]]\nname = \"h\"\nmaterial = \"hose3\"\nstart = [0, 0, 0]\n",
            "path = [{ line = { to = [300, 0, 0] } }]\nelements = 10\n",
            "\n[[timeline]]\naction = \"fix\"\nhose = \"h\"\nnode = 0\n",
            "\n[[timeline]]\naction = \"move_hand\"\nhand = 0\nby = [0, 0, -20]\nduration_s = 0.3\n",
        );
        assert_eq!(text, expected);
    }
}
