//! The workcell's input log in memory, append-only in chunks: full chunks are sealed and
//! shared (`Arc`), so that handing the whole log to another thread (a live session's
//! report) costs one reference per sealed chunk plus a copy of the open chunk — never a
//! copy of the whole log on the thread that steps the study.

use super::input::StampedInput;
use std::sync::Arc;

/// Inputs per sealed chunk.
pub const CHUNK: usize = 256;

/// An append-only log of stamped inputs in chunks of [`CHUNK`].
#[derive(Clone, Debug, Default)]
pub struct ChunkedLog {
    sealed: Vec<Arc<[StampedInput]>>,
    open: Vec<StampedInput>,
}

/// A copy of a [`ChunkedLog`] at one moment, sharing its sealed chunks.
#[derive(Clone, Debug, Default)]
pub struct LogShare {
    chunks: Vec<Arc<[StampedInput]>>,
    tail: Vec<StampedInput>,
}

impl ChunkedLog {
    /// Appends one input.
    pub fn push(&mut self, input: StampedInput) {
        if self.open.capacity() == 0 {
            self.open.reserve_exact(CHUNK);
        }
        self.open.push(input);
        if self.open.len() == CHUNK {
            let full = std::mem::take(&mut self.open);
            self.sealed.push(full.into());
        }
    }

    /// Inputs logged.
    pub fn len(&self) -> usize {
        self.sealed.len() * CHUNK + self.open.len()
    }

    /// Whether nothing is logged.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Cuts the log back to its first `len` inputs (a checkpoint restored).
    pub fn truncate(&mut self, len: usize) {
        if len >= self.len() {
            return;
        }
        let keep_sealed = len / CHUNK;
        let rest = len % CHUNK;
        if keep_sealed < self.sealed.len() {
            self.open = self.sealed[keep_sealed][..rest].to_vec();
            self.sealed.truncate(keep_sealed);
        } else {
            self.open.truncate(rest);
        }
    }

    /// The inputs in order.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = &StampedInput> + '_ {
        self.sealed
            .iter()
            .flat_map(|c| c.iter())
            .chain(self.open.iter())
    }

    /// The last input, if any.
    pub fn last(&self) -> Option<&StampedInput> {
        self.open
            .last()
            .or_else(|| self.sealed.last().and_then(|c| c.last()))
    }

    /// The inputs as one vector (a copy of every input).
    pub fn to_vec(&self) -> Vec<StampedInput> {
        self.iter().cloned().collect()
    }

    /// The log as it is now, for another thread: the sealed chunks shared, the open one
    /// (fewer than [`CHUNK`] inputs) copied.
    pub fn share(&self) -> LogShare {
        LogShare {
            chunks: self.sealed.clone(),
            tail: self.open.clone(),
        }
    }
}

impl LogShare {
    /// Inputs in the share.
    pub fn len(&self) -> usize {
        self.chunks.len() * CHUNK + self.tail.len()
    }

    /// Whether it holds no input.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Inputs that were copied when the share was made (the open chunk's); the rest are
    /// shared with the log.
    pub fn copied(&self) -> usize {
        self.tail.len()
    }

    /// Whether this share and `other` hold the same sealed chunk `k` (one allocation,
    /// not two copies).
    pub fn shares_chunk_with(&self, other: &LogShare, k: usize) -> bool {
        match (self.chunks.get(k), other.chunks.get(k)) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }

    /// The inputs as one vector (made on the caller's thread).
    pub fn to_vec(&self) -> Vec<StampedInput> {
        let mut v = Vec::with_capacity(self.len());
        for c in &self.chunks {
            v.extend_from_slice(c);
        }
        v.extend_from_slice(&self.tail);
        v
    }
}

impl PartialEq<[StampedInput]> for ChunkedLog {
    fn eq(&self, other: &[StampedInput]) -> bool {
        self.len() == other.len() && self.iter().zip(other).all(|(a, b)| a == b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::workcell::Input;

    fn stamped(tick: u64) -> StampedInput {
        StampedInput {
            tick,
            input: Input::Arrest,
        }
    }

    #[test]
    fn a_share_copies_only_the_open_chunk_and_truncation_keeps_order() {
        let mut log = ChunkedLog::default();
        for t in 0..(10 * CHUNK as u64 + 7) {
            log.push(stamped(t));
        }
        assert_eq!(log.len(), 10 * CHUNK + 7);
        let a = log.share();
        log.push(stamped(99_999));
        let b = log.share();
        assert_eq!((a.copied(), b.copied()), (7, 8));
        assert!((0..10).all(|k| a.shares_chunk_with(&b, k)));
        let all = b.to_vec();
        assert_eq!(all.len(), log.len());
        assert!(all
            .iter()
            .enumerate()
            .take(10 * CHUNK + 7)
            .all(|(k, s)| s.tick == k as u64));
        assert_eq!(log.last().unwrap().tick, 99_999);

        log.truncate(3 * CHUNK + 5);
        assert_eq!(log.len(), 3 * CHUNK + 5);
        assert_eq!(log.last().unwrap().tick, 3 * CHUNK as u64 + 4);
        log.push(stamped(7));
        assert_eq!(log.len(), 3 * CHUNK + 6);
        log.truncate(2 * CHUNK);
        assert_eq!(log.to_vec().len(), 2 * CHUNK);
        assert_eq!(log.last().unwrap().tick, 2 * CHUNK as u64 - 1);
        // the earlier shares are untouched
        assert_eq!(a.to_vec().len(), 10 * CHUNK + 7);
    }
}
