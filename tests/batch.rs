//! Batch evaluation (`tmm::kinematics::batch`) against the scalar blocks, bit for bit, with
//! failing lanes mixed in. (Path synthesis, the search built on it, is tested in
//! `tests/synthesis/path.rs`.)

use nalgebra::{Point2, Vector2};
use tmm::kinematics::batch::{
    coupler_point, four_bar_motions, four_bar_positions, four_bar_scores, four_bars_at,
    CrankAngles, FourBarColumns, FourBarDims, Lane, Positions, Rates,
};
use tmm::kinematics::{crank, rrr_dyad, Branch, Motion, PointMotion};
use tmm::Error;

/// splitmix64: a seeded, reproducible generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// A random four-bar, sometimes with a bad dimension (about one in twelve).
fn random_dims(rng: &mut Rng) -> FourBarDims {
    let mut d = FourBarDims {
        o: Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
        c: Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
        l_oa: rng.range(0.05, 1.0),
        l_ab: rng.range(0.05, 1.5),
        l_cb: rng.range(0.05, 1.5),
        branch: if rng.unit() < 0.5 {
            Branch::Plus
        } else {
            Branch::Minus
        },
        coupler: Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)),
    };
    let bad = [f64::NAN, f64::INFINITY, 0.0, -0.3, 1e308, 1e-310];
    if rng.unit() < 1.0 / 12.0 {
        let v = bad[(rng.next() % bad.len() as u64) as usize];
        match rng.next() % 5 {
            0 => d.l_oa = v,
            1 => d.l_ab = v,
            2 => d.l_cb = v,
            3 => d.o.x = v,
            _ => d.c.y = v,
        }
    }
    d
}

/// A crank angle at which `d` is at (or within rounding of) a dead or tangent position:
/// |AC| = l_AB + l_CB or |l_AB − l_CB|, by choosing l_CB from the angle.
fn at_dead_point(rng: &mut Rng, d: &mut FourBarDims) -> f64 {
    let phi = rng.range(0.0, std::f64::consts::TAU);
    let a = d.o + d.l_oa * Vector2::new(phi.cos(), phi.sin());
    let ac = (d.c - a).norm();
    let eps = [0.0, 1e-15, -1e-15, 1e-13, -1e-13, 1e-9][(rng.next() % 6) as usize];
    if rng.unit() < 0.5 && ac > d.l_ab {
        d.l_cb = ac - d.l_ab + eps;
    } else {
        d.l_cb = ac + d.l_ab + eps;
    }
    phi
}

/// The scalar blocks' answer for one lane: status, measure, and the written values
/// (B, P, then v_B, a_B, v_P, a_P, ω2, ω3, ε2, ε3).
fn scalar(d: &FourBarDims, phi: f64, w: f64, e: f64) -> (Lane, f64, Option<[f64; 16]>) {
    let r = crank(d.o, d.l_oa, Motion::new(phi, w, e)).and_then(|c| {
        rrr_dyad(c.a, PointMotion::fixed(d.c), d.l_ab, d.l_cb, d.branch).map(|r| (c.a, r))
    });
    match r {
        Ok((a, r)) => {
            let p = coupler_point(a.p, r.b.p, d.coupler_uv());
            let pm = r.link2.motion_of(p);
            let v = [
                r.b.p.x,
                r.b.p.y,
                p.x,
                p.y,
                r.b.v.x,
                r.b.v.y,
                r.b.a.x,
                r.b.a.y,
                pm.v.x,
                pm.v.y,
                pm.a.x,
                pm.a.y,
                r.link2.omega,
                r.link3.omega,
                r.link2.epsilon,
                r.link3.epsilon,
            ];
            if v[..12].iter().all(|x| x.is_finite()) {
                (Lane::Ok, r.det, Some(v))
            } else {
                (Lane::Invalid, f64::NAN, None)
            }
        }
        Err(Error::NotAssemblable { gap, .. }) => (Lane::NotAssemblable, gap, None),
        Err(Error::Singular { value, .. }) => (Lane::Singular, value, None),
        Err(_) => (Lane::Invalid, f64::NAN, None),
    }
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Tallies of the lanes' statuses: Ok, NotAssemblable, Singular, Invalid.
#[derive(Default, Debug)]
struct Tally([usize; 4]);

impl Tally {
    fn add(&mut self, l: Lane) {
        self.0[l as usize] += 1;
    }
}

/// Compares lane `i` of a batch with the scalar blocks; `rates` when they were computed.
#[allow(clippy::too_many_arguments)]
fn check_lane(
    out: &Positions,
    rates: Option<&Rates>,
    i: usize,
    d: &FourBarDims,
    phi: f64,
    w: f64,
    e: f64,
    tally: &mut Tally,
) {
    let (lane, measure, values) = scalar(d, phi, w, e);
    tally.add(lane);
    assert_eq!(out.status[i], lane, "lane {i}: {d:?} at {phi}");
    assert!(
        same(out.measure[i], measure),
        "lane {i}: measure {} vs {measure}",
        out.measure[i]
    );
    let got = [out.b_x[i], out.b_y[i], out.p_x[i], out.p_y[i]];
    match values {
        Some(v) => {
            for k in 0..4 {
                assert!(
                    same(got[k], v[k]),
                    "lane {i} value {k}: {} vs {}",
                    got[k],
                    v[k]
                );
            }
            if let Some(r) = rates {
                let got = [
                    r.v_b[0][i],
                    r.v_b[1][i],
                    r.a_b[0][i],
                    r.a_b[1][i],
                    r.v_p[0][i],
                    r.v_p[1][i],
                    r.a_p[0][i],
                    r.a_p[1][i],
                    r.omega[0][i],
                    r.omega[1][i],
                    r.epsilon[0][i],
                    r.epsilon[1][i],
                ];
                for k in 0..12 {
                    assert!(
                        same(got[k], v[k + 4]),
                        "lane {i} rate {k}: {} vs {}",
                        got[k],
                        v[k + 4]
                    );
                }
            }
        }
        None => assert!(got.iter().all(|x| x.is_nan()), "lane {i}: {got:?}"),
    }
}

/// Random angles, some far outside one turn and some not finite.
fn random_angles(rng: &mut Rng, n: usize) -> Vec<f64> {
    (0..n)
        .map(|_| match rng.next() % 50 {
            0 => f64::NAN,
            1 => rng.range(-100.0, 100.0),
            2 => f64::INFINITY,
            _ => rng.range(0.0, std::f64::consts::TAU),
        })
        .collect()
}

#[test]
fn positions_of_one_four_bar_equal_the_scalar_blocks_bit_for_bit() {
    let mut rng = Rng(26);
    let mut tally = Tally::default();
    let mut out = Positions::default();
    for case in 0..300 {
        let mut d = random_dims(&mut rng);
        let mut phi = random_angles(&mut rng, 67);
        if case % 3 == 0 {
            for p in &mut phi[..8] {
                *p = at_dead_point(&mut rng, &mut d);
            }
        }
        let angles = CrankAngles::new(&phi);
        out.resize(phi.len());
        let ok = four_bar_positions(&d, &angles, out.columns_mut()).unwrap();
        assert_eq!(ok, out.status.iter().filter(|&&s| s == Lane::Ok).count());
        for (i, &p) in phi.iter().enumerate() {
            check_lane(&out, None, i, &d, p, 0.0, 0.0, &mut tally);
        }
    }
    // Every kind of lane was met.
    assert!(tally.0.iter().all(|&c| c > 20), "{tally:?}");
}

#[test]
fn motions_of_one_four_bar_equal_the_scalar_blocks_bit_for_bit() {
    let mut rng = Rng(2026);
    let mut tally = Tally::default();
    let mut out = Positions::default();
    for case in 0..300 {
        let mut d = random_dims(&mut rng);
        let mut phi = random_angles(&mut rng, 41);
        if case % 3 == 0 {
            for p in &mut phi[..6] {
                *p = at_dead_point(&mut rng, &mut d);
            }
        }
        let (w, e) = match case % 7 {
            0 => (0.0, 0.0),
            1 => (1e200, 3.0),
            _ => (rng.range(-50.0, 50.0), rng.range(-500.0, 500.0)),
        };
        let angles = CrankAngles::new(&phi);
        out.resize(phi.len());
        let mut rates = Rates::new(phi.len());
        four_bar_motions(&d, &angles, w, e, out.columns_mut(), rates.columns_mut()).unwrap();
        for (i, &p) in phi.iter().enumerate() {
            check_lane(&out, Some(&rates), i, &d, p, w, e, &mut tally);
        }
    }
    assert!(tally.0.iter().all(|&c| c > 20), "{tally:?}");
}

#[test]
fn many_four_bars_at_one_angle_equal_the_scalar_blocks_bit_for_bit() {
    let mut rng = Rng(7);
    let mut tally = Tally::default();
    for _ in 0..20 {
        let phi = rng.range(-7.0, 7.0);
        let mut bars = FourBarColumns::default();
        let mut dims = Vec::new();
        for k in 0..500 {
            let mut d = random_dims(&mut rng);
            if k % 10 == 0 {
                // Dead or tangent at this very angle.
                let a = d.o + d.l_oa * Vector2::new(phi.cos(), phi.sin());
                d.l_cb = (d.c - a).norm() + d.l_ab * [1.0, -1.0][k % 20 / 10];
                if d.l_cb <= 0.0 {
                    d.l_cb = 0.1;
                }
            }
            bars.push(&d);
            dims.push(d);
        }
        let mut out = Positions::new(bars.len());
        four_bars_at(&bars, phi, out.columns_mut()).unwrap();
        for (i, d) in dims.iter().enumerate() {
            check_lane(&out, None, i, d, phi, 0.0, 0.0, &mut tally);
        }
    }
    assert!(tally.0.iter().all(|&c| c > 20), "{tally:?}");
}

#[test]
fn columns_of_the_wrong_length_are_an_error_naming_the_column() {
    let d = FourBarDims {
        o: Point2::origin(),
        c: Point2::new(0.4, 0.0),
        l_oa: 0.1,
        l_ab: 0.35,
        l_cb: 0.3,
        branch: Branch::Plus,
        coupler: Vector2::zeros(),
    };
    let angles = CrankAngles::turn(10);
    let mut out = Positions::new(10);
    out.p_y.pop();
    assert!(matches!(
        four_bar_positions(&d, &angles, out.columns_mut()),
        Err(Error::OutOfRange { name: "p_y", .. })
    ));
}

#[test]
fn split_columns_solved_in_parts_equal_the_whole_batch_and_a_bad_mid_is_an_error() {
    let mut rng = Rng(27);
    let d = random_dims(&mut rng);
    let phi = random_angles(&mut rng, 301);
    let n = phi.len();
    let mut whole = Positions::new(n);
    four_bar_positions(&d, &CrankAngles::new(&phi), whole.columns_mut()).unwrap();
    // Every mid from 0 to the length, the ends included (an empty part is a batch of none).
    for mid in [0, 1, 150, 300, 301] {
        let mut parts = Positions::new(n);
        let (lo, hi) = parts.columns_mut().split_at(mid).unwrap();
        assert_eq!((lo.b_x.len(), hi.status.len()), (mid, n - mid));
        four_bar_positions(&d, &CrankAngles::new(&phi[..mid]), lo).unwrap();
        four_bar_positions(&d, &CrankAngles::new(&phi[mid..]), hi).unwrap();
        assert_eq!(parts.status, whole.status);
        for (a, b) in [
            (&parts.b_x, &whole.b_x),
            (&parts.b_y, &whole.b_y),
            (&parts.p_x, &whole.p_x),
            (&parts.p_y, &whole.p_y),
            (&parts.measure, &whole.measure),
        ] {
            assert!(a.iter().zip(b).all(|(x, y)| same(*x, *y)), "mid {mid}");
        }
    }
    // Beyond the length: an error naming `mid` and its admissible range, not a panic.
    let mut cols = Positions::new(n);
    for mid in [302, usize::MAX] {
        match cols.columns_mut().split_at(mid) {
            Err(Error::OutOfRange {
                name: "mid", max, ..
            }) => assert_eq!(max, n as f64),
            other => panic!("mid {mid}: {other:?}"),
        }
    }
    // Columns of unequal lengths, which no mid splits alike: the short column is named.
    cols.measure.truncate(100);
    assert!(matches!(
        cols.columns_mut().split_at(50),
        Err(Error::OutOfRange {
            name: "measure",
            ..
        })
    ));
}

#[cfg(feature = "rayon")]
#[test]
fn the_parallel_batch_equals_the_serial_one() {
    use tmm::kinematics::batch::par_four_bar_positions;
    let mut rng = Rng(3);
    let d = random_dims(&mut rng);
    let angles = CrankAngles::new(&random_angles(&mut rng, 20_000));
    let (mut a, mut b) = (Positions::new(angles.len()), Positions::new(angles.len()));
    four_bar_positions(&d, &angles, a.columns_mut()).unwrap();
    par_four_bar_positions(&d, &angles, b.columns_mut()).unwrap();
    assert_eq!(a.status, b.status);
    for (x, y) in a.b_x.iter().zip(&b.b_x) {
        assert!(same(*x, *y));
    }
}

/// A path error of one candidate's positions against a target (a circle), with each failed
/// lane counted by its own term: every column and the status take part.
fn path_score(k: usize, p: &Positions) -> f64 {
    let mut e = k as f64;
    for i in 0..p.status.len() {
        if p.status[i] == Lane::Ok {
            let (dx, dy) = (p.p_x[i] - 0.3 * (i as f64).cos(), p.p_y[i] - 0.3);
            e += dx * dx + dy * dy + p.b_x[i] * p.b_y[i] + p.measure[i];
        } else {
            e += 1e3 * (p.status[i] as u8 as f64) + p.measure[i].abs().min(1.0);
        }
    }
    e
}

/// Candidates with failing lanes mixed in; each one's score is that of its own batch.
fn candidates(rng: &mut Rng, count: usize) -> (Vec<FourBarDims>, CrankAngles) {
    let dims: Vec<FourBarDims> = (0..count).map(|_| random_dims(rng)).collect();
    (dims, CrankAngles::new(&random_angles(rng, 97)))
}

#[test]
fn scores_of_candidates_are_those_of_their_own_batches() {
    let mut rng = Rng(2601);
    let (dims, angles) = candidates(&mut rng, 400);
    let scores = four_bar_scores(&dims, &angles, path_score);
    let mut out = Positions::new(angles.len());
    let mut failed = 0;
    for (k, d) in dims.iter().enumerate() {
        four_bar_positions(d, &angles, out.columns_mut()).unwrap();
        failed += out.status.iter().filter(|&&s| s != Lane::Ok).count();
        assert!(same(scores[k], path_score(k, &out)), "candidate {k}");
    }
    // Failing lanes were met (so a score depends on the previous candidate's columns only
    // if a lane left one unwritten).
    assert!(failed > 1000, "{failed}");
}

#[cfg(feature = "rayon")]
#[test]
fn the_parallel_scores_equal_the_serial_ones() {
    use tmm::kinematics::batch::par_four_bar_scores;
    let mut rng = Rng(2602);
    let (dims, angles) = candidates(&mut rng, 3000);
    let serial = four_bar_scores(&dims, &angles, path_score);
    let parallel = par_four_bar_scores(&dims, &angles, path_score);
    assert_eq!(serial.len(), parallel.len());
    for (a, b) in serial.iter().zip(&parallel) {
        assert!(same(*a, *b));
    }
}
