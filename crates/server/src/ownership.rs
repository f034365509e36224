//! Hands belong to the client that grabbed them: another client may neither move nor
//! release them nor grab with the same hand id; a client's hands are released when it
//! disconnects. Entries from before a reset (of the session or after a divergence) are
//! void: the `epoch` counts resets.

use std::collections::HashMap;

/// Identifies one connected client.
pub type ClientId = u64;
/// Identifies one hand within a session (chosen by the client).
pub type HandId = u32;

/// Most hands held at once in one session.
pub const MAX_HANDS: usize = 16;

/// Why a hand request was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// Another client holds this hand.
    OwnedByOther(ClientId),
    /// No hand with this id is held.
    NotHeld,
    /// The session already has [`MAX_HANDS`] hands.
    TooManyHands,
}

/// The owner of each hand.
#[derive(Debug, Default)]
pub struct Ownership {
    owners: HashMap<HandId, (ClientId, u64)>,
}

impl Ownership {
    fn owner(&self, hand: HandId, epoch: u64) -> Option<ClientId> {
        self.owners
            .get(&hand)
            .filter(|(_, e)| *e == epoch)
            .map(|(c, _)| *c)
    }

    /// `client` grabs with `hand` (a grab with a hand it already holds re-grabs).
    pub fn grab(&mut self, client: ClientId, hand: HandId, epoch: u64) -> Result<(), Refusal> {
        self.owners.retain(|_, (_, e)| *e == epoch);
        match self.owner(hand, epoch) {
            Some(c) if c != client => Err(Refusal::OwnedByOther(c)),
            Some(_) => Ok(()),
            None if self.owners.len() >= MAX_HANDS => Err(Refusal::TooManyHands),
            None => {
                self.owners.insert(hand, (client, epoch));
                Ok(())
            }
        }
    }

    /// Whether `client` may move `hand`.
    pub fn check(&self, client: ClientId, hand: HandId, epoch: u64) -> Result<(), Refusal> {
        match self.owner(hand, epoch) {
            Some(c) if c == client => Ok(()),
            Some(c) => Err(Refusal::OwnedByOther(c)),
            None => Err(Refusal::NotHeld),
        }
    }

    /// `client` lets go of `hand`.
    pub fn release(&mut self, client: ClientId, hand: HandId, epoch: u64) -> Result<(), Refusal> {
        self.check(client, hand, epoch)?;
        self.owners.remove(&hand);
        Ok(())
    }

    /// Removes and returns every hand `client` holds (it disconnected).
    pub fn release_all_of(&mut self, client: ClientId, epoch: u64) -> Vec<HandId> {
        let mine: Vec<HandId> = self
            .owners
            .iter()
            .filter(|(_, (c, e))| *c == client && *e == epoch)
            .map(|(h, _)| *h)
            .collect();
        for h in &mine {
            self.owners.remove(h);
        }
        mine
    }

    /// Forgets every hand (the session was reset).
    pub fn clear(&mut self) {
        self.owners.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_grabbing_client_moves_and_releases() {
        let mut o = Ownership::default();
        assert_eq!(o.grab(1, 0, 0), Ok(()));
        assert_eq!(o.grab(2, 0, 0), Err(Refusal::OwnedByOther(1)));
        assert_eq!(o.check(2, 0, 0), Err(Refusal::OwnedByOther(1)));
        assert_eq!(o.release(2, 0, 0), Err(Refusal::OwnedByOther(1)));
        assert_eq!(o.check(1, 0, 0), Ok(()));
        assert_eq!(o.release_all_of(1, 0), vec![0]);
        assert_eq!(o.check(1, 0, 0), Err(Refusal::NotHeld));
        assert_eq!(o.grab(2, 0, 0), Ok(()));
        // A new epoch (reset) voids old entries.
        assert_eq!(o.grab(1, 0, 1), Ok(()));
    }
}
