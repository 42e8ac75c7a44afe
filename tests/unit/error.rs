//! `src/error.rs`: the checks name what they reject, and the messages carry the values,
//! rounded, while the fields keep them exact.

use tmm::kinematics::{grashof, Grashof};
use tmm::linkage::IndicatorDiagram;
use tmm::{Ends, Error};

/// The shared checks, seen through public functions that apply them to named inputs: a
/// non-finite value is `NonFinite` with its name and value, a zero length `NonPositive`, an
/// infinite length `NonFinite`, and good values pass.
#[test]
fn checks_reject_what_they_name() {
    let d = IndicatorDiagram {
        area: 0.01,
        outward: vec![[0.0, 1e5], [1.0, 0.0]],
        inward: vec![[0.0, 1e5], [1.0, 1e5]],
    };
    assert!(matches!(
        d.pressure(f64::NAN, true),
        Err(Error::NonFinite { name: "stroke fraction", value }) if value.is_nan()
    ));
    assert!(matches!(
        grashof(1.0, 0.0, 1.0, 1.0),
        Err(Error::NonPositive { name: "input", value }) if value == 0.0
    ));
    assert!(matches!(
        grashof(1.0, 1.0, f64::INFINITY, 1.0),
        Err(Error::NonFinite {
            name: "coupler",
            ..
        })
    ));
    assert_eq!(grashof(0.4, 0.1, 0.35, 0.3), Ok(Grashof::CrankRocker));
}

#[test]
fn messages_carry_the_values() {
    let e = Error::Singular {
        what: "RRR dyad",
        measure: "sin(phi3 - phi2)",
        value: 0.0,
    };
    assert!(e.to_string().contains("sin(phi3 - phi2)"));
    let nested = Error::In {
        part: "group 1".into(),
        source: Box::new(e),
    };
    assert!(nested.to_string().starts_with("group 1: RRR dyad"));
}

#[test]
fn messages_round_numbers_and_keep_exact_fields() {
    let e = Error::NotAssemblable {
        group: "RRR dyad",
        gap: 0.267_123_456_789,
    };
    assert_eq!(
        e.to_string(),
        "RRR dyad cannot be assembled: closure fails by 0.2671 m"
    );
    assert!(matches!(e, Error::NotAssemblable { gap, .. } if gap == 0.267_123_456_789));
    let e = Error::Singular {
        what: "RRR dyad",
        measure: "sin(phi3 - phi2)",
        value: 1.234_567e-17,
    };
    assert_eq!(
        e.to_string(),
        "RRR dyad is singular: sin(phi3 - phi2) = 1.235e-17"
    );
    let e = Error::NonFiniteState { time: 239.712_345 };
    assert_eq!(e.to_string(), "non-finite state at t = 239.7 s");
    let e = Error::NonPositive {
        name: "l_AB",
        value: -2.0,
    };
    assert_eq!(e.to_string(), "l_AB must be positive, got -2");
    // Just past a bound: enough digits to see that it is past.
    let e = Error::OutOfRange {
        name: "alpha_w",
        value: std::f64::consts::FRAC_PI_2 + 1e-9,
        min: 0.0,
        max: std::f64::consts::FRAC_PI_2,
        ends: Ends::OpenAbove,
    };
    assert_eq!(
        e.to_string(),
        "alpha_w = 1.570796328 lies outside [0, 1.570796327)"
    );
    // The interval as it is checked: open ends, infinite ends, a single admissible value.
    let range = |value, min, max, ends| {
        Error::OutOfRange {
            name: "x",
            value,
            min,
            max,
            ends,
        }
        .to_string()
    };
    assert_eq!(
        range(2.5, 0.0, 2.0, Ends::Open),
        "x = 2.5 lies outside (0, 2)"
    );
    assert_eq!(
        range(-1.0, 0.0, 2.0, Ends::OpenBelow),
        "x = -1 lies outside (0, 2]"
    );
    assert_eq!(
        range(1.0, 2.0, f64::INFINITY, Ends::Closed),
        "x = 1 lies outside [2, ∞)"
    );
    assert_eq!(range(3.0, 2.0, 2.0, Ends::Closed), "x must be 2, got 3");
    // A value near a whole number is not written as one, and is written closer to itself than
    // to the bound it missed.
    assert_eq!(
        range(1.0001, 1.0317, f64::INFINITY, Ends::Closed),
        "x = 1.0001 lies outside [1.0317, ∞)"
    );
    assert_eq!(
        range(1.0 + 1e-13, 1.03, 3.0, Ends::Closed),
        "x = 1.0000000000001 lies outside [1.03, 3]"
    );
    // Bounds that round to one number are written apart, and a bound that is not whole is
    // not written as one (a swing near 180° leaves K the interval (1, 1.0000011)).
    assert_eq!(
        range(1.25, 1.0, 1.0000011, Ends::Open),
        "x = 1.25 lies outside (1, 1.000001)"
    );
    assert_eq!(
        range(0.5, 0.99999, 3.0, Ends::Closed),
        "x = 0.5 lies outside [0.99999, 3]"
    );
    // Four significant digits, plain from 10⁻³ to 10⁶ and scientific outside, as every
    // message that rounds prints them (here the singular measure's value).
    for (x, s) in [
        (0.0, "0"),
        (1500.0, "1500"),
        (999.96, "1000"),
        (-0.001_234_56, "-0.001235"),
        (2.67e-9, "2.67e-9"),
        (3.0e12, "3e12"),
        (f64::NAN, "NaN"),
        (f64::NEG_INFINITY, "-inf"),
    ] {
        let e = Error::Singular {
            what: "w",
            measure: "m",
            value: x,
        };
        assert_eq!(e.to_string(), format!("w is singular: m = {s}"), "{x}");
    }
}
