//! A press fit that relaxes (SPEC X2): the contact pressure of a rubber hose on a stub is
//! proportional to the wall's modulus (Lamé, [`super::press_fit`]), so under the held
//! interference each slice of the hose relaxes with the material's Prony series from the
//! moment it slid onto the stub (the correspondence principle of linear
//! viscoelasticity): the holding force at depth l is the elastic one times
//!
//! ```text
//! r = [(1 − Σᵢ gᵢ) l + Σᵢ gᵢ Sᵢ] / l,   Sᵢ = ∫₀ˡ e^{−(t − t_on(x))/τᵢ} dx
//! ```
//!
//! with t_on(x) the time the slice at depth x slid on. Each Sᵢ is kept recursively:
//! over a step h it decays by e^{−h/τᵢ} and gains the depth slid on in the step (at
//! age 0); when the hose slides back off, the slices slid on last leave first, and Sᵢ
//! loses them in proportion (they are the youngest: an approximation on the safe side,
//! as it keeps more of the holding force than the exact account would only when pulled
//! back and forth). Beads and barbs relax by the same ratio.

use pliant_core::material::PronyTerm;

/// Most terms of a relaxing press fit (as a material's Prony series).
pub const MAX_TERMS: usize = 8;

/// The material's Prony series, as a fixed array so that the fit stays `Copy`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitTerms {
    terms: [PronyTerm; MAX_TERMS],
    count: usize,
}

impl FitTerms {
    /// The first `MAX_TERMS` (8) terms of `terms` (a material has at most that many).
    pub fn new(terms: &[PronyTerm]) -> Self {
        let mut out = FitTerms {
            terms: [PronyTerm {
                weight: 0.0,
                time: 1.0,
            }; MAX_TERMS],
            count: terms.len().min(MAX_TERMS),
        };
        out.terms[..out.count].copy_from_slice(&terms[..out.count]);
        out
    }

    /// The terms.
    pub fn terms(&self) -> &[PronyTerm] {
        &self.terms[..self.count]
    }
}

/// The relaxation memory of one press fit (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitRelaxation {
    terms: FitTerms,
    /// Sᵢ \[m\].
    relaxing: [f64; MAX_TERMS],
    depth: f64,
    time: f64,
}

impl FitRelaxation {
    /// Nothing on the stub yet, at time `time`.
    pub fn new(terms: FitTerms, time: f64) -> Self {
        FitRelaxation {
            terms,
            relaxing: [0.0; MAX_TERMS],
            depth: 0.0,
            time,
        }
    }

    /// Moves the memory to time `time` with the hose at insertion depth `depth` \[m\].
    pub fn advance(&mut self, time: f64, depth: f64) {
        let h = (time - self.time).max(0.0);
        let depth = depth.max(0.0);
        for (s, p) in self.relaxing.iter_mut().zip(self.terms.terms()) {
            *s *= (-h / p.time).exp();
            if depth >= self.depth {
                *s += depth - self.depth;
            } else if self.depth > 0.0 {
                *s *= depth / self.depth;
            }
        }
        (self.depth, self.time) = (depth, time);
    }

    /// The ratio r of the relaxed holding force to the elastic one (1 off the stub and
    /// for an elastic hose).
    pub fn ratio(&self) -> f64 {
        if self.depth <= 0.0 {
            return 1.0;
        }
        let terms = self.terms.terms();
        let long_term = 1.0 - terms.iter().map(|p| p.weight).sum::<f64>();
        let relaxing: f64 = terms
            .iter()
            .zip(&self.relaxing)
            .map(|(p, s)| p.weight * s)
            .sum();
        (long_term * self.depth + relaxing) / self.depth
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pliant_core::material::relaxation_ratio;

    const TERMS: [PronyTerm; 2] = [
        PronyTerm {
            weight: 0.3,
            time: 0.5,
        },
        PronyTerm {
            weight: 0.2,
            time: 5.0,
        },
    ];

    /// Pushed on in one step and held, the fit relaxes as E(t)/E₀.
    #[test]
    fn a_fit_pushed_on_at_once_relaxes_as_the_modulus() {
        let mut m = FitRelaxation::new(FitTerms::new(&TERMS), 0.0);
        m.advance(0.0, 0.02);
        assert_eq!(m.ratio(), 1.0);
        for t in [0.1, 0.7, 3.0, 20.0] {
            m.advance(t, 0.02);
            let want = relaxation_ratio(&TERMS, t);
            assert!(
                (m.ratio() - want).abs() < 1e-12,
                "t {t}: {} vs {want}",
                m.ratio()
            );
        }
    }

    /// Pushed on at constant speed over T, each slice relaxes from its own time:
    /// r(T) = (1/T) ∫₀ᵀ R(T − t) dt, met by the recursion up to its first-order
    /// stepping error.
    #[test]
    fn a_fit_pushed_on_slowly_relaxes_slice_by_slice() {
        let (duration, depth, steps) = (2.0, 0.02, 20_000);
        let mut m = FitRelaxation::new(FitTerms::new(&TERMS), 0.0);
        for k in 1..=steps {
            let t = duration * k as f64 / steps as f64;
            m.advance(t, depth * t / duration);
        }
        let long = 1.0 - 0.5;
        let want = long
            + TERMS
                .iter()
                .map(|p| p.weight * p.time / duration * (1.0 - (-duration / p.time).exp()))
                .sum::<f64>();
        assert!((m.ratio() - want).abs() < 1e-4, "{} vs {want}", m.ratio());
    }
}
