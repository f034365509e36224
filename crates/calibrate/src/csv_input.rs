//! Reading a test curve from CSV. The header names each column's quantity and unit
//! (`force_N`, `displacement_mm`, `stress_MPa`, `strain`, `strain_percent`,
//! `torque_Nm`, `angle_deg`, `bend_radius_mm`, `plate_distance_mm`, `curvature_1_m`,
//! `time_s`, …); values are converted to SI here, at the file boundary, and nowhere else.
//! Columns of other quantities are allowed and ignored, as is a time column where the
//! test does not use it. Blank lines and lines starting with `#` are skipped.

use crate::error::CalibError;

/// A physical quantity a column may hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// Force \[N\].
    Force,
    /// Displacement, deflection or extension \[m\].
    Displacement,
    /// Strain [-].
    Strain,
    /// Stress \[Pa\].
    Stress,
    /// Torque or moment \[N·m\].
    Torque,
    /// Angle of twist \[rad\].
    Angle,
    /// Bend radius of the centre line \[m\].
    BendRadius,
    /// Distance between the plates of ISO 10619-1 (inner bend diameter) \[m\].
    PlateDistance,
    /// Curvature [1/m].
    Curvature,
    /// Time since the strain was applied \[s\] (relaxation tests).
    Time,
}

/// Names (header prefixes) of each quantity, longest first where they overlap.
const NAMES: [(&str, Quantity); 18] = [
    ("plate_distance", Quantity::PlateDistance),
    ("bend_radius", Quantity::BendRadius),
    ("displacement", Quantity::Displacement),
    ("deflection", Quantity::Displacement),
    ("extension", Quantity::Displacement),
    ("elongation", Quantity::Displacement),
    ("curvature", Quantity::Curvature),
    ("distance", Quantity::PlateDistance),
    ("rotation", Quantity::Angle),
    ("radius", Quantity::BendRadius),
    ("strain", Quantity::Strain),
    ("stress", Quantity::Stress),
    ("torque", Quantity::Torque),
    ("moment", Quantity::Torque),
    ("force", Quantity::Force),
    ("angle", Quantity::Angle),
    ("twist", Quantity::Angle),
    ("time", Quantity::Time),
];

impl Quantity {
    /// Units accepted (normalised: lower case, without `_ / · * ( ) [ ]` and spaces) and
    /// their factor to SI.
    fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Quantity::Force => &[("n", 1.0), ("kn", 1e3), ("mn", 1e-3)],
            Quantity::Displacement | Quantity::BendRadius | Quantity::PlateDistance => &[
                ("m", 1.0),
                ("mm", 1e-3),
                ("cm", 1e-2),
                ("um", 1e-6),
                ("µm", 1e-6),
            ],
            Quantity::Strain => &[
                ("", 1.0),
                ("-", 1.0),
                ("1", 1.0),
                ("mmmm", 1.0),
                ("percent", 1e-2),
                ("pct", 1e-2),
                ("%", 1e-2),
            ],
            Quantity::Stress => &[
                ("pa", 1.0),
                ("kpa", 1e3),
                ("mpa", 1e6),
                ("nmm2", 1e6),
                ("gpa", 1e9),
            ],
            Quantity::Torque => &[("nm", 1.0), ("nmm", 1e-3)],
            Quantity::Angle => &[("rad", 1.0), ("deg", std::f64::consts::PI / 180.0)],
            Quantity::Curvature => &[("1m", 1.0), ("perm", 1.0), ("1mm", 1e3), ("permm", 1e3)],
            Quantity::Time => &[("s", 1.0), ("ms", 1e-3), ("min", 60.0), ("h", 3600.0)],
        }
    }

    /// A column name of this quantity in its common unit, for messages.
    pub fn example(self) -> &'static str {
        match self {
            Quantity::Force => "force_N",
            Quantity::Displacement => "displacement_mm",
            Quantity::Strain => "strain (or strain_percent)",
            Quantity::Stress => "stress_MPa",
            Quantity::Torque => "torque_Nm",
            Quantity::Angle => "angle_deg",
            Quantity::BendRadius => "bend_radius_mm",
            Quantity::PlateDistance => "plate_distance_mm",
            Quantity::Curvature => "curvature_1_m",
            Quantity::Time => "time_s",
        }
    }
}

/// One recognised column.
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    /// The header as written.
    pub header: String,
    /// 0-based field index.
    pub index: usize,
    pub quantity: Quantity,
    /// Factor from the file's unit to SI.
    pub factor: f64,
}

/// A curve file: its recognised columns, values in SI, and the line of each row.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// The file name, as given (for messages).
    pub file: String,
    pub columns: Vec<Column>,
    /// Per recognised column (same order as `columns`), the values in SI.
    pub values: Vec<Vec<f64>>,
    /// 1-based line of each data row.
    pub lines: Vec<usize>,
}

/// Most data rows a curve may have.
pub const MAX_ROWS: usize = 1_000_000;

fn normalise_unit(s: &str) -> String {
    s.chars()
        .filter(|c| !matches!(c, '_' | '/' | '·' | '*' | '(' | ')' | '[' | ']' | ' ' | '.'))
        .flat_map(char::to_lowercase)
        .collect::<String>()
        .replace('²', "2")
}

/// Recognises a header: Ok(None) for a column of another quantity.
fn recognise(header: &str) -> Result<Option<(Quantity, f64)>, String> {
    let h = header.trim().trim_matches('"').trim().to_lowercase();
    for (name, q) in NAMES {
        let rest = match h.strip_prefix(name) {
            Some(r) => r,
            None => continue,
        };
        if !(rest.is_empty() || rest.starts_with(['_', ' ', '[', '(', '/'])) {
            continue;
        }
        let unit = normalise_unit(rest);
        if let Some((_, f)) = q.units().iter().find(|(u, _)| *u == unit) {
            return Ok(Some((q, *f)));
        }
        let accepted: Vec<&str> = q
            .units()
            .iter()
            .map(|(u, _)| *u)
            .filter(|u| !u.is_empty())
            .collect();
        return Err(if unit.is_empty() {
            format!(
                "column \"{}\" needs a unit, e.g. {}",
                header.trim(),
                q.example()
            )
        } else {
            format!(
                "column \"{}\": unknown unit for {name}; accepted: {}",
                header.trim(),
                accepted.join(", ")
            )
        });
    }
    Ok(None)
}

/// Parses CSV `text` read from `file`.
pub fn parse(text: &str, file: &str) -> Result<Table, CalibError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (header_line, header) = lines
        .next()
        .ok_or_else(|| CalibError::file(file, "empty file: expected a header line naming the columns and units, e.g. force_N,displacement_mm"))?;
    let headers: Vec<&str> = header.split(',').collect();
    let mut columns = Vec::new();
    for (index, h) in headers.iter().enumerate() {
        match recognise(h) {
            Ok(Some((quantity, factor))) => {
                if columns.iter().any(|c: &Column| c.quantity == quantity) {
                    return Err(CalibError::cell(
                        file,
                        header_line,
                        index + 1,
                        format!("a second column of the same quantity (\"{}\")", h.trim()),
                    ));
                }
                columns.push(Column {
                    header: h.trim().to_string(),
                    index,
                    quantity,
                    factor,
                })
            }
            Ok(None) => {}
            Err(message) => return Err(CalibError::cell(file, header_line, index + 1, message)),
        }
    }
    if columns.is_empty() {
        return Err(CalibError::line(
            file,
            header_line,
            format!(
                "no column names a known quantity with its unit (header \"{header}\"); e.g. force_N,displacement_mm or stress_MPa,strain"
            ),
        ));
    }
    let mut values = vec![Vec::new(); columns.len()];
    let mut row_lines = Vec::new();
    for (line, l) in lines {
        let fields: Vec<&str> = l.split(',').collect();
        if fields.len() != headers.len() {
            return Err(CalibError::line(
                file,
                line,
                format!("{} fields, the header has {}", fields.len(), headers.len()),
            ));
        }
        if row_lines.len() >= MAX_ROWS {
            return Err(CalibError::line(
                file,
                line,
                format!("more than {MAX_ROWS} rows"),
            ));
        }
        for (c, col) in columns.iter().enumerate() {
            let raw = fields[col.index].trim().trim_matches('"').trim();
            let v: f64 = raw.parse().map_err(|_| {
                CalibError::cell(
                    file,
                    line,
                    col.index + 1,
                    format!("{}: \"{raw}\" is not a number", col.header),
                )
            })?;
            if !v.is_finite() {
                return Err(CalibError::cell(
                    file,
                    line,
                    col.index + 1,
                    format!("{}: \"{raw}\" is not finite", col.header),
                ));
            }
            values[c].push(v * col.factor);
        }
        row_lines.push(line);
    }
    Ok(Table {
        file: file.to_string(),
        columns,
        values,
        lines: row_lines,
    })
}

impl Table {
    /// The SI values of the column holding `q`, with the column, if there is one.
    pub fn column(&self, q: Quantity) -> Option<(&Column, &[f64])> {
        self.columns
            .iter()
            .position(|c| c.quantity == q)
            .map(|i| (&self.columns[i], self.values[i].as_slice()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_are_converted_at_the_boundary() {
        let t = parse(
            "# a comment\ntime_s,force_kN,displacement_mm\n0,0,0\n1,0.5,2\n\n2,1.0,4\n",
            "t.csv",
        )
        .unwrap();
        let (_, f) = t.column(Quantity::Force).unwrap();
        let (_, d) = t.column(Quantity::Displacement).unwrap();
        assert_eq!(f, &[0.0, 500.0, 1000.0]);
        assert_eq!(d, &[0.0, 0.002, 0.004]);
        assert_eq!(t.lines, vec![3, 4, 6]);
        let s = parse("stress_MPa,strain_percent\n1,2\n", "s.csv").unwrap();
        assert_eq!(s.column(Quantity::Stress).unwrap().1, &[1e6]);
        assert_eq!(s.column(Quantity::Strain).unwrap().1, &[0.02]);
        let k = parse("Torque [N*mm], Angle (deg)\n1000,180\n", "k.csv").unwrap();
        assert_eq!(k.column(Quantity::Torque).unwrap().1, &[1.0]);
        assert!((k.column(Quantity::Angle).unwrap().1[0] - std::f64::consts::PI).abs() < 1e-15);
    }

    #[test]
    fn errors_name_file_line_and_column() {
        let e = parse("force_N,displacement_mm\n1,2\n3,x\n", "d.csv").unwrap_err();
        assert_eq!((e.line, e.column), (Some(3), Some(2)));
        assert!(
            e.to_string().starts_with("d.csv:3:2: displacement_mm"),
            "{e}"
        );
        let e = parse("force_N,displacement_mm\n1,2,3\n", "d.csv").unwrap_err();
        assert_eq!(e.line, Some(2));
        let e = parse("force_lbf,displacement_mm\n", "d.csv").unwrap_err();
        assert_eq!((e.line, e.column), (Some(1), Some(1)));
        assert!(e.message.contains("unknown unit"), "{e}");
        let e = parse("force,displacement_mm\n", "d.csv").unwrap_err();
        assert!(e.message.contains("needs a unit"), "{e}");
        let e = parse("a,b\n1,2\n", "d.csv").unwrap_err();
        assert!(e.message.contains("no column"), "{e}");
        assert!(parse("", "d.csv").unwrap_err().message.contains("empty"));
        let e = parse("force_N,displacement_mm\n1,inf\n", "d.csv").unwrap_err();
        assert!(e.message.contains("not finite"), "{e}");
    }
}
