//! STEP export: the file is read back by a small ISO 10303-21 reader written here (header,
//! every referenced #id defined, the product structure, one curve per segment with its
//! points), and by OpenCASCADE when a Python with OCP is at hand (never installed here).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use glam::DVec3;
use pliant_harness::step::{export_step, StepNames};
use pliant_harness::{read_kbl, SettledHarness};

mod common;
use common::*;

fn out_dir(name: &str) -> PathBuf {
    common::out_dir("harness-step-tests", name)
}

/// A Part 21 parameter.
#[derive(Debug, Clone, PartialEq)]
enum P {
    Str(String),
    Enum(String),
    Ref(usize),
    Num(f64),
    Unset,
    List(Vec<P>),
    /// A typed parameter or one part of a complex instance: NAME(params).
    Typed(String, Vec<P>),
}

/// Instances by id: the parts (entity name, parameters) of each.
type Instances = HashMap<usize, Vec<(String, Vec<P>)>>;

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn peek(&mut self) -> u8 {
        self.ws();
        self.s.get(self.i).copied().unwrap_or(0)
    }

    fn expect(&mut self, c: u8) {
        assert_eq!(self.peek() as char, c as char, "at byte {}", self.i);
        self.i += 1;
    }

    fn word(&mut self) -> String {
        self.ws();
        let start = self.i;
        while self.i < self.s.len()
            && (self.s[self.i].is_ascii_alphanumeric() || self.s[self.i] == b'_')
        {
            self.i += 1;
        }
        String::from_utf8(self.s[start..self.i].to_vec()).unwrap()
    }

    /// `( p, p, … )`
    fn list(&mut self) -> Vec<P> {
        self.expect(b'(');
        let mut out = Vec::new();
        if self.peek() == b')' {
            self.i += 1;
            return out;
        }
        loop {
            out.push(self.param());
            match self.peek() {
                b',' => self.i += 1,
                b')' => {
                    self.i += 1;
                    return out;
                }
                c => panic!("unexpected {:?} at byte {}", c as char, self.i),
            }
        }
    }

    fn param(&mut self) -> P {
        match self.peek() {
            b'\'' => {
                self.i += 1;
                let mut v = Vec::new();
                loop {
                    let c = self.s[self.i];
                    self.i += 1;
                    if c == b'\'' {
                        if self.s.get(self.i) == Some(&b'\'') {
                            self.i += 1;
                            v.push(b'\'');
                        } else {
                            break;
                        }
                    } else {
                        v.push(c);
                    }
                }
                P::Str(String::from_utf8(v).unwrap())
            }
            b'.' => {
                self.i += 1;
                let w = self.word();
                self.expect(b'.');
                P::Enum(w)
            }
            b'#' => {
                self.i += 1;
                P::Ref(self.word().parse().unwrap())
            }
            b'$' | b'*' => {
                self.i += 1;
                P::Unset
            }
            b'(' => P::List(self.list()),
            c if c.is_ascii_alphabetic() => {
                let name = self.word();
                P::Typed(name, self.list())
            }
            _ => {
                let start = self.i;
                while self.i < self.s.len()
                    && matches!(
                        self.s[self.i],
                        b'0'..=b'9' | b'-' | b'+' | b'.' | b'E' | b'e'
                    )
                {
                    self.i += 1;
                }
                let t = std::str::from_utf8(&self.s[start..self.i]).unwrap();
                assert!(
                    t.contains('.') || !t.is_empty(),
                    "number expected at {start}"
                );
                P::Num(t.parse().unwrap())
            }
        }
    }

    /// An instance's right-hand side: `NAME(params)` or a complex `(A(..)B(..))`.
    fn instance(&mut self) -> Vec<(String, Vec<P>)> {
        if self.peek() == b'(' {
            self.i += 1;
            let mut parts = Vec::new();
            while self.peek() != b')' {
                let name = self.word();
                parts.push((name, self.list()));
            }
            self.i += 1;
            parts
        } else {
            let name = self.word();
            vec![(name, self.list())]
        }
    }
}

fn collect_refs(p: &P, out: &mut Vec<usize>) {
    match p {
        P::Ref(r) => out.push(*r),
        P::List(l) | P::Typed(_, l) => l.iter().for_each(|q| collect_refs(q, out)),
        _ => {}
    }
}

/// The instances of a Part 21 file: id → parts (name, params). Checks the structure.
fn read_part21(text: &str) -> (String, Instances) {
    assert!(text.starts_with("ISO-10303-21;"), "no ISO-10303-21 start");
    assert!(text.trim_end().ends_with("END-ISO-10303-21;"), "no end");
    let header_start = text.find("HEADER;").expect("HEADER section");
    let data_start = text.find("\nDATA;").expect("DATA section");
    let header = &text[header_start..data_start];
    for e in ["FILE_DESCRIPTION(", "FILE_NAME(", "FILE_SCHEMA(", "ENDSEC;"] {
        assert!(header.contains(e), "header without {e}");
    }
    let data_end = text.rfind("ENDSEC;").unwrap();
    let data = &text[data_start + 6..data_end];
    let mut p = Parser {
        s: data.as_bytes(),
        i: 0,
    };
    let mut map = HashMap::new();
    loop {
        if p.peek() == 0 {
            break;
        }
        p.expect(b'#');
        let id: usize = p.word().parse().unwrap();
        p.expect(b'=');
        let inst = p.instance();
        p.expect(b';');
        assert!(map.insert(id, inst).is_none(), "#{id} defined twice");
    }
    (header.to_string(), map)
}

fn one<'a>(map: &'a Instances, name: &str) -> Vec<(usize, &'a Vec<P>)> {
    let mut v: Vec<(usize, &Vec<P>)> = map
        .iter()
        .filter_map(|(id, parts)| {
            parts
                .iter()
                .find(|(n, _)| n == name)
                .map(|(_, params)| (*id, params))
        })
        .collect();
    v.sort_by_key(|(id, _)| *id);
    v
}

fn point_of(map: &Instances, id: usize) -> DVec3 {
    let parts = &map[&id];
    assert_eq!(parts[0].0, "CARTESIAN_POINT");
    let P::List(c) = &parts[0].1[1] else {
        panic!("coordinates")
    };
    let v: Vec<f64> = c
        .iter()
        .map(|x| match x {
            P::Num(v) => *v,
            _ => panic!("coordinate"),
        })
        .collect();
    DVec3::new(v[0], v[1], v[2])
}

#[test]
fn main_harness_as_step() {
    let h = read_kbl(&data(MAIN)).unwrap();
    let route = SettledHarness::from_harness(&h, 5e-3);
    let out = out_dir("main").join("harness.stp");
    let mut names = StepNames::new("TAB016120 modular harness (Pliant route)");
    names.timestamp = Some("2026-01-01T00:00:00".into());
    let r = export_step(&route, &names, &out).unwrap();
    println!(
        "{} curves, {} points, {} entities",
        r.curves, r.points, r.entities
    );
    assert_eq!(r.curves, 183);
    let text = std::fs::read_to_string(&out).unwrap();
    let (header, map) = read_part21(&text);
    assert!(header.contains("AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }"));
    assert_eq!(map.len(), r.entities);
    // Every reference points at an instance.
    for (id, parts) in &map {
        let mut rs = Vec::new();
        for (_, params) in parts {
            params.iter().for_each(|p| collect_refs(p, &mut rs));
        }
        for r in rs {
            assert!(
                map.contains_key(&r),
                "#{id} refers to #{r}, which is not defined"
            );
        }
    }
    // Product structure: SDR → PDS → PD → PDF → PRODUCT; SDR → wireframe → curve set.
    let sdr = one(&map, "SHAPE_DEFINITION_REPRESENTATION");
    assert_eq!(sdr.len(), 1);
    let (P::Ref(pds), P::Ref(rep)) = (&sdr[0].1[0], &sdr[0].1[1]) else {
        panic!("SDR")
    };
    assert_eq!(map[pds][0].0, "PRODUCT_DEFINITION_SHAPE");
    assert_eq!(
        map[rep][0].0,
        "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION"
    );
    let P::Ref(pd) = &map[pds][0].1[2] else {
        panic!("PDS")
    };
    assert_eq!(map[pd][0].0, "PRODUCT_DEFINITION");
    assert_eq!(one(&map, "PRODUCT").len(), 1);
    assert_eq!(one(&map, "APPLICATION_PROTOCOL_DEFINITION").len(), 1);
    // Units: a complex instance with LENGTH_UNIT and SI_UNIT(.MILLI.,.METRE.).
    let length = map
        .values()
        .find(|parts| parts.iter().any(|(n, _)| n == "LENGTH_UNIT"))
        .unwrap();
    let si = length.iter().find(|(n, _)| n == "SI_UNIT").unwrap();
    assert_eq!(si.1, vec![P::Enum("MILLI".into()), P::Enum("METRE".into())]);
    // One curve per segment, named, with the route's points in mm.
    let sets = one(&map, "GEOMETRIC_CURVE_SET");
    assert_eq!(sets.len(), 1);
    let P::List(members) = &sets[0].1[1] else {
        panic!("set")
    };
    assert_eq!(members.len(), 183);
    let curves = one(&map, "B_SPLINE_CURVE_WITH_KNOTS");
    assert_eq!(curves.len(), 183);
    let mut worst: f64 = 0.0;
    for (id, params) in curves {
        assert!(members.contains(&P::Ref(id)));
        let P::Str(name) = &params[0] else {
            panic!("name")
        };
        let poly = route.get(name).unwrap_or_else(|| panic!("curve {name}"));
        assert_eq!(params[1], P::Num(1.0), "degree 1");
        let P::List(ctrl) = &params[2] else {
            panic!("control points")
        };
        assert_eq!(ctrl.len(), poly.len(), "{name}: point count");
        for (c, p) in ctrl.iter().zip(poly) {
            let P::Ref(c) = c else { panic!("point ref") };
            worst = worst.max(point_of(&map, *c).distance(*p * 1e3));
        }
        let (P::List(mult), P::List(knots)) = (&params[6], &params[7]) else {
            panic!("knots")
        };
        let total: f64 = mult
            .iter()
            .map(|m| match m {
                P::Num(v) => *v,
                _ => 0.0,
            })
            .sum();
        assert_eq!(total as usize, ctrl.len() + 2, "{name}: n + p + 2 knots");
        assert_eq!(knots.len(), ctrl.len());
    }
    assert!(worst < 1e-6, "points off by {worst} mm");

    check_with_opencascade(&out, 183);
}

/// Interpreters that might have OCP: `PLIANT_PYTHON`, the repository's `.venv`, python3.
fn python_with_ocp() -> Option<PathBuf> {
    let mut list: Vec<PathBuf> = Vec::new();
    if let Some(p) = std::env::var_os("PLIANT_PYTHON") {
        list.push(PathBuf::from(p));
    }
    let venv = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../.venv/bin/python");
    if venv.is_file() {
        list.push(venv);
    }
    list.push(PathBuf::from("python3"));
    list.into_iter().find(|py| {
        Command::new(py)
            .args([
                "-c",
                "import importlib.util, sys; sys.exit(importlib.util.find_spec('OCP') is None)",
            ])
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// OpenCASCADE's STEPControl_Reader reads the file and finds `curves` edges.
fn check_with_opencascade(file: &Path, curves: usize) {
    let Some(py) = python_with_ocp() else {
        println!("OpenCASCADE check skipped: no Python with OCP (scripts/install-cad.sh)");
        return;
    };
    let script = r#"
import sys
from OCP.STEPControl import STEPControl_Reader
from OCP.IFSelect import IFSelect_RetDone
from OCP.TopExp import TopExp_Explorer
from OCP.TopAbs import TopAbs_EDGE
r = STEPControl_Reader()
assert r.ReadFile(sys.argv[1]) == IFSelect_RetDone, "ReadFile failed"
r.TransferRoots()
s = r.OneShape()
ex, n = TopExp_Explorer(s, TopAbs_EDGE), 0
while ex.More():
    n += 1
    ex.Next()
print(n)
"#;
    let out = Command::new(&py)
        .args(["-c", script])
        .arg(file)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "OCP failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let edges: usize = stdout.trim().lines().last().unwrap_or("").parse().unwrap();
    println!("OpenCASCADE ({}) read {edges} edges", py.display());
    assert_eq!(edges, curves);
}
