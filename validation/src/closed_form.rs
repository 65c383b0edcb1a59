//! The closed forms of linear elasticity that the tests compare contopt with, each written once:
//! Hertz's sphere and line contact, the rigid flat punch (Boussinesq, Sneddon), uniform pressure
//! on a circle of a half-space and on a strip of a half-plane (Flamant), Westergaard's wavy
//! surface, Lamé's thick cylinder and its shrink fit, and Timoshenko's cantilever.
//!
//! Units: lengths in mm, forces in N, moduli, stresses and pressures in MPa (N/mm²); any
//! consistent set works, for nothing here holds a dimensional constant. Approaches and
//! deflections under pressure are positive into the body.
//!
//! Sources, cited by chapter: K. L. Johnson, *Contact Mechanics*, Cambridge University Press
//! (1985); S. P. Timoshenko and J. N. Goodier, *Theory of Elasticity*, 3rd ed., McGraw-Hill
//! (1970); R. G. Budynas and J. K. Nisbett, *Shigley's Mechanical Engineering Design*, 10th
//! ed., McGraw-Hill (2015).

use std::f64::consts::PI;

use contopt_core::Material;

/// The contact modulus E* of bodies pressed together, 1/E* = Σ (1 − νₖ²)/Eₖ \[MPa\]
/// (Johnson ch. 4); for one elastic body against a rigid one it is E/(1 − ν²).
pub fn contact_modulus(bodies: &[Material]) -> f64 {
    1.0 / bodies
        .iter()
        .map(|m| 1.0 / m.plane_strain_modulus())
        .sum::<f64>()
}

/// Hertz's sphere (Johnson ch. 4, solids of revolution): a rigid sphere of radius R \[mm\]
/// pressed into a half-space of contact modulus E* \[MPa\], so that the contact is a circle
/// of radius a \[mm\].
#[derive(Clone, Copy, Debug)]
pub struct HertzSphere {
    /// The sphere's radius R \[mm\].
    pub radius: f64,
    /// The contact modulus E* \[MPa\] ([`contact_modulus`]).
    pub modulus: f64,
}

impl HertzSphere {
    /// The initial gap of the sphere over the half-space at distance r \[mm\] from the axis,
    /// Hertz's paraboloid r²/(2R) \[mm\].
    pub fn gap(&self, r: f64) -> f64 {
        r * r / (2.0 * self.radius)
    }

    /// [`HertzSphere::gap`] at every point of `interface`, the sphere's axis through the origin
    /// along z \[mm\].
    pub fn gaps(&self, interface: &contopt_core::Interface) -> Vec<f64> {
        interface
            .points()
            .iter()
            .map(|x| self.gap(x[0].hypot(x[1])))
            .collect()
    }

    /// The force that makes the contact radius `a`: F = 4a³E*/(3R) \[N\].
    pub fn force(&self, a: f64) -> f64 {
        4.0 * a.powi(3) * self.modulus / (3.0 * self.radius)
    }

    /// The central (largest) pressure at contact radius `a`: p₀ = 3F/(2πa²) = 2aE*/(πR)
    /// \[MPa\]; the pressure is p₀√(1 − r²/a²).
    pub fn peak_pressure(&self, a: f64) -> f64 {
        3.0 * self.force(a) / (2.0 * PI * a * a)
    }

    /// The approach (indentation) at contact radius `a`: δ = a²/R \[mm\].
    pub fn approach(&self, a: f64) -> f64 {
        a * a / self.radius
    }
}

/// Hertz's line contact (Johnson ch. 4, two-dimensional contact of cylinders): a rigid
/// cylinder of radius R \[mm\] pressed by q \[N/mm\] per unit length into a half-space (or a
/// plane-strain half-plane) of contact modulus E* \[MPa\].
#[derive(Clone, Copy, Debug)]
pub struct HertzLine {
    /// The cylinder's radius R \[mm\].
    pub radius: f64,
    /// The contact modulus E* \[MPa\] ([`contact_modulus`]).
    pub modulus: f64,
}

impl HertzLine {
    /// The initial gap at distance y \[mm\] across the contact line: y²/(2R) \[mm\].
    pub fn gap(&self, y: f64) -> f64 {
        y * y / (2.0 * self.radius)
    }

    /// The half-width of the contact strip under the line load q: b = √(4qR/(πE*)) \[mm\].
    pub fn half_width(&self, q: f64) -> f64 {
        (4.0 * q * self.radius / (PI * self.modulus)).sqrt()
    }

    /// The largest pressure under the line load q: p₀ = 2q/(πb) = √(qE*/(πR)) \[MPa\]; the
    /// pressure is p₀√(1 − y²/b²).
    pub fn peak_pressure(&self, q: f64) -> f64 {
        2.0 * q / (PI * self.half_width(q))
    }
}

/// The peak pressure p₀ and the half-width b \[MPa, mm\] of a computed line contact centred
/// on y = 0, read as Hertz's p = p₀√(1 − y²/b²): the least-squares line p² = p₀² − (p₀/b)²·y²
/// through the samples (y, p) within 0.8 of the outermost sample that carries pressure (at the
/// contact's edge, where quadratic elements round off the square root with a ripple, the
/// samples are left out). `None` with fewer than two such samples, or a line that does not
/// fall.
pub fn fit_line_contact(samples: &[(f64, f64)]) -> Option<(f64, f64)> {
    let edge = samples
        .iter()
        .filter(|s| s.1 > 0.0)
        .fold(0.0f64, |m, s| m.max(s.0.abs()));
    let kept: Vec<(f64, f64)> = samples
        .iter()
        .filter(|s| s.0.abs() <= 0.8 * edge)
        .map(|&(y, p)| (y * y, p * p))
        .collect();
    let n = kept.len() as f64;
    if kept.len() < 2 {
        return None;
    }
    let (mx, my) = kept
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxx: f64 = kept.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    let sxy: f64 = kept.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let slope = sxy / sxx;
    let p0_squared = my - slope * mx;
    (slope < 0.0 && p0_squared > 0.0).then(|| (p0_squared.sqrt(), (-p0_squared / slope).sqrt()))
}

/// Points per side of the midpoint rule that averages Hertz's pressure over a cell in
/// [`fit_sphere_cells`]: 32² points put the square root's edge error below 10⁻³ of p₀ in a
/// cell a quarter of a wide.
const CELL_MEAN_RULE: usize = 32;

/// Golden-section steps of [`fit_sphere_cells`]'s search for a: the bracket shrinks by 0.618
/// a step, 80 steps to 10⁻¹⁶ of it.
const GOLDEN_STEPS: usize = 80;

/// The mean of Hertz's p/p₀ = √(1 − r²/a²) (0 beyond a) over the square cell of side `h`
/// centred at `c`, the sphere's axis through the origin.
pub fn hertz_cell_mean(c: [f64; 2], h: f64, a: f64) -> f64 {
    let m = CELL_MEAN_RULE;
    let at = |k: usize| (k as f64 + 0.5) / m as f64 - 0.5;
    (0..m * m)
        .map(|k| {
            let (x, y) = (c[0] + h * at(k % m), c[1] + h * at(k / m));
            (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt()
        })
        .sum::<f64>()
        / (m * m) as f64
}

/// The peak pressure p₀ and contact radius a \[MPa, mm\] of Hertz's sphere whose cell means
/// ([`hertz_cell_mean`]) fit the pressures of square cells (centre, side, pressure) best in
/// least squares, every cell counted. A contact solved on cells gives each cell its mean
/// pressure (a uniform pressure on it), so the pressures are compared with Hertz's means, not
/// with its values at the centres. A cell either carries pressure or not, so the contact's
/// edge is found to a cell, and the fit is biased by that much (it falls with the cells'
/// size). p₀ is linear for a given a; a is found by golden section between half and twice the
/// farthest loaded cell's reach. `None` without a loaded cell.
pub fn fit_sphere_cells(cells: &[([f64; 2], f64, f64)]) -> Option<(f64, f64)> {
    let reach = (cells.iter().filter(|c| c.2 > 0.0))
        .map(|c| c.0[0].hypot(c.0[1]) + c.1)
        .fold(0.0f64, f64::max);
    if reach == 0.0 {
        return None;
    }
    // For contact radius a: the best p₀ and the squared residual.
    let fit = |a: f64| {
        let means: Vec<f64> = cells.iter().map(|c| hertz_cell_mean(c.0, c.1, a)).collect();
        let p0 = (cells.iter().zip(&means))
            .map(|(c, m)| c.2 * m)
            .sum::<f64>()
            / means.iter().map(|m| m * m).sum::<f64>();
        let residual = (cells.iter().zip(&means))
            .map(|(c, m)| (c.2 - p0 * m).powi(2))
            .sum::<f64>();
        (p0, residual)
    };
    let golden = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (0.5 * reach, 2.0 * reach);
    for _ in 0..GOLDEN_STEPS {
        let (x1, x2) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
        match fit(x1).1 < fit(x2).1 {
            true => hi = x2,
            false => lo = x1,
        }
    }
    let a = 0.5 * (lo + hi);
    Some((fit(a).0, a))
}

/// The contact radius a \[mm\] of the Hertz sphere whose pressure has the same second moment
/// about the axis as square cells (centre, side, pressure), each a uniform pressure over its
/// cell: ∫p r² dA / ∫p dA = 2a²/5 for p = p₀√(1 − r²/a²) (Johnson ch. 4), and a cell of side
/// h centred at distance r_c carries p h² (r_c² + h²/6) of ∫p r² dA. `None` without a loaded
/// cell.
///
/// Why this estimate rather than where the pressure ends: a contact solved on cells finds its
/// edge only to a cell (a cell carries pressure or not), and the moment is an integral of every
/// cell's pressure. Where the cells' mean gaps are r²/2R (to a constant) and eq. 2.1 closes
/// every loaded cell, Σ pᵢAᵢ r²ᵢ = 2R(Fδ − 2W): the force times the approach less twice the
/// elastic energy W, global quantities that a discrete solution gets right sooner than its
/// edge's place. Nothing in it is set by a case. It is a property of Hertz's distribution: it
/// measures a only where the pressure has Hertz's shape. Hertz solved on the half-space grid
/// (`examples/sphere_on_block.rs`) gives its error on cells of each size.
pub fn sphere_radius_from_moment(cells: &[([f64; 2], f64, f64)]) -> Option<f64> {
    let (force, moment) = cells.iter().fold((0.0, 0.0), |(f, m), &(c, h, p)| {
        let area = h * h;
        let r2 = c[0] * c[0] + c[1] * c[1] + h * h / 6.0;
        (f + p * area, m + p * area * r2)
    });
    (force > 0.0).then(|| (2.5 * moment / force).sqrt())
}

/// A rigid flat-ended cylindrical punch of radius a \[mm\] pressed by F \[N\] into a
/// half-space of contact modulus E* \[MPa\] (Boussinesq; Sneddon 1946; Johnson ch. 3, pressure
/// applied to a circular region).
#[derive(Clone, Copy, Debug)]
pub struct FlatPunch {
    /// The punch's radius a \[mm\].
    pub radius: f64,
    /// The contact modulus E* \[MPa\] ([`contact_modulus`]).
    pub modulus: f64,
}

impl FlatPunch {
    /// The approach under `force`: δ = F/(2aE*) \[mm\].
    pub fn approach(&self, force: f64) -> f64 {
        force / (2.0 * self.radius * self.modulus)
    }

    /// The pressure at distance r < a from the axis under `force`: p = F/(2πa√(a² − r²))
    /// \[MPa\]; at the centre F/(2πa²), unbounded at the edge.
    pub fn pressure(&self, force: f64, r: f64) -> f64 {
        let a = self.radius;
        force / (2.0 * PI * a * (a * a - r * r).sqrt())
    }
}

/// A uniform pressure p \[MPa\] on the circle r < a \[mm\] of a half-space of modulus
/// E* = E/(1 − ν²) \[MPa\] (Johnson ch. 3, pressure applied to a circular region): the surface
/// deflects 2pa/E* at the centre and 4pa/(πE*) at the edge.
#[derive(Clone, Copy, Debug)]
pub struct UniformCircle {
    /// The loaded circle's radius a \[mm\].
    pub radius: f64,
    /// The pressure p \[MPa\].
    pub pressure: f64,
    /// The half-space's E* = E/(1 − ν²) \[MPa\].
    pub modulus: f64,
}

impl UniformCircle {
    /// The deflection at the centre, w(0) = 2pa/E* = 2(1 − ν²)pa/E \[mm\].
    pub fn centre_deflection(&self) -> f64 {
        2.0 * self.pressure * self.radius / self.modulus
    }

    /// How much more the centre deflects than the edge, w(0) − w(a) = 4pa(π/2 − 1)/(πE*)
    /// = (2 − 4/π)pa/E* \[mm\]: the gap change that makes a rigid flat punch's pressure uniform
    /// (the paper's §3 with v = 1 on a half-space).
    pub fn centre_minus_edge(&self) -> f64 {
        4.0 * self.pressure * self.radius * (PI / 2.0 - 1.0) / (PI * self.modulus)
    }
}

/// A uniform pressure p \[MPa\] on the strip |x| < a \[mm\] of an elastic half-plane (Flamant's
/// solution integrated over the strip, Johnson ch. 2): the surface deflection is
/// w(x) = 2p/(πE′)·[(x − a) ln|x − a| − (x + a) ln|x + a|] up to a constant, with E′ = E in
/// plane stress and E/(1 − ν²) in plane strain.
#[derive(Clone, Copy, Debug)]
pub struct FlamantStrip {
    /// The strip's half-width a \[mm\].
    pub half_width: f64,
    /// The pressure p \[MPa\].
    pub pressure: f64,
    /// E′: E in plane stress, E/(1 − ν²) in plane strain \[MPa\].
    pub modulus: f64,
}

impl FlamantStrip {
    /// The mean of w over [c, d] \[mm\], up to the same constant as w, by the antiderivative
    /// ∫ t ln|t| dt = t² ln|t|/2 − t²/4.
    pub fn mean_deflection(&self, c: f64, d: f64) -> f64 {
        let g = |t: f64| {
            if t == 0.0 {
                0.0
            } else {
                0.5 * t * t * t.abs().ln() - 0.25 * t * t
            }
        };
        let a = self.half_width;
        2.0 * self.pressure / (PI * self.modulus) * (-(g(d + a) - g(c + a)) + (g(d - a) - g(c - a)))
            / (d - c)
    }

    /// How much more the centre deflects than the edge, w(0) − w(a) = 4pa ln 2/(πE′) \[mm\]:
    /// the gap change that makes a rigid strip's pressure uniform.
    pub fn centre_minus_edge(&self) -> f64 {
        4.0 * self.pressure * self.half_width * 2f64.ln() / (PI * self.modulus)
    }
}

/// Westergaard's wavy surface (Johnson ch. 13): a rigid surface Δ(1 − cos 2πx/λ) pressed with
/// mean pressure p̄ \[MPa\] on a half-space of contact modulus E* \[MPa\]. Contact is full from
/// p* = πE*Δ/λ on.
#[derive(Clone, Copy, Debug)]
pub struct Westergaard {
    /// The wavelength λ \[mm\].
    pub wavelength: f64,
    /// The amplitude Δ \[mm\].
    pub amplitude: f64,
    /// The contact modulus E* \[MPa\] ([`contact_modulus`]).
    pub modulus: f64,
}

impl Westergaard {
    /// The initial gap of the wavy surface at x, Δ(1 − cos 2πx/λ) \[mm\].
    pub fn gap(&self, x: f64) -> f64 {
        self.amplitude * (1.0 - (2.0 * PI * x / self.wavelength).cos())
    }

    /// The mean pressure of full contact, p* = πE*Δ/λ \[MPa\].
    pub fn full_contact_pressure(&self) -> f64 {
        PI * self.modulus * self.amplitude / self.wavelength
    }

    /// The contact width 2a per wavelength at mean pressure p̄ < p*, from
    /// sin²(πa/λ) = p̄/p* \[mm\].
    pub fn contact_width(&self, mean: f64) -> f64 {
        let ratio = mean / self.full_contact_pressure();
        2.0 * self.wavelength / PI * ratio.sqrt().asin()
    }

    /// The largest pressure at mean pressure p̄ < p*: 2√(p̄p*) \[MPa\].
    pub fn peak_pressure(&self, mean: f64) -> f64 {
        2.0 * (mean * self.full_contact_pressure()).sqrt()
    }

    /// The pressure at x in full contact (p̄ ≥ p*): p̄ + p*·cos 2πx/λ \[MPa\].
    pub fn full_contact(&self, mean: f64, x: f64) -> f64 {
        mean + self.full_contact_pressure() * (2.0 * PI * x / self.wavelength).cos()
    }
}

/// Lamé's thick cylinder (Timoshenko & Goodier ch. 4, thick-walled cylinder): a tube of radii
/// a < b \[mm\] under an internal pressure p \[MPa\]. With k = pa²/(b² − a²) and c = kb²:
/// σ_r = k − c/r², σ_θ = k + c/r², so σ_r + σ_θ = 2k is uniform.
#[derive(Clone, Copy, Debug)]
pub struct ThickCylinder {
    /// The bore's radius a \[mm\].
    pub inner: f64,
    /// The outer radius b \[mm\].
    pub outer: f64,
    /// The internal pressure p \[MPa\].
    pub pressure: f64,
}

impl ThickCylinder {
    /// k = pa²/(b² − a²) and c = kb² \[MPa\], \[N\].
    fn constants(&self) -> (f64, f64) {
        let (a, b) = (self.inner, self.outer);
        let k = self.pressure * a * a / (b * b - a * a);
        (k, k * b * b)
    }

    /// The radial stress σ_r = k − c/r² at radius r \[MPa\].
    pub fn radial_stress(&self, r: f64) -> f64 {
        let (k, c) = self.constants();
        k - c / (r * r)
    }

    /// The hoop stress σ_θ = k + c/r² at radius r \[MPa\].
    pub fn hoop_stress(&self, r: f64) -> f64 {
        let (k, c) = self.constants();
        k + c / (r * r)
    }

    /// The axial stress in plane strain (ε_z = 0), σ_z = ν(σ_r + σ_θ) = 2νk \[MPa\].
    pub fn plane_strain_axial_stress(&self, nu: f64) -> f64 {
        2.0 * nu * self.constants().0
    }

    /// The radial displacement in plane strain (ε_z = 0) at radius r:
    /// u_r = (1 + ν)/E·((1 − 2ν)kr + c/r) \[mm\].
    pub fn plane_strain_displacement(&self, material: &Material, r: f64) -> f64 {
        let (k, c) = self.constants();
        let (e, nu) = (material.e(), material.nu());
        (1.0 + nu) / e * ((1.0 - 2.0 * nu) * k * r + c / r)
    }

    /// The radial displacement in plane stress (σ_z = 0) at radius r:
    /// u_r = ((1 − ν)kr + (1 + ν)c/r)/E \[mm\].
    pub fn plane_stress_displacement(&self, material: &Material, r: f64) -> f64 {
        let (k, c) = self.constants();
        let (e, nu) = (material.e(), material.nu());
        ((1.0 - nu) * k * r + (1.0 + nu) * c / r) / e
    }
}

/// Lamé's shrink fit (Timoshenko & Goodier ch. 4, thick-walled cylinder; Shigley §3-16, press
/// and shrink fits): a shaft of outer radius b_s (hollow with bore a, or solid with a = 0) in
/// a hub of bore b_h < b_s and outer radius c \[mm\], the radial interference δ = b_s − b_h
/// closed by the contact pressure p alone, in plane stress (thin disks, σ_z = 0) or plane strain
/// (long parts, ε_z = 0: E and ν replaced by E/(1 − ν²) and ν/(1 − ν)).
///
/// Lamé's tube (σ_r = k − c/r², σ_θ = k + c/r²) gives the hub's bore, under an internal
/// pressure p_h, the radial displacement u_h = b_h p_h (K_h + ν_h)/E_h with K_h = (c² + b_h²)/
/// (c² − b_h²), and the shaft's surface, under an external pressure p, u_s = −b_s p (K_s −
/// ν_s)/E_s with K_s = (b_s² + a²)/(b_s² − a²) (1 for a solid shaft). The pressure p acts on the
/// shaft's surface; the same force on the hub's shorter bore is p_h = p b_s/b_h. The parts fit
/// when u_h − u_s = δ:
///
/// p = δ / (b_s [(K_h + ν_h)/E_h + (K_s − ν_s)/E_s]).
///
/// With b_s = b_h = b (the textbook's, δ ≪ b) this is Shigley's interference-fit pressure; the
/// two differ by O(δ/b). A contact model whose pressure is measured on the shaft (the first
/// body) and applied to the hub with the same weights has exactly this one.
#[derive(Clone, Copy, Debug)]
pub struct ShrinkFit {
    /// The shaft's bore a \[mm\] (0 for a solid shaft).
    pub shaft_bore: f64,
    /// The shaft's outer radius b_s before assembly \[mm\].
    pub shaft_radius: f64,
    /// The hub's bore b_h before assembly \[mm\], less than b_s.
    pub hub_bore: f64,
    /// The hub's outer radius c \[mm\].
    pub hub_radius: f64,
    /// The shaft's material.
    pub shaft: Material,
    /// The hub's material.
    pub hub: Material,
    /// Plane strain (ε_z = 0); plane stress (σ_z = 0) when false.
    pub plane_strain: bool,
}

impl ShrinkFit {
    /// The radial interference δ = b_s − b_h \[mm\].
    pub fn interference(&self) -> f64 {
        self.shaft_radius - self.hub_bore
    }

    /// E and ν of `material` in the fit's plane state: as given in plane stress, E/(1 − ν²)
    /// and ν/(1 − ν) in plane strain.
    fn plane(&self, material: &Material) -> (f64, f64) {
        let (e, nu) = (material.e(), material.nu());
        if self.plane_strain {
            (e / (1.0 - nu * nu), nu / (1.0 - nu))
        } else {
            (e, nu)
        }
    }

    /// The contact pressure on the shaft's surface \[MPa\].
    pub fn pressure(&self) -> f64 {
        let (a, bs, bh, c) = (
            self.shaft_bore,
            self.shaft_radius,
            self.hub_bore,
            self.hub_radius,
        );
        let (eh, nuh) = self.plane(&self.hub);
        let (es, nus) = self.plane(&self.shaft);
        let kh = (c * c + bh * bh) / (c * c - bh * bh);
        let ks = (bs * bs + a * a) / (bs * bs - a * a);
        self.interference() / (bs * ((kh + nuh) / eh + (ks - nus) / es))
    }
}

/// Timoshenko's cantilever (Timoshenko & Goodier ch. 3, a cantilever loaded at the end): a
/// plane-stress beam of length L, depth D and thickness T \[mm\] on 0 ≤ x ≤ L, |y| ≤ D/2,
/// loaded at x = L by the parabolic shear traction whose resultant is P \[N\]. The
/// displacement field is exact elasticity, zero at the origin; a model that prescribes it on
/// x = 0 must reproduce it everywhere.
#[derive(Clone, Copy, Debug)]
pub struct Cantilever {
    /// The length L \[mm\].
    pub length: f64,
    /// The depth D \[mm\].
    pub depth: f64,
    /// The thickness T \[mm\].
    pub thickness: f64,
    /// The end load P \[N\].
    pub load: f64,
    /// The beam's material.
    pub material: Material,
}

impl Cantilever {
    /// The second moment of area I = TD³/12 \[mm⁴\].
    fn second_moment(&self) -> f64 {
        self.thickness * self.depth.powi(3) / 12.0
    }

    /// The end traction τ_xy(y) = P/(2I)·(D²/4 − y²) \[MPa\], whose resultant is P.
    pub fn end_traction(&self, y: f64) -> f64 {
        let d = self.depth;
        self.load / (2.0 * self.second_moment()) * (d * d / 4.0 - y * y)
    }

    /// The displacement (u_x, u_y) at (x, y) \[mm\].
    pub fn displacement(&self, p: [f64; 2]) -> [f64; 2] {
        let (x, y) = (p[0], p[1]);
        let (l, d, load) = (self.length, self.depth, self.load);
        let (e, nu) = (self.material.e(), self.material.nu());
        let scale = load / (6.0 * e * self.second_moment());
        let ux = -scale * y * ((6.0 * l - 3.0 * x) * x + (2.0 + nu) * (y * y - d * d / 4.0));
        let uy = scale
            * (3.0 * nu * y * y * (l - x)
                + (4.0 + 5.0 * nu) * d * d * x / 4.0
                + (3.0 * l - x) * x * x);
        [ux, uy]
    }

    /// The tip deflection of Euler–Bernoulli theory, PL³/(3EI) \[mm\]: elasticity adds the
    /// shear term (4 + 5ν)D²/(8L²) of it.
    pub fn bernoulli_tip_deflection(&self) -> f64 {
        self.load * self.length.powi(3) / (3.0 * self.material.e() * self.second_moment())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Round-off of a few operations on values of order one.
    const ROUND_OFF: f64 = 1e-13;

    fn steel() -> Material {
        Material::new(2e5, 0.3).unwrap()
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a / b - 1.0).abs() < tol
    }

    /// Hertz's own pressure, each cell carrying its mean over the cell, gives back its contact
    /// radius by the second moment as the cells shrink, the error falling with their size
    /// squared: +2.5 %, +0.16 % and +0.01 % on cells of a/4, a/16 and a/64, whatever p₀. (A
    /// contact solved on cells does not carry Hertz's means at its edge; on the half-space
    /// grid see `tests/solid_validation.rs`.)
    #[test]
    fn the_second_moment_of_hertz_cell_means_gives_a() {
        let a = 1.3;
        for (n, tol) in [(4, 0.03), (16, 2e-3), (64, 1.2e-4)] {
            let h = a / n as f64;
            let cells: Vec<([f64; 2], f64, f64)> = (0..4 * n * n)
                .map(|k| {
                    let c = [
                        ((k % (2 * n)) as f64 + 0.5) * h,
                        ((k / (2 * n)) as f64 + 0.5) * h,
                    ];
                    (c, h, 2500.0 * hertz_cell_mean(c, h, a))
                })
                .collect();
            let got = sphere_radius_from_moment(&cells).unwrap();
            assert!(close(got, a, tol), "{n} cells per a: {got} against {a}");
            assert!(got > a, "{n}: the edge cells' means lie outside a");
        }
        assert_eq!(sphere_radius_from_moment(&[([0.0, 0.0], 1.0, 0.0)]), None);
    }

    /// The contact modulus of one body is its E/(1 − ν²); two equal bodies halve it.
    #[test]
    fn contact_modulus_sums_compliances() {
        let one = contact_modulus(&[steel()]);
        assert!(close(one, 2e5 / 0.91, ROUND_OFF));
        assert!(close(
            contact_modulus(&[steel(), steel()]),
            one / 2.0,
            ROUND_OFF
        ));
    }

    /// Hertz's two forms of p₀ agree: 3F/(2πa²) = 2aE*/(πR) and 2q/(πb) = √(qE*/(πR)).
    #[test]
    fn hertz_forms_agree() {
        let sphere = HertzSphere {
            radius: 100.0,
            modulus: contact_modulus(&[steel()]),
        };
        let a = 1.3;
        let p0 = 2.0 * a * sphere.modulus / (PI * sphere.radius);
        assert!(close(sphere.peak_pressure(a), p0, ROUND_OFF));
        assert!(close(sphere.approach(a), 2.0 * sphere.gap(a), ROUND_OFF));
        let line = HertzLine {
            radius: 5.0,
            modulus: sphere.modulus,
        };
        let q = 544.6;
        let p0 = (q * line.modulus / (PI * line.radius)).sqrt();
        assert!(close(line.peak_pressure(q), p0, ROUND_OFF));
    }

    /// The flat punch's pressure carries its force: ∫ p 2πr dr = F (midpoints in r = a sin θ,
    /// where the integrand is F sin θ).
    #[test]
    fn flat_punch_pressure_carries_the_force() {
        let punch = FlatPunch {
            radius: 10.0,
            modulus: contact_modulus(&[steel()]),
        };
        let (force, n) = (1e4, 2000);
        let dtheta = PI / 2.0 / n as f64;
        let carried: f64 = (0..n)
            .map(|k| {
                let theta = (k as f64 + 0.5) * dtheta;
                let (r, dr) = (10.0 * theta.sin(), 10.0 * theta.cos() * dtheta);
                punch.pressure(force, r) * 2.0 * PI * r * dr
            })
            .sum();
        // Midpoint rule on a smooth integrand: error ~ (π/2n)²/24.
        assert!(close(carried, force, 1e-6), "{carried}");
    }

    /// The strip's mean deflections over vanishing intervals at the centre and at the edge
    /// differ by its centre-minus-edge value (to O(δ ln δ)), and the circle's centre minus edge
    /// is 2pa/E* − 4pa/(πE*).
    #[test]
    fn centre_minus_edge_is_the_deflection_difference() {
        let strip = FlamantStrip {
            half_width: 5.0,
            pressure: 100.0,
            modulus: 2e5,
        };
        let delta = 1e-6;
        let difference =
            strip.mean_deflection(-delta, delta) - strip.mean_deflection(5.0 - delta, 5.0 + delta);
        assert!(
            close(difference, strip.centre_minus_edge(), 1e-5),
            "{difference}"
        );
        let circle = UniformCircle {
            radius: 10.0,
            pressure: 100.0,
            modulus: contact_modulus(&[steel()]),
        };
        let edge = 4.0 * circle.pressure * circle.radius / (PI * circle.modulus);
        assert!(close(
            circle.centre_minus_edge(),
            circle.centre_deflection() - edge,
            ROUND_OFF
        ));
    }

    /// Westergaard's partial contact meets the full one at p̄ = p*: the whole wave in contact,
    /// the peak 2p*.
    #[test]
    fn westergaard_partial_meets_full_contact() {
        let wave = Westergaard {
            wavelength: 1.0,
            amplitude: 1e-3,
            modulus: contact_modulus(&[steel()]),
        };
        let p_star = wave.full_contact_pressure();
        assert!(close(
            wave.contact_width(p_star),
            wave.wavelength,
            ROUND_OFF
        ));
        assert!(close(
            wave.peak_pressure(p_star),
            wave.full_contact(p_star, 0.0),
            ROUND_OFF
        ));
        assert!(wave.full_contact(p_star, 0.5).abs() < ROUND_OFF * p_star);
    }

    /// Lamé's stresses meet the boundary conditions σ_r(a) = −p, σ_r(b) = 0, and the
    /// displacements satisfy Hooke's law for the hoop strain u_r/r.
    #[test]
    fn lame_meets_its_boundary_conditions_and_hookes_law() {
        let tube = ThickCylinder {
            inner: 10.0,
            outer: 20.0,
            pressure: 100.0,
        };
        let (m, r) = (steel(), 13.0);
        assert!((tube.radial_stress(10.0) + 100.0).abs() < ROUND_OFF * 100.0);
        assert!(tube.radial_stress(20.0).abs() < ROUND_OFF * 100.0);
        let (e, nu) = (m.e(), m.nu());
        let (sr, st) = (tube.radial_stress(r), tube.hoop_stress(r));
        let sz = tube.plane_strain_axial_stress(nu);
        let strain = (st - nu * (sr + sz)) / e;
        assert!(close(
            tube.plane_strain_displacement(&m, r) / r,
            strain,
            ROUND_OFF
        ));
        let strain = (st - nu * sr) / e;
        assert!(close(
            tube.plane_stress_displacement(&m, r) / r,
            strain,
            ROUND_OFF
        ));
    }

    /// The shrink fit closes its interference: the hub's bore under p·b_s/b_h (Lamé's
    /// [`ThickCylinder`]) and the shaft's surface under p (a hydrostatic −p plus a tube under
    /// the internal pressure −p, which frees its bore) move apart by δ, in plane stress and
    /// plane strain, for a solid and a hollow shaft; with equal radii of steel parts, plane
    /// stress, it is the textbook's p = Eδ(c² − b²)/(2bc²) to O(δ/b).
    #[test]
    fn shrink_fit_closes_the_interference() {
        let aluminium = Material::new(0.7e5, 0.34).unwrap();
        for plane_strain in [false, true] {
            for bore in [0.0, 12.0] {
                let fit = ShrinkFit {
                    shaft_bore: bore,
                    shaft_radius: 50.05,
                    hub_bore: 50.0,
                    hub_radius: 90.0,
                    shaft: steel(),
                    hub: aluminium,
                    plane_strain,
                };
                let p = fit.pressure();
                let displacement = |tube: ThickCylinder, m: &Material, r: f64| match plane_strain {
                    true => tube.plane_strain_displacement(m, r),
                    false => tube.plane_stress_displacement(m, r),
                };
                let hub = ThickCylinder {
                    inner: 50.0,
                    outer: 90.0,
                    pressure: p * 50.05 / 50.0,
                };
                let (e, nu) = (steel().e(), steel().nu());
                let hydrostatic = match plane_strain {
                    true => -p * (1.0 + nu) * (1.0 - 2.0 * nu) * 50.05 / e,
                    false => -p * (1.0 - nu) * 50.05 / e,
                };
                let freed = ThickCylinder {
                    inner: bore,
                    outer: 50.05,
                    pressure: -p,
                };
                let u_hub = displacement(hub, &aluminium, 50.0);
                let u_shaft = hydrostatic + displacement(freed, &steel(), 50.05);
                assert!(close(u_hub - u_shaft, fit.interference(), 1e-10));
            }
        }
        let (b, c, delta) = (40.0, 70.0, 0.02);
        let steel_fit = ShrinkFit {
            shaft_bore: 0.0,
            shaft_radius: b + delta,
            hub_bore: b,
            hub_radius: c,
            shaft: steel(),
            hub: steel(),
            plane_strain: false,
        };
        let textbook = 2e5 * delta * (c * c - b * b) / (2.0 * b * c * c);
        assert!(close(steel_fit.pressure(), textbook, 2.0 * delta / b));
        assert!(!close(steel_fit.pressure(), textbook, 1e-6));
    }

    /// The cantilever is held at the origin, its end traction sums to P (Simpson's rule is
    /// exact on the parabola), and its tip deflection is Euler–Bernoulli's plus the shear term
    /// (4 + 5ν)D²/(8L²).
    #[test]
    fn cantilever_is_beam_theory_with_shear() {
        let beam = Cantilever {
            length: 100.0,
            depth: 10.0,
            thickness: 2.0,
            load: 500.0,
            material: steel(),
        };
        assert_eq!(beam.displacement([0.0, 0.0]), [0.0, 0.0]);
        let h = beam.depth / 2.0;
        let resultant = beam.thickness * beam.depth / 6.0
            * (beam.end_traction(-h) + 4.0 * beam.end_traction(0.0) + beam.end_traction(h));
        assert!(close(resultant, beam.load, ROUND_OFF));
        let ratio = beam.displacement([beam.length, 0.0])[1] / beam.bernoulli_tip_deflection();
        let shear = (4.0 + 5.0 * 0.3) * beam.depth.powi(2) / (8.0 * beam.length.powi(2));
        assert!((ratio - 1.0 - shear).abs() < ROUND_OFF);
    }
}
