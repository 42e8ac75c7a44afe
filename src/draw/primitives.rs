//! How a picture is written: the SVG primitives every picture shares — pixel numbers, the
//! links' colours, hinges, dots, blocks, hatched ground lines, arrows, arc arrows, text and
//! its placing, and the document itself. Everything here works in pixels.

use super::style::Style;
use svg::node::element::path::Data;
use svg::node::element::{Circle, Group, Line, Path, Polygon, Text};
use svg::Node;

/// The colours of the moving links, by index (the frame is black).
const PALETTE: [&str; 8] = [
    "#1f5fa8", "#c0392b", "#2e8b57", "#7d3c98", "#d35400", "#138d90", "#7f5a3a", "#b03a7a",
];

/// A pixel number with two decimals: enough for any screen, and short SVG text.
pub(crate) fn r2(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

/// The colour of link `k`.
pub(crate) fn colour(k: usize) -> &'static str {
    if k == 0 {
        "#000000"
    } else {
        PALETTE[(k - 1) % PALETTE.len()]
    }
}

pub(crate) fn block(corners: &[[f64; 2]; 4], c: &str, w: f64) -> Polygon {
    let pts: Vec<String> = corners
        .iter()
        .map(|q| format!("{},{}", r2(q[0]), r2(q[1])))
        .collect();
    Polygon::new()
        .set("points", pts.join(" "))
        .set("fill", "#ffffff")
        .set("stroke", c)
        .set("stroke-width", r2(w.max(1.0)))
}

/// A hinge at pixel `q`: a white circle with a dark outline and a centre mark.
pub(crate) fn hinge(q: [f64; 2], style: &Style, stroke: &str) -> Group {
    Group::new()
        .add(
            Circle::new()
                .set("cx", r2(q[0]))
                .set("cy", r2(q[1]))
                .set("r", r2(style.hinge_radius))
                .set("fill", "#ffffff")
                .set("stroke", stroke)
                .set("stroke-width", 1.5),
        )
        .add(dot(q, 1.3, stroke))
}

/// A named point's dot at pixel `q`.
pub(crate) fn dot(q: [f64; 2], r: f64, fill: &str) -> Circle {
    Circle::new()
        .set("cx", r2(q[0]))
        .set("cy", r2(q[1]))
        .set("r", r2(r))
        .set("fill", fill)
}

/// A base line from `a` to `b` (px) with short hatches on its lower (right-hand) side.
pub(crate) fn hatch(g: &mut Group, a: [f64; 2], b: [f64; 2], r: f64) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    if len.is_nan() || len <= 0.0 {
        return;
    }
    let t = [dx / len, dy / len];
    // The normal pointing to the right of a→b on screen (below a line drawn left to right).
    let n = [-t[1], t[0]];
    let mut d = Data::new()
        .move_to((r2(a[0]), r2(a[1])))
        .line_to((r2(b[0]), r2(b[1])));
    let step = (1.4 * r).max(4.0);
    let h = 1.6 * r;
    let mut s = step * 0.5;
    while s < len {
        let p = [a[0] + t[0] * s, a[1] + t[1] * s];
        let q = [
            p[0] + h * (n[0] - t[0]) * 0.7,
            p[1] + h * (n[1] - t[1]) * 0.7,
        ];
        d = d
            .move_to((r2(p[0]), r2(p[1])))
            .line_to((r2(q[0]), r2(q[1])));
        s += step;
    }
    g.append(Path::new().set("d", d).set("fill", "none"));
}

/// An arrow from `a` to `b` (px): a line and a filled head.
pub(crate) fn arrow(a: [f64; 2], b: [f64; 2], width: f64, c: &str) -> Group {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    let mut g = Group::new();
    if len.is_nan() || len <= 0.0 {
        return g;
    }
    let t = [dx / len, dy / len];
    let n = [-t[1], t[0]];
    let head = (4.0 * width).max(8.0).min(0.6 * len.max(1.0));
    let base = [b[0] - t[0] * head, b[1] - t[1] * head];
    g.append(
        Line::new()
            .set("x1", r2(a[0]))
            .set("y1", r2(a[1]))
            .set("x2", r2(base[0]))
            .set("y2", r2(base[1]))
            .set("stroke", c)
            .set("stroke-width", r2(width)),
    );
    let w = 0.4 * head;
    g.append(
        Polygon::new()
            .set(
                "points",
                format!(
                    "{},{} {},{} {},{}",
                    r2(b[0]),
                    r2(b[1]),
                    r2(base[0] + n[0] * w),
                    r2(base[1] + n[1] * w),
                    r2(base[0] - n[0] * w),
                    r2(base[1] - n[1] * w)
                ),
            )
            .set("fill", c),
    );
    g
}

/// A text label.
pub(crate) fn text(s: &str, q: [f64; 2], size: f64, c: &str) -> Text {
    Text::new(s)
        .set("x", r2(q[0]))
        .set("y", r2(q[1]))
        .set("font-family", "sans-serif")
        .set("font-size", size)
        .set("fill", c)
}

/// Places labels next to their points, moving one down while it would overlap another.
#[derive(Debug, Default)]
pub(crate) struct Labels {
    placed: Vec<[f64; 2]>,
}

impl Labels {
    pub(crate) fn place(&mut self, q: [f64; 2], style: &Style) -> [f64; 2] {
        let off = style.hinge_radius + 3.0;
        let mut p = [q[0] + off, q[1] - off];
        for _ in 0..6 {
            if self
                .placed
                .iter()
                .all(|o| (o[0] - p[0]).abs() > 12.0 || (o[1] - p[1]).abs() > 12.0)
            {
                break;
            }
            p[1] += 14.0;
        }
        self.placed.push(p);
        p
    }
}

/// An arc arrow about the pixel `q0`, of radius `radius` px, spanning two radians about the
/// direction `theta` (rad, counter-clockwise on the picture), turning counter-clockwise for
/// `sense` > 0; and a place for its label, outside the arc's middle.
pub(crate) fn arc_arrow(
    q0: [f64; 2],
    radius: f64,
    theta: f64,
    sense: f64,
    r: f64,
    c: &str,
) -> (Group, [f64; 2]) {
    let at = |a: f64| [q0[0] + radius * a.cos(), q0[1] - radius * a.sin()];
    let n = 24;
    let mut d = Data::new();
    let mut last = [0.0; 2];
    let mut prev = [0.0; 2];
    for i in 0..=n {
        let a = theta + sense * (-1.0 + 2.0 * f64::from(i) / f64::from(n));
        let p = at(a);
        d = if i == 0 {
            d.move_to((r2(p[0]), r2(p[1])))
        } else {
            d.line_to((r2(p[0]), r2(p[1])))
        };
        prev = last;
        last = p;
    }
    let mut g = Group::new();
    g.append(
        Path::new()
            .set("d", d)
            .set("fill", "none")
            .set("stroke", c)
            .set("stroke-width", 1.5),
    );
    // The head along the arc's last chord, a little past its end.
    let t = [last[0] - prev[0], last[1] - prev[1]];
    let tl = t[0].hypot(t[1]).max(1e-9);
    let end = [last[0] + t[0] / tl * 2.4 * r, last[1] + t[1] / tl * 2.4 * r];
    g.append(arrow(last, end, 1.5, c));
    let l = at(theta);
    let out = [l[0] - q0[0], l[1] - q0[1]];
    let ol = out[0].hypot(out[1]).max(1e-9);
    let label = [
        l[0] + out[0] / ol * 12.0 - 6.0,
        l[1] + out[1] / ol * 12.0 + 5.0,
    ];
    (g, label)
}

/// `x` with about four significant digits, for a label.
pub(crate) fn short(x: f64) -> String {
    let a = x.abs();
    if a >= 1000.0 || a == 0.0 {
        format!("{x:.0}")
    } else if a >= 100.0 {
        format!("{x:.1}")
    } else if a >= 10.0 {
        format!("{x:.2}")
    } else if a >= 0.01 {
        format!("{x:.3}")
    } else {
        format!("{x:.3e}")
    }
}

/// The SVG document of a picture: size, view box and a white background.
pub(crate) fn document(style: &Style, title: &str) -> svg::Document {
    svg::Document::new()
        .set("width", style.width)
        .set("height", style.height)
        .set("viewBox", (0, 0, style.width, style.height))
        .add(svg::node::element::Title::new(title))
        .add(
            svg::node::element::Rectangle::new()
                .set("width", style.width)
                .set("height", style.height)
                .set("fill", "#ffffff"),
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_move_off_each_other() {
        let style = Style::default();
        let mut l = Labels::default();
        let a = l.place([100.0, 100.0], &style);
        let b = l.place([100.0, 100.0], &style);
        let c = l.place([300.0, 100.0], &style);
        assert_eq!(a, [108.0, 92.0]);
        assert_eq!(b, [108.0, 106.0]);
        assert_eq!(c, [308.0, 92.0]);
    }

    #[test]
    fn short_numbers_keep_four_digits() {
        assert_eq!(short(1469.4), "1469");
        assert_eq!(short(726.94), "726.9");
        assert_eq!(short(-0.4624), "-0.462");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(1.5e-5), "1.500e-5");
    }
}
