//! The bench four-bar of `four_bar.rs` as batch dimensions (with a coupler point), and its
//! positions solved one at a time by the scalar blocks: the set-up that the batch and the
//! synthesis benches share.

use super::hand_four_bar::{C, L1, L2, L3};
use std::hint::black_box;
use tmm::kinematics::batch::{coupler_point, FourBarDims};
use tmm::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};

/// The bench four-bar (crank at the origin, rocker's pivot at `C`), coupler point (0.2, 0.1).
pub fn bench_dims() -> FourBarDims {
    FourBarDims {
        o: nalgebra::Point2::origin(),
        c: C,
        l_oa: L1,
        l_ab: L2,
        l_cb: L3,
        branch: Branch::Plus,
        coupler: nalgebra::Vector2::new(0.2, 0.1),
    }
}

/// The scalar blocks, one position at a time: B and the coupler point.
pub fn scalar(d: &FourBarDims, angles: &[f64]) -> f64 {
    let uv = d.coupler_uv();
    let mut acc = 0.0;
    for &phi in angles {
        let a = crank(d.o, d.l_oa, Motion::fixed(black_box(phi))).unwrap().a;
        let r = rrr_dyad(a, PointMotion::fixed(d.c), d.l_ab, d.l_cb, d.branch).unwrap();
        acc += coupler_point(a.p, r.b.p, uv).y;
    }
    acc
}
