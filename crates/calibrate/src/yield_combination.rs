//! The material's yield law (`yield_stress_mpa`, `hardening_modulus_mpa`) from the tests
//! past yield of one calibration: at most one bending test (`plastic_bending`,
//! `plastic_cantilever`, `plastic_three_point_bending`) and at most one `plastic_torsion`
//! test.
//!
//! With both, the two are combined, not fitted jointly: σ_y and H come from the bending
//! test (the law's axial fibres, and the curve that also gives E), G from the torsion
//! test (as its GJ joins the stiffness fits). The torsion test's yield stress is a check:
//! by von Mises (τ_y = σ_y/√3, the law the simulator's section follows) it must give
//! √3 τ_y within the bending test's σ_y — their 95 % intervals must overlap, else the two
//! curves cannot describe one material and the calibration is refused, naming both tests
//! and both values. The torsion test's H is compared likewise and reported.

use crate::law_entry::{derived, describe, estimate};
use crate::law_fit::LawFit;
use crate::material_entry::{num, Derived};
use crate::mechanics::TestKind;

/// The yield law's entries and, with two tests, how they were combined.
pub struct YieldEntries {
    pub yield_stress: Derived,
    pub hardening: Derived,
    /// The combination, said in the material's warnings.
    pub note: Option<String>,
}

/// The test's yield stress σ_y with its 95 % interval, SI (σ_y = √3 τ_y from torsion).
fn yield_stress(f: &LawFit) -> Result<(f64, [f64; 2]), String> {
    if f.kind == TestKind::PlasticTorsion {
        let e = estimate(f, "tau_y")?;
        let s = 3f64.sqrt();
        Ok((s * e.value, [s * e.ci95[0], s * e.ci95[1]]))
    } else {
        let e = estimate(f, "sigma_y")?;
        Ok((e.value, e.ci95))
    }
}

/// The relative resolution of a converged fit: an interval narrower than this around
/// its value (a noise-free curve's) says nothing more, so the agreement of two tests is
/// judged on intervals at least this wide. The fits reproduce the law of noise-free
/// curves to 10⁻⁶ (docs/calibration.md).
const FIT_RESOLUTION: f64 = 1e-6;

/// Whether the intervals `a` and `b` of the values `va` and `vb` overlap, each widened
/// to at least ± [`FIT_RESOLUTION`] of its value.
fn overlap((va, a): (f64, [f64; 2]), (vb, b): (f64, [f64; 2])) -> bool {
    let widen = |v: f64, c: [f64; 2]| {
        let r = FIT_RESOLUTION * v.abs();
        [c[0].min(v - r), c[1].max(v + r)]
    };
    let (a, b) = (widen(va, a), widen(vb, b));
    a[0] <= b[1] && b[0] <= a[1]
}

/// "σ_y = 170 MPa (95% CI 168-172 MPa)" of a value and interval in Pa.
fn mpa(name: &str, v: f64, ci: [f64; 2]) -> String {
    format!(
        "{name} = {} MPa (95% CI {}-{} MPa)",
        num(v * 1e-6),
        num(ci[0] * 1e-6),
        num(ci[1] * 1e-6)
    )
}

fn test_name(f: &LawFit) -> String {
    format!("{} test {}", f.kind.name(), f.csv)
}

/// The yield law of a `bending` test past yield, a `torsion` one, or both (module doc);
/// `None` without either.
pub fn combine(
    bending: Option<&LawFit>,
    torsion: Option<&LawFit>,
) -> Result<Option<YieldEntries>, String> {
    let Some(source) = bending.or(torsion) else {
        return Ok(None);
    };
    let (sy, sy_ci) = yield_stress(source)?;
    let mut yield_stress_entry = Derived::source(
        sy * 1e-6,
        Some([sy_ci[0] * 1e-6, sy_ci[1] * 1e-6]),
        describe(source),
    );
    let h = estimate(source, "H")?;
    let mut hardening = derived(h, 1e-6, source);
    // a hardening interval reaching below zero means "consistent with perfect
    // plasticity": the law takes H ≥ 0
    if let Some(ci) = hardening.ci95.as_mut() {
        ci[0] = ci[0].max(0.0);
    }
    let (Some(b), Some(t)) = (bending, torsion) else {
        return Ok(Some(YieldEntries {
            yield_stress: yield_stress_entry,
            hardening,
            note: None,
        }));
    };
    let (st, st_ci) = yield_stress(t)?;
    let tau = estimate(t, "tau_y")?;
    let bending_text = mpa("σ_y", sy, sy_ci);
    let torsion_text = format!(
        "{} (τ_y = {} MPa)",
        mpa("√3 τ_y", st, st_ci),
        num(tau.value * 1e-6)
    );
    if !overlap((sy, sy_ci), (st, st_ci)) {
        return Err(format!(
            "the two tests past yield disagree on the yield stress: the {} gives {bending_text}, the {} gives {torsion_text} by von Mises (σ_y = √3 τ_y); their 95 % intervals do not overlap, so no one material follows both — check each test's section (d_outer_mm, d_inner_mm) and length_mm, or calibrate them as separate materials",
            test_name(b),
            test_name(t)
        ));
    }
    let ht = estimate(t, "H")?;
    let h_agrees = overlap((h.value, h.ci95), (ht.value, ht.ci95));
    let note = format!(
        "yield law from two tests, combined (not fitted jointly): σ_y and H from the {} ({bending_text}, {}), G from the {}; its {torsion_text} agrees with σ_y within the 95 % intervals (von Mises τ_y = σ_y/√3) and its H = {} MPa (95% CI {}-{} MPa) {}",
        test_name(b),
        mpa("H", h.value, h.ci95),
        test_name(t),
        num(ht.value * 1e-6),
        num(ht.ci95[0] * 1e-6),
        num(ht.ci95[1] * 1e-6),
        if h_agrees {
            "agrees with the bending test's"
        } else {
            "does not agree with the bending test's: the material keeps the bending test's H"
        }
    );
    yield_stress_entry.source = Some(format!(
        "{}; checked against the {}: {torsion_text}, within the intervals",
        describe(b),
        test_name(t)
    ));
    Ok(Some(YieldEntries {
        yield_stress: yield_stress_entry,
        hardening,
        note: Some(note),
    }))
}
