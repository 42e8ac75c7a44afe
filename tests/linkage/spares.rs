//! One-shot solves hand their buffers on from a dropped result to the next solve
//! (`solve/spare.rs`: the plan's spares). Whatever the order in which
//! plans of different sizes (and a clone of one) are solved, with results kept alive or
//! dropped, on one thread or several, each result is bit for bit that of a fresh solver.

use tmm::kinematics::Motion;
use tmm::linkage::{bundled, Analysis, Plan};

/// Every number of a result (its `Debug` text tells any two different `f64`s apart).
fn print(a: &Analysis<'_>) -> String {
    format!(
        "{:?} {:?} {:?} {:?}",
        a.link_motions(),
        a.reactions(),
        a.balances(),
        a.conditioning()
    )
}

fn motion(k: usize) -> Motion {
    Motion::new(k as f64 * 0.37, 10.0 - k as f64 * 0.05, 2.0)
}

/// The plans: two sizes, a triad (whose last pose a box carries), and a clone.
fn plans() -> Vec<Plan> {
    let four = Plan::new(&bundled::four_bar()).unwrap();
    let six = Plan::new(&bundled::watt_six_bar()).unwrap();
    let triad = Plan::new(&bundled::six_bar_triad()).unwrap();
    let copy = four.clone();
    vec![four, six, triad, copy]
}

/// Each plan's results from a fresh solver per position (no buffer handed on).
fn fresh(plans: &[Plan], n: usize) -> Vec<Vec<String>> {
    plans
        .iter()
        .map(|p| {
            (0..n)
                .map(|k| print(p.solver().analyse(motion(k)).unwrap()))
                .collect()
        })
        .collect()
}

/// One-shot solves of the plans interleaved, some results kept while others are made.
// Position k of every plan's reference at once: an index reads clearer than nested zips.
#[allow(clippy::needless_range_loop)]
fn interleaved(plans: &[Plan], n: usize, reference: &[Vec<String>]) {
    for k in 0..n {
        let kept: Vec<_> = plans
            .iter()
            .map(|p| p.analyse(motion(k)).unwrap())
            .collect();
        for (i, p) in plans.iter().enumerate().rev() {
            // A second result of the same plan while the first is alive, then dropped.
            let again = p.analyse(motion(k)).unwrap();
            assert_eq!(print(&again), reference[i][k], "plan {i}, position {k}");
            let kin = p.kinematics(motion(n - 1 - k)).unwrap();
            let solved = p
                .solver()
                .kinematics(motion(n - 1 - k))
                .unwrap()
                .link_motions()
                .to_vec();
            assert_eq!(format!("{:?}", kin.link_motions()), format!("{solved:?}"));
        }
        for (i, a) in kept.iter().enumerate() {
            assert_eq!(print(a), reference[i][k], "plan {i}, position {k}");
        }
    }
}

#[test]
fn interleaved_one_shot_solves_equal_fresh_solvers_bit_for_bit() {
    let plans = plans();
    let n = 60;
    let reference = fresh(&plans, n);
    interleaved(&plans, n, &reference);
    // The same on two threads sharing the plans.
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| interleaved(&plans, n, &reference));
        }
    });
}

/// A solve that fails half-way (an unassemblable input, a load function that errs, one that
/// panics and is caught) leaves its box half written; the next one-shot solves of every plan
/// are still bit for bit a fresh solver's.
#[test]
// Position k of every plan's reference at once, as in `interleaved`.
#[allow(clippy::needless_range_loop)]
fn failed_and_panicked_solves_leave_no_trace_in_the_next() {
    let plans = plans();
    let n = 24;
    let reference = fresh(&plans, n);
    let mut failing = Plan::new(&bundled::watt_six_bar()).unwrap();
    failing
        .add_load_fn("link 5", |a| {
            let phi = a.link("crank")?.value;
            if phi.sin() > 0.5 {
                panic!("a user's load function panics");
            }
            if phi.sin() < -0.5 {
                return Err(tmm::Error::NonFinite {
                    name: "a user's load",
                    value: f64::NAN,
                });
            }
            Ok(tmm::Load::zero(a.joint("F")?.p))
        })
        .unwrap();
    let (mut panicked, mut erred) = (0, 0);
    for k in 0..n {
        for j in 0..8 {
            let m = Motion::new(j as f64 * 0.8, 3.0, 1.0);
            match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                failing.analyse(m).map(|_| ())
            })) {
                Err(_) => panicked += 1,
                Ok(Err(_)) => erred += 1,
                Ok(Ok(())) => {}
            }
        }
        for (i, p) in plans.iter().enumerate() {
            assert_eq!(
                print(&p.analyse(motion(k)).unwrap()),
                reference[i][k],
                "plan {i}, {k}"
            );
        }
    }
    assert!(
        panicked > 0 && erred > 0,
        "{panicked} panics, {erred} errors"
    );
    // The failing plan itself, at positions where its load function is quiet, afterwards.
    for j in 0..8 {
        let m = Motion::new(j as f64 * 0.8, 3.0, 1.0);
        if m.value.sin().abs() <= 0.5 {
            let one = failing.analyse(m).unwrap();
            let fresh = failing.solver().analyse(m).map(print).unwrap();
            assert_eq!(print(&one), fresh, "input {}", m.value);
        }
    }
}
