//! A gas-pressure (indicator) diagram over the piston stroke, and the gas force it gives.

use crate::error::{finite, Error, Result};
use nalgebra::Vector2;

/// An indicator diagram: the gas pressure on a piston as a table over its stroke, one branch
/// for each direction of motion, linearly interpolated.
///
/// The position on the stroke is the fraction x = (s_head − s)/(s_head − s_crank) ∈ [0, 1]:
/// 0 at the head-end dead centre (the piston nearest the cylinder head, the largest s along the
/// guide), 1 at the crank-end dead centre. `outward` holds the pressures while the piston moves
/// away from the head (x increasing: suction or expansion), `inward` while it moves towards it
/// (x decreasing: compression and delivery). The pressure is gauge pressure, Pa; it pushes the
/// piston away from the head with the force p·A. At rest (ṡ = 0, a dead centre) the `outward`
/// branch is used: a closed diagram has equal pressures at the two ends of its branches.
///
/// Each branch lists points (x, p) with x strictly increasing from 0 to 1.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct IndicatorDiagram {
    /// The piston area A, m².
    pub area: f64,
    /// (x, p) while the piston moves away from the head, Pa.
    pub outward: Vec<[f64; 2]>,
    /// (x, p) while the piston moves towards the head, Pa.
    pub inward: Vec<[f64; 2]>,
}

/// How far outside [0, 1] a stroke fraction may come from rounding and still be clamped.
const STROKE_SLACK: f64 = 1e-9;

impl IndicatorDiagram {
    /// The idealised diagram of a single-stage air compressor: suction at `p_suction`,
    /// polytropic compression p·V^n = const from the crank end until `p_delivery`, delivery at
    /// `p_delivery`, polytropic re-expansion of the clearance volume (a fraction `clearance` of
    /// the swept volume). Pressures absolute in the process, stored as gauge pressures over
    /// `p_atm`; tabulated at `points` stations per branch, at least 2 and at most 100 001 (a
    /// finer table adds nothing to a linear interpolation, and `usize::MAX` stations would not
    /// fit in memory).
    ///
    /// # Examples
    /// Air from 0.1 MPa to 0.3 MPa (absolute) with n = 1.3 and 5 % clearance: the diagram
    /// reads 0 at the crank end of both strokes and 0.2 MPa gauge at the head end.
    /// ```
    /// use approx::assert_relative_eq;
    /// use tmm::linkage::IndicatorDiagram;
    /// let d = IndicatorDiagram::compressor(0.01, 1.0e5, 3.0e5, 1.0e5, 1.3, 0.05, 41);
    /// assert_relative_eq!(d.pressure(1.0, false).unwrap(), 0.0, epsilon = 1e-9);
    /// assert_relative_eq!(d.pressure(0.0, true).unwrap(), 2.0e5, epsilon = 1e-6);
    /// // Compression from the crank end: p_s·(c + 1)^n = p(x)·(c + x)^n; x = 0.5 is a station.
    /// let p = 1.0e5 * (1.05f64 / 0.55).powf(1.3) - 1.0e5;
    /// assert_relative_eq!(d.pressure(0.5, true).unwrap(), p, max_relative = 1e-14);
    /// ```
    #[must_use]
    pub fn compressor(
        area: f64,
        p_suction: f64,
        p_delivery: f64,
        p_atm: f64,
        n: f64,
        clearance: f64,
        points: usize,
    ) -> Self {
        let points = points.clamp(2, 100_001);
        // Volume per unit swept volume at the fraction x from the head end.
        let vol = |x: f64| clearance + x;
        let station = |k: usize| k as f64 / (points - 1) as f64;
        let inward = (0..points)
            .map(|k| {
                let x = station(k);
                let p = (p_suction * (vol(1.0) / vol(x)).powf(n)).min(p_delivery);
                [x, p - p_atm]
            })
            .collect();
        let outward = (0..points)
            .map(|k| {
                let x = station(k);
                let p = (p_delivery * (vol(0.0) / vol(x)).powf(n)).max(p_suction);
                [x, p - p_atm]
            })
            .collect();
        Self {
            area,
            outward,
            inward,
        }
    }

    /// The gauge pressure at the stroke fraction `x` on the branch of the motion: `inward`
    /// (towards the head) or outward.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for x outside [0, 1] by more than rounding, or a branch whose
    /// stations do not cover x; [`Error::NonFinite`] for a non-finite x.
    pub fn pressure(&self, x: f64, inward: bool) -> Result<f64> {
        finite("stroke fraction", x)?;
        if !(-STROKE_SLACK..=1.0 + STROKE_SLACK).contains(&x) {
            return Err(Error::OutOfRange {
                name: "stroke fraction",
                value: x,
                min: 0.0,
                max: 1.0,
                ends: crate::Ends::Closed,
            });
        }
        let x = x.clamp(0.0, 1.0);
        let table = if inward { &self.inward } else { &self.outward };
        interpolate(table, x)
    }

    /// The gas force on the piston at the slide coordinate s moving at ṡ along the guide
    /// direction `guide` (unit), with the head-end dead centre at `s_head` and the crank-end one
    /// at `s_crank` (s_head > s_crank). The force pushes away from the head: −p·A·guide.
    ///
    /// # Errors
    /// As [`IndicatorDiagram::pressure`]; [`Error::NonFinite`] for a non-finite s, ṡ, guide
    /// direction or piston area; [`Error::NonPositive`] for a stroke s_head − s_crank ≤ 0 or a
    /// piston area ≤ 0; [`Error::Overflow`] when the stroke (the difference of finite dead
    /// centres) or the force p·A overflows.
    pub fn force(
        &self,
        s: f64,
        s_rate: f64,
        guide: Vector2<f64>,
        s_head: f64,
        s_crank: f64,
    ) -> Result<Vector2<f64>> {
        finite("piston slide", s)?;
        finite("piston speed", s_rate)?;
        finite("head-end dead centre", s_head)?;
        finite("crank-end dead centre", s_crank)?;
        crate::error::finite2(["guide direction x", "guide direction y"], guide)?;
        let area = crate::error::positive("piston area", self.area)?;
        let stroke = crate::error::positive(
            "piston stroke",
            crate::error::computed("piston stroke", s_head - s_crank)?,
        )?;
        let x = crate::error::computed("stroke fraction", (s_head - s) / stroke)?;
        let p = self.pressure(x, s_rate > 0.0)?;
        let f = -p * area * guide;
        crate::error::computed_all("gas force", f.iter())?;
        Ok(f)
    }
}

impl IndicatorDiagram {
    /// The first point of either branch with a non-finite station or pressure, described for
    /// an error (`None` when every point is finite).
    pub(crate) fn non_finite_point(&self) -> Option<String> {
        [("outward", &self.outward), ("inward", &self.inward)]
            .into_iter()
            .find_map(|(branch, table)| {
                table
                    .iter()
                    .position(|p| !(p[0].is_finite() && p[1].is_finite()))
                    .map(|k| {
                        format!(
                            "diagram.{branch}[{k}] must be finite, got [{}, {}]",
                            table[k][0], table[k][1]
                        )
                    })
            })
    }
}

/// Linear interpolation in a table of (x, y) with x increasing.
fn interpolate(table: &[[f64; 2]], x: f64) -> Result<f64> {
    let out_of_table = |value: f64| Error::OutOfRange {
        name: "indicator diagram station",
        value,
        min: table.first().map_or(f64::NAN, |p| p[0]),
        max: table.last().map_or(f64::NAN, |p| p[0]),
        ends: crate::Ends::Closed,
    };
    let k = table.partition_point(|p| p[0] <= x);
    if k == 0 {
        return Err(out_of_table(x));
    }
    let [x0, y0] = table[k - 1];
    finite("indicator diagram station", x0)?;
    finite("indicator diagram pressure", y0)?;
    if x == x0 {
        return finite("pressure", y0);
    }
    let Some(&[x1, y1]) = table.get(k) else {
        return Err(out_of_table(x));
    };
    finite("indicator diagram station", x1)?;
    finite("indicator diagram pressure", y1)?;
    if x1 <= x0 {
        return Err(out_of_table(x1));
    }
    finite("pressure", y0 + (y1 - y0) * (x - x0) / (x1 - x0))
}
