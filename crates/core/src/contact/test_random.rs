//! Reproducible random numbers for the contact tests (Marsaglia's xorshift64).

/// Numbers uniform in [−0.5, 0.5), from `seed` (non-zero), the same on every run.
pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}
