//! The scan of an SVG for non-finite numbers, shared by the pictures' tests and the hostile
//! suite of the linkage engine.
#![allow(dead_code)]

/// Every number in every attribute of `svg` (the names in `class` aside) parses as a finite
/// `f64`, and no attribute holds a word `inf`, `infinity` or `NaN`: an SVG reader would take
/// a non-finite coordinate for an error, or draw nothing.
pub fn assert_finite_svg(svg: &str, name: &str) {
    let mut rest = svg;
    let mut numbers = 0;
    while let Some(lt) = rest.find('<') {
        let end = rest[lt..].find('>').map_or(rest.len(), |e| lt + e);
        let tag = &rest[lt..end];
        for (i, part) in tag.split('"').enumerate() {
            // Odd parts are attribute values; the part before names the attribute.
            if i % 2 == 0
                || tag
                    .split('"')
                    .nth(i - 1)
                    .is_some_and(|n| n.trim_end().ends_with("class="))
            {
                continue;
            }
            let tokens = part.split(|c: char| !(c.is_ascii_alphanumeric() || "+-.".contains(c)));
            for t in tokens.filter(|t| !t.is_empty()) {
                let lower = t.to_ascii_lowercase();
                let word = lower.trim_start_matches(['+', '-']);
                assert!(
                    !matches!(word, "inf" | "infinity" | "nan"),
                    "{name}: a non-finite number {t:?} in {tag:.200}"
                );
                if t.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '.')
                    && let Ok(x) = t.parse::<f64>()
                {
                    assert!(x.is_finite(), "{name}: {t:?} in {tag:.200}");
                    numbers += 1;
                }
            }
        }
        rest = &rest[end..];
    }
    assert!(numbers > 0, "{name}: no numbers in the SVG");
}
