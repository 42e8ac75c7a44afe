//! Linkages that ship with the crate, on realistic data: the layouts the linkage example runs
//! and the tests check. Each is written once, as a JSON description file under `linkages/`
//! (the format is in `docs/linkage-format.md`), compiled into the crate and read by
//! [`Linkage::from_json`]: this module needs the feature `serde` (on by default).
//!
//! # Examples
//! ```
//! use tmm::linkage::{bundled, Plan};
//! for linkage in bundled::all() {
//!     let plan = Plan::new(&linkage)?;
//!     assert_eq!(plan.input_count(), 1, "{}", linkage.name);
//! }
//! # Ok::<(), tmm::Error>(())
//! ```
#![cfg(feature = "serde")]
#![cfg_attr(docsrs, doc(cfg(feature = "serde")))]

use super::description::Linkage;

/// The bundled file `linkages/<name>` read as a description.
///
/// # Panics
/// If the file does not read, which the tests rule out for every bundled file
/// (`tests/linkage/files.rs`): a released crate never panics here.
macro_rules! bundled {
    ($name:literal) => {
        Linkage::from_json(include_str!(concat!("../../linkages/", $name)))
            .unwrap_or_else(|e| panic!("the bundled linkages/{} does not read: {e}", $name))
    };
}

/// A crank-rocker four-bar under a resisting moment on its rocker and a force on its coupler
/// point (O1 = (0, 0), O3 = (0.40, 0.05) m; crank 0.10, coupler 0.35, rocker 0.30 m).
///
/// The file `linkages/four-bar.json`.
#[must_use]
pub fn four_bar() -> Linkage {
    bundled!("four-bar.json")
}

/// The four-bar of [`four_bar`] driven through a gear pair: a wheel of r_w = 0.15 m on the
/// crank, the pitch point on the −x side of O1, α_w = 20°.
///
/// The file `linkages/geared-four-bar.json`.
#[must_use]
pub fn geared_four_bar() -> Linkage {
    bundled!("geared-four-bar.json")
}

/// A Watt six-bar: a crank-rocker whose coupler and rocker are ternary links joined by a
/// second RRR dyad (links 4 and 5), a press resisting the last link's rotation.
///
/// The file `linkages/watt-six-bar.json`.
#[must_use]
pub fn watt_six_bar() -> Linkage {
    bundled!("watt-six-bar.json")
}

/// A Stephenson III six-bar: a four-bar with a ternary coupler ABC whose point C drives the
/// rocker 5 about O5 through link 4; a resisting moment on the rocker 5 while it turns
/// counter-clockwise.
///
/// The file `linkages/stephenson-six-bar.json`.
#[must_use]
pub fn stephenson_six_bar() -> Linkage {
    bundled!("stephenson-six-bar.json")
}

/// A shaper: the crank O1A carries a slider block sliding in the slotted lever O3D (an RPR
/// group); the lever's top D drives the ram along a horizontal guide through the link DE (an
/// RRP group). The cutting force of 1.5 kN acts on the ram while it moves along −x.
///
/// The file `linkages/shaper.json`.
#[must_use]
pub fn shaper() -> Linkage {
    bundled!("shaper.json")
}

/// A Scotch yoke (sine mechanism): a crank of 0.1 m drives a block on its pin A in the
/// vertical slot of a yoke that slides along the frame's x axis, against a resistance of
/// 400 N both ways (a double-acting pump). One RPP group (block, yoke).
///
/// The file `linkages/scotch-yoke.json`.
#[must_use]
pub fn scotch_yoke() -> Linkage {
    bundled!("scotch-yoke.json")
}

/// The crank-rocker of [`four_bar`] with a slot along its rocker, in which a block (hinged
/// at F to a slider) drives the slider along a horizontal frame guide 0.2 m above the
/// rocker's pivot: F is where the rocker's line crosses the guide (a tangent mechanism). The
/// slider works against 300 N while it moves to −x. Groups: RRR (coupler, rocker), then PRP
/// (block, slider); the rocker swings between about 109° and 149°, so the slot never turns
/// parallel to the guide.
///
/// The file `linkages/slotted-rocker.json`.
#[must_use]
pub fn slotted_rocker() -> Linkage {
    bundled!("slotted-rocker.json")
}

/// A six-bar with a triad (an Assur group of the 3rd class): the crank O1A (0.08 m) drives
/// the ternary link B1 B2 B3 through link 2 (A–B1, 0.286 m); the ternary link is also held
/// by rocker 4 (0.303 m) from O2 = (0.47, 0) m and rocker 5 (0.255 m) from
/// O3 = (0.16, 0.54) m. One group: the triad (ternary; link 2, rocker 4, rocker 5), which
/// follows the crank round a whole turn in one assembly mode, its ternary link rocking
/// between about 30° and 39°. A resistance of 20 N·m opposes rocker 5's turning and a force
/// of (−150, 50) N acts on the ternary link at B2.
///
/// The file `linkages/six-bar-triad.json`.
///
/// # Examples
/// ```
/// use tmm::kinematics::Motion;
/// use tmm::linkage::{bundled, GroupKind, Plan};
/// let plan = Plan::new(&bundled::six_bar_triad())?;
/// assert_eq!(plan.groups()[0].kind, GroupKind::Triad);
/// let mut solver = plan.solver();
/// for k in 0..36 {
///     let phi = plan.reference_input() + f64::from(k) * std::f64::consts::TAU / 36.0;
///     let a = solver.analyse(Motion::turning(phi, 10.0))?;
///     assert!(a.power_check()?.relative_error() < 1e-9);
/// }
/// # Ok::<(), tmm::Error>(())
/// ```
#[must_use]
pub fn six_bar_triad() -> Linkage {
    bundled!("six-bar-triad.json")
}

/// The double butterfly eight-bar: the input ACD turns about A = (0, 0) and carries C and D;
/// one six-link group (CE, EFG, BFJ, DHI, GH, IJ, hinged to the frame at B = (6.17, 0)),
/// which holds neither a dyad nor a triad, solved as a general group. The file
/// `linkages/double-butterfly.json`.
#[must_use]
pub fn double_butterfly() -> Linkage {
    bundled!("double-butterfly.json")
}

/// The six-bar of [`six_bar_triad`] with a sliding pair in its triad: its rocker 4 replaced
/// by a slider block `slider 4` hinged to the ternary link at B2 = (0.51, 0.3) m and sliding
/// on a frame guide through B2 along (0.3, −0.04) (the tangent of rocker 4's arc at B2), so
/// that the group is a triad whose first leg is a slider on a guide of the frame (the outer
/// pair). A documented layout, not a published one: besides the loads of [`six_bar_triad`],
/// a resistance of 100 N opposes the slide. Its reference figure: over a turn of the crank
/// the slide travels from −0.221899 m to +0.016157 m of the drawn position, a stroke of
/// 0.238056 m (the tests check it, and every joint to 1e-9 of the size, against an
/// independent solve of the group). Not in [`all`]: the main example runs it from its file.
///
/// The file `linkages/six-bar-slider-triad.json`.
#[must_use]
pub fn six_bar_slider_triad() -> Linkage {
    bundled!("six-bar-slider-triad.json")
}

/// Every bundled linkage of one input, in the order of the files under `linkages/`.
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
        six_bar_triad(),
        double_butterfly(),
        six_bar_slider_triad(),
    ]
}

/// The five-bar robot of [`FiveBar::default`](crate::dynamics::machines::FiveBar) as a
/// linkage with two inputs: cranks `crank 1` (O–A, 0.15 m) and `crank 4` (D–C, 0.15 m) on
/// the frame hinges O = (0, 0) and D = (0.2, 0) m, couplers `coupler 2` (A–B) and
/// `coupler 3` (C–B) of 0.25 m meeting at the end effector B; reference pose φ1 = 120°,
/// φ4 = 60°. The cranks carry I1 = I4 = 0.02 kg·m² about their pivots; each coupler 0.6 kg
/// at its middle with J_S = m·l²/4 (the seed's two point masses m/2 at its hinges, as a rigid
/// body); a tool moment of 0.3 N·m resists on coupler 3 (−0.3 N·m: it opposes increasing
/// φ3 as a positive M_on of the seed); no gravity (a horizontal robot).
///
/// The file `linkages/five-bar-robot.json`.
///
/// # Examples
/// ```
/// let plan = tmm::linkage::Plan::new(&tmm::linkage::bundled::five_bar_robot())?;
/// assert_eq!((plan.mobility(), plan.input_count(), plan.groups().len()), (2, 2, 1));
/// # Ok::<(), tmm::Error>(())
/// ```
#[must_use]
pub fn five_bar_robot() -> Linkage {
    bundled!("five-bar-robot.json")
}

/// The Peaucellier–Lipkin inversor (Peaucellier 1864, Lipkin 1871), the first exact
/// straight-line linkage: the crank O1A (45 mm) turns about O1 = (45, 0) mm, so A's circle
/// passes through the pivot O of the long links (100 mm); the rhombus A–C–P–D has sides of
/// 40 mm. Since OA·OP = 100² − 40² mm² (P is A's inverse in the circle about O of that power),
/// P runs on the line x = (100² − 40²)/(2·45) mm = 93.33 mm. The crank cannot turn fully: it
/// rocks between the positions where |OA| = 100 − 40 mm and the rhombus folds. Its joints O,
/// A, C and D each join three links (hinges of three); a 20 N load hangs at P.
///
/// The file `linkages/peaucellier-lipkin.json`.
#[must_use]
pub fn peaucellier_lipkin() -> Linkage {
    bundled!("peaucellier-lipkin.json")
}

/// Chebyshev's straight-line linkage (P. L. Chebyshev, 1850s; the proportions of every
/// textbook): frame A0B0 = 4a, crossed cranks A0A = B0B = 5a, coupler AB = 2a, a = 50 mm;
/// the coupler's middle P is at the height 4a in the middle position and at both ends of its
/// stroke of length 4a (when either crank stands vertical), and near it in between. The cranks
/// rock (the coupler is the shortest link); a 30 N force resists at P.
///
/// The file `linkages/chebyshev-straight-line.json`.
#[must_use]
pub fn chebyshev_straight_line() -> Linkage {
    bundled!("chebyshev-straight-line.json")
}

/// Hoekens' straight-line linkage (K. Hoecken, Werkstattstechnik, 1926): crank 1, frame 2,
/// rocker 2.5, coupler 2.5 extended to 5 (the point P at its end), in units a = 50 mm. It is
/// a cognate of [`chebyshev_straight_line`] (Roberts–Chebyshev theorem): its crank turns
/// fully and P traces the same curve, its crank parallel to Chebyshev's coupler.
///
/// The file `linkages/hoekens-straight-line.json`.
#[must_use]
pub fn hoekens_straight_line() -> Linkage {
    bundled!("hoekens-straight-line.json")
}

/// Theo Jansen's leg with his "holy numbers" (T. Jansen, *The Great Pretender*, 2007):
/// a = 38, l = 7.8 (the frame pivot Z from the crank's axle O), m = 15 (the crank), j = 50,
/// k = 61.9, b = 41.5, c = 39.3, d = 40.1, e = 55.8 (the triangle Z–Y–U), f = 39.4,
/// g = 36.7, h = 65.7, i = 49 (the leg's triangle W–V–foot), read as centimetres. The joints
/// Z, X and W each join three links. The foot runs along a nearly straight ground line for a
/// large part of the turn and lifts for the rest.
///
/// The file `linkages/jansen-leg.json`.
#[must_use]
pub fn jansen_leg() -> Linkage {
    bundled!("jansen-leg.json")
}

/// A Watt II six-bar: two four-bars in series (Svoboda's "double three-bar" layout), the
/// first four-bar's rocker 3, a ternary link on the frame, being the second's input; the
/// frame and rocker 3 are the Watt chain's two ternary links, joined at O3.
///
/// The file `linkages/watt-ii-six-bar.json`.
#[must_use]
pub fn watt_ii_six_bar() -> Linkage {
    bundled!("watt-ii-six-bar.json")
}

/// A Stephenson six-bar whose frame is the binary link joining its two ternary links: the
/// ternary crank O1–A–E and the ternary rocker O3–B–F are joined by the coupler AB (a
/// four-bar) and by the dyad E–G–F. The texts number the Stephenson inversions differently;
/// this is the one that is neither [`stephenson_six_bar`] (whose frame is ternary) nor the
/// inversion whose frame lies in the chain's path of two binary links (a group of the 3rd
/// class for either input).
///
/// The file `linkages/stephenson-ii-six-bar.json`.
#[must_use]
pub fn stephenson_ii_six_bar() -> Linkage {
    bundled!("stephenson-ii-six-bar.json")
}

/// The gallery of published linkages, each with the figure it reproduces (see each
/// function): the Peaucellier–Lipkin inversor, Chebyshev's and Hoekens' straight-line
/// linkages, Jansen's leg, a Watt II and a Stephenson six-bar. Two rock
/// ([`peaucellier_lipkin`], [`chebyshev_straight_line`]), so they are not in [`all`].
#[must_use]
pub fn gallery() -> Vec<Linkage> {
    vec![
        peaucellier_lipkin(),
        chebyshev_straight_line(),
        hoekens_straight_line(),
        jansen_leg(),
        watt_ii_six_bar(),
        stephenson_ii_six_bar(),
    ]
}
