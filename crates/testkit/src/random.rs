//! Deterministic pseudo-random numbers: the same sequence on every machine and run, so a
//! test that samples its inputs fails only for the inputs it names.

use glam::DVec3;

/// A linear congruential generator (Knuth's MMIX constants) giving numbers in \[0, 1).
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in \[0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A vector of the next three numbers.
    pub fn vec(&mut self) -> DVec3 {
        DVec3::new(self.unit(), self.unit(), self.unit())
    }
}
