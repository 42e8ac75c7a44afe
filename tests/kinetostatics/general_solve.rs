//! The independent check: each group's full Newton–Euler system, every Cartesian reaction
//! component an unknown, assembled as a matrix and solved by LU. Moments are taken about a
//! pole of the test's choosing (not the closed forms' B or E) and divided by a length, so the
//! rows are of one scale.

use nalgebra::{Point2, SMatrix, SVector, Vector2};
use tmm::Load;

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The moment row of a force unknown (x, y) acting at `at`, about `pole`, divided by `len`.
fn moment_row(at: Point2<f64>, pole: Point2<f64>, len: f64) -> [f64; 2] {
    let r = at - pole;
    [-r.y / len, r.x / len]
}

fn solve6(m: SMatrix<f64, 6, 6>, rhs: SVector<f64, 6>) -> SVector<f64, 6> {
    m.lu().solve(&rhs).expect("general system is singular")
}

fn solve3(m: SMatrix<f64, 3, 3>, rhs: SVector<f64, 3>) -> SVector<f64, 3> {
    m.lu().solve(&rhs).expect("general system is singular")
}

fn pole_and_len(points: &[Point2<f64>]) -> (Point2<f64>, f64) {
    let n = points.len() as f64;
    let c = points.iter().fold(Vector2::zeros(), |s, p| s + p.coords) / n;
    let pole = Point2::from(c);
    let len = points
        .iter()
        .map(|p| (p - pole).norm())
        .fold(1e-3, f64::max);
    (pole, len)
}

/// RRR: unknowns [R12x, R12y, R43x, R43y, R23x, R23y].
pub fn rrr(
    a: Point2<f64>,
    b: Point2<f64>,
    c: Point2<f64>,
    l2: &Load,
    l3: &Load,
) -> [Vector2<f64>; 3] {
    let (p, len) = pole_and_len(&[a, b, c]);
    let mut m = SMatrix::<f64, 6, 6>::zeros();
    let mut f = SVector::<f64, 6>::zeros();
    // Link 2: R12 − R23 + F2 = 0, and its moments about p.
    m[(0, 0)] = 1.0;
    m[(0, 4)] = -1.0;
    m[(1, 1)] = 1.0;
    m[(1, 5)] = -1.0;
    let [ax, ay] = moment_row(a, p, len);
    let [bx, by] = moment_row(b, p, len);
    let [cx, cy] = moment_row(c, p, len);
    m[(2, 0)] = ax;
    m[(2, 1)] = ay;
    m[(2, 4)] = -bx;
    m[(2, 5)] = -by;
    f[0] = -l2.force.x;
    f[1] = -l2.force.y;
    f[2] = -l2.moment_about(p) / len;
    // Link 3: R43 + R23 + F3 = 0, and its moments about p.
    m[(3, 2)] = 1.0;
    m[(3, 4)] = 1.0;
    m[(4, 3)] = 1.0;
    m[(4, 5)] = 1.0;
    m[(5, 2)] = cx;
    m[(5, 3)] = cy;
    m[(5, 4)] = bx;
    m[(5, 5)] = by;
    f[3] = -l3.force.x;
    f[4] = -l3.force.y;
    f[5] = -l3.moment_about(p) / len;
    let x = solve6(m, f);
    [
        Vector2::new(x[0], x[1]),
        Vector2::new(x[2], x[3]),
        Vector2::new(x[4], x[5]),
    ]
}

/// RRP: unknowns [R12x, R12y, N, K, R23x, R23y] with R43 = N·ν (ν the guide normal) and K its
/// moment about B. Returns (R12, R43, R23, K).
pub fn rrp(
    a: Point2<f64>,
    b: Point2<f64>,
    guide: Vector2<f64>,
    l2: &Load,
    l3: &Load,
) -> ([Vector2<f64>; 3], f64) {
    let g = guide.normalize();
    let nu = Vector2::new(-g.y, g.x);
    let (p, len) = pole_and_len(&[a, b]);
    let mut m = SMatrix::<f64, 6, 6>::zeros();
    let mut f = SVector::<f64, 6>::zeros();
    let [ax, ay] = moment_row(a, p, len);
    let [bx, by] = moment_row(b, p, len);
    // Link 2.
    m[(0, 0)] = 1.0;
    m[(0, 4)] = -1.0;
    m[(1, 1)] = 1.0;
    m[(1, 5)] = -1.0;
    m[(2, 0)] = ax;
    m[(2, 1)] = ay;
    m[(2, 4)] = -bx;
    m[(2, 5)] = -by;
    f[0] = -l2.force.x;
    f[1] = -l2.force.y;
    f[2] = -l2.moment_about(p) / len;
    // Slider: N·ν + R23 + F3 = 0; moment: (B − p) × N·ν + K + (B − p) × R23 + M3(p) = 0.
    m[(3, 2)] = nu.x;
    m[(3, 4)] = 1.0;
    m[(4, 2)] = nu.y;
    m[(4, 5)] = 1.0;
    m[(5, 2)] = cross(b - p, nu) / len;
    m[(5, 3)] = 1.0 / len;
    m[(5, 4)] = bx;
    m[(5, 5)] = by;
    f[3] = -l3.force.x;
    f[4] = -l3.force.y;
    f[5] = -l3.moment_about(p) / len;
    let x = solve6(m, f);
    (
        [
            Vector2::new(x[0], x[1]),
            nu * x[2],
            Vector2::new(x[4], x[5]),
        ],
        x[3],
    )
}

/// RPR: unknowns [R12x, R12y, N, K, R43x, R43y] with R32 = N·u⊥ and K its moment about A.
/// Returns (R12, R32, R43, K).
pub fn rpr(
    a: Point2<f64>,
    e: Point2<f64>,
    axis: Vector2<f64>,
    l2: &Load,
    l3: &Load,
) -> ([Vector2<f64>; 3], f64) {
    let u = axis.normalize();
    let n = Vector2::new(-u.y, u.x);
    let (p, len) = pole_and_len(&[a, e]);
    let mut m = SMatrix::<f64, 6, 6>::zeros();
    let mut f = SVector::<f64, 6>::zeros();
    let [ax, ay] = moment_row(a, p, len);
    let [ex, ey] = moment_row(e, p, len);
    // Rod: R12 + N·n + F2 = 0; moment: (A − p) × R12 + (A − p) × N·n + K + M2(p) = 0.
    m[(0, 0)] = 1.0;
    m[(0, 2)] = n.x;
    m[(1, 1)] = 1.0;
    m[(1, 2)] = n.y;
    m[(2, 0)] = ax;
    m[(2, 1)] = ay;
    m[(2, 2)] = cross(a - p, n) / len;
    m[(2, 3)] = 1.0 / len;
    f[0] = -l2.force.x;
    f[1] = -l2.force.y;
    f[2] = -l2.moment_about(p) / len;
    // Cylinder: R43 − N·n + F3 = 0; moment: (E − p) × R43 − (A − p) × N·n − K + M3(p) = 0.
    m[(3, 4)] = 1.0;
    m[(3, 2)] = -n.x;
    m[(4, 5)] = 1.0;
    m[(4, 2)] = -n.y;
    m[(5, 4)] = ex;
    m[(5, 5)] = ey;
    m[(5, 2)] = -cross(a - p, n) / len;
    m[(5, 3)] = -1.0 / len;
    f[3] = -l3.force.x;
    f[4] = -l3.force.y;
    f[5] = -l3.moment_about(p) / len;
    let x = solve6(m, f);
    (
        [Vector2::new(x[0], x[1]), n * x[2], Vector2::new(x[4], x[5])],
        x[3],
    )
}

/// PRP: unknowns [N12, K12, N43, K43, R23x, R23y] with R12 = N12·ν2 and R43 = N43·ν3 (ν the
/// guides' normals) and K12, K43 their couples when moved to B. Returns ([R12, R43, R23],
/// K12, K43).
pub fn prp(
    b: Point2<f64>,
    guide2: Vector2<f64>,
    guide3: Vector2<f64>,
    l2: &Load,
    l3: &Load,
) -> ([Vector2<f64>; 3], f64, f64) {
    let g2 = guide2.normalize();
    let g3 = guide3.normalize();
    let (n2, n3) = (Vector2::new(-g2.y, g2.x), Vector2::new(-g3.y, g3.x));
    let (p, len) = pole_and_len(&[b, l2.point, l3.point]);
    let mut m = SMatrix::<f64, 6, 6>::zeros();
    let mut f = SVector::<f64, 6>::zeros();
    let [bx, by] = moment_row(b, p, len);
    // Slider 2: N12·ν2 − R23 + F2 = 0; moment: (B − p) × N12·ν2 + K12 − (B − p) × R23 + M2(p) = 0.
    m[(0, 0)] = n2.x;
    m[(0, 4)] = -1.0;
    m[(1, 0)] = n2.y;
    m[(1, 5)] = -1.0;
    m[(2, 0)] = cross(b - p, n2) / len;
    m[(2, 1)] = 1.0 / len;
    m[(2, 4)] = -bx;
    m[(2, 5)] = -by;
    f[0] = -l2.force.x;
    f[1] = -l2.force.y;
    f[2] = -l2.moment_about(p) / len;
    // Slider 3: N43·ν3 + R23 + F3 = 0; moment: (B − p) × N43·ν3 + K43 + (B − p) × R23 + M3(p) = 0.
    m[(3, 2)] = n3.x;
    m[(3, 4)] = 1.0;
    m[(4, 2)] = n3.y;
    m[(4, 5)] = 1.0;
    m[(5, 2)] = cross(b - p, n3) / len;
    m[(5, 3)] = 1.0 / len;
    m[(5, 4)] = bx;
    m[(5, 5)] = by;
    f[3] = -l3.force.x;
    f[4] = -l3.force.y;
    f[5] = -l3.moment_about(p) / len;
    let x = solve6(m, f);
    ([n2 * x[0], n3 * x[2], Vector2::new(x[4], x[5])], x[1], x[3])
}

/// RPP: unknowns [R12x, R12y, N32, K32, N43, K43] with R32 = N32·ν_slot (K32 its couple when
/// moved to A) and R43 = N43·ν_guide (K43 its couple when moved to B). Returns
/// ([R12, R32, R43], K32, K43).
pub fn rpp(
    a: Point2<f64>,
    b: Point2<f64>,
    guide: Vector2<f64>,
    slot: Vector2<f64>,
    l2: &Load,
    l3: &Load,
) -> ([Vector2<f64>; 3], f64, f64) {
    let u = guide.normalize();
    let v = slot.normalize();
    let (nu, nv) = (Vector2::new(-u.y, u.x), Vector2::new(-v.y, v.x));
    let (p, len) = pole_and_len(&[a, b, l2.point, l3.point]);
    let mut m = SMatrix::<f64, 6, 6>::zeros();
    let mut f = SVector::<f64, 6>::zeros();
    let [ax, ay] = moment_row(a, p, len);
    // Link 2: R12 + N32·ν_slot + F2 = 0; moment: (A − p) × R12 + (A − p) × N32·ν_slot + K32
    // + M2(p) = 0.
    m[(0, 0)] = 1.0;
    m[(0, 2)] = nv.x;
    m[(1, 1)] = 1.0;
    m[(1, 2)] = nv.y;
    m[(2, 0)] = ax;
    m[(2, 1)] = ay;
    m[(2, 2)] = cross(a - p, nv) / len;
    m[(2, 3)] = 1.0 / len;
    f[0] = -l2.force.x;
    f[1] = -l2.force.y;
    f[2] = -l2.moment_about(p) / len;
    // Link 3: N43·ν_guide − N32·ν_slot + F3 = 0; moment: (B − p) × N43·ν_guide + K43
    // − (A − p) × N32·ν_slot − K32 + M3(p) = 0.
    m[(3, 4)] = nu.x;
    m[(3, 2)] = -nv.x;
    m[(4, 4)] = nu.y;
    m[(4, 2)] = -nv.y;
    m[(5, 4)] = cross(b - p, nu) / len;
    m[(5, 5)] = 1.0 / len;
    m[(5, 2)] = -cross(a - p, nv) / len;
    m[(5, 3)] = -1.0 / len;
    f[3] = -l3.force.x;
    f[4] = -l3.force.y;
    f[5] = -l3.moment_about(p) / len;
    let x = solve6(m, f);
    ([Vector2::new(x[0], x[1]), nv * x[2], nu * x[4]], x[3], x[5])
}

/// An input link with a balancing moment: unknowns [R01x, R01y, M_b].
pub fn coupling(o1: Point2<f64>, loads: &[Load]) -> (Vector2<f64>, f64) {
    let pts: Vec<_> = std::iter::once(o1)
        .chain(loads.iter().map(|l| l.point))
        .collect();
    let (p, len) = pole_and_len(&pts);
    let total_f = loads.iter().fold(Vector2::zeros(), |s, l| s + l.force);
    let total_m: f64 = loads.iter().map(|l| l.moment_about(p)).sum();
    let [ox, oy] = moment_row(o1, p, len);
    let m = SMatrix::<f64, 3, 3>::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, ox, oy, 1.0 / len);
    let f = SVector::<f64, 3>::new(-total_f.x, -total_f.y, -total_m / len);
    let x = solve3(m, f);
    (Vector2::new(x[0], x[1]), x[2])
}

/// An input link with a tooth force of unknown magnitude F along `direction` at the pitch
/// point: unknowns [R01x, R01y, F].
pub fn gear(
    o1: Point2<f64>,
    pitch: Point2<f64>,
    direction: Vector2<f64>,
    loads: &[Load],
) -> (Vector2<f64>, f64) {
    let pts: Vec<_> = [o1, pitch]
        .into_iter()
        .chain(loads.iter().map(|l| l.point))
        .collect();
    let (p, len) = pole_and_len(&pts);
    let total_f = loads.iter().fold(Vector2::zeros(), |s, l| s + l.force);
    let total_m: f64 = loads.iter().map(|l| l.moment_about(p)).sum();
    let [ox, oy] = moment_row(o1, p, len);
    let m = SMatrix::<f64, 3, 3>::new(
        1.0,
        0.0,
        direction.x,
        0.0,
        1.0,
        direction.y,
        ox,
        oy,
        cross(pitch - p, direction) / len,
    );
    let f = SVector::<f64, 3>::new(-total_f.x, -total_f.y, -total_m / len);
    let x = solve3(m, f);
    (Vector2::new(x[0], x[1]), x[2])
}
