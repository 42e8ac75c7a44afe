use tmm::kinematics::Motion;
use tmm::mechanism::*;

#[test]
fn scratch() {
    let m = SixBar::course_example();
    for k in 0..36 {
        let phi = k as f64 * 10f64.to_radians();
        let p = m.analyse(Motion::new(phi, 10.0, 3.0)).unwrap();
        let c = p.power_check().unwrap();
        println!("{k} s5={:.4} Mb={:.4} vp={:.4} rel={:.2e} res={:.2e} det={:.3} {:.3}", p.group45.slide.value, c.chain, c.virtual_power, c.relative_error(), p.worst_residual(), p.group23.det, p.group45.det);
    }
    println!("{:?}", m.strokes(tmm::kinematics::Rotation::Ccw));
}
