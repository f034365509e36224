//! The message protocol, version [`PROTOCOL_VERSION`]: JSON text messages over WebSocket,
//! each an object with a `type` field. Documented in `docs/protocol.md`.

use crate::ownership::HandId;
use crate::snapshot::{SceneData, Snapshot};
use serde::{Deserialize, Serialize};

/// Version of the protocol this server speaks.
pub const PROTOCOL_VERSION: u32 = 1;

/// Client → server.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ClientMessage {
    /// Must come first; the server answers `welcome` and starts sending snapshots.
    Hello { version: u32 },
    /// Grab the beam nearest to `position` \[m\] with hand `hand_id`; `grip` "firm"
    /// (default), "axial" or "ball" (the hose may turn in the hand).
    Grab {
        hand_id: HandId,
        position: [f64; 3],
        #[serde(default, skip_serializing_if = "pliant_assembly::Grip::is_firm")]
        grip: pliant_assembly::Grip,
    },
    /// Set the hand's target pose: position \[m\], orientation as a unit quaternion
    /// `[x, y, z, w]` (kept when omitted).
    Move {
        hand_id: HandId,
        position: [f64; 3],
        #[serde(default)]
        orientation: Option<[f64; 4]>,
    },
    /// Let go.
    Release { hand_id: HandId },
    /// Move the part called `part` over `duration_s` seconds (smooth start and stop):
    /// by the offset `by` \[m\] from where it is, or so that its centre (its bounding
    /// box's) is `to` \[m\] from where the scene placed it (one of the two). The part must be movable (`movable = true`
    /// in the scene) and have no scripted motion; a refusal comes back as the
    /// snapshot's `notice`.
    MovePart {
        part: String,
        #[serde(default)]
        by: Option<[f64; 3]>,
        #[serde(default)]
        to: Option<[f64; 3]>,
        duration_s: f64,
    },
    /// Turn the part called `part` about `axis` through `point` \[m\] (a point of the
    /// part where the scene placed it; default: its bounding box's centre) by `by_deg`
    /// degrees from where it is, or to `to_deg` degrees from where the scene placed it,
    /// over `duration_s` seconds. Refused as `move_part`.
    RotatePart {
        part: String,
        axis: [f64; 3],
        #[serde(default)]
        point: Option<[f64; 3]>,
        #[serde(default)]
        by_deg: Option<f64>,
        #[serde(default)]
        to_deg: Option<f64>,
        duration_s: f64,
    },
    /// The VR user's body poses the worker (docs/worker.md; only in a scene with a
    /// `[worker]`): `head` the headset's eyes (`position` \[m\]) and where it looks
    /// (`gaze`, a direction of any non-zero length), `hands` the controllers' grips
    /// (right, left; `null`: not tracked) \[m\]. Send it at most 20 times a second;
    /// it is recorded in the session's log like every input.
    WorkerPose {
        #[serde(default)]
        head: Option<HeadPose>,
        #[serde(default)]
        hands: [Option<[f64; 3]>; 2],
    },
    /// Stop stepping (snapshots keep coming).
    Pause,
    /// Step in real time again.
    Resume,
    /// Advance `n` steps now (1 ≤ n ≤ 100 000), mainly while paused.
    Step { n: u32 },
    /// Back to the rest state; every hand is released.
    Reset,
    /// Judge hand loads with another ergonomic profile (SPEC I3) from now on: `posture`
    /// (standing, crouching, sitting), `population` (women, men), `duty` (continuous,
    /// occasional) and optionally `moments_decide` (whether twist and bending at the hand
    /// count towards feasibility; default false). Omitted fields keep their current value. The running verdict is re-judged against the new limits.
    SetErgonomics {
        /// A whole profile in the form of `pliant run --ergonomics` (e.g.
        /// `standard=en1005-3, action=arm`): replaces the current one before the other
        /// fields apply.
        #[serde(default)]
        profile: Option<String>,
        #[serde(default)]
        posture: Option<String>,
        #[serde(default)]
        population: Option<String>,
        #[serde(default)]
        duty: Option<String>,
        #[serde(default)]
        moments_decide: Option<bool>,
    },
    /// Replace the session's scene with the scene file `text` (TOML, or JSON when
    /// `format` is `"json"`); `name` names it in messages. On success every client gets a
    /// new `welcome`; on error the sender gets `error{invalid_scene}` with the loader's
    /// message and the old session keeps running.
    LoadScene {
        text: String,
        #[serde(default)]
        format: Option<String>,
        #[serde(default)]
        name: Option<String>,
    },
    /// Write the session's report so far (SPEC W2): the same `report.html`,
    /// `report.json`, `summary.json` and CSVs as `pliant run`, made by replaying the
    /// session's input log, with the log beside them. The sender gets `report` when it
    /// is written; the session runs on meanwhile.
    Report,
    /// Ask for the session's scene file as a document to edit (scene authoring in the
    /// viewer, docs/authoring.md): the server answers `scene_source` with the file's text,
    /// its raw structure as JSON and the built-in material library. (A struct variant,
    /// so that unknown fields are refused as for every other message.)
    SceneSource {},
}

/// A headset's pose in `worker_pose`: where the eyes are and where they look.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadPose {
    pub position: [f64; 3],
    pub gaze: [f64; 3],
}

/// Error codes of `error` messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorCode {
    /// Not JSON, or not a known message (unknown `type`, missing or wrong fields).
    Malformed,
    /// Larger than the size limit.
    MessageTooLarge,
    /// Over the rate limit; messages were dropped.
    RateLimited,
    /// `hello` with a version this server does not speak.
    UnsupportedVersion,
    /// A message other than `hello` before `hello`.
    HelloRequired,
    /// The hand belongs to another client.
    HandOwned,
    /// No such hand is held.
    HandNotHeld,
    /// The session holds the most hands it may.
    TooManyHands,
    /// A value out of range (non-finite position, n out of range, zero quaternion).
    InvalidValue,
    /// Binary messages are not part of the protocol.
    BinaryNotSupported,
    /// A `load_scene` whose scene could not be loaded (the message is the loader's).
    InvalidScene,
    /// A `report` that could not be written (the session records into no folder, or
    /// writing failed).
    ReportFailed,
    /// The session's command queue is full; the command was dropped.
    Busy,
    /// `hello` while the server has its most clients (`--max-clients`); say `hello`
    /// again later (the connection is closed at the hello deadline meanwhile).
    ServerFull,
}

/// Server → client.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ServerMessage<'a> {
    Welcome {
        version: u32,
        client_id: u64,
        session: &'a SceneData,
    },
    Snapshot(&'a Snapshot),
    /// The answer to `report`: where the report is and its verdict, its size, the
    /// record interval of its time series (raised above the scene's to keep a long
    /// session's report within its size limit) and the session's older reports removed
    /// to keep them all within theirs (`crate::reports`).
    Report {
        folder: String,
        verdict: &'a pliant_assembly::Verdict,
        bytes: u64,
        record_interval_s: f64,
        removed: Vec<String>,
    },
    Error {
        code: ErrorCode,
        message: String,
    },
    /// The answer to `scene_source`.
    SceneSource(&'a SceneSource),
}

/// The session's scene file, for editing in the viewer (the answer to `scene_source`).
#[derive(Clone, Debug, Serialize)]
pub struct SceneSource {
    /// The scene's name.
    pub scene: String,
    /// Where it came from (a path, or the built-in demo).
    pub source: String,
    /// The file's `length_unit`: `"mm"` or `"m"`.
    pub length_unit: &'static str,
    /// The scene file's text as loaded.
    pub text: String,
    /// Its raw structure (lengths in `length_unit`, nothing converted), or `null` when the
    /// text is neither TOML nor JSON (it always is for a loaded scene).
    pub document: Option<serde_json::Value>,
    /// The built-in material library: the materials a hose may name without a
    /// `[materials]` table.
    pub library: Vec<LibraryHose>,
}

/// One built-in library hose (SI units).
#[derive(Clone, Debug, Serialize)]
pub struct LibraryHose {
    pub name: String,
    pub description: String,
    /// The library hose's own cross-section \[m\]: the default `section`.
    pub d_inner: f64,
    pub d_outer: f64,
    /// Smallest bend radius of the centre line \[m\].
    pub min_bend_radius: f64,
}

impl SceneSource {
    /// The source of a loaded scene, with the built-in library.
    pub fn of(scene: &pliant_scene::LoadedScene) -> SceneSource {
        let library = pliant_scene::Library::builtin()
            .map(|l| {
                l.entries()
                    .iter()
                    .map(|e| LibraryHose {
                        name: e.name.clone(),
                        description: e.description.clone(),
                        d_inner: e.section.d_inner,
                        d_outer: e.section.d_outer,
                        min_bend_radius: e.min_bend_radius,
                    })
                    .collect()
            })
            .unwrap_or_default();
        SceneSource {
            scene: scene.name.clone(),
            source: scene.source.clone(),
            length_unit: scene.length_unit.symbol(),
            text: scene.text.clone(),
            document: pliant_scene::scene_document(&scene.text).ok(),
            library,
        }
    }
}

impl ServerMessage<'_> {
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("server messages always serialise")
    }
}

/// An error message as JSON text.
pub fn error_json(code: ErrorCode, message: impl Into<String>) -> String {
    let message = message.into();
    ServerMessage::Error {
        code,
        // a client's key or value echoed in the message is clipped
        message: pliant_scene::clip::clip_words(&message).into_owned(),
    }
    .to_json()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grab_takes_a_grip_firm_by_default() {
        let grab = |text: &str| serde_json::from_str::<ClientMessage>(text).unwrap();
        let m = grab(r#"{"type":"grab","hand_id":1,"position":[0,0,0],"grip":"ball"}"#);
        assert!(matches!(
            m,
            ClientMessage::Grab {
                grip: pliant_assembly::Grip::Ball,
                ..
            }
        ));
        let m = grab(r#"{"type":"grab","hand_id":1,"position":[0,0,0]}"#);
        assert!(matches!(
            m,
            ClientMessage::Grab {
                grip: pliant_assembly::Grip::Firm,
                ..
            }
        ));
        assert!(serde_json::from_str::<ClientMessage>(
            r#"{"type":"grab","hand_id":1,"position":[0,0,0],"grip":"loose"}"#
        )
        .is_err());
    }

    #[test]
    fn scene_source_takes_no_fields() {
        let m: ClientMessage = serde_json::from_str(r#"{"type":"scene_source"}"#).unwrap();
        assert_eq!(m, ClientMessage::SceneSource {});
        assert!(serde_json::from_str::<ClientMessage>(
            r#"{"type":"scene_source","path":"/etc/passwd"}"#
        )
        .is_err());
    }

    #[test]
    fn messages_parse_as_documented() {
        let m: ClientMessage =
            serde_json::from_str(r#"{"type":"move","hand_id":2,"position":[1,2,3]}"#).unwrap();
        assert_eq!(
            m,
            ClientMessage::Move {
                hand_id: 2,
                position: [1.0, 2.0, 3.0],
                orientation: None
            }
        );
        let m: ClientMessage = serde_json::from_str(r#"{"type":"pause"}"#).unwrap();
        assert_eq!(m, ClientMessage::Pause);
        assert!(serde_json::from_str::<ClientMessage>(r#"{"type":"jump"}"#).is_err());
        assert!(serde_json::from_str::<ClientMessage>(r#"{"type":"step","n":-1}"#).is_err());
        let m: ClientMessage =
            serde_json::from_str(r#"{"type":"set_ergonomics","posture":"sitting"}"#).unwrap();
        assert_eq!(
            m,
            ClientMessage::SetErgonomics {
                profile: None,
                posture: Some("sitting".into()),
                population: None,
                duty: None,
                moments_decide: None
            }
        );
        let m: ClientMessage =
            serde_json::from_str(r#"{"type":"load_scene","text":"x","name":"a.toml"}"#).unwrap();
        assert!(matches!(m, ClientMessage::LoadScene { .. }));
        let e = error_json(ErrorCode::HandOwned, "x");
        assert_eq!(e, r#"{"type":"error","code":"hand_owned","message":"x"}"#);
    }
}
