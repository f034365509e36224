//! Renders the validation results as the Markdown table of docs/validation.md.

use crate::Check;

/// The whole generated page.
pub fn page(checks: &[Check], header: &str) -> String {
    let mut s = String::new();
    s.push_str(header);
    s.push_str("\n| case | quantity | computed | reference | error | tolerance | pass |\n|---|---|---|---|---|---|---|\n");
    for c in checks {
        s.push_str(&format!(
            "| {} | {} | {:.6e} | {:.6e} | {:.2e} | {:.1e} | {} |\n",
            c.case,
            c.quantity,
            c.computed,
            c.reference,
            c.error,
            c.tolerance,
            if c.pass { "yes" } else { "**NO**" }
        ));
    }
    let passed = checks.iter().filter(|c| c.pass).count();
    s.push_str(&format!("\n{passed} of {} checks pass.\n", checks.len()));
    s
}
