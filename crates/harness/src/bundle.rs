//! Bundle sections (SPEC N2): the beam section of a segment from the wires routed through it.
//!
//! **One wire** (a conductor of metal cross-section A_c with insulation to the outer
//! diameter d; data and sources in `data/bundle.toml`):
//!
//! - conductor circle d_c = √(4 A_c / (π φ)), φ its metal fill;
//! - EA = E_cu A_c + E_ins π (d² − d_c²)/4;
//! - EI = E_cu A_c d_s²/16 + E_ins π (d⁴ − d_c⁴)/64 — the stranded conductor bends as its
//!   strands of diameter d_s acting alone (n strands: n E π d_s⁴/64 = E A_c d_s²/16);
//! - GJ = G_cu A_c d_s²/8 + G_ins π (d⁴ − d_c⁴)/32, G_ins = E_ins / (2 (1 + ν));
//! - mass per length: the KBL value when given, else ρ_cu A_c + ρ_ins π (d² − d_c²)/4.
//!
//! **The bundle** (wires i at positions p_i of the cross-section, see [`ring_layout`]):
//!
//! - EA = Σ EA_i, mass = Σ m_i (+ the protection's);
//! - slip bound EI_slip = Σ EI_i, GJ_slip = Σ GJ_i (wires slide freely);
//! - bonded bound about the EA-weighted centroid c (parallel-axis theorem):
//!   EI_bond,yy = Σ (EI_i + EA_i (z_i − c_z)²), EI_bond,zz = Σ (EI_i + EA_i (y_i − c_y)²),
//!   EI_bond,yz = Σ EA_i (y_i − c_y)(z_i − c_z); its principal values EI_bond,max/min;
//!   GJ_bond = Σ (GJ_i + GA_i |p_i − c|²);
//! - effective EI = EI_slip + f_ei (EI_bond − EI_slip) with EI_bond the mean of the two
//!   principal values (a real bundle twists along its length, so the section is taken
//!   round); GJ = GJ_slip + f_gj (GJ_bond − GJ_slip); f per protection kind (data);
//! - outer diameter D = max_i (2 |p_i − o| + d_i) over the ring layout (o its centre), or
//!   the protection's outer diameter when larger;
//! - minimum bend radius = the largest of the wires' bend radii and the protection's own
//!   (`min_bend_radius_d` × D).

use std::collections::HashMap;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::model::ProtectionKind;

/// A value with its source (or "assumption: …").
#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct Sourced {
    pub value: f64,
    pub source: String,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct ConductorData {
    pub e_gpa: Sourced,
    pub g_gpa: Sourced,
    pub density_kg_m3: Sourced,
    pub strand_diameter_mm: Sourced,
    pub metal_fill: Sourced,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct InsulationData {
    pub e_mpa: Sourced,
    pub poisson: Sourced,
    pub density_kg_m3: Sourced,
}

/// Coupling factors and bend-radius rule of one protection kind.
#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct ProtectionData {
    pub f_ei: Sourced,
    pub f_gj: Sourced,
    pub min_bend_radius_d: Sourced,
    /// Dahl friction between the wires: M_s/κ_s as a multiple of the effective EI (and
    /// GJ); absent or 0: none ([`bundle_friction`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dahl_stiffness_ratio: Option<Sourced>,
    /// κ_s × D: the curvature over which the friction saturates, in 1/D.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dahl_curvature_d: Option<Sourced>,
}

/// The bundle model's data (`data/bundle.toml`).
#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct BundleData {
    pub conductor: ConductorData,
    pub insulation: InsulationData,
    /// Keys: `none`, `tape`, `fleece_tape`, `corrugated_tube`, `sleeve`, `other`.
    pub protection: HashMap<String, ProtectionData>,
}

/// The built-in data file.
pub const BUNDLE_TOML: &str = include_str!("../data/bundle.toml");

impl BundleData {
    /// The built-in data (checked by a unit test, so this cannot fail at run time).
    pub fn builtin() -> Self {
        Self::from_toml(BUNDLE_TOML).unwrap_or_else(|e| panic!("data/bundle.toml is invalid: {e}"))
    }

    /// Data from TOML text (for calibrated values).
    pub fn from_toml(text: &str) -> Result<Self, String> {
        let d: BundleData = toml::from_str(text).map_err(|e| e.to_string())?;
        for key in [
            "none",
            "tape",
            "fleece_tape",
            "corrugated_tube",
            "sleeve",
            "other",
        ] {
            if !d.protection.contains_key(key) {
                return Err(format!("protection.{key} is missing"));
            }
        }
        Ok(d)
    }

    /// Factors of a protection kind (`None`: unprotected).
    pub fn protection(&self, kind: Option<ProtectionKind>) -> &ProtectionData {
        let key = kind.map_or("none", ProtectionKind::key);
        // `from_toml` checked that every key exists.
        &self.protection[key]
    }
}

/// Stiffnesses and mass of one wire (SI).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WireSection {
    /// Outer diameter \[m\].
    pub d: f64,
    /// EA \[N\], EI \[N·m²\], GJ \[N·m²\], GA \[N\].
    pub ea: f64,
    pub ei: f64,
    pub gj: f64,
    pub ga: f64,
    /// Mass per length \[kg/m\].
    pub mass: f64,
    /// Minimum bend radius \[m\], if known.
    pub bend_radius: Option<f64>,
}

impl WireSection {
    /// A wire of outer diameter `d` \[m\] with conductor cross-section `a_c` \[m²\]; `mass`
    /// \[kg/m\] from the part if known.
    pub fn new(
        data: &BundleData,
        d: f64,
        a_c: f64,
        mass: Option<f64>,
        bend_radius: Option<f64>,
    ) -> Self {
        use std::f64::consts::PI;
        let c = &data.conductor;
        let e_cu = c.e_gpa.value * 1e9;
        let g_cu = c.g_gpa.value * 1e9;
        let ds = c.strand_diameter_mm.value * 1e-3;
        let e_ins = data.insulation.e_mpa.value * 1e6;
        let g_ins = e_ins / (2.0 * (1.0 + data.insulation.poisson.value));
        let a_c = a_c.max(0.0);
        let d_c = (4.0 * a_c / (PI * c.metal_fill.value)).sqrt().min(0.95 * d);
        let a_ins = PI * (d * d - d_c * d_c) / 4.0;
        let i_ins = PI * (d.powi(4) - d_c.powi(4)) / 64.0;
        WireSection {
            d,
            ea: e_cu * a_c + e_ins * a_ins,
            ei: e_cu * a_c * ds * ds / 16.0 + e_ins * i_ins,
            gj: g_cu * a_c * ds * ds / 8.0 + g_ins * 2.0 * i_ins,
            ga: g_cu * a_c + g_ins * a_ins,
            mass: mass.unwrap_or(
                c.density_kg_m3.value * a_c + data.insulation.density_kg_m3.value * a_ins,
            ),
            bend_radius,
        }
    }
}

/// Positions of round wires of diameters `d` in a bundle cross-section, by concentric-ring
/// packing with the mean diameter d̄: one wire in the centre; 2 … 6 wires on one ring of
/// radius d̄ / (2 sin(π/N)) (touching neighbours: two wires side by side at ±d̄/2); more:
/// a centre wire and rings k = 1, 2, … of radius k d̄ holding ⌊π / asin(1/(2k))⌋ wires
/// each (6, 12, 18, …: the hexagonal numbers), the last ring spread evenly. The thickest
/// wires go to the centre. Returns positions in the order of `d`.
pub fn ring_layout(d: &[f64]) -> Vec<DVec2> {
    use std::f64::consts::PI;
    let n = d.len();
    let mut pos = vec![DVec2::ZERO; n];
    if n <= 1 {
        return pos;
    }
    let mean = d.iter().sum::<f64>() / n as f64;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| d[b].total_cmp(&d[a]));
    let ring = |count: usize, radius: f64, slots: &[usize], pos: &mut Vec<DVec2>| {
        for (j, &i) in slots.iter().enumerate() {
            let a = 2.0 * PI * j as f64 / count as f64;
            pos[i] = DVec2::new(a.cos(), a.sin()) * radius;
        }
    };
    if n <= 6 {
        ring(n, mean / (2.0 * (PI / n as f64).sin()), &order, &mut pos);
        return pos;
    }
    // order[0] stays in the centre.
    let mut next = 1;
    let mut k = 1;
    while next < n {
        let capacity = (PI / (1.0 / (2.0 * k as f64)).asin() + 1e-9).floor() as usize;
        let take = capacity.min(n - next);
        ring(take, k as f64 * mean, &order[next..next + take], &mut pos);
        next += take;
        k += 1;
    }
    pos
}

/// The section of a bundle (SI units).
#[derive(Debug, Clone, Serialize)]
pub struct BundleSection {
    pub wire_count: usize,
    /// Outer diameter \[m\].
    pub d_outer: f64,
    pub ea: f64,
    pub ei_slip: f64,
    pub ei_bond_max: f64,
    pub ei_bond_min: f64,
    /// Mean of the bonded principal values, used for the effective EI.
    pub ei_bond: f64,
    /// Effective EI \[N·m²\].
    pub ei: f64,
    pub gj_slip: f64,
    pub gj_bond: f64,
    /// Effective GJ \[N·m²\].
    pub gj: f64,
    /// Mass per length \[kg/m\], protection included.
    pub mass: f64,
    /// Minimum bend radius \[m\] (0 when neither the wires nor the protection give one).
    pub min_bend_radius: f64,
    /// Protection the factors come from (`None`: unprotected).
    pub protection: Option<ProtectionKind>,
    pub f_ei: f64,
    pub f_gj: f64,
    /// Σ d_i² / D²: share of the bundle circle filled by wires.
    pub fill: f64,
}

/// The protection that sets a segment's factors: kind, covered share, outer diameter \[m\]
/// and mass per length \[kg/m\] if known.
#[derive(Debug, Clone, Copy)]
pub struct ProtectionCover {
    pub kind: ProtectionKind,
    pub coverage: f64,
    pub outer_diameter: Option<f64>,
    pub mass_per_length: Option<f64>,
}

/// The bundle section of `wires` under an optional protection.
pub fn bundle_section(
    data: &BundleData,
    wires: &[WireSection],
    protection: Option<ProtectionCover>,
) -> BundleSection {
    let d: Vec<f64> = wires.iter().map(|w| w.d).collect();
    let p = ring_layout(&d);
    let ea: f64 = wires.iter().map(|w| w.ea).sum();
    let c = if ea > 0.0 {
        wires.iter().zip(&p).map(|(w, p)| *p * w.ea).sum::<DVec2>() / ea
    } else {
        DVec2::ZERO
    };
    let ei_slip: f64 = wires.iter().map(|w| w.ei).sum();
    let gj_slip: f64 = wires.iter().map(|w| w.gj).sum();
    let (mut iyy, mut izz, mut iyz, mut gj_bond) = (0.0, 0.0, 0.0, 0.0);
    for (w, p) in wires.iter().zip(&p) {
        let r = *p - c;
        iyy += w.ei + w.ea * r.y * r.y;
        izz += w.ei + w.ea * r.x * r.x;
        iyz += w.ea * r.x * r.y;
        gj_bond += w.gj + w.ga * r.length_squared();
    }
    // Principal values of [[iyy, iyz], [iyz, izz]].
    let mean = 0.5 * (iyy + izz);
    let half = (0.25 * (iyy - izz).powi(2) + iyz * iyz).sqrt();
    let (ei_bond_max, ei_bond_min) = (mean + half, mean - half);
    let kind = protection.map(|p| p.kind);
    let pd = data.protection(kind);
    let (f_ei, f_gj) = (pd.f_ei.value, pd.f_gj.value);
    let ei_bond = mean;
    let centre = if p.is_empty() {
        DVec2::ZERO
    } else {
        p.iter().sum::<DVec2>() / p.len() as f64
    };
    let mut d_outer = wires
        .iter()
        .zip(&p)
        .map(|(w, p)| 2.0 * (*p - centre).length() + w.d)
        .fold(0.0, f64::max);
    let mut mass: f64 = wires.iter().map(|w| w.mass).sum();
    if let Some(cover) = protection {
        if let Some(da) = cover.outer_diameter {
            d_outer = d_outer.max(da);
        }
        // The protection's mass spread over the segment by the share it covers.
        mass += cover.mass_per_length.unwrap_or(0.0) * cover.coverage;
    }
    let wire_radius = wires
        .iter()
        .filter_map(|w| w.bend_radius)
        .fold(0.0, f64::max);
    let min_bend_radius = wire_radius.max(pd.min_bend_radius_d.value * d_outer);
    let fill = if d_outer > 0.0 {
        d.iter().map(|x| x * x).sum::<f64>() / (d_outer * d_outer)
    } else {
        0.0
    };
    BundleSection {
        wire_count: wires.len(),
        d_outer,
        ea,
        ei_slip,
        ei_bond_max,
        ei_bond_min,
        ei_bond,
        ei: ei_slip + f_ei * (ei_bond - ei_slip),
        gj_slip,
        gj_bond,
        gj: gj_slip + f_gj * (gj_bond - gj_slip),
        mass,
        min_bend_radius,
        protection: kind,
        f_ei,
        f_gj,
        fill,
    }
}

/// Dahl's friction pair (M_s \[N·m\], κ_s \[1/m\]) of one stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DahlPair {
    pub moment: f64,
    pub curvature: f64,
}

/// The friction between a bundle's wires in bending and torsion (Dahl's law, the scene's
/// `hysteresis`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BundleFriction {
    pub bending: DahlPair,
    pub torsion: DahlPair,
}

/// The default friction of a bundle section under its protection (`data/bundle.toml`,
/// modelling choices): κ_s = `dahl_curvature_d` / D and M_s = `dahl_stiffness_ratio` ×
/// EI κ_s (GJ κ_s in torsion); `None` when the protection has none (ratio 0 or absent)
/// or the section has no size or stiffness.
pub fn bundle_friction(data: &BundleData, sec: &BundleSection) -> Option<BundleFriction> {
    let pd = data.protection(sec.protection);
    let ratio = pd.dahl_stiffness_ratio.as_ref()?.value;
    let per_d = pd.dahl_curvature_d.as_ref()?.value;
    let kappa = per_d / sec.d_outer;
    let pair = |k: f64| DahlPair {
        moment: ratio * k * kappa,
        curvature: kappa,
    };
    let f = BundleFriction {
        bending: pair(sec.ei),
        torsion: pair(sec.gj),
    };
    let ok = |p: &DahlPair| p.moment > 0.0 && p.moment.is_finite() && p.curvature.is_finite();
    (ratio > 0.0 && per_d > 0.0 && ok(&f.bending) && ok(&f.torsion)).then_some(f)
}

/// The wires of one segment as [`WireSection`]s. A cable whose part gives its own outer
/// diameter counts as one wire (conductor = its cores' cross-sections); a cable without
/// one counts as its cores (its mass shared equally). Parts without any diameter are
/// left out and named in the returned warnings.
pub fn segment_wires(
    data: &BundleData,
    h: &crate::model::Harness,
    seg: &crate::model::Segment,
) -> (Vec<WireSection>, Vec<String>) {
    let mut out = Vec::new();
    let mut warnings = Vec::new();
    for &wi in &seg.wires {
        let wire = &h.wires[wi];
        let part = &h.wire_parts[wire.part];
        if let Some(d) = part.own.outer_diameter.filter(|d| *d > 0.0) {
            let a_c = part
                .own
                .cross_section
                .unwrap_or_else(|| part.cores.iter().filter_map(|c| c.cross_section).sum());
            let bend = part.own.bend_radius.or_else(|| {
                part.cores
                    .iter()
                    .filter_map(|c| c.bend_radius)
                    .reduce(f64::max)
            });
            out.push(WireSection::new(data, d, a_c, part.mass_per_length, bend));
        } else if !part.cores.is_empty()
            && part
                .cores
                .iter()
                .all(|c| c.outer_diameter.is_some_and(|d| d > 0.0))
        {
            let share = part.mass_per_length.map(|m| m / part.cores.len() as f64);
            for c in &part.cores {
                let d = c.outer_diameter.unwrap_or(0.0);
                out.push(WireSection::new(
                    data,
                    d,
                    c.cross_section.unwrap_or(0.0),
                    share,
                    c.bend_radius,
                ));
            }
        } else {
            warnings.push(format!(
                "{}: wire {} (part {}) has no outer diameter; left out of the bundle",
                seg.kbl_id, wire.kbl_id, part.kbl_id
            ));
        }
    }
    (out, warnings)
}

/// The protection that sets a segment's factors: of the protection areas on the segment,
/// the one covering the largest share, if that share is at least one half.
pub fn segment_protection(h: &crate::model::Harness, segment: usize) -> Option<ProtectionCover> {
    h.protections
        .iter()
        .filter(|p| p.segment == segment)
        .map(|p| ProtectionCover {
            kind: p.kind,
            coverage: (p.to - p.from).clamp(0.0, 1.0),
            outer_diameter: p.outer_diameter,
            mass_per_length: p.mass_per_length,
        })
        .fold(None, |best: Option<ProtectionCover>, c| match best {
            Some(b) if b.coverage >= c.coverage => Some(b),
            _ => Some(c),
        })
        .filter(|c| c.coverage >= 0.5)
}

/// A stretch of a segment under one set of protections, `from..to` as shares of its
/// length, with its section.
#[derive(Debug, Clone)]
pub struct CoveredStretch {
    pub from: f64,
    pub to: f64,
    /// The protections over it, in the order of their keys.
    pub kinds: Vec<ProtectionKind>,
    /// The wires' section under them (see [`covered_section`]).
    pub section: BundleSection,
}

/// The bundle's outer diameter \[m\] at `fraction` of a segment's length: the thickest
/// protected stretch there, else the bare wires' `bare`.
pub fn d_outer_at(bare: &BundleSection, stretches: &[CoveredStretch], fraction: f64) -> f64 {
    stretches
        .iter()
        .filter(|c| (c.from..=c.to).contains(&fraction))
        .map(|c| c.section.d_outer)
        .reduce(f64::max)
        .unwrap_or(bare.d_outer)
}

/// The section of `wires` under the protections `covers` lying over one another (tape
/// under a corrugated tube), each covering the whole stretch: the coupling factors of the
/// one binding the wires tightest (largest f_ei), the largest outer diameter given, the
/// masses of all, and the minimum bend radius the largest of the wires' and every
/// protection's.
pub fn covered_section(
    data: &BundleData,
    wires: &[WireSection],
    covers: &[ProtectionCover],
) -> BundleSection {
    let f_ei = |c: &&ProtectionCover| data.protection(Some(c.kind)).f_ei.value;
    let tightest = covers
        .iter()
        .max_by(|a, b| f_ei(a).total_cmp(&f_ei(b)))
        .map(|c| ProtectionCover {
            kind: c.kind,
            coverage: 1.0,
            outer_diameter: covers
                .iter()
                .filter_map(|c| c.outer_diameter)
                .reduce(f64::max),
            mass_per_length: covers
                .iter()
                .filter_map(|c| c.mass_per_length)
                .reduce(|a, b| a + b),
        });
    let mut section = bundle_section(data, wires, tightest);
    for c in covers {
        let own = data.protection(Some(c.kind)).min_bend_radius_d.value * section.d_outer;
        section.min_bend_radius = section.min_bend_radius.max(own);
    }
    section
}

/// The protected stretches of segment `segment`: its protection areas cut at every
/// start and end, neighbours under the same protections joined.
pub fn covered_stretches(
    data: &BundleData,
    h: &crate::model::Harness,
    segment: usize,
    wires: &[WireSection],
) -> Vec<CoveredStretch> {
    let areas: Vec<&crate::model::Protection> = h
        .protections
        .iter()
        .filter(|p| p.segment == segment && p.to > p.from)
        .collect();
    let mut cuts: Vec<f64> = areas
        .iter()
        .flat_map(|p| [p.from.clamp(0.0, 1.0), p.to.clamp(0.0, 1.0)])
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut out: Vec<CoveredStretch> = Vec::new();
    for w in cuts.windows(2) {
        let (from, to) = (w[0], w[1]);
        let middle = 0.5 * (from + to);
        let mut over: Vec<&crate::model::Protection> = areas
            .iter()
            .copied()
            .filter(|p| p.from <= middle && middle < p.to)
            .collect();
        if over.is_empty() {
            continue;
        }
        over.sort_by_key(|p| p.kind.key());
        let kinds: Vec<ProtectionKind> = over.iter().map(|p| p.kind).collect();
        if let Some(last) = out.last_mut() {
            if last.to == from && last.kinds == kinds {
                last.to = to;
                continue;
            }
        }
        let covers: Vec<ProtectionCover> = over
            .iter()
            .map(|p| ProtectionCover {
                kind: p.kind,
                coverage: 1.0,
                outer_diameter: p.outer_diameter,
                mass_per_length: p.mass_per_length,
            })
            .collect();
        out.push(CoveredStretch {
            from,
            to,
            kinds,
            section: covered_section(data, wires, &covers),
        });
    }
    out
}

/// One segment's bundle: its wires, the protection that sets its factors, its section.
#[derive(Debug, Clone)]
pub struct SegmentBundle {
    pub kbl_id: String,
    pub wires: Vec<WireSection>,
    pub protection: Option<ProtectionCover>,
    /// The section of the segment as one (its factors from the protection covering most
    /// of it).
    pub section: BundleSection,
    /// The section of the bare wires, where no protection lies.
    pub bare: BundleSection,
    /// Its protected stretches.
    pub stretches: Vec<CoveredStretch>,
    /// Wires left out, or the stand-in wire used when none is routed.
    pub warnings: Vec<String>,
}

/// The bundle of segment `segment` (an index into `h.segments`), as the importer builds
/// it: a segment without a routed wire gets one stand-in wire as thick as its KBL
/// cross-section (or 5 mm), with a warning.
pub fn segment_bundle(
    data: &BundleData,
    h: &crate::model::Harness,
    segment: usize,
) -> SegmentBundle {
    let s = &h.segments[segment];
    let (mut wires, mut warnings) = segment_wires(data, h, s);
    if wires.is_empty() {
        let d = s
            .cross_section_area
            .map_or(5e-3, |a| (4.0 * a / std::f64::consts::PI).sqrt());
        warnings.push(format!(
            "{}: no wire routed through it; section of one stand-in wire {:.1} mm thick",
            s.kbl_id,
            d * 1e3
        ));
        wires.push(WireSection::new(data, d, 0.0, None, None));
    }
    let protection = segment_protection(h, segment);
    let section = bundle_section(data, &wires, protection);
    let bare = bundle_section(data, &wires, None);
    let stretches = covered_stretches(data, h, segment, &wires);
    SegmentBundle {
        kbl_id: s.kbl_id.clone(),
        wires,
        protection,
        section,
        bare,
        stretches,
        warnings,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(1e-300)
    }

    #[test]
    fn builtin_data_loads() {
        let d = BundleData::from_toml(BUNDLE_TOML).unwrap();
        assert_eq!(d.protection.len(), 6);
        assert!(d.conductor.e_gpa.source.contains("117"));
    }

    #[test]
    fn wire_by_hand() {
        // d = 1.6 mm, A_c = 0.5 mm², E_cu 117 GPa, d_s 0.25 mm, E_ins 200 MPa, φ 0.85.
        let data = BundleData::builtin();
        let w = WireSection::new(&data, 1.6e-3, 0.5e-6, None, Some(4.8e-3));
        let pi = std::f64::consts::PI;
        let d_c = (4.0 * 0.5e-6 / (pi * 0.85)).sqrt();
        let ea = 117e9 * 0.5e-6 + 200e6 * pi * (1.6e-3f64.powi(2) - d_c * d_c) / 4.0;
        let ei = 117e9 * 0.5e-6 * 0.25e-3f64.powi(2) / 16.0
            + 200e6 * pi * (1.6e-3f64.powi(4) - d_c.powi(4)) / 64.0;
        assert!(rel(w.ea, ea) < 1e-12);
        assert!(rel(w.ei, ei) < 1e-12);
        // Magnitude: EA ≈ 59 kN; EI ≈ 2.9e-4 N·m² (strands 2.3e-4, insulation 0.6e-4).
        assert!((5.8e4..6.0e4).contains(&w.ea), "{}", w.ea);
        assert!((2.5e-4..3.2e-4).contains(&w.ei), "{}", w.ei);
        let m = 8960.0 * 0.5e-6 + 1400.0 * pi * (1.6e-3f64.powi(2) - d_c * d_c) / 4.0;
        assert!(rel(w.mass, m) < 1e-12);
        assert_eq!(
            WireSection::new(&data, 1.6e-3, 0.5e-6, Some(0.006), None).mass,
            0.006
        );
    }

    #[test]
    fn one_wire_both_bounds_are_its_own() {
        let data = BundleData::builtin();
        let w = WireSection::new(&data, 2.9e-3, 2.5e-6, Some(0.026), Some(8.7e-3));
        for kind in [None, Some(ProtectionKind::Tape)] {
            let cover = kind.map(|kind| ProtectionCover {
                kind,
                coverage: 1.0,
                outer_diameter: None,
                mass_per_length: None,
            });
            let b = bundle_section(&data, &[w], cover);
            assert!(rel(b.ei_slip, w.ei) < 1e-12);
            assert!(rel(b.ei_bond_max, w.ei) < 1e-12 && rel(b.ei_bond_min, w.ei) < 1e-12);
            assert!(rel(b.ei, w.ei) < 1e-12);
            assert!(rel(b.gj, w.gj) < 1e-12 && rel(b.gj_bond, w.gj) < 1e-12);
            assert!(rel(b.d_outer, 2.9e-3) < 1e-12);
            assert_eq!(b.ea, w.ea);
            assert!(rel(b.min_bend_radius, 8.7e-3) < 1e-12);
        }
    }

    #[test]
    fn two_equal_wires_side_by_side() {
        let data = BundleData::builtin();
        let d = 1.6e-3;
        let w = WireSection::new(&data, d, 0.5e-6, None, None);
        let b = bundle_section(&data, &[w, w], None);
        // Bonded about the axis across the pair: 2 EI + 2 EA (d/2)²; about the other: 2 EI.
        assert!(rel(b.ei_bond_max, 2.0 * w.ei + 2.0 * w.ea * (d / 2.0).powi(2)) < 1e-12);
        assert!(rel(b.ei_bond_min, 2.0 * w.ei) < 1e-12);
        assert!(rel(b.ei_slip, 2.0 * w.ei) < 1e-12);
        assert!(rel(b.gj_bond, 2.0 * w.gj + 2.0 * w.ga * (d / 2.0).powi(2)) < 1e-12);
        assert!(rel(b.d_outer, 2.0 * d) < 1e-12);
        assert_eq!(b.ei, b.ei_slip, "unprotected: f = 0");
        // Tape: EI between the bounds by its factor.
        let cover = ProtectionCover {
            kind: ProtectionKind::Tape,
            coverage: 1.0,
            outer_diameter: None,
            mass_per_length: Some(0.004),
        };
        let t = bundle_section(&data, &[w, w], Some(cover));
        let f = data.protection(Some(ProtectionKind::Tape)).f_ei.value;
        assert!(rel(t.ei, t.ei_slip + f * (t.ei_bond - t.ei_slip)) < 1e-12);
        assert!(t.ei > t.ei_slip && t.ei < t.ei_bond_max);
        assert!(rel(t.mass, 2.0 * w.mass + 0.004) < 1e-12);
    }

    #[test]
    fn seven_wires_hexagonal() {
        let d = vec![1.0; 7];
        let p = ring_layout(&d);
        assert_eq!(p[0], DVec2::ZERO);
        for q in &p[1..] {
            assert!((q.length() - 1.0).abs() < 1e-12);
        }
        // 19 wires: 1 + 6 + 12.
        let p = ring_layout(&[1.0; 19]);
        assert_eq!(
            p.iter().filter(|q| (q.length() - 2.0).abs() < 1e-9).count(),
            12
        );
    }

    #[test]
    fn tape_under_a_corrugated_tube() {
        // The tape binds the wires (its factors), the tube sets the diameter and the bend
        // radius (2.5 D), both weigh.
        let data = BundleData::builtin();
        let w = WireSection::new(&data, 1.6e-3, 0.5e-6, None, Some(4.8e-3));
        let tape = ProtectionCover {
            kind: ProtectionKind::Tape,
            coverage: 1.0,
            outer_diameter: None,
            mass_per_length: Some(0.004),
        };
        let tube = ProtectionCover {
            kind: ProtectionKind::CorrugatedTube,
            coverage: 1.0,
            outer_diameter: Some(13.4e-3),
            mass_per_length: Some(0.017),
        };
        let both = covered_section(&data, &[w; 3], &[tube, tape]);
        let taped = bundle_section(&data, &[w; 3], Some(tape));
        assert!(rel(both.ei, taped.ei) < 1e-12);
        assert!(rel(both.d_outer, 13.4e-3) < 1e-12);
        assert!(rel(both.mass, 3.0 * w.mass + 0.021) < 1e-12);
        let r = data
            .protection(Some(ProtectionKind::CorrugatedTube))
            .min_bend_radius_d
            .value;
        assert!(rel(both.min_bend_radius, (r * 13.4e-3).max(4.8e-3)) < 1e-12);
    }

    #[test]
    fn corrugated_tube_sets_diameter_and_bend_radius() {
        let data = BundleData::builtin();
        let w = WireSection::new(&data, 1.6e-3, 0.5e-6, None, Some(4.8e-3));
        let cover = ProtectionCover {
            kind: ProtectionKind::CorrugatedTube,
            coverage: 0.5,
            outer_diameter: Some(13.4e-3),
            mass_per_length: Some(0.017),
        };
        let b = bundle_section(&data, &[w; 3], Some(cover));
        assert!(rel(b.d_outer, 13.4e-3) < 1e-12);
        assert!(rel(b.min_bend_radius, 2.5 * 13.4e-3) < 1e-12);
        assert!(rel(b.mass, 3.0 * w.mass + 0.0085) < 1e-12);
    }

    #[test]
    fn the_diameter_at_a_place_is_its_stretchs_or_the_bare_wires() {
        let data = BundleData::builtin();
        let w = WireSection::new(&data, 1.6e-3, 0.5e-6, None, Some(4.8e-3));
        let tube = ProtectionCover {
            kind: ProtectionKind::CorrugatedTube,
            coverage: 1.0,
            outer_diameter: Some(13.4e-3),
            mass_per_length: Some(0.017),
        };
        let bare = bundle_section(&data, &[w; 3], None);
        let stretch = CoveredStretch {
            from: 0.25,
            to: 0.5,
            kinds: vec![ProtectionKind::CorrugatedTube],
            section: covered_section(&data, &[w; 3], &[tube]),
        };
        let stretches = [stretch];
        assert!(bare.d_outer < 13.4e-3);
        assert_eq!(d_outer_at(&bare, &stretches, 0.1), bare.d_outer);
        assert!(rel(d_outer_at(&bare, &stretches, 0.3), 13.4e-3) < 1e-12);
        assert!(rel(d_outer_at(&bare, &stretches, 0.5), 13.4e-3) < 1e-12);
        assert_eq!(d_outer_at(&bare, &stretches, 0.9), bare.d_outer);
    }
}
