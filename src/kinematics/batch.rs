//! Four-bar kinematics over a batch: many crank positions of one four-bar, or many four-bars
//! at one crank position (the synthesis case), written into columns.
//!
//! The data are laid out as a structure of arrays: the inputs are columns (crank angles with
//! their cosines and sines, or one column per dimension of the candidates), the outputs are
//! columns the caller provides ([`PositionsMut`], [`RatesMut`]), so a call allocates nothing
//! and the lane loop has no branch and no `Result`: the compiler vectorises it (stable Rust,
//! no `unsafe`, no SIMD crate).
//!
//! # Exactly the scalar blocks
//! A lane computes, operation for operation, what [`crank`] followed by [`rrr_dyad`] computes
//! on their fast paths (the same additions, products, quotients and square roots in the same
//! order; Rust never contracts them into fused multiply-adds), and accepts a lane by the same
//! test. The one libm call of the chain, the crank's `sin_cos`, is made once per angle when
//! the [`CrankAngles`] are built, by the same function. So every value a lane writes equals
//! the scalar blocks' bit for bit. A lane that the fast test rejects (it cannot be assembled,
//! it is at or near a dead point, an input is bad) is handed to the scalar blocks themselves
//! after the loop: their result, value or error, is what the lane reports. Nothing aborts the
//! batch; each lane has a [`Lane`] status and a `measure`:
//!
//! | status                   | `measure`                                             |
//! |--------------------------|-------------------------------------------------------|
//! | [`Lane::Ok`]             | det = sin(φ3 − φ2), the dyad's conditioning            |
//! | [`Lane::NotAssemblable`] | the gap by which the loop fails to close, m            |
//! | [`Lane::Singular`]       | the vanished determinant sin(φ3 − φ2)                  |
//! | [`Lane::Invalid`]        | NaN (a non-finite or non-positive input, an overflow) |
//!
//! A failed lane's positions and rates are NaN: the status says why.
//!
//! The coupler point P is given in the coupler's frame scaled by its length: with
//! e = B − A, P = A + (u·e.x − v·e.y, u·e.y + v·e.x) ([`coupler_point`]), so (u, v) = (1, 0)
//! is B and a point `along` metres along A→B and `across` metres to its left has
//! (u, v) = (along, across)/l_AB ([`FourBarDims::coupler_uv`]). Its velocity and acceleration
//! are [`LinkMotion::motion_of`](super::LinkMotion::motion_of) of the coupler.
//!
//! The link angles φ2 and φ3 are not written (each is an `atan2`); they are the directions of
//! B − A and B − C.
//!
//! # Examples
//! A crank-rocker over a full turn of 360 positions, checked against the scalar blocks:
//! ```
//! use nalgebra::{Point2, Vector2};
//! use tmm::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
//! use tmm::kinematics::batch::{four_bar_positions, CrankAngles, FourBarDims, Lane, Positions};
//! let dims = FourBarDims {
//!     o: Point2::origin(),
//!     c: Point2::new(0.4, 0.05),
//!     l_oa: 0.1,
//!     l_ab: 0.35,
//!     l_cb: 0.3,
//!     branch: Branch::Plus,
//!     coupler: Vector2::new(0.2, 0.1),
//! };
//! let angles = CrankAngles::turn(360);
//! let mut out = Positions::new(angles.len());
//! let ok = four_bar_positions(&dims, &angles, out.columns_mut())?;
//! assert_eq!(ok, 360);
//! let a = crank(dims.o, dims.l_oa, Motion::fixed(angles.phi()[7]))?.a;
//! let d = rrr_dyad(a, PointMotion::fixed(dims.c), dims.l_ab, dims.l_cb, Branch::Plus)?;
//! assert_eq!(out.b_x[7], d.b.p.x); // bit for bit
//! assert_eq!(out.status[7], Lane::Ok);
//! # Ok::<(), tmm::Error>(())
//! ```

// The lane loops index a dozen columns by one index (each re-sliced to the batch's length,
// so that the bounds checks fold away and the loop vectorises): clearer than a zip of twelve.
#![allow(clippy::needless_range_loop)]

use super::contour::Branch;
use super::crank::crank;
use super::motion::{Motion, PointMotion};
use super::rrr::rrr_dyad;
use crate::error::{Error, Result};
use nalgebra::{Point2, Vector2};

/// What became of one lane of a batch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[repr(u8)]
pub enum Lane {
    /// Solved; `measure` is det = sin(φ3 − φ2).
    #[default]
    Ok = 0,
    /// The dyad cannot be assembled; `measure` is the gap, m.
    NotAssemblable = 1,
    /// A dead point (links 2 and 3 collinear); `measure` is sin(φ3 − φ2).
    Singular = 2,
    /// A bad input (non-finite, a length not positive) or an overflow; `measure` is NaN.
    Invalid = 3,
    /// Not decided by the vectorised pass: the scalar blocks decide it (never left in an
    /// output once a batch call has returned).
    #[doc(hidden)]
    Pending = 4,
}

impl Lane {
    /// The status and measure of a scalar error.
    fn of_error(e: &Error) -> (Self, f64) {
        match *e {
            Error::NotAssemblable { gap, .. } => (Self::NotAssemblable, gap),
            Error::Singular { value, .. } => (Self::Singular, value),
            _ => (Self::Invalid, f64::NAN),
        }
    }
}

/// One four-bar O A B C: the crank O A (input), the coupler A B with a coupler point P, the
/// rocker C B, both pivots O and C fixed.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FourBarDims {
    /// The crank's pivot O, m.
    pub o: Point2<f64>,
    /// The rocker's pivot C, m.
    pub c: Point2<f64>,
    /// Crank O A, m.
    pub l_oa: f64,
    /// Coupler A B, m.
    pub l_ab: f64,
    /// Rocker C B, m.
    pub l_cb: f64,
    /// The assembly mode of the dyad, as in [`rrr_dyad`].
    pub branch: Branch,
    /// The coupler point P in the coupler's frame: `along` A→B and `across` to its left, m.
    pub coupler: Vector2<f64>,
}

impl FourBarDims {
    /// The coupler point's (u, v) = (along, across)/l_AB (see the module docs).
    #[must_use]
    pub fn coupler_uv(&self) -> [f64; 2] {
        [self.coupler.x / self.l_ab, self.coupler.y / self.l_ab]
    }
}

/// The coupler point P = A + (u·e.x − v·e.y, u·e.y + v·e.x) with e = B − A: the formula
/// every lane uses, so that the scalar blocks' A and B give the batch's P bit for bit.
#[must_use]
#[inline(always)]
pub fn coupler_point(a: Point2<f64>, b: Point2<f64>, uv: [f64; 2]) -> Point2<f64> {
    let (ex, ey) = (b.x - a.x, b.y - a.y);
    Point2::new(
        a.x + (uv[0] * ex - uv[1] * ey),
        a.y + (uv[0] * ey + uv[1] * ex),
    )
}

/// Crank angles with their cosines and sines, computed once by the `sin_cos` the scalar
/// [`crank`] calls (the only transcendental function of a four-bar's positions).
///
/// Build it once and reuse it for every candidate of a search; [`CrankAngles::set`] refills
/// it without allocating when the capacity suffices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CrankAngles {
    phi: Vec<f64>,
    cos: Vec<f64>,
    sin: Vec<f64>,
}

impl CrankAngles {
    /// The angles `phi` (rad).
    #[must_use]
    pub fn new(phi: &[f64]) -> Self {
        let mut s = Self::default();
        s.set(phi);
        s
    }

    /// `n` angles over a full turn from 0, 2π·k/n.
    #[must_use]
    pub fn turn(n: usize) -> Self {
        let phi: Vec<f64> = (0..n)
            .map(|k| std::f64::consts::TAU * k as f64 / n as f64)
            .collect();
        Self::new(&phi)
    }

    /// Replaces the angles by `phi`.
    pub fn set(&mut self, phi: &[f64]) {
        self.phi.clear();
        self.cos.clear();
        self.sin.clear();
        self.phi.extend_from_slice(phi);
        for &p in phi {
            let (s, c) = p.sin_cos();
            self.sin.push(s);
            self.cos.push(c);
        }
    }

    /// The angles, rad.
    #[must_use]
    pub fn phi(&self) -> &[f64] {
        &self.phi
    }

    /// Their cosines.
    #[must_use]
    pub fn cos(&self) -> &[f64] {
        &self.cos
    }

    /// Their sines.
    #[must_use]
    pub fn sin(&self) -> &[f64] {
        &self.sin
    }

    /// The number of angles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.phi.len()
    }

    /// No angles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.phi.is_empty()
    }
}

/// Many four-bars as columns (one per dimension), for evaluating candidates side by side.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FourBarColumns {
    /// O.x, m.
    pub o_x: Vec<f64>,
    /// O.y, m.
    pub o_y: Vec<f64>,
    /// C.x, m.
    pub c_x: Vec<f64>,
    /// C.y, m.
    pub c_y: Vec<f64>,
    /// Crank O A, m.
    pub l_oa: Vec<f64>,
    /// Coupler A B, m.
    pub l_ab: Vec<f64>,
    /// Rocker C B, m.
    pub l_cb: Vec<f64>,
    /// The branch's sign, +1 ([`Branch::Plus`]) or −1 ([`Branch::Minus`]).
    pub sign: Vec<f64>,
    /// The coupler point's u (see the module docs).
    pub u: Vec<f64>,
    /// The coupler point's v.
    pub v: Vec<f64>,
}

impl FourBarColumns {
    /// Appends one four-bar.
    pub fn push(&mut self, d: &FourBarDims) {
        let [u, v] = d.coupler_uv();
        self.o_x.push(d.o.x);
        self.o_y.push(d.o.y);
        self.c_x.push(d.c.x);
        self.c_y.push(d.c.y);
        self.l_oa.push(d.l_oa);
        self.l_ab.push(d.l_ab);
        self.l_cb.push(d.l_cb);
        self.sign.push(d.branch.sign());
        self.u.push(u);
        self.v.push(v);
    }

    /// Removes every four-bar, keeping the capacity.
    pub fn clear(&mut self) {
        for c in self.columns_mut() {
            c.clear();
        }
    }

    fn columns_mut(&mut self) -> [&mut Vec<f64>; 10] {
        [
            &mut self.o_x,
            &mut self.o_y,
            &mut self.c_x,
            &mut self.c_y,
            &mut self.l_oa,
            &mut self.l_ab,
            &mut self.l_cb,
            &mut self.sign,
            &mut self.u,
            &mut self.v,
        ]
    }

    /// The number of four-bars (the length of the shortest column).
    #[must_use]
    pub fn len(&self) -> usize {
        [
            &self.o_x, &self.o_y, &self.c_x, &self.c_y, &self.l_oa, &self.l_ab, &self.l_cb,
            &self.sign, &self.u, &self.v,
        ]
        .iter()
        .map(|c| c.len())
        .min()
        .unwrap_or(0)
    }

    /// No four-bars.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn lane(&self, i: usize) -> Dims {
        Dims {
            ox: self.o_x[i],
            oy: self.o_y[i],
            cx: self.c_x[i],
            cy: self.c_y[i],
            l1: self.l_oa[i],
            l2: self.l_ab[i],
            l3: self.l_cb[i],
            sign: self.sign[i],
            u: self.u[i],
            v: self.v[i],
        }
    }
}

/// The output columns of positions, borrowed from the caller (all of one length, the batch's).
#[derive(Debug)]
pub struct PositionsMut<'a> {
    /// B.x, m.
    pub b_x: &'a mut [f64],
    /// B.y, m.
    pub b_y: &'a mut [f64],
    /// P.x (the coupler point), m.
    pub p_x: &'a mut [f64],
    /// P.y, m.
    pub p_y: &'a mut [f64],
    /// Each lane's measure (see the module docs).
    pub measure: &'a mut [f64],
    /// Each lane's status.
    pub status: &'a mut [Lane],
}

impl<'a> PositionsMut<'a> {
    fn len(&self) -> Result<usize> {
        let n = self.b_x.len();
        for (name, len) in [
            ("b_y", self.b_y.len()),
            ("p_x", self.p_x.len()),
            ("p_y", self.p_y.len()),
            ("measure", self.measure.len()),
            ("status", self.status.len()),
        ] {
            check_len(name, len, n)?;
        }
        Ok(n)
    }

    /// The five number columns (B.x, B.y, P.x, P.y, measure) and the status, each a slice
    /// of its own: the form every lane loop writes through ([`put`]).
    #[inline(always)]
    fn columns(&mut self) -> ([&mut [f64]; 5], &mut [Lane]) {
        let Self {
            b_x,
            b_y,
            p_x,
            p_y,
            measure,
            status,
        } = self;
        ([b_x, b_y, p_x, p_y, measure], status)
    }

    /// Splits the columns at `mid` (the first part has lanes `0..mid`, the second the rest),
    /// as [`slice::split_at_mut`] does each column; `mid` equal to the length gives an empty
    /// second part.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] naming the column whose length differs from `b_x`'s, or `"mid"`
    /// (admissible `[0, len]`) for a `mid` beyond the columns' length: the columns come back
    /// unsplit only through the error's absence, never by a panic.
    ///
    /// # Examples
    /// ```
    /// use tmm::kinematics::batch::Positions;
    /// let mut cols = Positions::new(10);
    /// let (lo, hi) = cols.columns_mut().split_at(4)?;
    /// assert_eq!((lo.b_x.len(), hi.status.len()), (4, 6));
    /// assert!(cols.columns_mut().split_at(11).is_err());
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn split_at(self, mid: usize) -> Result<(PositionsMut<'a>, PositionsMut<'a>)> {
        let n = self.len()?;
        if mid > n {
            return Err(Error::OutOfRange {
                name: "mid",
                value: mid as f64,
                min: 0.0,
                max: n as f64,
                ends: crate::Ends::Closed,
            });
        }
        Ok(self.split(mid))
    }

    /// [`split_at`](Self::split_at) at a `mid` known to be within every column.
    fn split(self, mid: usize) -> (PositionsMut<'a>, PositionsMut<'a>) {
        let (b_x, b_x2) = self.b_x.split_at_mut(mid);
        let (b_y, b_y2) = self.b_y.split_at_mut(mid);
        let (p_x, p_x2) = self.p_x.split_at_mut(mid);
        let (p_y, p_y2) = self.p_y.split_at_mut(mid);
        let (measure, measure2) = self.measure.split_at_mut(mid);
        let (status, status2) = self.status.split_at_mut(mid);
        (
            PositionsMut {
                b_x,
                b_y,
                p_x,
                p_y,
                measure,
                status,
            },
            PositionsMut {
                b_x: b_x2,
                b_y: b_y2,
                p_x: p_x2,
                p_y: p_y2,
                measure: measure2,
                status: status2,
            },
        )
    }
}

/// The output columns of velocities and accelerations (all of the batch's length).
#[derive(Debug)]
pub struct RatesMut<'a> {
    /// v_B (x, y), m/s.
    pub v_b: [&'a mut [f64]; 2],
    /// a_B (x, y), m/s².
    pub a_b: [&'a mut [f64]; 2],
    /// v_P (x, y), m/s.
    pub v_p: [&'a mut [f64]; 2],
    /// a_P (x, y), m/s².
    pub a_p: [&'a mut [f64]; 2],
    /// ω2, ω3 (coupler, rocker), rad/s.
    pub omega: [&'a mut [f64]; 2],
    /// ε2, ε3, rad/s².
    pub epsilon: [&'a mut [f64]; 2],
}

impl RatesMut<'_> {
    /// The twelve columns, each a slice of its own, in [`put_rates`]' order.
    #[inline(always)]
    fn columns(&mut self) -> [&mut [f64]; 12] {
        let Self {
            v_b: [v_bx, v_by],
            a_b: [a_bx, a_by],
            v_p: [v_px, v_py],
            a_p: [a_px, a_py],
            omega: [w2, w3],
            epsilon: [e2, e3],
        } = self;
        [
            v_bx, v_by, a_bx, a_by, v_px, v_py, a_px, a_py, w2, w3, e2, e3,
        ]
    }

    fn check(&self, n: usize) -> Result<()> {
        let names = ["v_b", "a_b", "v_p", "a_p", "omega", "epsilon"];
        let cols = [
            &self.v_b,
            &self.a_b,
            &self.v_p,
            &self.a_p,
            &self.omega,
            &self.epsilon,
        ];
        for (name, c) in names.iter().zip(cols) {
            check_len(name, c[0].len(), n)?;
            check_len(name, c[1].len(), n)?;
        }
        Ok(())
    }
}

/// Owned output columns of positions, for callers that keep them between batches.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Positions {
    /// B.x, m.
    pub b_x: Vec<f64>,
    /// B.y, m.
    pub b_y: Vec<f64>,
    /// P.x, m.
    pub p_x: Vec<f64>,
    /// P.y, m.
    pub p_y: Vec<f64>,
    /// Each lane's measure.
    pub measure: Vec<f64>,
    /// Each lane's status.
    pub status: Vec<Lane>,
}

impl Positions {
    /// Columns for `n` lanes.
    #[must_use]
    pub fn new(n: usize) -> Self {
        let mut s = Self::default();
        s.resize(n);
        s
    }

    /// Resizes every column to `n` lanes (allocating only when the capacity is short).
    pub fn resize(&mut self, n: usize) {
        for c in [
            &mut self.b_x,
            &mut self.b_y,
            &mut self.p_x,
            &mut self.p_y,
            &mut self.measure,
        ] {
            c.resize(n, 0.0);
        }
        self.status.resize(n, Lane::Ok);
    }

    /// The columns as a [`PositionsMut`].
    pub fn columns_mut(&mut self) -> PositionsMut<'_> {
        PositionsMut {
            b_x: &mut self.b_x,
            b_y: &mut self.b_y,
            p_x: &mut self.p_x,
            p_y: &mut self.p_y,
            measure: &mut self.measure,
            status: &mut self.status,
        }
    }
}

/// Owned output columns of velocities and accelerations.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rates {
    /// v_B (x, y), m/s.
    pub v_b: [Vec<f64>; 2],
    /// a_B (x, y), m/s².
    pub a_b: [Vec<f64>; 2],
    /// v_P (x, y), m/s.
    pub v_p: [Vec<f64>; 2],
    /// a_P (x, y), m/s².
    pub a_p: [Vec<f64>; 2],
    /// ω2, ω3, rad/s.
    pub omega: [Vec<f64>; 2],
    /// ε2, ε3, rad/s².
    pub epsilon: [Vec<f64>; 2],
}

impl Rates {
    /// Columns for `n` lanes.
    #[must_use]
    pub fn new(n: usize) -> Self {
        let c = || [vec![0.0; n], vec![0.0; n]];
        Self {
            v_b: c(),
            a_b: c(),
            v_p: c(),
            a_p: c(),
            omega: c(),
            epsilon: c(),
        }
    }

    /// The columns as a [`RatesMut`].
    pub fn columns_mut(&mut self) -> RatesMut<'_> {
        fn two(c: &mut [Vec<f64>; 2]) -> [&mut [f64]; 2] {
            let [x, y] = c;
            [x.as_mut_slice(), y.as_mut_slice()]
        }
        RatesMut {
            v_b: two(&mut self.v_b),
            a_b: two(&mut self.a_b),
            v_p: two(&mut self.v_p),
            a_p: two(&mut self.a_p),
            omega: two(&mut self.omega),
            epsilon: two(&mut self.epsilon),
        }
    }
}

fn check_len(name: &'static str, len: usize, n: usize) -> Result<()> {
    if len == n {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            name,
            value: len as f64,
            min: n as f64,
            max: n as f64,
            ends: crate::Ends::Closed,
        })
    }
}

/// One lane's dimensions (u, v: the coupler point).
#[derive(Clone, Copy)]
struct Dims {
    ox: f64,
    oy: f64,
    cx: f64,
    cy: f64,
    l1: f64,
    l2: f64,
    l3: f64,
    sign: f64,
    u: f64,
    v: f64,
}

impl Dims {
    fn of(d: &FourBarDims) -> Self {
        let [u, v] = d.coupler_uv();
        Self {
            ox: d.o.x,
            oy: d.o.y,
            cx: d.c.x,
            cy: d.c.y,
            l1: d.l_oa,
            l2: d.l_ab,
            l3: d.l_cb,
            sign: d.branch.sign(),
            u,
            v,
        }
    }

    fn branch(&self) -> Branch {
        if self.sign > 0.0 {
            Branch::Plus
        } else {
            Branch::Minus
        }
    }
}

/// One lane's results.
#[derive(Clone, Copy)]
struct Out {
    bx: f64,
    by: f64,
    px: f64,
    py: f64,
    det: f64,
    ok: bool,
    // Rates (zero unless computed).
    vb: [f64; 2],
    ab: [f64; 2],
    vp: [f64; 2],
    ap: [f64; 2],
    w: [f64; 2],
    e: [f64; 2],
}

/// The sum test of `rrr::all_finite`, term by term in the same order (four partial sums).
#[derive(Clone, Copy)]
struct Sum {
    acc: [f64; 4],
    i: usize,
}

impl Sum {
    #[inline(always)]
    fn new() -> Self {
        Self {
            acc: [0.0; 4],
            i: 0,
        }
    }
    #[inline(always)]
    fn add(&mut self, v: f64) {
        self.acc[self.i % 4] += v;
        self.i += 1;
    }
    /// Skips a term that is +0 (it cannot change whether the sum is finite).
    #[inline(always)]
    fn skip(&mut self) {
        self.i += 1;
    }
    #[inline(always)]
    fn finite(&self) -> bool {
        ((self.acc[0] + self.acc[1]) + (self.acc[2] + self.acc[3])).is_finite()
    }
}

/// The lane kernel: `crank` and `rrr_dyad`'s fast paths, operation for operation, with the
/// crank moving at (ω1, ε1) = `rate` when `RATES` (else at rest, and the rates are skipped:
/// they are zero then, and a zero term changes neither a sum nor the acceptance test).
#[inline(always)]
#[allow(clippy::similar_names, clippy::many_single_char_names)]
fn lane<const RATES: bool>(d: Dims, phi: f64, cos: f64, sin: f64, rate: [f64; 2]) -> Out {
    let [w1, e1] = if RATES { rate } else { [0.0, 0.0] };
    // crank: r = (cos, sin)·l; A = O + r; v_A = ω1·perp(r); a_A = ε1·perp(r) − ω1·ω1·r.
    let (rx, ry) = (cos * d.l1, sin * d.l1);
    let (ax, ay) = (d.ox + rx, d.oy + ry);
    let (vax, vay) = (w1 * -ry, w1 * rx);
    let w1w1 = w1 * w1;
    let (aax, aay) = (e1 * -ry - w1w1 * rx, e1 * rx - w1w1 * ry);
    let mut crank_sum = Sum::new();
    for t in [d.ox, d.oy, d.l1, phi] {
        crank_sum.add(t);
    }
    if RATES {
        for t in [w1, e1] {
            crank_sum.add(t);
        }
    } else {
        crank_sum.skip();
        crank_sum.skip();
    }
    crank_sum.add(ax);
    crank_sum.add(ay);
    if RATES {
        for t in [vax, vay, aax, aay] {
            crank_sum.add(t);
        }
    }
    let crank_ok = crank_sum.finite() & (d.l1 > 0.0);

    // rrr_dyad's fast path with C fixed (v_C = a_C = 0).
    let (dx, dy) = (d.cx - ax, d.cy - ay);
    let l_sq = dx * dx + dy * dy;
    let l = l_sq.sqrt();
    // h² and the link vectors from the shorter link's pivot, as in rrr_dyad.
    let short_c = d.l3 < d.l2;
    let q = (d.l2 - d.l3) * (d.l2 + d.l3) / l;
    let along = 0.5 * (q + if short_c { -l } else { l });
    let ls = if short_c { d.l3 } else { d.l2 };
    let h2 = (ls - along) * (ls + along);
    let tol = 16.0 * f64::EPSILON * (d.l2 * d.l2 + d.l3 * d.l3 + l_sq);
    let h = h2.sqrt();
    let (ex, ey) = (dx / l, dy / l);
    let sh = d.sign * h;
    let (vx, vy) = (along * ex + sh * -ey, along * ey + sh * ex);
    let (cx, cy) = if short_c { (dx, dy) } else { (0.0, 0.0) };
    let (ax_, ay_) = if short_c { (0.0, 0.0) } else { (dx, dy) };
    let (r2x, r2y) = (vx + cx, vy + cy);
    let (r3x, r3y) = (vx - ax_, vy - ay_);
    let big_d = r2x * r3y - r2y * r3x;
    let det = big_d / (d.l2 * d.l3);
    let (bx, by) = (ax + r2x, ay + r2y);
    let (pex, pey) = (bx - ax, by - ay);
    let (px, py) = (ax + (d.u * pex - d.v * pey), ay + (d.u * pey + d.v * pex));
    let mut s = Sum::new();
    s.add(ax);
    s.add(ay);
    let mut out = Out {
        bx,
        by,
        px,
        py,
        det,
        ok: false,
        vb: [0.0; 2],
        ab: [0.0; 2],
        vp: [0.0; 2],
        ap: [0.0; 2],
        w: [0.0; 2],
        e: [0.0; 2],
    };
    let rates_ok;
    if RATES {
        let i_d = 1.0 / big_d;
        let (dvx, dvy) = (0.0 - vax, 0.0 - vay);
        let (dax, day) = (0.0 - aax, 0.0 - aay);
        let omega2 = (dvx * r3x + dvy * r3y) * i_d;
        let omega3 = (dvx * r2x + dvy * r2y) * i_d;
        let (o22, o33) = (omega2 * omega2, omega3 * omega3);
        let rhsx = (dax + o22 * r2x) - o33 * r3x;
        let rhsy = (day + o22 * r2y) - o33 * r3y;
        let epsilon2 = (rhsx * r3x + rhsy * r3y) * i_d;
        let epsilon3 = (rhsx * r2x + rhsy * r2y) * i_d;
        let vb = [vax + omega2 * -r2y, vay + omega2 * r2x];
        let ab = [
            (aax + epsilon2 * -r2y) - o22 * r2x,
            (aay + epsilon2 * r2x) - o22 * r2y,
        ];
        // s: A.p, v_A, a_A, C.p, v_C, a_C, l_AB, l_CB, l², dv, da, h, ω2, ω3, ε2, ε3, B, det.
        for t in [vax, vay, aax, aay, d.cx, d.cy] {
            s.add(t);
        }
        for _ in 0..4 {
            s.skip();
        }
        for t in [d.l2, d.l3, l_sq, dvx, dvy, dax, day, h] {
            s.add(t);
        }
        for t in [omega2, omega3, epsilon2, epsilon3] {
            s.add(t);
        }
        for t in [bx, by, vb[0], vb[1], ab[0], ab[1], det] {
            s.add(t);
        }
        // The coupler point as LinkMotion::motion_of(P) on link 2 (origin A).
        let (qx, qy) = (px - ax, py - ay);
        out.vp = [vax + omega2 * -qy, vay + omega2 * qx];
        out.ap = [
            (aax + epsilon2 * -qy) - o22 * qx,
            (aay + epsilon2 * qx) - o22 * qy,
        ];
        out.vb = vb;
        out.ab = ab;
        out.w = [omega2, omega3];
        out.e = [epsilon2, epsilon3];
        rates_ok = out.vp[0].is_finite()
            & out.vp[1].is_finite()
            & out.ap[0].is_finite()
            & out.ap[1].is_finite();
    } else {
        // At rest the rates are 0·(1/D) and the like: zero when 1/D is finite, NaN when
        // D is so small that 1/D overflows. Rather than divide, send every lane with
        // |D| ≤ 1e-300 to the scalar blocks (1/D is finite above it).
        for _ in 0..4 {
            s.skip();
        }
        s.add(d.cx);
        s.add(d.cy);
        for _ in 0..4 {
            s.skip();
        }
        s.add(d.l2);
        s.add(d.l3);
        s.add(l_sq);
        for _ in 0..4 {
            s.skip();
        }
        s.add(h);
        for _ in 0..4 {
            s.skip();
        }
        s.add(bx);
        s.add(by);
        for _ in 0..4 {
            s.skip();
        }
        s.add(det);
        rates_ok = big_d.abs() > 1e-300;
    }
    out.ok = crank_ok
        & rates_ok
        & s.finite()
        & (d.l2 > 0.0)
        & (d.l3 > 0.0)
        & (l_sq >= f64::MIN_POSITIVE)
        & (h2 > 2.0 * tol)
        & (det.abs() > 2.0 * super::contour::SINGULAR_DETERMINANT)
        & px.is_finite()
        & py.is_finite();
    out
}

/// Writes one lane's result into the position columns B.x, B.y, P.x, P.y, measure and the
/// status (NaN and `Pending` where the fast test failed). Every lane loop writes through this
/// and [`put_rates`], given each column as a slice of its own: inlined into a loop whose
/// columns are separate `&mut` arguments, the compiler knows they do not overlap and
/// vectorises the loop (through a struct of columns it may not).
#[inline(always)]
fn put(o: &Out, i: usize, [b_x, b_y, p_x, p_y, measure]: [&mut [f64]; 5], status: &mut [Lane]) {
    let pick = |v: f64| if o.ok { v } else { f64::NAN };
    b_x[i] = pick(o.bx);
    b_y[i] = pick(o.by);
    p_x[i] = pick(o.px);
    p_y[i] = pick(o.py);
    measure[i] = pick(o.det);
    status[i] = if o.ok { Lane::Ok } else { Lane::Pending };
}

/// Writes one lane's rates into v_B, a_B, v_P, a_P (x, y each), ω2, ω3, ε2, ε3 (NaN where the
/// fast test failed); see [`put`].
#[inline(always)]
fn put_rates(
    o: &Out,
    i: usize,
    [v_bx, v_by, a_bx, a_by, v_px, v_py, a_px, a_py, w2, w3, e2, e3]: [&mut [f64]; 12],
) {
    let pick = |v: f64| if o.ok { v } else { f64::NAN };
    v_bx[i] = pick(o.vb[0]);
    v_by[i] = pick(o.vb[1]);
    a_bx[i] = pick(o.ab[0]);
    a_by[i] = pick(o.ab[1]);
    v_px[i] = pick(o.vp[0]);
    v_py[i] = pick(o.vp[1]);
    a_px[i] = pick(o.ap[0]);
    a_py[i] = pick(o.ap[1]);
    w2[i] = pick(o.w[0]);
    w3[i] = pick(o.w[1]);
    e2[i] = pick(o.e[0]);
    e3[i] = pick(o.e[1]);
}

/// [`put`] into borrowed position columns.
#[inline(always)]
fn store(o: &Out, i: usize, out: &mut PositionsMut<'_>) {
    let (columns, status) = out.columns();
    put(o, i, columns, status);
}

/// [`put_rates`] into borrowed rate columns.
#[inline(always)]
fn store_rates(o: &Out, i: usize, r: &mut RatesMut<'_>) {
    put_rates(o, i, r.columns());
}

/// The scalar blocks at one lane: what a `Pending` lane becomes.
fn scalar_lane(d: Dims, phi: f64, rate: [f64; 2]) -> (Lane, f64, Option<Out>) {
    let solved = crank(
        Point2::new(d.ox, d.oy),
        d.l1,
        Motion::new(phi, rate[0], rate[1]),
    )
    .and_then(|c| {
        rrr_dyad(
            c.a,
            PointMotion::fixed(Point2::new(d.cx, d.cy)),
            d.l2,
            d.l3,
            d.branch(),
        )
        .map(|r| (c.a, r))
    });
    match solved {
        Ok((a, r)) => {
            let p = coupler_point(a.p, r.b.p, [d.u, d.v]);
            let pm = r.link2.motion_of(p);
            let ok = [p.x, p.y, pm.v.x, pm.v.y, pm.a.x, pm.a.y]
                .iter()
                .all(|v| v.is_finite());
            if !ok {
                return (Lane::Invalid, f64::NAN, None);
            }
            let out = Out {
                bx: r.b.p.x,
                by: r.b.p.y,
                px: p.x,
                py: p.y,
                det: r.det,
                ok: true,
                vb: [r.b.v.x, r.b.v.y],
                ab: [r.b.a.x, r.b.a.y],
                vp: [pm.v.x, pm.v.y],
                ap: [pm.a.x, pm.a.y],
                w: [r.link2.omega, r.link3.omega],
                e: [r.link2.epsilon, r.link3.epsilon],
            };
            (Lane::Ok, r.det, Some(out))
        }
        Err(e) => {
            let (lane, m) = Lane::of_error(&e);
            (lane, m, None)
        }
    }
}

/// Settles the `Pending` lanes by the scalar blocks; returns the number of `Ok` lanes.
fn settle(
    out: &mut PositionsMut<'_>,
    mut rates: Option<&mut RatesMut<'_>>,
    lane_of: impl Fn(usize) -> (Dims, f64),
    rate: [f64; 2],
) -> usize {
    let mut ok = 0;
    for i in 0..out.status.len() {
        if out.status[i] != Lane::Pending {
            ok += 1;
            continue;
        }
        let (d, phi) = lane_of(i);
        let (lane, measure, o) = scalar_lane(d, phi, rate);
        out.status[i] = lane;
        out.measure[i] = measure;
        if let Some(o) = o {
            ok += 1;
            store(&o, i, out);
            if let Some(r) = rates.as_deref_mut() {
                store_rates(&o, i, r);
            }
        }
    }
    ok
}

/// The positions of one four-bar at every crank angle of `angles` (the crank at rest).
///
/// Lane i is the scalar `crank(o, l_oa, Motion::fixed(φ_i))` followed by
/// `rrr_dyad(A, PointMotion::fixed(c), l_ab, l_cb, branch)` and [`coupler_point`], bit for
/// bit (see the module docs); a lane that fails reports its [`Lane`] status and measure.
/// Returns the number of lanes solved.
///
/// # Errors
/// [`Error::OutOfRange`] naming an output column whose length is not `angles.len()`.
pub fn four_bar_positions(
    dims: &FourBarDims,
    angles: &CrankAngles,
    out: PositionsMut<'_>,
) -> Result<usize> {
    let n = angles.len();
    check_len("b_x", out.len()?, n)?;
    Ok(positions_of(Dims::of(dims), angles, 0, n, out))
}

/// The lanes `start..end` of `angles` into `out` (of `end − start` lanes, checked by the
/// caller), the failing ones settled; returns the number solved.
fn positions_of(
    d: Dims,
    angles: &CrankAngles,
    start: usize,
    end: usize,
    mut out: PositionsMut<'_>,
) -> usize {
    let phi = &angles.phi[start..end];
    {
        let (columns, status) = out.columns();
        position_lanes(
            d,
            [phi, &angles.cos[start..end], &angles.sin[start..end]],
            columns,
            status,
        );
    }
    settle(&mut out, None, |i| (d, phi[i]), [0.0; 2])
}

/// The lane loop of the positions (the crank at rest), in a function of its own with every
/// column a separate `&mut` argument, as [`motion_lanes`]: the serial batch and each chunk
/// of the parallel one run this same vectorised loop. Each column has `phi.len()` lanes.
#[inline(never)]
fn position_lanes(
    d: Dims,
    [phi, cos, sin]: [&[f64]; 3],
    [b_x, b_y, p_x, p_y, measure]: [&mut [f64]; 5],
    status: &mut [Lane],
) {
    let n = phi.len();
    let (cos, sin) = (&cos[..n], &sin[..n]);
    let (b_x, b_y, p_x, p_y) = (&mut b_x[..n], &mut b_y[..n], &mut p_x[..n], &mut p_y[..n]);
    let (measure, status) = (&mut measure[..n], &mut status[..n]);
    for i in 0..n {
        let o = lane::<false>(d, phi[i], cos[i], sin[i], [0.0; 2]);
        put(
            &o,
            i,
            [&mut *b_x, &mut *b_y, &mut *p_x, &mut *p_y, &mut *measure],
            status,
        );
    }
}

/// The positions, velocities and accelerations of one four-bar at every crank angle of
/// `angles`, the crank turning at ω1 = `omega1` with ε1 = `epsilon1` (the same at every
/// angle): lane i equals `crank(o, l_oa, Motion::new(φ_i, ω1, ε1))` and `rrr_dyad` bit for
/// bit, the coupler point's motion [`LinkMotion::motion_of`](super::LinkMotion::motion_of).
///
/// # Errors
/// [`Error::OutOfRange`] naming an output column whose length is not `angles.len()`.
pub fn four_bar_motions(
    dims: &FourBarDims,
    angles: &CrankAngles,
    omega1: f64,
    epsilon1: f64,
    mut out: PositionsMut<'_>,
    mut rates: RatesMut<'_>,
) -> Result<usize> {
    let n = angles.len();
    check_len("b_x", out.len()?, n)?;
    rates.check(n)?;
    let d = Dims::of(dims);
    let rate = [omega1, epsilon1];
    let (phi, cos, sin) = (&angles.phi[..n], &angles.cos[..n], &angles.sin[..n]);
    {
        let ([b_x, b_y, p_x, p_y, measure], status) = out.columns();
        motion_lanes(
            d,
            rate,
            [phi, cos, sin],
            b_x,
            b_y,
            p_x,
            p_y,
            measure,
            status,
            rates.columns(),
        );
    }
    Ok(settle(&mut out, Some(&mut rates), |i| (d, phi[i]), rate))
}

/// The lane loop of [`four_bar_motions`] in a function of its own, every output column a
/// separate `&mut` argument: the compiler then knows that no two columns overlap and
/// vectorises the loop with no run-time overlap checks (for eighteen columns reached through
/// a struct it made none and kept the loop scalar). Each column has `phi.len()` lanes.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn motion_lanes(
    d: Dims,
    rate: [f64; 2],
    [phi, cos, sin]: [&[f64]; 3],
    b_x: &mut [f64],
    b_y: &mut [f64],
    p_x: &mut [f64],
    p_y: &mut [f64],
    measure: &mut [f64],
    status: &mut [Lane],
    [v_bx, v_by, a_bx, a_by, v_px, v_py, a_px, a_py, w2, w3, e2, e3]: [&mut [f64]; 12],
) {
    let n = phi.len();
    let (cos, sin) = (&cos[..n], &sin[..n]);
    let (b_x, b_y, p_x, p_y) = (&mut b_x[..n], &mut b_y[..n], &mut p_x[..n], &mut p_y[..n]);
    let (measure, status) = (&mut measure[..n], &mut status[..n]);
    let (v_bx, v_by, a_bx, a_by) = (
        &mut v_bx[..n],
        &mut v_by[..n],
        &mut a_bx[..n],
        &mut a_by[..n],
    );
    let (v_px, v_py, a_px, a_py) = (
        &mut v_px[..n],
        &mut v_py[..n],
        &mut a_px[..n],
        &mut a_py[..n],
    );
    let (w2, w3, e2, e3) = (&mut w2[..n], &mut w3[..n], &mut e2[..n], &mut e3[..n]);
    for i in 0..n {
        let o = lane::<true>(d, phi[i], cos[i], sin[i], rate);
        put(
            &o,
            i,
            [&mut *b_x, &mut *b_y, &mut *p_x, &mut *p_y, &mut *measure],
            status,
        );
        put_rates(
            &o,
            i,
            [
                &mut *v_bx, &mut *v_by, &mut *a_bx, &mut *a_by, &mut *v_px, &mut *v_py, &mut *a_px,
                &mut *a_py, &mut *w2, &mut *w3, &mut *e2, &mut *e3,
            ],
        );
    }
}

/// The positions of many four-bars (`bars`, one lane each) at one crank angle `phi` (rad),
/// the crank at rest: the synthesis case, one topology for many sets of dimensions. Lane i
/// equals the scalar blocks on four-bar i bit for bit.
///
/// # Errors
/// [`Error::OutOfRange`] naming an output column whose length is not `bars.len()`.
pub fn four_bars_at(bars: &FourBarColumns, phi: f64, mut out: PositionsMut<'_>) -> Result<usize> {
    let n = bars.len();
    check_len("b_x", out.len()?, n)?;
    let (sin, cos) = phi.sin_cos();
    let c = [
        &bars.o_x[..n],
        &bars.o_y[..n],
        &bars.c_x[..n],
        &bars.c_y[..n],
        &bars.l_oa[..n],
        &bars.l_ab[..n],
        &bars.l_cb[..n],
        &bars.sign[..n],
        &bars.u[..n],
        &bars.v[..n],
    ];
    for i in 0..n {
        let d = Dims {
            ox: c[0][i],
            oy: c[1][i],
            cx: c[2][i],
            cy: c[3][i],
            l1: c[4][i],
            l2: c[5][i],
            l3: c[6][i],
            sign: c[7][i],
            u: c[8][i],
            v: c[9][i],
        };
        let o = lane::<false>(d, phi, cos, sin, [0.0; 2]);
        store(&o, i, &mut out);
    }
    Ok(settle(&mut out, None, |i| (bars.lane(i), phi), [0.0; 2]))
}

/// One number per candidate four-bar, each over every crank angle of `angles` (the crank at
/// rest): candidate k's positions are solved into columns as by [`four_bar_positions`], then
/// `score(k, &positions)` reduces them (a path error, a count of failed lanes, …). The
/// synthesis case: a population of candidates, each a batch of positions. One set of
/// columns is reused for every candidate (every lane writes all of them, so no candidate
/// sees another's).
///
/// # Examples
/// The number of the 360 positions at which each of two four-bars assembles: a crank-rocker
/// (all of them) and one whose coupler is too short to reach the rocker at some angles.
/// ```
/// use nalgebra::{Point2, Vector2};
/// use tmm::kinematics::Branch;
/// use tmm::kinematics::batch::{four_bar_scores, CrankAngles, FourBarDims, Lane};
/// let rocker = FourBarDims {
///     o: Point2::origin(),
///     c: Point2::new(0.4, 0.05),
///     l_oa: 0.1,
///     l_ab: 0.35,
///     l_cb: 0.3,
///     branch: Branch::Plus,
///     coupler: Vector2::new(0.2, 0.1),
/// };
/// let short = FourBarDims { l_ab: 0.2, l_cb: 0.12, ..rocker };
/// let ok = four_bar_scores(&[rocker, short], &CrankAngles::turn(360), |_, p| {
///     p.status.iter().filter(|&&s| s == Lane::Ok).count() as f64
/// });
/// assert_eq!(ok[0], 360.0);
/// assert!(ok[1] < 360.0);
/// ```
pub fn four_bar_scores(
    candidates: &[FourBarDims],
    angles: &CrankAngles,
    mut score: impl FnMut(usize, &Positions) -> f64,
) -> Vec<f64> {
    let mut out = Positions::new(angles.len());
    candidates
        .iter()
        .enumerate()
        .map(|(k, d)| score_one(k, d, angles, &mut out, &mut score))
        .collect()
}

/// [`four_bar_scores`] with the candidates evaluated in parallel (feature `rayon`), a set of
/// columns per worker: the same numbers, candidate for candidate. Each candidate is a
/// whole batch (some 6 µs for 360 angles), so the work splits with no contention.
#[cfg(feature = "rayon")]
pub fn par_four_bar_scores(
    candidates: &[FourBarDims],
    angles: &CrankAngles,
    score: impl Fn(usize, &Positions) -> f64 + Sync,
) -> Vec<f64> {
    use rayon::prelude::*;
    candidates
        .par_iter()
        .enumerate()
        .map_init(
            || Positions::new(angles.len()),
            |out, (k, d)| score_one(k, d, angles, out, |k, p| score(k, p)),
        )
        .collect()
}

/// Candidate `k`'s positions into `out` (already of `angles.len()` lanes), then its score.
fn score_one(
    k: usize,
    d: &FourBarDims,
    angles: &CrankAngles,
    out: &mut Positions,
    mut score: impl FnMut(usize, &Positions) -> f64,
) -> f64 {
    positions_of(Dims::of(d), angles, 0, angles.len(), out.columns_mut());
    score(k, out)
}

/// [`four_bar_positions`] with the angles split into chunks evaluated in parallel (feature
/// `rayon`); the same results, lane for lane.
///
/// # Errors
/// As [`four_bar_positions`].
#[cfg(feature = "rayon")]
pub fn par_four_bar_positions(
    dims: &FourBarDims,
    angles: &CrankAngles,
    out: PositionsMut<'_>,
) -> Result<usize> {
    let n = angles.len();
    check_len("b_x", out.len()?, n)?;
    let d = Dims::of(dims);
    Ok(par_range(d, angles, 0, n, out))
}

/// Splits `start..end` in halves down to chunks of [`CHUNK`] lanes, each run by
/// [`positions_of`] (the serial batch's own vectorised loop).
#[cfg(feature = "rayon")]
fn par_range(
    d: Dims,
    angles: &CrankAngles,
    start: usize,
    end: usize,
    out: PositionsMut<'_>,
) -> usize {
    let n = end - start;
    if n <= CHUNK {
        return positions_of(d, angles, start, end, out);
    }
    let mid = n / 2;
    // Within every column: the caller checked them all to be `n` long, and mid < n.
    let (lo, hi) = out.split(mid);
    let (a, b) = rayon::join(
        || par_range(d, angles, start, start + mid, lo),
        || par_range(d, angles, start + mid, end, hi),
    );
    a + b
}

/// The lanes of one chunk of a parallel batch: 4096 lanes are some 60 µs of work (the
/// split's cost is a few hundred nanoseconds) and 160 KiB of columns.
#[cfg(feature = "rayon")]
const CHUNK: usize = 4096;
