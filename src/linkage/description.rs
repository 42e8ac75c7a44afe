//! The description of a linkage as plain data: joints in a reference pose, links as sets of
//! joints and named points, the input, masses and loads. This is what a person writes (in Rust
//! or, with the `serde` feature, in a JSON file); [`Plan::new`](super::Plan::new) checks it and
//! turns it into the solve plan.

use super::indicator::IndicatorDiagram;
use crate::kinematics::Branch;

/// An output coordinate of a linkage, for its extreme positions and strokes.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Output {
    /// A link's angle along its reference direction, rad.
    Angle(String),
    /// A prismatic joint's slide, m.
    Slide(String),
    /// A joint's or named point's x coordinate, m.
    X(String),
    /// A joint's or named point's y coordinate, m.
    Y(String),
}

/// A planar linkage of the 2nd class, described by its reference pose.
///
/// Every length, every local coordinate of a point on a link and every angle between a link
/// and its guides is read off the reference pose: the joints' coordinates as drawn. Units: m,
/// kg, kg·m², N, N·m, rad, and m/s² for gravity.
///
/// # Examples
/// A crank-rocker four-bar: the crank O1A, the coupler AB, the rocker O3B.
/// ```
/// use tmm::linkage::{Joint, Linkage, Link, Input};
/// let four_bar = Linkage {
///     joints: vec![
///         Joint::revolute("O1", [0.0, 0.0]),
///         Joint::revolute("A", [0.1, 0.0]),
///         Joint::revolute("B", [0.3, 0.25]),
///         Joint::revolute("O3", [0.4, 0.0]),
///     ],
///     links: vec![
///         Link::new("frame", &["O1", "O3"]),
///         Link::new("crank", &["O1", "A"]),
///         Link::new("coupler", &["A", "B"]),
///         Link::new("rocker", &["O3", "B"]),
///     ],
///     input: Input::crank("crank"),
///     ..Linkage::default()
/// };
/// let plan = tmm::linkage::Plan::new(&four_bar)?;
/// assert_eq!(plan.mobility(), 1);
/// assert_eq!(plan.groups().len(), 1);
/// # Ok::<(), tmm::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Linkage {
    /// A name for tables and pictures.
    #[cfg_attr(feature = "serde", serde(default))]
    pub name: String,
    /// The name of the fixed link (the frame). Default `"frame"`.
    #[cfg_attr(feature = "serde", serde(default = "default_frame"))]
    pub frame: String,
    /// The joints, each at its position in the reference pose.
    pub joints: Vec<Joint>,
    /// The links, the frame among them, each listing its joints and named points.
    pub links: Vec<Link>,
    /// The input link and how it is driven.
    pub input: Input,
    /// A second input, for a linkage of mobility 2 driven by two motors (for example the
    /// five-bar robot: two cranks and one RRR dyad). `None` (the default): one input.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub second_input: Option<Input>,
    /// The acceleration of gravity as a vector, m/s². Default (0, −9.81): y points up.
    #[cfg_attr(feature = "serde", serde(default = "default_gravity"))]
    pub gravity: [f64; 2],
    /// External loads: forces, moments, resistances, an indicator diagram.
    #[cfg_attr(feature = "serde", serde(default))]
    pub loads: Vec<LoadSpec>,
    /// The Assur groups in attachment order, as pairs of link names, when the automatic
    /// decomposition is not wanted. Empty: found from the joints and links.
    #[cfg_attr(feature = "serde", serde(default))]
    pub groups: Vec<[String; 2]>,
    /// Assembly modes that override the ones read off the reference pose, keyed by the group's
    /// inner joint (the joint between its two links).
    #[cfg_attr(feature = "serde", serde(default))]
    pub modes: Vec<Mode>,
    /// The output whose extreme positions start the 12 course positions (a link's angle, a
    /// slide, a point's coordinate), if any.
    #[cfg_attr(feature = "serde", serde(default))]
    pub output: Option<Output>,
    /// The input speed of the course table, rad/s (m/s for a slider); negative turns the
    /// crank clockwise. Default 10.
    #[cfg_attr(feature = "serde", serde(default))]
    pub speed: Option<f64>,
    /// The friction of every joint that gives none of its own (see [`Friction`]). `None`
    /// (the default): those joints are frictionless.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub friction: Option<Friction>,
}

#[cfg(feature = "serde")]
fn default_frame() -> String {
    "frame".to_owned()
}

#[cfg(feature = "serde")]
fn default_gravity() -> [f64; 2] {
    [0.0, -9.81]
}

impl Default for Linkage {
    /// An empty linkage with the frame called `"frame"`, gravity (0, −9.81) m/s² and the
    /// input a crank called `"crank"` driven through a coupling.
    fn default() -> Self {
        Self {
            name: String::new(),
            frame: "frame".to_owned(),
            joints: Vec::new(),
            links: Vec::new(),
            input: Input::crank("crank"),
            second_input: None,
            gravity: [0.0, -9.81],
            loads: Vec::new(),
            groups: Vec::new(),
            modes: Vec::new(),
            output: None,
            speed: None,
            friction: None,
        }
    }
}

/// A joint (a lower kinematic pair) between two links, at its reference position.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Joint {
    /// The joint's name, unique among joints and points (for example `"B"`).
    pub name: String,
    /// Its position in the reference pose, m.
    pub at: [f64; 2],
    /// Revolute (the default) or prismatic.
    #[cfg_attr(feature = "serde", serde(default))]
    pub kind: JointKind,
    /// Coulomb friction in the joint; `None` (the default): the linkage's
    /// [`friction`](Linkage::friction), if any.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub friction: Option<Friction>,
}

impl Joint {
    /// A revolute joint (a hinge) at `at`.
    #[must_use]
    pub fn revolute(name: &str, at: [f64; 2]) -> Self {
        Self {
            name: name.to_owned(),
            at,
            kind: JointKind::Revolute,
            friction: None,
        }
    }

    /// A prismatic joint: the other link that lists it slides along a guide line of `guide`
    /// through `at` with the direction `direction` (in the reference pose).
    #[must_use]
    pub fn prismatic(name: &str, at: [f64; 2], guide: &str, direction: [f64; 2]) -> Self {
        Self {
            name: name.to_owned(),
            at,
            kind: JointKind::Prismatic {
                guide: guide.to_owned(),
                direction,
            },
            friction: None,
        }
    }

    /// The same joint with its own friction.
    #[must_use]
    pub fn with_friction(mut self, friction: Friction) -> Self {
        self.friction = Some(friction);
        self
    }
}

/// Coulomb friction in a joint (the model of
/// [`kinetostatics::friction`](crate::kinetostatics::friction)): every field optional, so one
/// value can serve as the linkage-wide default for both kinds of joint.
///
/// - A revolute joint's friction circle has the radius ρ = `rho` if given, else
///   f·`pin_radius` (both needed); a friction couple ρ·|R| opposes the relative rotation.
/// - A prismatic joint's friction force is f·|N| against the relative sliding; with the
///   slider's `length` L along the guide (centred `centre` along the guide from the joint,
///   default 0), the normal reaction is two contact forces at the slider's ends, each with
///   its own friction (a cocked slider). `pin_radius` and `rho` are not for it.
///
/// Every number must be finite and ≥ 0 (`length` > 0), checked by
/// [`Plan::new`](super::Plan::new) with an error naming the joint and the field. Every
/// coefficient zero is the frictionless linkage, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Friction {
    /// f, the coefficient of friction (of the journal with `pin_radius`, of the slide).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub f: Option<f64>,
    /// r, a revolute joint's pin radius, m: ρ = f·r.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub pin_radius: Option<f64>,
    /// ρ, a revolute joint's friction-circle radius, m (instead of f and `pin_radius`).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub rho: Option<f64>,
    /// L, a prismatic joint's slider length along the guide, m (> 0).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub length: Option<f64>,
    /// Where a prismatic joint's slider's middle lies along the guide from the joint, m
    /// (default 0).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub centre: Option<f64>,
}

impl Friction {
    /// A journal of radius `pin_radius` (m) with the coefficient `f`: ρ = f·r.
    #[must_use]
    pub fn pin(f: f64, pin_radius: f64) -> Self {
        Self {
            f: Some(f),
            pin_radius: Some(pin_radius),
            ..Self::default()
        }
    }

    /// A friction circle of radius `rho` (m).
    #[must_use]
    pub fn circle(rho: f64) -> Self {
        Self {
            rho: Some(rho),
            ..Self::default()
        }
    }

    /// A slide with the coefficient `f` that takes any couple.
    #[must_use]
    pub fn slide(f: f64) -> Self {
        Self {
            f: Some(f),
            ..Self::default()
        }
    }

    /// A slide with the coefficient `f`, its slider `length` (m) long along the guide.
    #[must_use]
    pub fn cocked(f: f64, length: f64) -> Self {
        Self {
            f: Some(f),
            length: Some(length),
            ..Self::default()
        }
    }

    /// The default for every joint: a journal (f, `pin_radius`) for the revolute joints and
    /// the same f on the slides.
    #[must_use]
    pub fn everywhere(f: f64, pin_radius: f64) -> Self {
        Self::pin(f, pin_radius)
    }
}

/// The kind of a joint.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum JointKind {
    /// A hinge: the two links turn relative to each other about the joint.
    #[default]
    Revolute,
    /// A sliding pair: the link that is not `guide` translates relative to `guide` along a
    /// line fixed to `guide`, through the joint's reference position, along `direction`.
    Prismatic {
        /// The link that carries the guide line (the frame for a fixed guide).
        guide: String,
        /// The direction of the guide in the reference pose (any non-zero length). The
        /// slide's coordinate s grows along it.
        direction: [f64; 2],
    },
}

/// A link: the joints it carries and its named points.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Link {
    /// The link's name, unique among links (for example `"coupler"`).
    pub name: String,
    /// The joints of the link (at least two, one for the frame).
    pub joints: Vec<String>,
    /// Named points of the link (tracer points, points where loads act), at their reference
    /// positions.
    #[cfg_attr(feature = "serde", serde(default))]
    pub points: Vec<NamedPoint>,
    /// The direction along which the link's angle is measured: from the first named joint or
    /// point to the second. Default: from the link's first joint to its second.
    #[cfg_attr(feature = "serde", serde(default))]
    pub reference: Option<[String; 2]>,
    /// The link's mass properties (none: massless).
    #[cfg_attr(feature = "serde", serde(default))]
    pub mass: Option<Mass>,
}

impl Link {
    /// A massless link carrying `joints`, its angle measured from the first to the second.
    #[must_use]
    pub fn new(name: &str, joints: &[&str]) -> Self {
        Self {
            name: name.to_owned(),
            joints: joints.iter().map(|&j| j.to_owned()).collect(),
            ..Self::default()
        }
    }

    /// The same link with mass properties.
    #[must_use]
    pub fn with_mass(mut self, mass: Mass) -> Self {
        self.mass = Some(mass);
        self
    }

    /// The same link with a named point at `at` (reference pose).
    #[must_use]
    pub fn with_point(mut self, name: &str, at: [f64; 2]) -> Self {
        self.points.push(NamedPoint {
            name: name.to_owned(),
            at,
        });
        self
    }
}

/// A named point of a link at its reference position.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct NamedPoint {
    /// The point's name, unique among joints and points.
    pub name: String,
    /// Its position in the reference pose, m.
    pub at: [f64; 2],
}

/// The mass properties of a link.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Mass {
    /// The mass m, kg (≥ 0).
    pub m: f64,
    /// The moment of inertia about the centre of mass J_S, kg·m² (≥ 0).
    #[cfg_attr(feature = "serde", serde(default))]
    pub j: f64,
    /// The centre of mass S: a joint or point name, or coordinates in the reference pose.
    pub centre: At,
}

impl Mass {
    /// Mass `m`, moment of inertia `j` about the centre `centre`.
    #[must_use]
    pub fn new(m: f64, j: f64, centre: At) -> Self {
        Self { m, j, centre }
    }

    /// A uniform slender rod between the reference positions `from` and `to`: S at the
    /// middle, J_S = m·l²/12.
    #[must_use]
    pub fn rod(m: f64, from: [f64; 2], to: [f64; 2]) -> Self {
        let l2 = (to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2);
        let mid = [0.5 * (from[0] + to[0]), 0.5 * (from[1] + to[1])];
        Self::new(m, m * l2 / 12.0, At::Coords(mid))
    }
}

/// A place on a link: a joint or named point by its name, or coordinates in the reference
/// pose.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(untagged))]
pub enum At {
    /// A joint or named point.
    Name(String),
    /// Coordinates in the reference pose, m.
    Coords([f64; 2]),
}

impl At {
    /// The joint or point called `name`.
    #[must_use]
    pub fn name(name: &str) -> Self {
        Self::Name(name.to_owned())
    }
}

/// The input link and how it is driven.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Input {
    /// The input link: a crank hinged to the frame, or a slider on a fixed guide.
    pub link: String,
    /// How the motor drives it (for a crank). A slider is always driven by a force along its
    /// guide.
    #[cfg_attr(feature = "serde", serde(default))]
    pub drive: Drive,
}

impl Input {
    /// The crank (or slider) `link`, driven through a coupling.
    #[must_use]
    pub fn crank(link: &str) -> Self {
        Self {
            link: link.to_owned(),
            drive: Drive::Coupling,
        }
    }
}

/// How a crank is driven, for its kinetostatics (the last step of the analysis).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum Drive {
    /// Through a coupling on its shaft: a balancing moment (the seeds' SRWL2).
    #[default]
    Coupling,
    /// Through a gear pair: a balancing force of the driving pinion at the pitch point, along
    /// the line of action (the seeds' SRWL1), with the tooth-flank rule of
    /// [`GearDrive`](crate::kinetostatics::GearDrive).
    Gear {
        /// r_w, the pitch radius of the wheel on the input link, m.
        pitch_radius: f64,
        /// The polar angle of the pitch point P about the crank's pivot (fixed in the frame),
        /// rad. π puts P on the −x side.
        pitch_angle: f64,
        /// α_w, the pressure angle of the mesh, rad, in [0, π/2).
        pressure_angle: f64,
    },
}

/// An assembly mode chosen by hand for the group whose inner joint is `joint`.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Mode {
    /// The inner joint of the group (between its two links).
    pub joint: String,
    /// The mode: for RRR, `Plus` puts the inner joint to the left of the line from the outer
    /// joint of the group's first link to that of its second; for RRP, `Plus` puts the slider's
    /// hinge ahead (along the guide) of the foot of the perpendicular from the other hinge.
    #[cfg_attr(feature = "serde", serde(with = "BranchDef"))]
    pub branch: Branch,
}

#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(remote = "Branch")]
enum BranchDef {
    Plus,
    Minus,
}

/// An external load of the linkage.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum LoadSpec {
    /// A constant force (fixed direction in the plane) at a point of a link, N.
    Force {
        /// The link.
        link: String,
        /// Where it acts.
        at: At,
        /// The force, N.
        force: [f64; 2],
    },
    /// A constant couple on a link, N·m, counter-clockwise positive.
    Moment {
        /// The link.
        link: String,
        /// The moment, N·m.
        moment: f64,
    },
    /// A resistance against the motion: on a link, a couple opposing its angular velocity;
    /// on a prismatic joint, a force along the guide on the sliding link (and its reaction on
    /// the guide's link) opposing the sliding. Its magnitude may differ by direction: zero in
    /// one direction makes it act on the working stroke only. Zero at rest.
    Resistance {
        /// A link (a resisting couple) or a prismatic joint (a resisting force).
        on: String,
        /// The magnitude while the coordinate grows (ω > 0, or ṡ > 0 along the guide), ≥ 0.
        forward: f64,
        /// The magnitude while the coordinate falls, ≥ 0.
        backward: f64,
        /// For a prismatic joint: the point of the sliding link where the force acts
        /// (default: the joint).
        #[cfg_attr(feature = "serde", serde(default))]
        at: Option<At>,
    },
    /// The gas pressure of an indicator diagram on a piston: the sliding link of the
    /// prismatic joint `joint`, on a fixed guide. The cylinder head lies along the guide's
    /// direction (`head` = +1) or against it (−1); the force p·A pushes the piston away from
    /// the head, at the joint.
    Indicator {
        /// The piston's prismatic joint (its guide must be the frame).
        joint: String,
        /// The pressure over the stroke.
        diagram: IndicatorDiagram,
        /// +1: the head lies along the guide direction; −1: against it.
        head: f64,
    },
    /// A linear spring between two places: its tension (positive pulls the ends together)
    /// is T = `preload` + `stiffness`·(L − `free_length`) at the length L between its ends,
    /// and its potential energy V = `preload`·(L − L₀) + ½·`stiffness`·(L − L₀)² (so a
    /// spring with zero stiffness is a constant force, a gas spring's model).
    Spring {
        /// A name for errors and readings (default: the load's number).
        #[cfg_attr(feature = "serde", serde(default))]
        name: String,
        /// Its two ends.
        ends: [Anchor; 2],
        /// k, N/m (≥ 0).
        stiffness: f64,
        /// L₀, the length at which it carries only its preload, m (≥ 0).
        free_length: f64,
        /// The tension at the free length, N (default 0; negative pushes the ends apart).
        #[cfg_attr(feature = "serde", serde(default))]
        preload: f64,
    },
    /// A linear viscous damper between two places: the force c·L̇ along the line of its ends
    /// opposes the rate L̇ of their distance (it dissipates the power c·L̇²).
    Damper {
        /// A name for errors and readings (default: the load's number).
        #[cfg_attr(feature = "serde", serde(default))]
        name: String,
        /// Its two ends.
        ends: [Anchor; 2],
        /// c, N·s/m (≥ 0).
        c: f64,
    },
    /// A torsion spring between two links: the moment k·(Δθ − Δθ₀) + `preload` on the
    /// first link (and its opposite on the second), Δθ = θ₂ − θ₁ the angle of the second link
    /// from the first, measured along their reference directions. The twist Δθ − Δθ₀ is read
    /// in (−π, π]: the spring is for links that turn less than half a turn either way from its
    /// free angle, and one whose twist comes within 0.1 rad of ±π over the inputs' range (links
    /// that turn fully relative to each other) is refused when the plan is made, by name.
    TorsionSpring {
        /// A name for errors and readings (default: the load's number).
        #[cfg_attr(feature = "serde", serde(default))]
        name: String,
        /// The two links (one may be the frame).
        links: [String; 2],
        /// k, N·m/rad (≥ 0).
        stiffness: f64,
        /// Δθ₀, rad; default: the angle in the reference pose (the spring relaxed as drawn).
        #[cfg_attr(
            feature = "serde",
            serde(default, skip_serializing_if = "Option::is_none")
        )]
        free_angle: Option<f64>,
        /// The moment at the free angle, N·m (default 0).
        #[cfg_attr(feature = "serde", serde(default))]
        preload: f64,
    },
}

/// Where a spring or damper is fastened: a place on a link.
///
/// With `link` given, `at` is a joint of that link, one of its named points, or coordinates
/// in the reference pose. Without it, `at` names a point (fastened to its link) or a joint
/// with the frame (fastened to the joint's other link); a joint between two moving links
/// needs `link`, since the reactions in the joint depend on which link holds the end.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Anchor {
    /// The link the end is fastened to (see above when it may be left out).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub link: Option<String>,
    /// The place: a joint or point name, or coordinates in the reference pose, m.
    pub at: At,
}

impl Anchor {
    /// The named point (or the joint with the frame) `name`.
    #[must_use]
    pub fn named(name: &str) -> Self {
        Self {
            link: None,
            at: At::name(name),
        }
    }

    /// The place `at` of link `link`.
    #[must_use]
    pub fn on(link: &str, at: At) -> Self {
        Self {
            link: Some(link.to_owned()),
            at,
        }
    }
}

#[cfg(feature = "serde")]
impl Linkage {
    /// Reads a description from JSON (feature `serde`); the format is documented field by
    /// field in `docs/linkage-format.md`.
    ///
    /// # Errors
    /// [`Error::Description`](crate::Error::Description) with the parser's message, which
    /// names the field and the line and column.
    ///
    /// # Examples
    /// ```
    /// let l = tmm::linkage::Linkage::from_json(r#"{
    ///   "joints": [{"name": "O1", "at": [0, 0]}, {"name": "A", "at": [0.1, 0]},
    ///              {"name": "B", "at": [0.3, 0.25]}, {"name": "O3", "at": [0.4, 0]}],
    ///   "links": [{"name": "frame", "joints": ["O1", "O3"]}, {"name": "crank", "joints": ["O1", "A"]},
    ///             {"name": "coupler", "joints": ["A", "B"]}, {"name": "rocker", "joints": ["O3", "B"]}],
    ///   "input": {"link": "crank"}
    /// }"#)?;
    /// assert_eq!(tmm::linkage::Plan::new(&l)?.groups().len(), 1);
    /// let bad = tmm::linkage::Linkage::from_json(r#"{"joints": [], "links": [], "input": {"lnk": "x"}}"#);
    /// assert!(bad.unwrap_err().to_string().contains("lnk"));
    /// # Ok::<(), tmm::Error>(())
    /// ```
    pub fn from_json(text: &str) -> crate::Result<Self> {
        serde_json::from_str(text).map_err(|e| crate::Error::Description {
            item: "description file".to_owned(),
            problem: e.to_string(),
        })
    }

    /// The description as pretty-printed JSON (feature `serde`).
    ///
    /// # Errors
    /// [`Error::Description`](crate::Error::Description) if a number cannot be written (JSON
    /// has no NaN or infinity).
    pub fn to_json(&self) -> crate::Result<String> {
        if let Some(bad) = self.non_finite() {
            return Err(crate::Error::Description {
                item: bad,
                problem: "JSON cannot hold a non-finite number".to_owned(),
            });
        }
        serde_json::to_string_pretty(self).map_err(|e| crate::Error::Description {
            item: "description".to_owned(),
            problem: e.to_string(),
        })
    }

    fn non_finite(&self) -> Option<String> {
        let bad = |v: &[f64]| v.iter().any(|x| !x.is_finite());
        self.joints
            .iter()
            .find(|j| {
                bad(&j.at)
                    || matches!(&j.kind, JointKind::Prismatic { direction, .. } if bad(direction))
            })
            .map(|j| format!("joint {}", j.name))
            .or_else(|| bad(&self.gravity).then(|| "field gravity".to_owned()))
    }
}
