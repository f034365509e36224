//! Synthetic test curves with known answers, for the validation tests and the examples:
//! a toe region (the slope rising from 0, as slack is taken up), a linear range of a known
//! slope, a softening tail, and Gaussian noise from a seeded generator.

/// SplitMix64: a small, seeded, reproducible generator (Steele, Lea & Flood 2014).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

/// The shape of a synthetic curve.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    /// Slope of the linear range (y per x).
    pub slope: f64,
    /// Largest x.
    pub x_max: f64,
    /// Number of points (x evenly spaced from x_max/(2n) to x_max).
    pub points: usize,
    /// End of the toe region as a fraction of x_max (0: none).
    pub toe: f64,
    /// End of the linear range as a fraction of x_max (1: no tail).
    pub linear_end: f64,
    /// Slope at x_max as a fraction of `slope` (the tail softens to it).
    pub tail_slope: f64,
    /// Noise standard deviation relative to the curve's largest y.
    pub noise: f64,
    pub seed: u64,
}

/// A synthetic curve: x, y, the noise σ used, and the last index of the linear range.
pub struct Synthetic {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub noise_std: f64,
    /// Index of the first and last point inside the true linear range.
    pub linear_first: usize,
    pub linear_last: usize,
}

/// The noise-free curve at x.
pub fn exact(s: &Shape, x: f64) -> f64 {
    let k = s.slope;
    let xt = s.toe * s.x_max;
    let xe = s.linear_end * s.x_max;
    // toe: y = k x² / (2 x_t) (slope rising from 0 to k), then linear, C¹ at x_t
    let lin = |x: f64| k * (x - 0.5 * xt);
    if x < xt {
        k * x * x / (2.0 * xt)
    } else if x <= xe {
        lin(x)
    } else {
        // tail: slope falls linearly from k at x_e to tail_slope·k at x_max, C¹ at x_e
        let c = 0.5 * k * (1.0 - s.tail_slope) / (s.x_max - xe).max(1e-300);
        lin(x) - c * (x - xe) * (x - xe)
    }
}

/// Generates the curve.
pub fn generate(s: &Shape) -> Synthetic {
    let n = s.points;
    let x: Vec<f64> = (0..n)
        .map(|i| s.x_max * (i as f64 + 0.5) / n as f64)
        .collect();
    let clean: Vec<f64> = x.iter().map(|&x| exact(s, x)).collect();
    let y_max = clean.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let sigma = s.noise * y_max;
    let mut rng = Rng::new(s.seed);
    let y = clean.iter().map(|v| v + sigma * rng.normal()).collect();
    let xt = s.toe * s.x_max;
    let xe = s.linear_end * s.x_max;
    let linear_first = x.iter().position(|&v| v >= xt).unwrap_or(0);
    let linear_last = x.iter().rposition(|&v| v <= xe).unwrap_or(n - 1);
    Synthetic {
        x,
        y,
        noise_std: sigma,
        linear_first,
        linear_last,
    }
}

/// The curve as CSV text with the given header, x and y scaled by the factors from SI
/// to the header's units.
pub fn csv(
    header: &str,
    x: &[f64],
    y: &[f64],
    x_factor: f64,
    y_factor: f64,
    y_first: bool,
) -> String {
    let mut s = format!("{header}\n");
    for (a, b) in x.iter().zip(y) {
        let (a, b) = (a * x_factor, b * y_factor);
        if y_first {
            s.push_str(&format!("{b:.6e},{a:.6e}\n"));
        } else {
            s.push_str(&format!("{a:.6e},{b:.6e}\n"));
        }
    }
    s
}

/// A cantilever's exact force–deflection line, F = 3 E I δ / L³ (free length `length`
/// \[m\], bending stiffness `ei` \[N·m²\]), at ten deflections up to 1 mm, as CSV
/// `force_N,deflection_mm` with twelve significant digits.
pub fn cantilever_line(ei: f64, length: f64) -> String {
    let mut text = format!(
        "# cantilever, free length {} mm\nforce_N,deflection_mm\n",
        length * 1e3
    );
    for k in 1..=10 {
        let deflection = 1e-4 * k as f64;
        let force = 3.0 * ei * deflection / length.powi(3);
        text.push_str(&format!("{force:.12e},{:.12e}\n", deflection * 1e3));
    }
    text
}

/// The known answers of [`example_files`].
#[derive(Clone, Copy, Debug)]
pub struct Truth {
    /// E_t, E_c, E_b \[Pa\].
    pub e_tension: f64,
    pub e_compression: f64,
    pub e_bending: f64,
    /// G \[Pa\].
    pub shear: f64,
    /// Diameters \[m\].
    pub d_inner: f64,
    pub d_outer: f64,
}

impl Truth {
    /// The example's material: hose 1's E_t and E_c (dissertation tables 3.3, 3.4), a
    /// bending modulus of 12 MPa and G for ν = 0.45; the section 10/16 mm.
    pub const EXAMPLE: Truth = Truth {
        e_tension: 11.583e6,
        e_compression: 13.1363e6,
        e_bending: 12.0e6,
        shear: 12.0e6 / (2.0 * 1.45),
        d_inner: 0.010,
        d_outer: 0.016,
    };

    pub fn section(&self) -> pliant_core::Section {
        pliant_core::Section::new(self.d_inner, self.d_outer)
    }
    pub fn ei(&self) -> f64 {
        self.e_bending * self.section().second_moment()
    }
    pub fn gj(&self) -> f64 {
        self.shear * self.section().polar_moment()
    }
}

/// Gauge length, span, grip distance and lever arm of the example tests \[m\].
pub const EXAMPLE_GAUGE: f64 = 0.100;
pub const EXAMPLE_SPAN: f64 = 0.200;
pub const EXAMPLE_TORSION_LENGTH: f64 = 0.300;
pub const EXAMPLE_LEVER_ARM: f64 = 0.100;

/// A file's name and its text.
pub type NamedText = (String, String);
/// The first and last row of a range.
pub type RowRange = (usize, usize);

/// The example calibration (examples/calibration/): its TOML and five CSV curves of a
/// hose with the answers `truth`, noise `noise` (relative to each curve's largest value)
/// and generator seed `seed`. Returns (file name, text) pairs and each curve's true
/// linear range (first, last row).
pub fn example_files(truth: &Truth, noise: f64, seed: u64) -> (Vec<NamedText>, Vec<RowRange>) {
    let area = truth.section().area();
    let mut files = Vec::new();
    let mut ranges = Vec::new();
    let mut shape = |slope: f64, x_max: f64, toe: f64, end: f64, tail: f64, k: u64| {
        let s = generate(&Shape {
            slope,
            x_max,
            points: 150,
            toe,
            linear_end: end,
            tail_slope: tail,
            noise,
            seed: seed.wrapping_mul(31).wrapping_add(k),
        });
        ranges.push((s.linear_first, s.linear_last));
        s
    };
    // tension: force–displacement of a 100 mm gauge length, strain to 30 %
    let t = shape(
        truth.e_tension * area / EXAMPLE_GAUGE,
        0.3 * EXAMPLE_GAUGE,
        0.06,
        0.5,
        0.3,
        1,
    );
    files.push((
        "tension.csv".into(),
        csv("displacement_mm,force_N", &t.x, &t.y, 1e3, 1.0, false),
    ));
    // compression: stress–strain, recorded negative
    let c = shape(truth.e_compression, 0.2, 0.08, 0.55, 0.4, 2);
    let neg = |v: &[f64]| v.iter().map(|a| -a).collect::<Vec<_>>();
    files.push((
        "compression.csv".into(),
        csv(
            "strain_percent,stress_MPa",
            &neg(&c.x),
            &neg(&c.y),
            100.0,
            1e-6,
            false,
        ),
    ));
    // three-point bending: span 200 mm, deflection to 30 mm
    let b = shape(
        48.0 * truth.ei() / EXAMPLE_SPAN.powi(3),
        0.030,
        0.05,
        0.6,
        0.3,
        3,
    );
    files.push((
        "bending.csv".into(),
        csv("force_N,deflection_mm", &b.x, &b.y, 1e3, 1.0, true),
    ));
    // torsion: grips 300 mm apart, twist to 180°
    let q = shape(
        truth.gj() / EXAMPLE_TORSION_LENGTH,
        std::f64::consts::PI,
        0.04,
        0.6,
        0.3,
        4,
    );
    files.push((
        "torsion.csv".into(),
        csv(
            "angle_deg,torque_Nm",
            &q.x,
            &q.y,
            180.0 / std::f64::consts::PI,
            1.0,
            false,
        ),
    ));
    // ISO 10619-1: force against the bend radius, lever arm 100 mm, curvature to 1/60 mm
    let i = shape(
        truth.ei() / EXAMPLE_LEVER_ARM,
        1.0 / 0.060,
        0.0,
        0.55,
        0.35,
        5,
    );
    let radius: Vec<f64> = i.x.iter().map(|k| 1.0 / k).collect();
    files.push((
        "iso10619.csv".into(),
        csv("bend_radius_mm,force_N", &radius, &i.y, 1e3, 1.0, false),
    ));
    let toml = format!(
        "# Example calibration (docs/calibration.md): synthetic curves of a hose with known stiffness,\n\
         # E_t = 11.583 MPa, E_c = 13.1363 MPa, EI = {ei:.6e} N·m² (E_b = 12 MPa), GJ = {gj:.6e} N·m² (G = {g:.4} MPa),\n\
         # each with a toe region, a softening tail and {pct}% noise (seed {seed}).\n\
         # Run: pliant calibrate examples/calibration/hose.toml --out out/calibration\n\
         format = \"pliant-calibration\"\n\
         name = \"calibrated_hose\"\n\
         description = \"oil return hose, chloroprene/NBR (synthetic test data)\"\n\
         d_inner_mm = {di}\n\
         d_outer_mm = {da}\n\
         density_kg_m3 = 940\n\
         density_source = \"dissertation worked time-step example (hose 1)\"\n\n\
         [[tests]]\nkind = \"tension\"\ncsv = \"tension.csv\"\nlength_mm = {gauge}   # gauge length L0\n\n\
         [[tests]]\nkind = \"compression\"\ncsv = \"compression.csv\"   # stress–strain: no length needed\n\n\
         [[tests]]\nkind = \"three_point_bending\"\ncsv = \"bending.csv\"\nlength_mm = {span}   # span between the supports\n\n\
         [[tests]]\nkind = \"torsion\"\ncsv = \"torsion.csv\"\nlength_mm = {tl}   # between the grips\n\n\
         [[tests]]\nkind = \"iso10619\"\ncsv = \"iso10619.csv\"\nlength_mm = {arm}   # lever arm to the apex of the bend\n",
        ei = truth.ei(),
        gj = truth.gj(),
        g = truth.shear * 1e-6,
        pct = noise * 100.0,
        di = truth.d_inner * 1e3,
        da = truth.d_outer * 1e3,
        gauge = EXAMPLE_GAUGE * 1e3,
        span = EXAMPLE_SPAN * 1e3,
        tl = EXAMPLE_TORSION_LENGTH * 1e3,
        arm = EXAMPLE_LEVER_ARM * 1e3,
    );
    files.insert(0, ("hose.toml".into(), toml));
    (files, ranges)
}
