//! Hand-written deserialisation of timeline actions. Serde's derived internally tagged
//! enums buffer their content, which loses the path of any error inside an action; here
//! the `action` tag is read first and the rest deserialised as that action's struct with
//! its path tracked, so an error names e.g. `timeline[1].rotate.axis`.
//!
//! Errors inside an action are reported as ``in `PATH`: MESSAGE``; the loader folds PATH
//! into the field path.

use crate::format::{ActionEntry, ACTION_NAMES};
use serde::de::{DeserializeOwned, Error};
use serde::{Deserialize, Deserializer};

/// Prefix of an error message that carries a path inside an action.
pub const INNER_PATH_PREFIX: &str = "in `";

/// Deserialises `rest` as `T`, reporting errors with their path inside the action.
fn part<T: DeserializeOwned, E: Error>(rest: toml::Table) -> Result<T, E> {
    serde_path_to_error::deserialize(toml::Value::Table(rest)).map_err(|e| {
        let path = e.path().to_string();
        let message = e.into_inner().to_string();
        let message = message.trim();
        if path == "." {
            E::custom(message)
        } else {
            E::custom(format!("{INNER_PATH_PREFIX}{path}`: {message}"))
        }
    })
}

impl<'de> Deserialize<'de> for ActionEntry {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = toml::Value::deserialize(deserializer)?;
        let toml::Value::Table(mut table) = value else {
            return Err(D::Error::custom(format!(
                "expected a table with an `action`, found {}",
                value.type_str()
            )));
        };
        let tag = match table.remove("action") {
            Some(toml::Value::String(s)) => s,
            Some(other) => {
                return Err(D::Error::custom(format!(
                    "{INNER_PATH_PREFIX}action`: expected a string, found {}",
                    other.type_str()
                )))
            }
            None => return Err(D::Error::missing_field("action")),
        };
        Ok(match tag.as_str() {
            "fix" => ActionEntry::Fix(part(table)?),
            "mount" => ActionEntry::Mount(part(table)?),
            "move" => ActionEntry::Move(part(table)?),
            "load" => ActionEntry::Load(part(table)?),
            "unload" => ActionEntry::Unload(part(table)?),
            "release" => ActionEntry::Release(part(table)?),
            "tie" => ActionEntry::Tie(part(table)?),
            "grab" => ActionEntry::Grab(part(table)?),
            "move_hand" => ActionEntry::MoveHand(part(table)?),
            "align_hand" => ActionEntry::AlignHand(part(table)?),
            "aim_hand" => ActionEntry::AimHand(part(table)?),
            "release_hand" => ActionEntry::ReleaseHand(part(table)?),
            "move_part" => ActionEntry::MovePart(part(table)?),
            "rotate_part" => ActionEntry::RotatePart(part(table)?),
            "run" => ActionEntry::Run(part(table)?),
            "settle" => ActionEntry::Settle(part(table)?),
            other => {
                let expected: Vec<String> = ACTION_NAMES.iter().map(|n| format!("`{n}`")).collect();
                return Err(D::Error::custom(format!(
                    "{INNER_PATH_PREFIX}action`: unknown action `{other}`, expected one of {}",
                    expected.join(", ")
                )));
            }
        })
    }
}
