//! Pliant's interactive server (SPEC I1, I2, I4, I6): the simulation runs in its own thread
//! at its own rate ([`session`]), publishes the newest snapshot ([`snapshot`]) and takes
//! hand input from any client — browser, VR, script — through one versioned JSON protocol
//! over WebSocket ([`protocol`], documented in `docs/protocol.md`), and serves the
//! browser/VR viewer embedded at compile time ([`assets`]). Only the server's own pages
//! (and allowed origins, with the token when one is set) may connect ([`access`]); misbehaving clients get
//! error replies ([`limits`]); hands belong to the client that grabbed them ([`ownership`]); a
//! session's reports are bounded in rate and size ([`reports`]).

pub mod access;
pub mod assets;
pub mod haptic;
pub mod joints;
pub mod limits;
pub mod ownership;
pub mod protocol;
pub mod reports;
pub mod server;
pub mod session;
pub mod snapshot;

pub use protocol::{ClientMessage, ServerMessage, PROTOCOL_VERSION};
pub use server::{router, serve, start, RunningServer, ServerConfig};
pub use session::{Command, Session, SessionError};
pub use snapshot::{HandSnapshot, HoseSnapshot, Snapshot};
