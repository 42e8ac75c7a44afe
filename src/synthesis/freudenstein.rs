#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` rejects NaN too, on purpose.
//! Freudenstein's equation: crank-rockers through given positions, and function generators.
//!
//! In Freudenstein's frame (O1 at the origin, O3 at (d, 0)), A = a(cos φ, sin φ) and
//! B = (d + c·cos ψ, c·sin ψ); |AB|² = b² expands to
//! d² + a² + c² + 2dc·cos ψ − 2ad·cos φ − 2ac·cos(φ − ψ) = b², and divided by 2ac:
//!
//! K1·cos ψ − K2·cos φ + K3 = cos(φ − ψ), K1 = d/a, K2 = d/c, K3 = (a² − b² + c² + d²)/(2ac),
//!
//! linear in (K1, K2, K3): three pairs (φ, ψ) fix them (a 3×3 system), more are met in the
//! least-squares sense. Back: a = d/K1, c = d/K2, b² = a² + c² + d² − 2ac·K3. The equation
//! does not see the assembly mode, so every answer is checked for one mode at all its
//! positions (no branch defect).

use super::four_bar::FourBar;
use super::search::{maximise, narrow_stretches};
use super::{check, length, require_transmission, Options, Synthesis, MAX_POINTS};
use crate::angle::normalize;
use crate::error::{finite, positive, Ends, Error, Result};
use crate::kinematics::Grashof;
use crate::linkage::Output;
use nalgebra::{DMatrix, DVector, Matrix3, Vector2, Vector3};
use std::f64::consts::PI;

/// The intervals the crank's range is swept in: where the four-bar must assemble, and along
/// which the rocker's angle is followed by continuity for the structural error.
const SWEEP: u32 = 1024;

/// Freudenstein's coefficients (K1, K2, K3) = (d/a, d/c, (a² − b² + c² + d²)/(2ac)) of the
/// four-bar with the frame d, the crank a, the coupler b and the rocker c (m): every position
/// (φ, ψ) of it satisfies K1·cos ψ − K2·cos φ + K3 = cos(φ − ψ) (angles from the frame line
/// O1→O3).
///
/// # Examples
/// ```
/// use tmm::synthesis::freudenstein_coefficients;
/// let k = freudenstein_coefficients(0.4, 0.1, 0.35, 0.3)?;
/// assert!((k[0] - 4.0).abs() < 1e-15 && (k[1] - 0.4 / 0.3).abs() < 1e-15);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] or [`Error::NonPositive`] for a length that is not a finite positive
/// number; [`Error::Overflow`] when the coefficients overflow.
pub fn freudenstein_coefficients(
    frame: f64,
    crank: f64,
    coupler: f64,
    rocker: f64,
) -> Result<[f64; 3]> {
    let d = positive("frame", frame)?;
    let a = positive("crank", crank)?;
    let b = positive("coupler", coupler)?;
    let c = positive("rocker", rocker)?;
    let k = [
        d / a,
        d / c,
        (a * a - b * b + c * c + d * d) / (2.0 * a * c),
    ];
    crate::error::computed_all("Freudenstein's coefficients", &k)?;
    Ok(k)
}

/// The lengths (a, b, c) from (K1, K2, K3) and the frame d.
fn lengths(method: &'static str, d: f64, k: [f64; 3]) -> Result<(f64, f64, f64)> {
    let bad = |what: &str, v: f64| Error::NoMechanism {
        method,
        problem: format!("the {what} comes out {v:.4e} (not a positive length)"),
    };
    let a = d / k[0];
    let c = d / k[1];
    if !(a > 0.0 && a.is_finite()) {
        return Err(bad("crank d/K1", a));
    }
    if !(c > 0.0 && c.is_finite()) {
        return Err(bad("rocker d/K2", c));
    }
    let b2 = a * a + c * c + d * d - 2.0 * a * c * k[2];
    if !(b2 > 0.0 && b2.is_finite()) {
        return Err(bad("coupler's square b²", b2));
    }
    Ok((a, b2.sqrt(), c))
}

/// The assembly mode of each position (φ, ψ) of the four-bar (d, a, c): one mode for all
/// (±1), or a branch defect.
fn one_mode(method: &'static str, d: f64, a: f64, c: f64, at: &[(f64, f64)]) -> Result<f64> {
    let modes: Vec<f64> = at
        .iter()
        .map(|&(phi, psi)| {
            let pa = a * Vector2::new(phi.cos(), phi.sin());
            let pb = Vector2::new(d + c * psi.cos(), c * psi.sin());
            FourBar::mode_of(d, pa, pb)
        })
        .collect();
    if modes.contains(&0.0) || modes.iter().any(|&m| m != modes[0]) {
        return Err(Error::NoMechanism {
            method,
            problem: format!(
                "branch defect: the positions need the assembly modes {modes:?} (+1: B left of A→O3)"
            ),
        });
    }
    Ok(modes[0])
}

fn check_positions(positions: &[(f64, f64)]) -> Result<()> {
    for &(phi, psi) in positions {
        finite("crank angle", phi)?;
        finite("rocker angle", psi)?;
    }
    for (i, p) in positions.iter().enumerate() {
        for (j, q) in positions.iter().enumerate().skip(i + 1) {
            if (0.5 * (p.0 - q.0)).sin().abs() < 1e-9 {
                return Err(Error::NoMechanism {
                    method: "Freudenstein's equation",
                    problem: format!(
                        "the crank angles of positions {} and {} coincide ({} rad)",
                        i + 1,
                        j + 1,
                        p.0
                    ),
                });
            }
        }
    }
    Ok(())
}

/// The exact solution of Freudenstein's equation at three positions.
fn solve3(p: &[(f64, f64)]) -> Result<[f64; 3]> {
    let m = Matrix3::from_fn(|i, j| match j {
        0 => p[i].1.cos(),
        1 => -p[i].0.cos(),
        _ => 1.0,
    });
    let rhs = Vector3::from_fn(|i, _| (p[i].0 - p[i].1).cos());
    let det = m.determinant();
    if !(det.abs() > 1e-12) {
        return Err(Error::Singular {
            what: "Freudenstein's system at three positions",
            measure: "det",
            value: det,
        });
    }
    let k = m.lu().solve(&rhs).ok_or(Error::Singular {
        what: "Freudenstein's system at three positions",
        measure: "det",
        value: det,
    })?;
    Ok([k[0], k[1], k[2]])
}

/// The least-squares solution of Freudenstein's equation at N ≥ 3 positions (SVD).
fn solve_ls(p: &[(f64, f64)]) -> Result<[f64; 3]> {
    let n = p.len();
    let m = DMatrix::from_fn(n, 3, |i, j| match j {
        0 => p[i].1.cos(),
        1 => -p[i].0.cos(),
        _ => 1.0,
    });
    let rhs = DVector::from_fn(n, |i, _| (p[i].0 - p[i].1).cos());
    // The SVD's iteration does not end on a non-finite entry.
    crate::error::computed_all(
        "Freudenstein's least-squares system",
        m.iter().chain(rhs.iter()),
    )?;
    let svd = m.svd(true, true);
    let (smax, smin) = (svd.singular_values.max(), svd.singular_values.min());
    if !(smin > 1e-12 * smax) {
        return Err(Error::Singular {
            what: "Freudenstein's least-squares system",
            measure: "smallest singular value / largest",
            value: smin / smax,
        });
    }
    let k = svd.solve(&rhs, 0.0).map_err(|_| Error::Overflow {
        what: "Freudenstein's least-squares solution",
    })?;
    Ok([k[0], k[1], k[2]])
}

/// A crank-rocker four-bar whose rocker stands at ψ_i when the crank stands at φ_i, for two
/// or three given pairs (angles from the frame line O1→O3, rad; the frame `frame` = d, m).
///
/// Three pairs fix Freudenstein's coefficients (a 3×3 linear system; see the module's
/// derivation); two leave one free, the crank's ratio a/d, which is chosen in (0, 1) where the
/// smallest transmission angle over a turn is largest (the 2×2 system for K2, K3 at each
/// trial). The answer must be a crank-rocker (Grashof) in one assembly mode at every pair.
/// The description is in Freudenstein's frame, posed at the first pair; output: the rocker's
/// angle.
///
/// # Examples
/// The rocker at 101.4°, 112.8°, 131.8° for the crank at 40°, 100°, 160° (near the
/// positions of the crank-rocker d = 0.4, a = 0.1, b = 0.35, c = 0.3 m):
/// ```
/// use tmm::synthesis::{crank_rocker_through, Options};
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{Output, Plan};
/// let deg = f64::to_radians;
/// let pairs = [(deg(40.0), deg(101.4)), (deg(100.0), deg(112.8)), (deg(160.0), deg(131.8))];
/// let s = crank_rocker_through(0.4, &pairs, &Options::default().with_min_transmission_angle(0.0))?;
/// let plan = Plan::new(&s.linkage)?;
/// assert!((s.report.dimension("crank").unwrap() - 0.1).abs() < 1e-3);
/// for (phi, psi) in pairs {
///     let rocker = plan.output(&Output::Angle("rocker".into()), Motion::fixed(phi))?.value;
///     assert!((rocker - psi).abs() < 1e-12);
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonPositive`] / [`Error::NonFinite`] for the frame or an angle;
/// [`Error::OutOfRange`] (`"positions"`) for fewer than two or more than three pairs;
/// [`Error::NoMechanism`] for coinciding crank angles, a negative length, a branch defect or a
/// four-bar that is not a crank-rocker; [`Error::Singular`] when the pairs do not determine the
/// coefficients; [`Error::Infeasible`] for γ_min below \[γ\].
pub fn crank_rocker_through(
    frame: f64,
    positions: &[(f64, f64)],
    options: &Options,
) -> Result<Synthesis> {
    const METHOD: &str = "crank-rocker through given positions";
    let d = length("frame", frame)?;
    let required = options.check()?;
    if !(2..=3).contains(&positions.len()) {
        return Err(Error::OutOfRange {
            name: "positions",
            value: positions.len() as f64,
            min: 2.0,
            max: 3.0,
            ends: Ends::Closed,
        });
    }
    check_positions(positions)?;
    let design_of = |(a, b, c): (f64, f64, f64)| -> Result<FourBar> {
        let sigma = one_mode(METHOD, d, a, c, positions)?;
        let fb = FourBar::local(d, a, b, c, sigma);
        fb.proportions(METHOD)?;
        let class = fb.grashof()?;
        if class != Grashof::CrankRocker {
            return Err(Error::NoMechanism {
                method: METHOD,
                problem: format!(
                    "the four-bar (d, a, b, c) = ({d:.4e}, {a:.4e}, {b:.4e}, {c:.4e}) m is a {class}, not a crank-rocker"
                ),
            });
        }
        Ok(fb)
    };
    let design = |k: [f64; 3]| design_of(lengths(METHOD, d, k)?);
    let fb = if positions.len() == 3 {
        design(solve3(positions)?)?
    } else {
        let (p, q) = (positions[0], positions[1]);
        let det = p.0.cos() - q.0.cos();
        if !(det.abs() > 1e-12) {
            return Err(Error::Singular {
                what: "Freudenstein's system at two positions",
                measure: "cos φ1 − cos φ2",
                value: det,
            });
        }
        // −K2·cos φi + K3 = cos(φi − ψi) − K1·cos ψi, i = 1, 2.
        let k_of = |t: f64| {
            let k1 = 1.0 / t;
            let (r1, r2) = (
                (p.0 - p.1).cos() - k1 * p.1.cos(),
                (q.0 - q.1).cos() - k1 * q.1.cos(),
            );
            let k2 = (r2 - r1) / det;
            let k3 = r1 + k2 * p.0.cos();
            [k1, k2, k3]
        };
        let gamma = |t: f64| design(k_of(t)).ok().map(|f| f.gamma_full().0);
        let (lo, hi) = (1e-6, 1.0 - 1e-6);
        let best = maximise(gamma, lo, hi, SCAN).or_else(|| {
            // Crank-rockers may exist on a stretch of a/d narrower than the scan's step:
            // found where the margin of the conditions peaks between samples.
            let margin = |t: f64| two_pair_margin(d, t, k_of(t), positions);
            let ok = |t: f64| design(k_of(t)).is_ok();
            narrow_stretches(margin, ok, lo, hi, SCAN)
                .into_iter()
                .filter_map(|(a, b)| maximise(gamma, a.min(b), a.max(b), 64))
                .max_by(|x, y| x.1.total_cmp(&y.1))
        });
        let (t, _) = best.ok_or_else(|| Error::NoMechanism {
            method: METHOD,
            problem: "no crank-rocker (one assembly mode, crank the shortest) passes through these two positions".to_owned(),
        })?;
        // The chosen a/d's lengths from the geometry (no cancellation), else as scanned.
        match two_pair_lengths(d, t * d, p, q) {
            Some(abc) => design_of(abc).or_else(|_| design(k_of(t)))?,
            None => design(k_of(t))?,
        }
    };
    let report = fb.report("crank-rocker through given positions", None)?;
    require_transmission(report.min_transmission_angle, required)?;
    let linkage = fb.linkage(
        "crank-rocker through given positions",
        positions[0].0,
        Vec::new(),
        None,
    )?;
    check::accepted(&linkage)?;
    Ok(Synthesis { linkage, report })
}

/// The rocker c and the coupler b of the four-bar with the frame d and the crank a through
/// the pairs `p` and `q`, from the geometry instead of Freudenstein's coefficients: at a ratio
/// a : d of 1 : 1000, K1 = d/a and K3 ≈ −K1·cos ψ cancel, and b² = a² + c² + d² − 2ac·K3
/// cancels again, so the pairs were met only to about 3e-10 rad.
///
/// Derivation: A_i = a(cos φ_i, sin φ_i), O3 = (d, 0), w_i = O3 − A_i, u_i = (cos ψ_i,
/// sin ψ_i), B_i = O3 + c·u_i; the coupler keeps its length, |B_1 − A_1|² = |B_2 − A_2|², and
/// |B_i − A_i|² = |w_i|² + 2c·u_i·w_i + c², so c = (|w_2|² − |w_1|²)/(2(u_1·w_1 − u_2·w_2)),
/// with |w_2|² − |w_1|² = 2ad(cos φ1 − cos φ2) (|w_i|² = d² − 2ad cos φ_i + a²); then
/// b = |B_1 − A_1|. `None` unless both are positive and finite.
fn two_pair_lengths(d: f64, a: f64, p: (f64, f64), q: (f64, f64)) -> Option<(f64, f64, f64)> {
    let o3 = Vector2::new(d, 0.0);
    let at = |phi: f64| a * Vector2::new(phi.cos(), phi.sin());
    let unit = |psi: f64| Vector2::new(psi.cos(), psi.sin());
    let (w1, w2) = (o3 - at(p.0), o3 - at(q.0));
    let (u1, u2) = (unit(p.1), unit(q.1));
    let c = a * d * (p.0.cos() - q.0.cos()) / (u1.dot(&w1) - u2.dot(&w2));
    let b = (w1 + c * u1).norm();
    (c > 0.0 && c.is_finite() && b > 0.0 && b.is_finite()).then_some((a, b, c))
}

/// The samples of a/d in the two-position crank-rocker's scan.
const SCAN: usize = 4096;

/// How far the two-position four-bar with a = t·d and Freudenstein's coefficients `k` is from
/// a crank-rocker in one assembly mode, in units of d (positive when it is one; continuous in
/// t where the lengths exist): the least of the rocker's and the coupler's existence, the
/// crank's being the shortest, Grashof's inequality, the two positions' modes agreeing and
/// the link ratio.
fn two_pair_margin(d: f64, t: f64, k: [f64; 3], at: &[(f64, f64)]) -> f64 {
    let a = t * d;
    if !(k[1] > 0.0) {
        return k[1] - 1.0;
    }
    let c = d / k[1];
    let b2 = a * a + c * c + d * d - 2.0 * a * c * k[2];
    if !(b2 > 0.0) {
        return b2 / (a * a + c * c + d * d) - 1.0;
    }
    let b = b2.sqrt();
    let longest = b.max(c).max(d);
    let shortest_other = b.min(c).min(d);
    let grashof = (b + c + d - longest) - (a + longest);
    let ratio = super::MAX_LINK_RATIO * a.min(shortest_other) - longest.max(a);
    let sides: Vec<f64> = at
        .iter()
        .map(|&(phi, psi)| {
            let pa = a * Vector2::new(phi.cos(), phi.sin());
            let pb = Vector2::new(d + c * psi.cos(), c * psi.sin());
            let (u, w) = (Vector2::new(d, 0.0) - pa, pb - pa);
            (u.x * w.y - u.y * w.x) / (u.norm() * w.norm()).max(f64::MIN_POSITIVE)
        })
        .collect();
    let least = sides.iter().fold(f64::INFINITY, |m, s| m.min(s.abs()));
    let mode = if sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0) {
        least
    } else {
        -least
    };
    [
        (shortest_other - a) / d,
        grashof / d,
        ratio / (super::MAX_LINK_RATIO * d),
        mode,
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

/// Where the precision points of a [`function_generator`] lie.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Spacing {
    /// Three precision points at Chebyshev spacing, met exactly.
    Chebyshev,
    /// Least squares over N points at Chebyshev spacing (3 ≤ N ≤ [`MAX_POINTS`]; N = 3 is
    /// [`Spacing::Chebyshev`]).
    LeastSquares(usize),
}

/// What a [`function_generator`] must do: the crank angle is a linear image of x, the rocker
/// angle one of y = f(x).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FunctionRequirement {
    /// [x0, x1], the range of x (x0 ≠ x1).
    pub x_range: [f64; 2],
    /// The crank angles at x0 and x1, rad (from the frame line O1→O3).
    pub crank_range: [f64; 2],
    /// The rocker angles at y0 = f(x0) and y1 = f(x1), rad.
    pub rocker_range: [f64; 2],
    /// d, the frame O1O3, m.
    pub frame: f64,
    /// The precision points.
    pub spacing: Spacing,
}

/// A synthesised function generator: the four-bar, the linear maps between (x, y) and
/// (φ, ψ), Freudenstein's coefficients and the precision points.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct FunctionGenerator {
    /// The four-bar and its report (γ_min over the crank's range).
    pub synthesis: Synthesis,
    /// The requirement it was made for.
    pub requirement: FunctionRequirement,
    /// f(x0) and f(x1).
    pub y_range: [f64; 2],
    /// (K1, K2, K3) of the four-bar.
    pub coefficients: [f64; 3],
    /// The x of the precision points.
    pub precision_x: Vec<f64>,
}

/// One point of the structural error curve.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StructuralError {
    /// x.
    pub x: f64,
    /// The wanted y = f(x).
    pub wanted: f64,
    /// The y the four-bar generates: its rocker angle (by the engine) mapped back to y.
    pub generated: f64,
    /// generated − wanted.
    pub error: f64,
}

impl FunctionGenerator {
    /// The crank angle φ(x) = φ0 + (φ1 − φ0)(x − x0)/(x1 − x0), rad.
    #[must_use]
    pub fn crank_angle(&self, x: f64) -> f64 {
        let r = &self.requirement;
        r.crank_range[0]
            + (r.crank_range[1] - r.crank_range[0]) * (x - r.x_range[0])
                / (r.x_range[1] - r.x_range[0])
    }

    /// The wanted rocker angle ψ(y) = ψ0 + (ψ1 − ψ0)(y − y0)/(y1 − y0), rad.
    #[must_use]
    pub fn rocker_angle(&self, y: f64) -> f64 {
        let r = &self.requirement;
        r.rocker_range[0]
            + (r.rocker_range[1] - r.rocker_range[0]) * (y - self.y_range[0])
                / (self.y_range[1] - self.y_range[0])
    }

    /// The structural error over the whole range at `n` (≥ 2) evenly spaced x: the engine's
    /// rocker angle at φ(x), mapped back to y, against f(x).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for n outside [2, [`MAX_POINTS`]]; as
    /// [`FunctionGenerator::structural_error_at`].
    pub fn structural_error<F: Fn(f64) -> f64>(
        &self,
        f: F,
        n: usize,
    ) -> Result<Vec<StructuralError>> {
        if !(2..=MAX_POINTS).contains(&n) {
            return Err(Error::OutOfRange {
                name: "n",
                value: n as f64,
                min: 2.0,
                max: MAX_POINTS as f64,
                ends: Ends::Closed,
            });
        }
        let [x0, x1] = self.requirement.x_range;
        let xs: Vec<f64> = (0..n)
            .map(|k| x0 + (x1 - x0) * k as f64 / (n - 1) as f64)
            .collect();
        self.structural_error_at(f, &xs)
    }

    /// The structural error at the given x (for example the precision points, where it
    /// vanishes): the engine's rocker angle at φ(x), mapped back to y, against f(x). The
    /// rocker's angle is followed by continuity from x0 over the range (not compared mod 2π),
    /// so an f the four-bar cannot follow, a pole in the range say, shows its whole error.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"x"`) for more than [`MAX_POINTS`] of them or an x outside the
    /// range; [`Error::NonFinite`]
    /// for a non-finite x or where f is not finite; the engine's error at a position where
    /// the four-bar does not assemble.
    pub fn structural_error_at<F: Fn(f64) -> f64>(
        &self,
        f: F,
        xs: &[f64],
    ) -> Result<Vec<StructuralError>> {
        if xs.len() > MAX_POINTS {
            return Err(Error::OutOfRange {
                name: "x",
                value: xs.len() as f64,
                min: 0.0,
                max: MAX_POINTS as f64,
                ends: Ends::Closed,
            });
        }
        let [x0, x1] = self.requirement.x_range;
        let (lo, hi) = (x0.min(x1), x0.max(x1));
        for &x in xs {
            finite("x", x)?;
            if !(lo..=hi).contains(&x) {
                return Err(Error::OutOfRange {
                    name: "x",
                    value: x,
                    min: lo,
                    max: hi,
                    ends: Ends::Closed,
                });
            }
        }
        // The rocker's angle by continuity from x0: the engine gives it in [0, 2π), and a
        // comparison mod 2π would cap every error at half a turn (a wanted f with a pole in
        // the range would read as a bounded error). So the angle is followed over a sweep of
        // the range fine enough that it moves less than half a turn between neighbours (the
        // four-bar assembles in one mode over the whole range, checked when it was made),
        // and anchored at x0, where the wanted angle is ψ0.
        let mut sweep: Vec<(f64, Option<usize>)> = (0..=SWEEP)
            .map(|i| (x0 + (x1 - x0) * f64::from(i) / f64::from(SWEEP), None))
            .chain(xs.iter().enumerate().map(|(k, &x)| (x, Some(k))))
            .collect();
        // From x0 to x1, whichever way the range runs; x0 (the first grid point) first.
        let toward = (x1 - x0).signum();
        sweep.sort_by(|a, b| {
            ((a.0 - x0) * toward)
                .total_cmp(&((b.0 - x0) * toward))
                .then(a.1.is_some().cmp(&b.1.is_some()))
        });
        let phis: Vec<f64> = sweep.iter().map(|&(x, _)| self.crank_angle(x)).collect();
        crate::error::computed_all("the crank angles φ(x)", &phis)?;
        let psis = check::output_values(
            &self.synthesis.linkage,
            &Output::Angle("rocker".to_owned()),
            &phis,
        )?;
        let r = &self.requirement;
        let mut unwrapped = Vec::with_capacity(psis.len());
        let mut last = r.rocker_range[0] + normalize(psis[0] - r.rocker_range[0] + PI) - PI;
        for (i, &psi) in psis.iter().enumerate() {
            if i > 0 {
                last += normalize(psi - psis[i - 1] + PI) - PI;
            }
            unwrapped.push(last);
        }
        let mut at = vec![0.0; xs.len()];
        for (&(_, k), &u) in sweep.iter().zip(&unwrapped) {
            if let Some(k) = k {
                at[k] = u;
            }
        }
        let scale = (self.y_range[1] - self.y_range[0]) / (r.rocker_range[1] - r.rocker_range[0]);
        xs.iter()
            .zip(at)
            .map(|(&x, psi)| {
                let wanted = finite("f(x)", f(x))?;
                let diff = psi - self.rocker_angle(wanted);
                let generated = wanted + diff * scale;
                crate::error::computed("the generated y", generated)?;
                Ok(StructuralError {
                    x,
                    wanted,
                    generated,
                    error: generated - wanted,
                })
            })
            .collect()
    }
}

/// A four-bar function generator for y = f(x) over `x_range`: its crank angle is the linear
/// image of x onto `crank_range`, its rocker angle that of y onto `rocker_range`, exactly at
/// three precision points at Chebyshev spacing (x_j = (x0 + x1)/2 − (x1 − x0)/2 ·
/// cos((2j − 1)π/6), j = 1, 2, 3) or in the least-squares sense of Freudenstein's equation at
/// N Chebyshev points.
///
/// The four-bar must assemble in one mode over the whole crank range (checked at the
/// precision points for a branch defect and at 1024 points of the range), and keep γ_min ≥
/// \[γ\] over the range. The description is in Freudenstein's frame, posed at x0.
///
/// # Examples
/// The classic worked problem: y = log10(x) on [1, 2], the crank turning 60° from −30°, the
/// rocker 90° from 0°. By hand, Chebyshev's precision points for three are
/// x_j = 1.5 − 0.5·cos((2j − 1)·30°) = 1.0670, 1.5000, 1.9330:
/// ```
/// use tmm::synthesis::{function_generator, FunctionRequirement, Options, Spacing};
/// let deg = f64::to_radians;
/// let need = FunctionRequirement {
///     x_range: [1.0, 2.0],
///     crank_range: [deg(-30.0), deg(30.0)],
///     rocker_range: [deg(0.0), deg(90.0)],
///     frame: 0.1,
///     spacing: Spacing::Chebyshev,
/// };
/// let g = function_generator(f64::log10, &need, &Options::default())?;
/// for (x, by_hand) in g.precision_x.iter().zip([1.0670, 1.5, 1.9330]) {
///     assert!((x - by_hand).abs() < 5e-5);
/// }
/// assert!(g.synthesis.report.min_transmission_angle > 40f64.to_radians());
/// // The structural error over the range, by the engine: small against the range of y
/// // (log10 2 ≈ 0.301): 1.2 % of it at x = 1; it changes sign at the three precision points.
/// let curve = g.structural_error(f64::log10, 200)?;
/// let worst = curve.iter().map(|p| p.error.abs()).fold(0.0, f64::max);
/// assert!(worst < 0.015 * 2f64.log10(), "{worst}");
/// let crossings = curve.windows(2).filter(|w| w[0].error * w[1].error < 0.0).count();
/// assert_eq!(crossings, 3);
/// # Ok::<(), tmm::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite number in the requirement or f;
/// [`Error::NonPositive`] for the frame; [`Error::OutOfRange`] (`"N"`) for fewer than three
/// least-squares points or more than [`MAX_POINTS`]; [`Error::NoMechanism`] for x0 = x1, f(x0) = f(x1), a zero crank or
/// rocker range, a negative length, a branch defect, a four-bar that does not assemble
/// over the range, or one that meets a precision point only a whole rocker turn away (f not
/// generated continuously: a pole or a jump in the range); [`Error::Singular`] for a degenerate system; [`Error::Infeasible`] for
/// γ_min below \[γ\].
pub fn function_generator<F: Fn(f64) -> f64>(
    f: F,
    need: &FunctionRequirement,
    options: &Options,
) -> Result<FunctionGenerator> {
    const METHOD: &str = "function generator";
    let required = options.check()?;
    let [x0, x1] = need.x_range;
    finite("x0", x0)?;
    finite("x1", x1)?;
    let [p0, p1] = need.crank_range;
    finite("crank angle at x0", p0)?;
    finite("crank angle at x1", p1)?;
    let [q0, q1] = need.rocker_range;
    finite("rocker angle at y0", q0)?;
    finite("rocker angle at y1", q1)?;
    let d = length("frame", need.frame)?;
    let n = match need.spacing {
        Spacing::Chebyshev => 3,
        Spacing::LeastSquares(n) if !(3..=MAX_POINTS).contains(&n) => {
            return Err(Error::OutOfRange {
                name: "N",
                value: n as f64,
                min: 3.0,
                max: MAX_POINTS as f64,
                ends: Ends::Closed,
            });
        }
        Spacing::LeastSquares(n) => n,
    };
    let nothing = |what: &str| Error::NoMechanism {
        method: METHOD,
        problem: format!("{what}: the range maps to nothing"),
    };
    let span = (p1 - p0).abs();
    if x0 == x1 {
        return Err(nothing("x0 = x1"));
    }
    if !(span > 0.0 && span < 2.0 * PI) {
        return Err(nothing("the crank's range is zero or a full turn"));
    }
    if q0 == q1 {
        return Err(nothing("the rocker's range is zero"));
    }
    let (y0, y1) = (finite("f(x0)", f(x0))?, finite("f(x1)", f(x1))?);
    if y0 == y1 {
        return Err(nothing("f(x0) = f(x1)"));
    }
    let precision_x: Vec<f64> = (1..=n)
        .map(|j| {
            0.5 * (x0 + x1) - 0.5 * (x1 - x0) * ((2 * j - 1) as f64 * PI / (2 * n) as f64).cos()
        })
        .collect();
    let crank_angle = |x: f64| p0 + (p1 - p0) * (x - x0) / (x1 - x0);
    let rocker_angle = |y: f64| q0 + (q1 - q0) * (y - y0) / (y1 - y0);
    let pairs: Vec<(f64, f64)> = precision_x
        .iter()
        .map(|&x| Ok((crank_angle(x), rocker_angle(finite("f(x)", f(x))?))))
        .collect::<Result<_>>()?;
    // Linear maps of huge ranges may overflow; a non-finite angle would stall the SVD.
    crate::error::computed_all(
        "the precision points' angles",
        pairs.iter().flat_map(|(p, q)| [p, q]),
    )?;
    let k = if n == 3 {
        solve3(&pairs)?
    } else {
        solve_ls(&pairs)?
    };
    let (a, b, c) = lengths(METHOD, d, k)?;
    let sigma = if n == 3 {
        one_mode(METHOD, d, a, c, &pairs)?
    } else {
        // Least squares: the mode whose rocker angles come nearest the wanted ones.
        let miss = |s: f64| {
            let fb = FourBar::local(d, a, b, c, s);
            pairs.iter().try_fold(0.0, |acc, &(phi, psi)| {
                let (_, pb) = fb.local_pose(phi)?;
                let got = (pb.y).atan2(pb.x - d);
                Some(acc + (normalize(got - psi + PI) - PI).powi(2))
            })
        };
        match (miss(1.0), miss(-1.0)) {
            (Some(p), Some(m)) => {
                if p <= m {
                    1.0
                } else {
                    -1.0
                }
            }
            (Some(_), None) => 1.0,
            (None, Some(_)) => -1.0,
            (None, None) => {
                return Err(Error::NoMechanism {
                    method: METHOD,
                    problem: "the least-squares four-bar does not assemble at every point"
                        .to_owned(),
                })
            }
        }
    };
    let fb = FourBar::local(d, a, b, c, sigma);
    fb.proportions(METHOD)?;
    let start = p0.min(p1);
    for i in 0..=SWEEP {
        let phi = start + span * f64::from(i) / f64::from(SWEEP);
        if fb.local_pose(phi).is_none() {
            return Err(Error::NoMechanism {
                method: METHOD,
                problem: format!(
                    "the four-bar does not assemble at the crank angle {phi:.6} rad of its range"
                ),
            });
        }
    }
    let mut report = fb.report("four-bar function generator", Some((start, span)))?;
    // The crank works over its range only: γ_min over that range.
    (report.min_transmission_angle, report.min_transmission_at) = fb.gamma_over(start, span);
    require_transmission(report.min_transmission_angle, required)?;
    let linkage = fb.linkage("four-bar function generator", p0, Vec::new(), None)?;
    check::accepted(&linkage)?;
    let made = FunctionGenerator {
        synthesis: Synthesis { linkage, report },
        requirement: *need,
        y_range: [y0, y1],
        coefficients: k,
        precision_x,
    };
    // Freudenstein's equation holds the rocker's angle only mod 2π: a wanted f that the
    // rocker cannot follow continuously from x0 (a pole or a jump in the range, or a y far
    // outside [y0, y1]) is met at a precision point only a whole turn away. Followed by
    // continuity, such a point misses by at least a turn; a true one by rounding (a
    // least-squares point by the fit's residual, far below half a turn).
    let scale = (y1 - y0) / (q1 - q0);
    for p in made.structural_error_at(&f, &made.precision_x)? {
        let turns = p.error / scale / (2.0 * PI);
        if turns.abs() > 0.5 {
            return Err(Error::NoMechanism {
                method: METHOD,
                problem: format!(
                    "the four-bar meets the point x = {} only {:.0} rocker turn(s) away: f is \
                     not generated continuously from x0 (a pole or a jump in the range, or f \
                     far outside [f(x0), f(x1)])",
                    p.x,
                    turns.round()
                ),
            });
        }
    }
    Ok(made)
}
