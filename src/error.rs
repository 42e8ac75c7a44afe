//! The crate's one error type.
//!
//! Every solver validates its input and reports what went wrong with the values involved, so a
//! caller sweeping millions of positions can tell a bad input from a singular position without a
//! debugger. No solver panics on bad input or returns a NaN or an infinity in place of an error.
//!
//! The messages are for a person: numbers with four significant digits (`closure fails by
//! 0.267 m`, `det = -3.1e-18`), units in SI as everywhere in the crate (m, s, N, N·m, rad).
//! The fields keep the exact values for a program.

/// A `Result` whose error is [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

/// What went wrong, with the values involved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// An input number is NaN or infinite.
    #[error("{name} must be finite, got {value}")]
    NonFinite {
        /// The input's name, in the crate's notation (for example `"A.x"` or `"l_AB"`).
        name: &'static str,
        /// The offending value.
        value: f64,
    },

    /// A length (or another quantity that must be positive, such as a mass) is zero or negative.
    #[error("{name} must be positive, got {}", sig(*.value))]
    NonPositive {
        /// The quantity's name.
        name: &'static str,
        /// The offending value.
        value: f64,
    },

    /// An input lies outside the range in which it has a meaning (for example a pressure angle
    /// of 90° or more, or a table lookup outside the table).
    ///
    /// The message writes the interval as it is checked: `[0, π/2)` for a pressure angle,
    /// `[2, ∞)` for a table's length, "must be 2" when only one value is admissible.
    #[error("{name} {}", outside(*.value, *.min, *.max, *.ends))]
    OutOfRange {
        /// The input's name.
        name: &'static str,
        /// The offending value.
        value: f64,
        /// The lower end of the admissible interval.
        min: f64,
        /// The upper end of the admissible interval.
        max: f64,
        /// Which ends belong to the interval.
        ends: Ends,
    },

    /// A closed form would divide by a quantity that vanishes here: the configuration is
    /// singular (a dead point, a zero arm, a degenerate group).
    #[error("{what} is singular: {measure} = {}", sig(*.value))]
    Singular {
        /// The group, link or system that is singular.
        what: &'static str,
        /// The name of the quantity that vanished (for example `"sin(phi3 - phi2)"`).
        measure: &'static str,
        /// Its value here (zero, or too small to divide by).
        value: f64,
    },

    /// A group cannot be assembled at this position: the closure equations have no real
    /// solution.
    #[error("{group} cannot be assembled: closure fails by {} m", sig(*.gap))]
    NotAssemblable {
        /// The group that cannot be closed.
        group: &'static str,
        /// By how much the closure fails (a distance, in metres).
        gap: f64,
    },

    /// An integrator met a non-finite state (it diverged).
    #[error("non-finite state at t = {} s", sig(*.time))]
    NonFiniteState {
        /// The time at which the state stopped being finite.
        time: f64,
    },

    /// An inertia (mass) matrix is not positive-definite.
    #[error("inertia matrix is not positive-definite at {at}: det = {}", sig(*.det))]
    NotPositiveDefinite {
        /// Where it happened (for example the coordinates or the time).
        at: String,
        /// The determinant found there.
        det: f64,
    },

    /// A linkage description is malformed: `item` names the joint, link, load or field, and
    /// `problem` says what is wrong with it.
    #[error("{item}: {problem}")]
    Description {
        /// The joint, link, load or field at fault (for example `"joint B"`).
        item: String,
        /// What is wrong, with the values involved.
        problem: String,
    },

    /// A picture could not be drawn (feature `draw`): `what` names the picture and `problem`
    /// says why (a bad drawing option, or the drawing back end's message).
    #[error("drawing {what}: {problem}")]
    Drawing {
        /// The picture (for example `"diagram of the balancing moment"`).
        what: String,
        /// What went wrong.
        problem: String,
    },

    /// A computed quantity overflowed (or lost all meaning) although every input was finite:
    /// the inputs are too large (or too small) for `f64` at this point.
    #[error("{what} overflows for these inputs")]
    Overflow {
        /// The quantity that overflowed.
        what: &'static str,
    },

    /// A run used up its budget of steps, evaluations or recorded rows before it ended.
    #[error("{what} budget of {limit} exhausted at t = {time} s")]
    Budget {
        /// The budget used up (for example `"step"` or `"evaluation"`).
        what: &'static str,
        /// Its limit.
        limit: usize,
        /// The time the run had reached, s.
        time: f64,
    },

    /// A synthesis requirement that no mechanism of the kind meets: `parameter` names it,
    /// `required` is the value asked for and `reachable` the nearest value that can be met
    /// (the best minimum transmission angle, the largest feasible time ratio, ...), so the
    /// message says by how much the requirement misses.
    #[error("{parameter} = {} cannot be met: the nearest reachable is {} (misses by {})",
        sig(*.required), sig(*.reachable), sig((*.required - *.reachable).abs()))]
    Infeasible {
        /// The requirement (for example `"minimum transmission angle (rad)"`).
        parameter: &'static str,
        /// The value asked for.
        required: f64,
        /// The nearest value that can be met.
        reachable: f64,
    },

    /// A synthesis method found no mechanism of its kind for the requirement: `method` names
    /// the method and its data, `problem` says what came out instead (a negative length, a
    /// branch defect, a crank that cannot turn fully), with the values involved.
    #[error("{method}: {problem}")]
    NoMechanism {
        /// The method (for example `"crank-rocker through three positions"`).
        method: &'static str,
        /// What is wrong with its answer.
        problem: String,
    },

    /// A motion stopped for good where a resistance that opposes it (dry friction, a constant
    /// resisting moment) holds it: the drive, every other load along the motion, is below the
    /// resistance's breakaway load (see [`crate::dynamics::SwitchLoads`]).
    ///
    /// (No field names what stopped: the variant stays within the size of the others, so
    /// that a `Result` costs the hot loops of a run no more to move.)
    #[error(
        "stopped at t = {} s: the driving load {} {unit} is below the resistance {} {unit}",
        sig(*.time),
        sig(*.drive),
        sig(*.resistance)
    )]
    Stalled {
        /// When, s.
        time: f64,
        /// The magnitude of the driving load there.
        drive: f64,
        /// The resistance's breakaway load against it.
        resistance: f64,
        /// The unit of both loads (`"N·m"` or `"N"`).
        unit: &'static str,
    },

    /// A motion with friction in the joints jams: at `time` the friction statics has no
    /// solution under the motion's loads (joint `joint` self-locks: the friction's feedback
    /// reached the loads), so no finite reactions carry the motion on. A run ends there with
    /// [`Outcome::Jammed`](crate::dynamics::Outcome::Jammed).
    #[error(
        "the linkage jams at t = {} s: joint {joint} self-locks, {measure} = {}",
        sig(*.time),
        sig(*.value)
    )]
    Jammed {
        /// When (the time of the evaluation that found it), s.
        time: f64,
        /// The joint that self-locks, by its index in the description.
        index: usize,
        /// Its name.
        joint: String,
        /// The measure that vanished (`"det(I - J)"`, the friction's feedback).
        measure: &'static str,
        /// Its value there.
        value: f64,
    },

    /// A crank turned back within a turn ([`LinkageSystem::turn`]): its speed reached zero
    /// against the turn's direction and the drive, above the resistances' breakaway load,
    /// turned it the other way (located to the method's own state). Not a singularity: the
    /// motion goes on the other way, as [`LinkageSystem::run_up_from`] does.
    ///
    /// [`LinkageSystem::turn`]: crate::linkage::dynamics::LinkageSystem::turn
    /// [`LinkageSystem::run_up_from`]: crate::linkage::dynamics::LinkageSystem::run_up_from
    #[error(
        "the crank turned back at t = {} s, at φ = {} rad, from {} rad/s at t = {} s (its \
         speed reached zero and the drive turned it the other way), {} of the turn made",
        sig(*.time),
        sig(*.angle),
        sig(*.from_speed),
        sig(*.from_time),
        sig(*.fraction)
    )]
    TurnedBack {
        /// When the crank's speed reached zero, s.
        time: f64,
        /// The crank angle there, rad.
        angle: f64,
        /// The fraction of a turn made from the turn's start before it turned back (≥ 0).
        fraction: f64,
        /// The crank speed at the turn's start, rad/s.
        from_speed: f64,
        /// When the turn started, s.
        from_time: f64,
    },

    /// A described machine's state at (or within
    /// [`DEAD_CENTRE_DETERMINANT`](crate::linkage::DEAD_CENTRE_DETERMINANT) of) a dead centre
    /// of one of its RRR or RRP dyads, where its inputs no longer describe the motion. A run
    /// ends there with [`Outcome::DeadCentre`](crate::dynamics::Outcome::DeadCentre).
    #[error(
        "{group} is at a dead centre, where the inputs do not describe the motion: its \
         determinant is {} (at most 1e-3 at a dead centre)",
        sig(*.value)
    )]
    DeadCentre {
        /// The dyad, by its index among the plan's groups
        /// ([`Plan::groups`](crate::linkage::Plan::groups)).
        index: usize,
        /// Its name.
        group: String,
        /// Its determinant there.
        value: f64,
    },

    /// An error inside one named part of a larger analysis (for example one group of a
    /// mechanism at one position).
    #[error("{part}: {source}")]
    In {
        /// The part (for example `"group 2 (RRP)"`).
        part: String,
        /// What went wrong in it.
        source: Box<Error>,
    },
}

impl Error {
    /// The jam this error is or holds within named parts ([`Error::Jammed`]): its time, its
    /// joint's index and its measure's value.
    pub(crate) fn jam(&self) -> Option<(f64, usize, f64)> {
        match self {
            Self::Jammed {
                time, index, value, ..
            } => Some((*time, *index, *value)),
            Self::In { source, .. } => source.jam(),
            _ => None,
        }
    }
}

impl Error {
    /// The dead centre this error is or holds within named parts ([`Error::DeadCentre`]):
    /// the dyad's index and its determinant.
    pub(crate) fn dead_centre(&self) -> Option<(usize, f64)> {
        match self {
            Self::DeadCentre { index, value, .. } => Some((*index, *value)),
            Self::In { source, .. } => source.dead_centre(),
            _ => None,
        }
    }

    /// Whether this error is, or holds within named parts, a position that cannot be
    /// assembled ([`Error::NotAssemblable`]).
    pub(crate) fn not_assemblable(&self) -> bool {
        match self {
            Self::NotAssemblable { .. } => true,
            Self::In { source, .. } => source.not_assemblable(),
            _ => false,
        }
    }
}

/// Which ends of an [`Error::OutOfRange`] interval are admissible values themselves. An infinite
/// end is never admissible, whatever this says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ends {
    /// `[min, max]`: both ends are admissible.
    Closed,
    /// `[min, max)`: the upper end is not (a pressure angle below π/2).
    OpenAbove,
    /// `(min, max]`: the lower end is not.
    OpenBelow,
    /// `(min, max)`: neither end is (a coefficient of speed fluctuation in (0, 2)).
    Open,
}

/// `x` with `digits` significant digits for a message: plain notation from 10⁻³ up to 10⁶
/// (`0.267`, `1500`), scientific outside it (`2.67e-9`), trailing zeros dropped.
fn sig_digits(x: f64, digits: i32) -> String {
    if !x.is_finite() || x == 0.0 {
        return if x == 0.0 { "0".into() } else { x.to_string() };
    }
    let a = x.abs();
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if (1e-3..1e6).contains(&a) {
        // The exponent is between −3 and 5 here, so the cast cannot truncate.
        #[allow(clippy::cast_possible_truncation)]
        let exponent = a.log10().floor() as i32;
        let decimals = usize::try_from((digits - 1 - exponent).max(0)).unwrap_or(0);
        trim(format!("{x:.decimals$}"))
    } else {
        let decimals = usize::try_from(digits - 1).unwrap_or(0);
        let s = format!("{x:.decimals$e}");
        match s.split_once('e') {
            Some((mantissa, exponent)) => format!("{}e{exponent}", trim(mantissa.to_string())),
            None => s,
        }
    }
}

/// `x` with four significant digits, for a message (the error's field keeps the exact value).
fn sig(x: f64) -> String {
    sig_digits(x, 4)
}

/// "= value lies outside [min, max)", the interval written as it is checked, with as many
/// digits as it takes to tell the value from the bound it crossed (a value just past a bound
/// would otherwise print equal to it), to write the value closer to itself than to the nearer
/// bound, and not as a whole number when it is not one; "must be min, got value"
/// when min = max.
fn outside(value: f64, min: f64, max: f64, ends: Ends) -> String {
    let mut digits = 4;
    loop {
        let end = |x: f64| match x {
            f64::INFINITY => "∞".to_string(),
            f64::NEG_INFINITY => "−∞".to_string(),
            x => sig_digits(x, digits),
        };
        let (v, lo, hi) = (sig_digits(value, digits), end(min), end(max));
        if min == max && ends == Ends::Closed {
            return format!("must be {lo}, got {v}");
        }
        // The value written closer to itself than to the bounds: K = 1.0001 outside [1.03, 3]
        // must not read "K = 1".
        let gap = [min, max]
            .into_iter()
            .filter(|b| b.is_finite())
            .map(|b| (value - b).abs())
            .fold(f64::INFINITY, f64::min);
        let faithful = v.parse::<f64>().map_or(true, |p| {
            (p - value).abs() < 0.5 * gap && (p.fract() != 0.0 || value.fract() == 0.0)
        });
        // The bounds told apart from each other, and a bound that is not a whole number not
        // written as one: K outside (1, 1.0000011) must not read "(1, 1)".
        let whole = |x: f64, w: &str| {
            !x.is_finite()
                || x.fract() == 0.0
                || w.parse::<f64>().map_or(true, |p| p.fract() != 0.0)
        };
        let bounds = (lo != hi || min == max) && whole(min, &lo) && whole(max, &hi);
        if (v != lo && v != hi && faithful && bounds) || digits >= 17 {
            let open_below = matches!(ends, Ends::OpenBelow | Ends::Open) || min.is_infinite();
            let open_above = matches!(ends, Ends::OpenAbove | Ends::Open) || max.is_infinite();
            let (l, r) = (
                if open_below { '(' } else { '[' },
                if open_above { ')' } else { ']' },
            );
            return format!("= {v} lies outside {l}{lo}, {hi}{r}");
        }
        digits += 1;
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite { name, value })
    }
}

/// Checks that `value` is finite and positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::NonPositive { name, value })
    }
}

/// Checks that every named number is finite; the error names the first that is not.
pub(crate) fn all_finite(named: &[(&'static str, f64)]) -> Result<()> {
    named
        .iter()
        .try_for_each(|&(name, v)| finite(name, v).map(|_| ()))
}

/// Checks that a value computed from finite inputs is finite: [`Error::Overflow`] otherwise.
pub(crate) fn computed(what: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::Overflow { what })
    }
}

/// As [`computed`], for every component of a vector or matrix.
pub(crate) fn computed_all<'a>(
    what: &'static str,
    values: impl IntoIterator<Item = &'a f64>,
) -> Result<()> {
    if values.into_iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::Overflow { what })
    }
}

/// The length of a vector made of finite inputs, which must be positive: [`Error::Overflow`]
/// when it overflows (components beyond about 1.3·10¹⁵⁴), [`Error::NonPositive`] when it is
/// zero, [`Error::NonFinite`] when a component is not finite.
pub(crate) fn length(name: &'static str, v: nalgebra::Vector2<f64>) -> Result<f64> {
    if !(v.x.is_finite() && v.y.is_finite()) {
        return Err(Error::Overflow { what: name });
    }
    let l = v.norm();
    if !l.is_finite() {
        return Err(Error::Overflow { what: name });
    }
    positive(name, l)
}

/// The unit vector of a direction given by any finite non-zero vector: scaled by its larger
/// component first, so that neither a huge nor a tiny (but non-zero) vector overflows or
/// underflows on the way. [`Error::NonFinite`] or [`Error::NonPositive`] (its length) else.
pub(crate) fn unit_direction(
    name: &'static str,
    v: nalgebra::Vector2<f64>,
) -> Result<nalgebra::Vector2<f64>> {
    finite(name, v.x)?;
    finite(name, v.y)?;
    let m = v.x.abs().max(v.y.abs());
    positive(name, m)?;
    let w = v / m;
    Ok(w / w.norm())
}

/// Checks that both components of a point or vector are finite.
pub(crate) fn finite2(
    names: [&'static str; 2],
    v: impl Into<nalgebra::Vector2<f64>>,
) -> Result<()> {
    let v = v.into();
    finite(names[0], v.x)?;
    finite(names[1], v.y)?;
    Ok(())
}
