use tmm::kinematics::Motion;
use tmm::linkage::{bundled, Plan};

#[test]
fn smoke() {
    for l in [bundled::four_bar(), bundled::geared_four_bar(), bundled::watt_six_bar(), bundled::stephenson_six_bar(), bundled::shaper()] {
        let plan = Plan::new(&l).unwrap_or_else(|e| panic!("{}: {e}", l.name));
        let mut worst = (0.0f64, 0.0f64);
        let mut fails = 0;
        for k in 0..72 {
            let phi = k as f64 * std::f64::consts::TAU / 72.0;
            match plan.analyse(Motion::new(phi, 10.0, 3.0)) {
                Ok(a) => {
                    worst.0 = worst.0.max(a.power_check().unwrap().relative_error());
                    worst.1 = worst.1.max(a.worst_residual());
                }
                Err(e) => { fails += 1; println!("{} at {phi}: {e}", l.name); }
            }
        }
        println!("{}: groups {:?} power {:e} residual {:e} fails {fails}", l.name, plan.groups().iter().map(|g| g.name.clone()).collect::<Vec<_>>(), worst.0, worst.1);
    }
}
