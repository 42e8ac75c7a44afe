//! Linkages that ship with the crate, on realistic data: the layouts the linkage example runs
//! and the tests check. The same linkages are bundled as JSON files under `linkages/` (feature
//! `serde`; a test checks that each file reads back as the linkage built here).

use super::description::{At, Drive, Input, Joint, Link, Linkage, LoadSpec, Mass};
use super::Output;

fn rod(m: f64, a: [f64; 2], b: [f64; 2]) -> Mass {
    Mass::rod(m, a, b)
}

/// A crank-rocker four-bar under a resisting moment on its rocker and a force on its coupler
/// point (O1 = (0, 0), O3 = (0.40, 0.05) m; crank 0.10, coupler 0.35, rocker 0.30 m).
#[must_use]
pub fn four_bar() -> Linkage {
    let (o1, a, o3) = ([0.0, 0.0], [0.1, 0.0], [0.4, 0.05]);
    // B at 0.35 from A and 0.30 from O3, to the left of A→O3.
    let b = [0.25612516773077276, 0.3132489936153635];
    let e = [0.25, 0.25];
    Linkage {
        name: "four-bar".to_owned(),
        joints: vec![
            Joint::revolute("O1", o1),
            Joint::revolute("A", a),
            Joint::revolute("B", b),
            Joint::revolute("O3", o3),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]).with_mass(Mass::new(1.0, 0.002, At::Coords(o1))),
            Link::new("coupler", &["A", "B"])
                .with_point("E", e)
                .with_mass(rod(1.5, a, b)),
            Link::new("rocker", &["O3", "B"]).with_mass(rod(2.0, o3, b)),
        ],
        input: Input::crank("crank"),
        loads: vec![
            LoadSpec::Resistance {
                on: "rocker".to_owned(),
                forward: 40.0,
                backward: 40.0,
                at: None,
            },
            LoadSpec::Force {
                link: "coupler".to_owned(),
                at: At::name("E"),
                force: [0.0, -50.0],
            },
        ],
        output: Some(Output::Angle("rocker".to_owned())),
        ..Linkage::default()
    }
}

/// The four-bar of [`four_bar`] driven through a gear pair: a wheel of r_w = 0.15 m on the
/// crank, the pitch point on the −x side of O1, α_w = 20°.
#[must_use]
pub fn geared_four_bar() -> Linkage {
    Linkage {
        name: "geared four-bar".to_owned(),
        input: Input {
            link: "crank".to_owned(),
            drive: Drive::Gear {
                pitch_radius: 0.15,
                pitch_angle: std::f64::consts::PI,
                pressure_angle: 20f64.to_radians(),
            },
        },
        ..four_bar()
    }
}

/// A Watt six-bar: a crank-rocker whose coupler and rocker are ternary links joined by a
/// second RRR dyad (links 4 and 5), a press resisting the last link's rotation.
#[must_use]
pub fn watt_six_bar() -> Linkage {
    let (o1, a, b, o3) = ([0.0, 0.0], [0.08, 0.0], [0.3, 0.3], [0.38, 0.0]);
    let (e, f, g) = ([0.25, 0.45], [0.52, 0.28], [0.45, 0.6]);
    Linkage {
        name: "Watt six-bar".to_owned(),
        joints: ["O1", "A", "B", "O3", "E", "F", "G"]
            .iter()
            .zip([o1, a, b, o3, e, f, g])
            .map(|(n, p)| Joint::revolute(n, p))
            .collect(),
        links: vec![
            Link::new("frame", &["O1", "O3"]),
            Link::new("crank", &["O1", "A"]).with_mass(Mass::new(1.0, 0.002, At::Coords(o1))),
            Link::new("coupler", &["A", "B", "E"]).with_mass(Mass::new(
                3.0,
                0.02,
                At::Coords([0.21, 0.25]),
            )),
            Link::new("rocker", &["O3", "B", "F"]).with_mass(Mass::new(
                2.5,
                0.015,
                At::Coords([0.4, 0.19]),
            )),
            Link::new("link 4", &["E", "G"]).with_mass(rod(1.0, e, g)),
            Link::new("link 5", &["F", "G"]).with_mass(rod(1.0, f, g)),
        ],
        input: Input::crank("crank"),
        loads: vec![LoadSpec::Resistance {
            on: "link 5".to_owned(),
            forward: 30.0,
            backward: 30.0,
            at: None,
        }],
        output: Some(Output::Angle("link 5".to_owned())),
        ..Linkage::default()
    }
}

/// A Stephenson III six-bar: a four-bar with a ternary coupler ABC whose point C drives the
/// rocker 5 about O5 through link 4; a resisting moment on the rocker 5 while it turns
/// counter-clockwise.
#[must_use]
pub fn stephenson_six_bar() -> Linkage {
    let (o1, a, b, o3) = ([0.0, 0.0], [0.0, 0.1], [0.3, 0.35], [0.35, 0.0]);
    let (c, d, o5) = (
        [0.2, 0.5],
        [0.6245894940175953, 0.6490763615395896],
        [0.65, 0.3],
    );
    Linkage {
        name: "Stephenson III six-bar".to_owned(),
        joints: ["O1", "A", "B", "O3", "C", "D", "O5"]
            .iter()
            .zip([o1, a, b, o3, c, d, o5])
            .map(|(n, p)| Joint::revolute(n, p))
            .collect(),
        links: vec![
            Link::new("frame", &["O1", "O3", "O5"]),
            Link::new("crank", &["O1", "A"]).with_mass(Mass::new(1.0, 0.002, At::Coords(o1))),
            Link::new("coupler", &["A", "B", "C"]).with_mass(Mass::new(
                2.0,
                0.012,
                At::Coords([0.17, 0.32]),
            )),
            Link::new("rocker", &["O3", "B"]).with_mass(rod(1.5, o3, b)),
            Link::new("link 4", &["C", "D"]).with_mass(rod(1.0, c, d)),
            Link::new("link 5", &["O5", "D"]).with_mass(rod(1.2, o5, d)),
        ],
        input: Input::crank("crank"),
        loads: vec![LoadSpec::Resistance {
            on: "link 5".to_owned(),
            forward: 25.0,
            backward: 0.0,
            at: None,
        }],
        output: Some(Output::Angle("link 5".to_owned())),
        ..Linkage::default()
    }
}

/// A shaper: the crank O1A carries a slider block sliding in the slotted lever O3D (an RPR
/// group); the lever's top D drives the ram along a horizontal guide through the link DE (an
/// RRP group). The cutting force of 1.5 kN acts on the ram while it moves along −x.
#[must_use]
pub fn shaper() -> Linkage {
    let (o1, a, o3) = ([0.0, 0.0], [0.0, 0.1], [0.0, -0.3]);
    let d = [0.0, 0.3];
    let e = [-0.12, 0.38];
    let lever = [a[0] - o3[0], a[1] - o3[1]];
    Linkage {
        name: "shaper".to_owned(),
        joints: vec![
            Joint::revolute("O1", o1),
            Joint::revolute("A", a),
            Joint::prismatic("P", a, "lever", lever),
            Joint::revolute("O3", o3),
            Joint::revolute("D", d),
            Joint::revolute("E", e),
            Joint::prismatic("Q", e, "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3", "Q"]),
            Link::new("crank", &["O1", "A"]).with_mass(Mass::new(2.0, 0.005, At::Coords(o1))),
            Link::new("block", &["A", "P"]).with_mass(Mass::new(0.5, 0.0002, At::Coords(a))),
            Link::new("lever", &["O3", "P", "D"]).with_mass(rod(6.0, o3, d)),
            Link::new("link", &["D", "E"]).with_mass(rod(1.0, d, e)),
            Link::new("ram", &["E", "Q"]).with_mass(Mass::new(15.0, 0.1, At::Coords(e))),
        ],
        input: Input::crank("crank"),
        loads: vec![LoadSpec::Resistance {
            on: "Q".to_owned(),
            forward: 0.0,
            backward: 1500.0,
            at: None,
        }],
        output: Some(Output::Slide("Q".to_owned())),
        ..Linkage::default()
    }
}

/// A Scotch yoke (sine mechanism): a crank of 0.1 m drives a block on its pin A in the
/// vertical slot of a yoke that slides along the frame's x axis, against a resistance of
/// 400 N both ways (a double-acting pump). One RPP group (block, yoke).
#[must_use]
pub fn scotch_yoke() -> Linkage {
    let (o1, a) = ([0.0, 0.0], [0.1, 0.0]);
    Linkage {
        name: "Scotch yoke".to_owned(),
        joints: vec![
            Joint::revolute("O1", o1),
            Joint::revolute("A", a),
            Joint::prismatic("S", a, "yoke", [0.0, 1.0]),
            Joint::prismatic("Q", a, "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "Q"]),
            Link::new("crank", &["O1", "A"]).with_mass(Mass::new(1.0, 0.002, At::Coords(o1))),
            Link::new("block", &["A", "S"]).with_mass(Mass::new(0.2, 0.0001, At::Coords(a))),
            Link::new("yoke", &["S", "Q"]).with_mass(Mass::new(3.0, 0.02, At::Coords([0.25, 0.0]))),
        ],
        input: Input::crank("crank"),
        loads: vec![LoadSpec::Resistance {
            on: "Q".to_owned(),
            forward: 400.0,
            backward: 400.0,
            at: Some(At::Coords([0.4, 0.0])),
        }],
        output: Some(Output::Slide("Q".to_owned())),
        ..Linkage::default()
    }
}

/// The crank-rocker of [`four_bar`] with a slot along its rocker, in which a block (hinged
/// at F to a slider) drives the slider along a horizontal frame guide 0.2 m above the
/// rocker's pivot: F is where the rocker's line crosses the guide (a tangent mechanism). The
/// slider works against 300 N while it moves to −x. Groups: RRR (coupler, rocker), then PRP
/// (block, slider); the rocker swings between about 109° and 149°, so the slot never turns
/// parallel to the guide.
#[must_use]
pub fn slotted_rocker() -> Linkage {
    let (o1, a, o3) = ([0.0, 0.0], [0.1, 0.0], [0.4, 0.05]);
    let b = [0.25612516773077276, 0.3132489936153635];
    let f = [0.2906929669182746, 0.25];
    Linkage {
        name: "slotted rocker".to_owned(),
        joints: vec![
            Joint::revolute("O1", o1),
            Joint::revolute("A", a),
            Joint::revolute("B", b),
            Joint::revolute("O3", o3),
            Joint::prismatic("S", f, "rocker", [b[0] - o3[0], b[1] - o3[1]]),
            Joint::revolute("F", f),
            Joint::prismatic("G", f, "frame", [1.0, 0.0]),
        ],
        links: vec![
            Link::new("frame", &["O1", "O3", "G"]),
            Link::new("crank", &["O1", "A"]).with_mass(Mass::new(1.0, 0.002, At::Coords(o1))),
            Link::new("coupler", &["A", "B"]).with_mass(rod(1.5, a, b)),
            Link::new("rocker", &["O3", "B", "S"]).with_mass(rod(2.0, o3, b)),
            Link::new("block", &["S", "F"]).with_mass(Mass::new(0.3, 0.0002, At::Coords(f))),
            Link::new("slider", &["F", "G"]).with_mass(Mass::new(4.0, 0.01, At::Coords(f))),
        ],
        input: Input::crank("crank"),
        loads: vec![LoadSpec::Resistance {
            on: "G".to_owned(),
            forward: 0.0,
            backward: 300.0,
            at: None,
        }],
        output: Some(Output::Slide("G".to_owned())),
        ..Linkage::default()
    }
}

/// Every bundled linkage, in the order of the files under `linkages/`.
#[must_use]
pub fn all() -> Vec<Linkage> {
    vec![
        four_bar(),
        geared_four_bar(),
        watt_six_bar(),
        stephenson_six_bar(),
        shaper(),
        scotch_yoke(),
        slotted_rocker(),
    ]
}

/// The five-bar robot of [`FiveBar::default`](crate::dynamics::machines::FiveBar) as a
/// linkage with two inputs: cranks `crank 1` (O–A, 0.15 m) and `crank 4` (D–C, 0.15 m) on
/// the frame hinges O = (0, 0) and D = (0.2, 0) m, couplers `coupler 2` (A–B) and
/// `coupler 3` (C–B) of 0.25 m meeting at the end effector B; reference pose φ1 = 120°,
/// φ4 = 60°. The cranks carry I1 = I4 = 0.02 kg·m² about their pivots; each coupler 0.6 kg
/// at its middle with J_S = m·l²/4 (the seed's two point masses m/2 at its hinges, as a rigid
/// body); a tool moment of 0.3 N·m resists on coupler 3 (−0.3 N·m: it opposes increasing
/// φ3 as a positive M_on of the seed); no gravity (a horizontal robot). The same linkage is
/// `linkages/five-bar-robot.json`.
///
/// # Examples
/// ```
/// let plan = tmm::linkage::Plan::new(&tmm::linkage::bundled::five_bar_robot())?;
/// assert_eq!((plan.mobility(), plan.input_count(), plan.groups().len()), (2, 2, 1));
/// # Ok::<(), tmm::Error>(())
/// ```
#[must_use]
pub fn five_bar_robot() -> Linkage {
    let (l1, l2, l3, l4) = (0.15, 0.25, 0.25, 0.15);
    let (o, d) = ([0.0, 0.0], [0.2, 0.0]);
    let (p1, p4) = (120f64.to_radians(), 60f64.to_radians());
    let a = [o[0] + l1 * p1.cos(), o[1] + l1 * p1.sin()];
    let c = [d[0] + l4 * p4.cos(), d[1] + l4 * p4.sin()];
    // B: to the left of A→C, l2 from A and l3 from C.
    let (dx, dy) = (c[0] - a[0], c[1] - a[1]);
    let dist = dx.hypot(dy);
    let along = (l2 * l2 - l3 * l3 + dist * dist) / (2.0 * dist);
    let height = (l2 * l2 - along * along).sqrt();
    let (ex, ey) = (dx / dist, dy / dist);
    let b = [
        a[0] + along * ex - height * ey,
        a[1] + along * ey + height * ex,
    ];
    let coupler = |m: f64, l: f64, p: [f64; 2], q: [f64; 2]| {
        Mass::new(
            m,
            m * l * l / 4.0,
            At::Coords([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]),
        )
    };
    Linkage {
        name: "five-bar robot".to_owned(),
        joints: vec![
            Joint::revolute("O", o),
            Joint::revolute("A", a),
            Joint::revolute("B", b),
            Joint::revolute("C", c),
            Joint::revolute("D", d),
        ],
        links: vec![
            Link::new("frame", &["O", "D"]),
            Link::new("crank 1", &["O", "A"]).with_mass(Mass::new(0.0, 0.02, At::name("O"))),
            Link::new("coupler 2", &["A", "B"]).with_mass(coupler(0.6, l2, a, b)),
            Link::new("coupler 3", &["C", "B"]).with_mass(coupler(0.6, l3, c, b)),
            Link::new("crank 4", &["D", "C"]).with_mass(Mass::new(0.0, 0.02, At::name("D"))),
        ],
        input: Input::crank("crank 1"),
        second_input: Some(Input::crank("crank 4")),
        gravity: [0.0, 0.0],
        loads: vec![LoadSpec::Moment {
            link: "coupler 3".to_owned(),
            moment: -0.3,
        }],
        ..Linkage::default()
    }
}
