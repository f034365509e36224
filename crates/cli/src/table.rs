//! The peak-load table printed at the end of `pliant run` and `pliant replay`.

use comfy_table::{presets::UTF8_FULL_CONDENSED, Table};
use pliant_assembly::report::PeakRow;

/// The table of peak support loads.
pub fn peak_table(rows: &[PeakRow]) -> Table {
    let mut table = Table::new();
    table.load_preset(UTF8_FULL_CONDENSED);
    table.set_header(vec![
        "hose",
        "node",
        "peak |F| [N]",
        "at [s]",
        "peak |M| [N·m]",
        "at [s]",
        "final |F| [N]",
        "final |M| [N·m]",
    ]);
    for r in rows {
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        table.add_row(vec![
            r.hose.clone(),
            r.node.to_string(),
            format!("{:.3}", r.max_force_n),
            format!("{:.3}", r.max_force_time_s),
            format!("{:.4}", r.max_moment_nm),
            format!("{:.3}", r.max_moment_time_s),
            format!("{:.3}", norm(r.final_force_n)),
            format!("{:.4}", norm(r.final_moment_nm)),
        ]);
    }
    table
}
