//! The haptic stream's datagrams (SPEC H1, docs/protocol.md "Haptic force stream"):
//! fixed-size, little-endian, each starting with a magic and a version byte. A request
//! carries a hand pose (or a grab or release) and a sequence number; the reply echoes the
//! sequence number and carries the hand's force and torque and a status. Decoding never
//! panics: every byte string is either a [`Request`] or a [`Status`] saying why not.

use glam::{DQuat, DVec3};
use pliant_assembly::Grip;

/// Version of the datagram layout.
pub const VERSION: u8 = 1;
/// First four bytes of a request.
pub const REQUEST_MAGIC: [u8; 4] = *b"PLHP";
/// First four bytes of a reply.
pub const REPLY_MAGIC: [u8; 4] = *b"PLHR";
/// Size of every request \[bytes\].
pub const REQUEST_BYTES: usize = 112;
/// Size of every reply \[bytes\] (smaller than a request: a reply never amplifies).
pub const REPLY_BYTES: usize = 96;
/// Size of the key field (the server's token, zero-padded).
pub const KEY_BYTES: usize = 32;

/// Whether `b` has a request's size and magic: the only datagrams answered (a reply is
/// smaller than a request, so the stream never amplifies).
pub fn is_request_sized(b: &[u8]) -> bool {
    b.len() == REQUEST_BYTES && b[0..4] == REQUEST_MAGIC
}

/// What a request asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// The hand's pose now: answer its force and torque (and move the session's hand).
    Pose,
    /// Grab the beam nearest to the position with the grip.
    Grab(Grip),
    /// Let go.
    Release,
}

/// A decoded request.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Request {
    pub kind: Kind,
    pub hand: u32,
    pub sequence: u64,
    /// \[m\], world frame.
    pub position: DVec3,
    /// Unit quaternion; `None` when the request sent all zeros (keep the orientation).
    pub orientation: Option<DQuat>,
    pub key: [u8; KEY_BYTES],
}

/// The status byte of a reply.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Status {
    /// Force and torque are the equilibrium's at the pose sent.
    Ok = 0,
    /// The equilibrium solve stopped short of its tolerance: the force is the last
    /// iterate's (finite), to be used with care.
    NotConverged = 1,
    /// The grab was forwarded; the session has not taken it yet. Send again.
    Pending = 2,
    /// The hand holds nothing (never grabbed, released, or released by a reset or a
    /// divergence): grab first.
    NotHeld = 3,
    /// A WebSocket client owns this hand id (ownership as in the WebSocket protocol).
    HandOwned = 4,
    /// The session already has its maximum number of hands.
    TooManyHands = 5,
    /// A position not finite or beyond 1 km, a non-finite or zero quaternion, an unknown
    /// grip.
    InvalidValue = 6,
    /// Wrong size, wrong magic or unknown kind.
    Malformed = 7,
    /// A version other than [`VERSION`].
    UnsupportedVersion = 8,
    /// The server has a token and the key field does not carry it (a token is required
    /// whenever the WebSocket requires one).
    Unauthorised = 9,
    /// The equilibrium solve failed (singular or non-finite); the mirror was put back
    /// to the session's state. Force and torque are zero.
    SolveFailed = 10,
    /// The session's command queue was full: the grab or release was dropped.
    Busy = 11,
}

impl Status {
    /// Whether the force and torque of a reply with this status are meaningful.
    pub fn has_load(self) -> bool {
        matches!(self, Status::Ok | Status::NotConverged)
    }

    pub fn from_byte(b: u8) -> Option<Status> {
        use Status::*;
        [
            Ok,
            NotConverged,
            Pending,
            NotHeld,
            HandOwned,
            TooManyHands,
            InvalidValue,
            Malformed,
            UnsupportedVersion,
            Unauthorised,
            SolveFailed,
            Busy,
        ]
        .into_iter()
        .find(|s| *s as u8 == b)
    }

    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotConverged => "not_converged",
            Status::Pending => "pending",
            Status::NotHeld => "not_held",
            Status::HandOwned => "hand_owned",
            Status::TooManyHands => "too_many_hands",
            Status::InvalidValue => "invalid_value",
            Status::Malformed => "malformed",
            Status::UnsupportedVersion => "unsupported_version",
            Status::Unauthorised => "unauthorised",
            Status::SolveFailed => "solve_failed",
            Status::Busy => "busy",
        }
    }
}

/// A reply.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reply {
    pub status: Status,
    /// Newton iterations of the solve (0 without one).
    pub iterations: u16,
    pub hand: u32,
    /// The hose the hand holds, `u32::MAX` for none.
    pub hose: u32,
    pub sequence: u64,
    /// Force the hand applies to the hose \[N\].
    pub force: DVec3,
    /// Torque the hand applies about its position \[N·m\].
    pub torque: DVec3,
    /// Simulated time of the session state the answer started from \[s\].
    pub session_time: f64,
    /// Wall time of the answer's solve \[s\].
    pub solve_seconds: f64,
    /// Malformed datagrams received since the stream started (saturating).
    pub malformed: u32,
}

fn f64_at(b: &[u8], at: usize) -> f64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[at..at + 8]);
    f64::from_le_bytes(a)
}

fn u64_at(b: &[u8], at: usize) -> u64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[at..at + 8]);
    u64::from_le_bytes(a)
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    let mut a = [0u8; 4];
    a.copy_from_slice(&b[at..at + 4]);
    u32::from_le_bytes(a)
}

fn vec_at(b: &[u8], at: usize) -> DVec3 {
    DVec3::new(f64_at(b, at), f64_at(b, at + 8), f64_at(b, at + 16))
}

/// The sequence number a datagram carries where a request would, if it is long enough
/// (so that even a malformed datagram's reply can be matched); else 0.
pub fn sequence_of(b: &[u8]) -> u64 {
    if b.len() >= 24 {
        u64_at(b, 16)
    } else {
        0
    }
}

/// The hand id a datagram carries where a request would, if it is long enough; else 0.
pub fn hand_of(b: &[u8]) -> u32 {
    if b.len() >= 12 {
        u32_at(b, 8)
    } else {
        0
    }
}

impl Request {
    /// A request keeping the hand's orientation.
    pub fn new(
        kind: Kind,
        hand: u32,
        sequence: u64,
        position: DVec3,
        key: [u8; KEY_BYTES],
    ) -> Request {
        Request {
            kind,
            hand,
            sequence,
            position,
            orientation: None,
            key,
        }
    }

    /// Decodes a request. Layout (little-endian):
    /// magic `PLHP` (0..4), version (4), kind 0 pose / 1 grab / 2 release (5),
    /// grip 0 firm / 1 axial / 2 ball (6), reserved (7), hand id u32 (8..12),
    /// reserved (12..16), sequence u64 (16..24), position f64×3 \[m\] (24..48),
    /// orientation f64×4 x, y, z, w (48..80; all zero = keep), key (80..112).
    pub fn decode(b: &[u8]) -> Result<Request, Status> {
        if b.len() != REQUEST_BYTES || b[0..4] != REQUEST_MAGIC {
            return Err(Status::Malformed);
        }
        if b[4] != VERSION {
            return Err(Status::UnsupportedVersion);
        }
        let kind = match (b[5], b[6]) {
            (0, _) => Kind::Pose,
            (1, 0) => Kind::Grab(Grip::Firm),
            (1, 1) => Kind::Grab(Grip::Axial),
            (1, 2) => Kind::Grab(Grip::Ball),
            (1, _) => return Err(Status::InvalidValue),
            (2, _) => Kind::Release,
            _ => return Err(Status::Malformed),
        };
        let position = vec_at(b, 24);
        if !(position.is_finite() && position.abs().max_element() < 1e3) {
            return Err(Status::InvalidValue);
        }
        let q = [f64_at(b, 48), f64_at(b, 56), f64_at(b, 64), f64_at(b, 72)];
        let orientation = if q == [0.0; 4] {
            None
        } else {
            Some(
                pliant_core::math::near_unit_quaternion(DQuat::from_array(q))
                    .map_err(|_| Status::InvalidValue)?,
            )
        };
        let mut key = [0u8; KEY_BYTES];
        key.copy_from_slice(&b[80..112]);
        Ok(Request {
            kind,
            hand: u32_at(b, 8),
            sequence: u64_at(b, 16),
            position,
            orientation,
            key,
        })
    }

    /// Encodes the request (the test client's side of [`Request::decode`]).
    pub fn encode(&self) -> [u8; REQUEST_BYTES] {
        let mut b = [0u8; REQUEST_BYTES];
        b[0..4].copy_from_slice(&REQUEST_MAGIC);
        b[4] = VERSION;
        (b[5], b[6]) = match self.kind {
            Kind::Pose => (0, 0),
            Kind::Grab(Grip::Firm) => (1, 0),
            Kind::Grab(Grip::Axial) => (1, 1),
            Kind::Grab(Grip::Ball) => (1, 2),
            Kind::Release => (2, 0),
        };
        b[8..12].copy_from_slice(&self.hand.to_le_bytes());
        b[16..24].copy_from_slice(&self.sequence.to_le_bytes());
        for (k, v) in self.position.to_array().into_iter().enumerate() {
            b[24 + 8 * k..32 + 8 * k].copy_from_slice(&v.to_le_bytes());
        }
        let q = self.orientation.map_or([0.0; 4], |q| q.to_array());
        for (k, v) in q.into_iter().enumerate() {
            b[48 + 8 * k..56 + 8 * k].copy_from_slice(&v.to_le_bytes());
        }
        b[80..112].copy_from_slice(&self.key);
        b
    }

    /// The key field for a token: its bytes, zero-padded (`None` if longer than
    /// [`KEY_BYTES`]).
    pub fn key_for(token: Option<&str>) -> Option<[u8; KEY_BYTES]> {
        let mut key = [0u8; KEY_BYTES];
        if let Some(t) = token {
            let t = t.as_bytes();
            if t.len() > KEY_BYTES {
                return None;
            }
            key[..t.len()].copy_from_slice(t);
        }
        Some(key)
    }
}

impl Reply {
    /// A reply carrying only a status.
    pub fn status(status: Status, hand: u32, sequence: u64, malformed: u32) -> Reply {
        Reply {
            status,
            iterations: 0,
            hand,
            hose: u32::MAX,
            sequence,
            force: DVec3::ZERO,
            torque: DVec3::ZERO,
            session_time: 0.0,
            solve_seconds: 0.0,
            malformed,
        }
    }

    /// Encodes the reply. Layout (little-endian): magic `PLHR` (0..4), version (4),
    /// status (5), Newton iterations u16 (6..8), hand id u32 (8..12), hose u32 (12..16;
    /// `u32::MAX` none), sequence u64 echoed (16..24), force f64×3 \[N\] (24..48), torque
    /// f64×3 \[N·m\] about the hand position (48..72), session time f64 \[s\] (72..80),
    /// solve time f64 \[s\] (80..88), malformed datagrams so far u32 (88..92), reserved
    /// (92..96). Non-finite loads are sent as zeros.
    pub fn encode(&self) -> [u8; REPLY_BYTES] {
        let mut b = [0u8; REPLY_BYTES];
        b[0..4].copy_from_slice(&REPLY_MAGIC);
        b[4] = VERSION;
        b[5] = self.status as u8;
        b[6..8].copy_from_slice(&self.iterations.to_le_bytes());
        b[8..12].copy_from_slice(&self.hand.to_le_bytes());
        b[12..16].copy_from_slice(&self.hose.to_le_bytes());
        b[16..24].copy_from_slice(&self.sequence.to_le_bytes());
        let finite = |v: DVec3| if v.is_finite() { v } else { DVec3::ZERO };
        let values = finite(self.force)
            .to_array()
            .into_iter()
            .chain(finite(self.torque).to_array())
            .chain([self.session_time, self.solve_seconds]);
        for (k, v) in values.enumerate() {
            let v = if v.is_finite() { v } else { 0.0 };
            b[24 + 8 * k..32 + 8 * k].copy_from_slice(&v.to_le_bytes());
        }
        b[88..92].copy_from_slice(&self.malformed.to_le_bytes());
        b
    }

    /// Decodes a reply (the client's side); `None` if it is not one.
    pub fn decode(b: &[u8]) -> Option<Reply> {
        if b.len() != REPLY_BYTES || b[0..4] != REPLY_MAGIC || b[4] != VERSION {
            return None;
        }
        Some(Reply {
            status: Status::from_byte(b[5])?,
            iterations: u16::from_le_bytes([b[6], b[7]]),
            hand: u32_at(b, 8),
            hose: u32_at(b, 12),
            sequence: u64_at(b, 16),
            force: vec_at(b, 24),
            torque: vec_at(b, 48),
            session_time: f64_at(b, 72),
            solve_seconds: f64_at(b, 80),
            malformed: u32_at(b, 88),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_and_replies_round_trip() {
        let r = Request {
            kind: Kind::Grab(Grip::Axial),
            hand: 7,
            sequence: 1 << 40,
            position: DVec3::new(0.1, -0.2, 0.3),
            orientation: Some(DQuat::from_rotation_z(0.5)),
            key: Request::key_for(Some("secret-token")).unwrap(),
        };
        let back = Request::decode(&r.encode()).unwrap();
        // the orientation is normalised on the way in (equal to round-off)
        let (q, q_back) = (r.orientation.unwrap(), back.orientation.unwrap());
        assert!(q.abs_diff_eq(q_back, 1e-12), "{q} vs {q_back}");
        assert_eq!(
            Request {
                orientation: None,
                ..back
            },
            Request {
                orientation: None,
                ..r
            }
        );
        let reply = Reply {
            status: Status::NotConverged,
            iterations: 3,
            hand: 7,
            hose: 1,
            sequence: 99,
            force: DVec3::new(1.0, 2.0, 3.0),
            torque: DVec3::new(-1.0, 0.5, 0.25),
            session_time: 1.5,
            solve_seconds: 2e-4,
            malformed: 4,
        };
        assert_eq!(Reply::decode(&reply.encode()), Some(reply));
    }

    #[test]
    fn bad_bytes_are_statuses_not_panics() {
        let good = Request {
            kind: Kind::Pose,
            hand: 1,
            sequence: 5,
            position: DVec3::ZERO,
            orientation: None,
            key: [0; KEY_BYTES],
        }
        .encode();
        assert_eq!(Request::decode(&[]), Err(Status::Malformed));
        assert_eq!(Request::decode(&good[..50]), Err(Status::Malformed));
        let mut b = good;
        b[0] = b'X';
        assert_eq!(Request::decode(&b), Err(Status::Malformed));
        let mut b = good;
        b[4] = 2;
        assert_eq!(Request::decode(&b), Err(Status::UnsupportedVersion));
        let mut b = good;
        b[5] = 9;
        assert_eq!(Request::decode(&b), Err(Status::Malformed));
        let mut b = good;
        b[24..32].copy_from_slice(&f64::NAN.to_le_bytes());
        assert_eq!(Request::decode(&b), Err(Status::InvalidValue));
        let mut b = good;
        b[48..56].copy_from_slice(&f64::INFINITY.to_le_bytes());
        assert_eq!(Request::decode(&b), Err(Status::InvalidValue));
        // orientations whose length is not 1 (within the tolerance) are refused, not
        // normalised
        for c in [1e200_f64, 1e-200, 3.0, 0.51, 0.6] {
            let mut b = good;
            for k in 0..4 {
                b[48 + 8 * k..56 + 8 * k].copy_from_slice(&c.to_le_bytes());
            }
            assert_eq!(Request::decode(&b), Err(Status::InvalidValue), "{c}");
        }
        // only a request's size and magic is answered
        assert!(is_request_sized(&good));
        for n in [0, 1, 4, 95, 96, 111] {
            assert!(!is_request_sized(&good[..n]), "{n}");
        }
        assert_eq!(sequence_of(&good), 5);
        assert_eq!(sequence_of(&good[..10]), 0);
        assert!(Request::key_for(Some(&"x".repeat(33))).is_none());
    }
}
