//! A part's `motion` and `parent` (SPEC K1), checked and converted to SI at the file
//! boundary: lengths from the scene's unit to metres, degrees to radians, a path's CSV
//! read and its poses converted. Errors name the field (`parts[2].motion.axis`) or, for
//! a path file, the file and its line.

use crate::error::FieldError;
use crate::files::FileAccess;
use crate::format::{KeyframesEntry, MotionEntry, OscillationEntry};
use crate::units::LengthUnit;
use crate::validate::{finite, finite_vec, non_negative, non_zero_vec};
use glam::{DQuat, DVec3};
use pliant_core::kinematics::{
    Hinge, Oscillation, PartMotion, Periodic, Profile, SampledPath, Slide,
};

/// The kinds, as written.
const KINDS: &str = "\"hinge\", \"slide\", \"periodic\", \"path\"";
/// Most samples a path file may hold.
pub const MAX_PATH_SAMPLES: usize = 1_000_000;

/// Builds `motion` of `parts[index]` (`at` gives a field's full name).
pub fn build_motion(
    raw: &MotionEntry,
    at: &dyn Fn(&str) -> String,
    unit: LengthUnit,
    files: &FileAccess,
) -> Result<PartMotion, FieldError> {
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let need = |name: &str, present: bool| {
        if present {
            Ok(())
        } else {
            Err(FieldError::about(
                at(name),
                format!("a {} motion needs `{name}`", raw.kind),
            ))
        }
    };
    let motion = match raw.kind.as_str() {
        "hinge" => {
            need("axis", raw.axis.is_some())?;
            need("point", raw.point.is_some())?;
            need("angle_deg", raw.angle_deg.is_some())?;
            let axis = non_zero_vec(&at("axis"), raw.axis.unwrap_or_default(), "")?;
            let point = finite_vec(&at("point"), raw.point.unwrap_or_default(), u)? * scale;
            let angle = keyframes(
                raw.angle_deg.as_ref(),
                &at("angle_deg"),
                "°",
                1f64.to_radians(),
            )?;
            PartMotion::Hinge(Hinge {
                point,
                axis: axis.normalize(),
                angle,
            })
        }
        "slide" => {
            need("direction", raw.direction.is_some())?;
            need("distance", raw.distance.is_some())?;
            let direction = non_zero_vec(&at("direction"), raw.direction.unwrap_or_default(), "")?;
            let distance = keyframes(raw.distance.as_ref(), &at("distance"), u, scale)?;
            PartMotion::Slide(Slide {
                direction: direction.normalize(),
                distance,
            })
        }
        "periodic" => {
            let centre = centre(raw, at, unit)?;
            let osc = |name: &str, o: Option<OscillationEntry>, unit: &str, to_si: f64| {
                o.map_or(Ok(Oscillation::default()), |o| {
                    oscillation(&o, &at(name), unit, to_si)
                })
            };
            let deg = 1f64.to_radians();
            PartMotion::Periodic(Periodic {
                centre,
                translation: [
                    osc("x", raw.x, u, scale)?,
                    osc("y", raw.y, u, scale)?,
                    osc("z", raw.z, u, scale)?,
                ],
                rotation: [
                    osc("roll", raw.roll, "°", deg)?,
                    osc("pitch", raw.pitch, "°", deg)?,
                    osc("yaw", raw.yaw, "°", deg)?,
                ],
            })
        }
        "path" => {
            need("file", raw.file.is_some())?;
            let name = raw.file.clone().unwrap_or_default();
            let bytes = files
                .read(&name)
                .map_err(|e| FieldError::new(at("file"), format!("\"{name}\""), e))?;
            let text = String::from_utf8_lossy(&bytes);
            let mut path = read_path_csv(&text, scale)
                .map_err(|e| FieldError::new(at("file"), format!("\"{name}\""), e))?;
            path.centre = centre(raw, at, unit)?;
            PartMotion::SampledPath(path)
        }
        other => {
            return Err(FieldError::new(
                at("kind"),
                format!("\"{other}\""),
                format!("must be one of {KINDS}"),
            ))
        }
    };
    motion
        .check()
        .map_err(|e| FieldError::about(at("kind"), e))?;
    Ok(motion)
}

fn centre(
    raw: &MotionEntry,
    at: &dyn Fn(&str) -> String,
    unit: LengthUnit,
) -> Result<DVec3, FieldError> {
    Ok(match raw.centre {
        Some(c) => finite_vec(&at("centre"), c, unit.symbol())? * unit.to_metres(),
        None => DVec3::ZERO,
    })
}

/// Keyframes converted by `to_si`.
fn keyframes(
    raw: Option<&KeyframesEntry>,
    field: &str,
    unit: &str,
    to_si: f64,
) -> Result<Profile, FieldError> {
    let Some(k) = raw else {
        return Err(FieldError::about(field, "missing"));
    };
    if k.times_s.is_empty() || k.times_s.len() != k.values.len() {
        return Err(FieldError::new(
            format!("{field}.values"),
            format!("{} values for {} times", k.values.len(), k.times_s.len()),
            "needs one value per time, at least one",
        ));
    }
    for (i, t) in k.times_s.iter().enumerate() {
        finite(&format!("{field}.times_s[{i}]"), *t, "s")?;
        if i > 0 && *t <= k.times_s[i - 1] {
            return Err(FieldError::new(
                format!("{field}.times_s[{i}]"),
                format!("{t} s"),
                format!("times must increase (after {} s)", k.times_s[i - 1]),
            ));
        }
    }
    let mut values = Vec::with_capacity(k.values.len());
    for (i, v) in k.values.iter().enumerate() {
        values.push(finite(&format!("{field}.values[{i}]"), *v, unit)? * to_si);
    }
    Ok(Profile::Keyframes {
        times: k.times_s.clone(),
        values,
        smooth: k.smooth.unwrap_or(true),
    })
}

fn oscillation(
    o: &OscillationEntry,
    field: &str,
    unit: &str,
    to_si: f64,
) -> Result<Oscillation, FieldError> {
    Ok(Oscillation {
        amplitude: finite(&format!("{field}.amplitude"), o.amplitude, unit)? * to_si,
        frequency: non_negative(&format!("{field}.frequency_hz"), o.frequency_hz, "Hz")?,
        phase: finite(
            &format!("{field}.phase_deg"),
            o.phase_deg.unwrap_or(0.0),
            "°",
        )?
        .to_radians(),
    })
}

/// The poses of a path file (`time_s, x, y, z, roll_deg, pitch_deg, yaw_deg` a line),
/// lengths multiplied by `scale` to metres; errors name the line.
pub fn read_path_csv(text: &str, scale: f64) -> Result<SampledPath, String> {
    let mut path = SampledPath {
        times: Vec::new(),
        positions: Vec::new(),
        rotations: Vec::new(),
        centre: DVec3::ZERO,
    };
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        let starts_numeric = line
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_digit() || c == '-' || c == '+' || c == '.');
        if !starts_numeric {
            continue; // a header, a comment or an empty line
        }
        let fields: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
        if fields.len() != 7 {
            return Err(format!(
                "line {}: {} columns; a pose line has 7 (time_s, x, y, z, roll_deg, pitch_deg, yaw_deg)",
                n + 1,
                fields.len()
            ));
        }
        let mut v = [0.0; 7];
        for (k, f) in fields.iter().enumerate() {
            v[k] = f
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    format!(
                        "line {}: column {} is not a finite number: \"{f}\"",
                        n + 1,
                        k + 1
                    )
                })?;
        }
        if let Some(&last) = path.times.last() {
            if v[0] <= last {
                return Err(format!(
                    "line {}: time {} s does not increase (after {last} s)",
                    n + 1,
                    v[0]
                ));
            }
        }
        if path.times.len() >= MAX_PATH_SAMPLES {
            return Err(format!("more than {MAX_PATH_SAMPLES} poses"));
        }
        let (roll, pitch, yaw) = (v[4].to_radians(), v[5].to_radians(), v[6].to_radians());
        path.times.push(v[0]);
        path.positions.push(DVec3::new(v[1], v[2], v[3]) * scale);
        path.rotations.push(
            DQuat::from_rotation_z(yaw)
                * DQuat::from_rotation_y(pitch)
                * DQuat::from_rotation_x(roll),
        );
    }
    if path.times.is_empty() {
        return Err("no pose lines".into());
    }
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_csv_converts_units_and_names_bad_lines() {
        let text = "time_s,x,y,z,roll,pitch,yaw\n0,0,0,0,0,0,0\n1,10,0,0,0,0,90\n";
        let path = read_path_csv(text, 1e-3).unwrap();
        assert_eq!(path.times, vec![0.0, 1.0]);
        assert!((path.positions[1] - DVec3::new(0.01, 0.0, 0.0)).length() < 1e-15);
        assert!((path.rotations[1] * DVec3::X - DVec3::Y).length() < 1e-12);
        let e = read_path_csv("0,0,0,0,0,0,0\n0,1,0,0,0,0,0\n", 1.0).unwrap_err();
        assert!(
            e.contains("line 2") && e.contains("does not increase"),
            "{e}"
        );
        let e = read_path_csv("0,0,0,x,0,0,0\n", 1.0).unwrap_err();
        assert!(e.contains("line 1") && e.contains("column 4"), "{e}");
        assert!(read_path_csv("0,1,2\n", 1.0).unwrap_err().contains("7"));
    }
}
