//! Observed orders: the least-squares slope of log(error) against log(step), and a reader
//! for the CSV files the example writes, so that a test can check the committed data too.

/// The least-squares slope of log10(y) against log10(x).
pub fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) =
        x.iter().zip(y).map(|(a, b)| (a.log10(), b.log10())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// A CSV table with a header line: the rows as strings, looked up by column name.
pub struct Csv {
    header: Vec<String>,
    /// The data rows.
    pub rows: Vec<Vec<String>>,
}

impl Csv {
    /// Parses comma-separated text (no quoting: the example writes none).
    pub fn parse(text: &str) -> Self {
        let mut lines = text.lines().filter(|l| !l.is_empty());
        let split = |l: &str| l.split(',').map(str::to_owned).collect::<Vec<_>>();
        let header = lines.next().map(split).unwrap_or_default();
        Self {
            header,
            rows: lines.map(split).collect(),
        }
    }

    /// The index of a column.
    pub fn col(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    }

    /// The values of `column` (as f64) of the rows whose `key` columns equal `values`.
    pub fn select(&self, key: &[(&str, &str)], column: &str) -> Vec<f64> {
        let c = self.col(column);
        let keys: Vec<(usize, &str)> = key.iter().map(|(k, v)| (self.col(k), *v)).collect();
        self.rows
            .iter()
            .filter(|r| keys.iter().all(|(i, v)| r[*i] == *v))
            .map(|r| r[c].parse().expect("a number"))
            .collect()
    }
}
