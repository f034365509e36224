//! Wire-harness import for Pliant (SPEC N2, N3): KBL harness data in, a Pliant scene out.
//!
//! - [`kbl`] reads KBL 2.3–2.5 into the plain model of [`model`] (units via [`units`]);
//! - [`bspline`] and [`geometry`] evaluate and trim the segments' centre curves;
//! - [`bundle`] turns the wires routed through a segment into a beam section;
//! - [`scene`] writes `scene.toml` and `harness.json`, [`install`] `install.toml` (the
//!   harness installed by a worker);
//! - [`mod@vec`] reads VEC 2.x files with 3-D geometry into the same model, with their
//!   wires, routings, fixings, protections and connectors (topology-only ones are refused);
//! - [`export`] writes a settled route ([`settled`]) back as KBL, [`step`] as STEP (AP214);
//! - [`calibrate`] fits a protection's coupling factor from a bundle's EI,
//!   [`bundle_calibration`] from a bending-test curve (`pliant calibrate` for bundles);
//! - [`import_kbl`] does all of it and returns an [`ImportReport`].

pub mod branch;
pub mod bspline;
pub mod bundle;
pub mod bundle_calibration;
pub mod calibrate;
pub mod error;
pub mod export;
pub mod geometry;
pub mod install;
pub mod install_data;
pub mod kbl;
pub mod model;
pub mod report;
pub mod scene;
pub mod settled;
pub mod step;
pub mod units;
pub mod vec;
mod vec_parts;

use std::path::Path;

pub use calibrate::{
    bundle_of_segment, fit_protection_factor, three_point_bending_ei, Fit, Stiffness,
};
pub use error::HarnessError;
pub use export::{export_kbl, ExportReport};
pub use model::Harness;
pub use report::ImportReport;
pub use settled::SettledHarness;
pub use step::{export_step, StepNames, StepReport};

use bundle::{segment_bundle, BundleData};
use geometry::SegmentCurve;
pub use install_data::InstallData;
use scene::{element_count, sanitise, unique, SegmentOut};

pub(crate) fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// Largest KBL or VEC file read \[bytes\] (a regular file only).
pub const MAX_HARNESS_FILE_BYTES: u64 = 256 * 1024 * 1024;

pub(crate) fn read_text(path: &Path) -> Result<(String, String), HarnessError> {
    let file = file_name(path);
    let text = pliant_files::read_regular_text(path, MAX_HARNESS_FILE_BYTES).map_err(|e| {
        HarnessError::Read {
            file: file.clone(),
            source: e.kind.into_io(),
        }
    })?;
    Ok((file, text))
}

/// Read a KBL file, or a VEC 2.x file with 3-D geometry, into the harness model (a VEC
/// file without 3-D geometry is refused with the reason).
pub fn read_kbl(path: &Path) -> Result<Harness, HarnessError> {
    let (file, text) = read_text(path)?;
    if vec::looks_like_vec(&file, &text) {
        return vec::parse_vec(&file, &text);
    }
    kbl::parse_kbl(&file, &text)
}

/// The absolute path of the imported file (as given when it cannot be resolved).
fn source_path(path: &Path) -> String {
    std::fs::canonicalize(path)
        .unwrap_or_else(|_| path.to_path_buf())
        .display()
        .to_string()
}

/// The licence line for the scene header: the sample files' README says CC BY-SA 4.0.
fn licence_note(path: &Path) -> String {
    let readme = path.parent().map(|d| d.join("README.md"));
    let text = readme
        .and_then(|r| std::fs::read_to_string(r).ok())
        .unwrap_or_default();
    if text.contains("CC BY-SA 4.0") {
        "Source data licence: CC BY-SA 4.0 (see README.md beside the source file: Volkswagen AG /\n\
         prostep ivip e.V. test data); a modified copy of the data stays CC BY-SA 4.0."
            .to_string()
    } else {
        "Source data licence: as given by the provider of the source file.".to_string()
    }
}

/// Import a KBL file: write `out_dir/scene.toml` and `out_dir/harness.json` and report
/// what was imported, skipped and assumed.
pub fn import_kbl(path: &Path, out_dir: &Path) -> Result<ImportReport, HarnessError> {
    import_kbl_opts(path, out_dir, &ImportOptions::default())
}

/// [`import_kbl`] with bundle data of one's own (e.g. calibrated factors).
pub fn import_kbl_with(
    path: &Path,
    out_dir: &Path,
    data: &BundleData,
) -> Result<ImportReport, HarnessError> {
    import_kbl_opts(
        path,
        out_dir,
        &ImportOptions {
            bundle: data.clone(),
            ..ImportOptions::default()
        },
    )
}

/// What an import may be told besides the file.
#[derive(Clone, Debug)]
pub struct ImportOptions {
    /// The bundle model's data ([`BundleData::builtin`] by default).
    pub bundle: BundleData,
    /// The data `install.toml` is written with: connectors' mating forces, the assembly
    /// slack ([`InstallData::builtin`]).
    pub install: InstallData,
    /// Import only the branch beyond this node or segment (KBL id or `<Id>` text; see
    /// [`branch`]), held where it was cut off.
    pub branch: Option<String>,
    /// Give each bundle the default friction between its wires of its protection
    /// ([`bundle::bundle_friction`], modelling choices in `data/bundle.toml`): each hose
    /// then has a material of its own with a `hysteresis`. Off by default.
    pub bundle_friction: bool,
}

impl Default for ImportOptions {
    fn default() -> Self {
        ImportOptions {
            bundle: BundleData::builtin(),
            install: InstallData::builtin(),
            branch: None,
            bundle_friction: false,
        }
    }
}

/// [`import_kbl`] with [`ImportOptions`].
pub fn import_kbl_opts(
    path: &Path,
    out_dir: &Path,
    options: &ImportOptions,
) -> Result<ImportReport, HarnessError> {
    let data = &options.bundle;
    let mut h = read_kbl(path)?;
    let mut cut = None;
    let mut branch_note = None;
    if let Some(id) = &options.branch {
        let b = branch::branch(&h, id)?;
        branch_note = Some(format!(
            "branch beyond {} {}: {} of {} segments, held at {} where it was cut off",
            b.named,
            b.id,
            b.harness.segments.len(),
            b.of_segments,
            b.harness.nodes[b.cut].kbl_id
        ));
        cut = Some(b.cut);
        h = b.harness;
    }
    let curves: Vec<SegmentCurve> = h.segments.iter().map(|s| SegmentCurve::of(&h, s)).collect();
    let mut bundles = Vec::with_capacity(h.segments.len());
    let mut warnings = Vec::new();
    for i in 0..h.segments.len() {
        let mut b = segment_bundle(data, &h, i);
        warnings.append(&mut b.warnings);
        bundles.push(b);
    }
    for (s, c) in h.segments.iter().zip(&curves) {
        if c.straight_fallback {
            continue;
        }
        if let Some(v) = s.virtual_length {
            let rel = (c.length - v).abs() / v;
            if rel > report::LENGTH_TOLERANCE {
                warnings.push(format!(
                    "{}: centre-curve length {:.3} mm differs from Virtual_length {:.3} mm by {:.3} %{}",
                    s.kbl_id,
                    c.length * 1e3,
                    v * 1e3,
                    rel * 100.0,
                    if c.trimmed { " (a trimmed Split segment)" } else { "" }
                ));
            }
        }
    }
    h.warnings.extend(warnings);
    let names = unique(h.segments.iter().map(|s| sanitise(&s.kbl_id)));
    let segs: Vec<SegmentOut> = names
        .into_iter()
        .zip(&curves)
        .zip(&bundles)
        .map(|((hose, curve), b)| SegmentOut {
            hose,
            curve,
            section: &b.section,
            bare: &b.bare,
            stretches: &b.stretches,
            elements: element_count(curve.length),
            friction: if options.bundle_friction {
                bundle::bundle_friction(data, &b.section)
            } else {
                None
            },
        })
        .collect();
    let note = licence_note(path);
    std::fs::create_dir_all(out_dir).map_err(|source| HarnessError::Write {
        path: out_dir.to_path_buf(),
        source,
    })?;
    let scene_path = out_dir.join("scene.toml");
    let text = scene::scene_toml(&h, &segs, &note, cut);
    std::fs::write(&scene_path, text).map_err(|source| HarnessError::Write {
        path: scene_path.clone(),
        source,
    })?;
    let json_path = out_dir.join("harness.json");
    let json =
        serde_json::to_string_pretty(&scene::harness_json(&h, &segs, &note, source_path(path)))
            .map_err(|e| HarnessError::Write {
                path: json_path.clone(),
                source: std::io::Error::other(e),
            })?;
    std::fs::write(&json_path, json).map_err(|source| HarnessError::Write {
        path: json_path.clone(),
        source,
    })?;
    let mut report = ImportReport::new(&h, &segs, cut, scene_path, json_path);
    report.branch = branch_note;
    report.install = match install::install_toml(&h, &segs, &note, cut, &options.install) {
        Ok(text) => {
            let path = out_dir.join("install.toml");
            std::fs::write(&path, text).map_err(|source| HarnessError::Write {
                path: path.clone(),
                source,
            })?;
            Ok(path)
        }
        Err(why) => Err(why),
    };
    Ok(report)
}
