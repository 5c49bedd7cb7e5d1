//! The data a chart draws: named point series and bar series.

/// One named set of points in a [`scatter_svg`](super::scatter_svg).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Series {
    /// Name shown in the legend (e.g. the technique).
    pub name: String,
    /// `(x, y)` points in data units; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Optional small text beside each point (e.g. the parameter value); empty for none, or
    /// one per point (missing entries draw nothing).
    pub labels: Vec<String>,
    /// Whether to join the points with a line, in the order given.
    pub connect: bool,
}

impl Series {
    /// A series of unconnected, unlabelled points.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), points, labels: Vec::new(), connect: false }
    }

    /// Adds one label per point.
    pub fn with_labels(mut self, labels: Vec<String>) -> Self {
        self.labels = labels;
        self
    }

    /// Joins the points with a line in the order given.
    pub fn connected(mut self) -> Self {
        self.connect = true;
        self
    }
}

/// One named set of bars in a [`bar_svg`](super::bar_svg): one value per category.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BarSeries {
    /// Name shown in the legend (e.g. the technique).
    pub name: String,
    /// Value per category, in category order; missing or non-finite values draw no bar.
    pub values: Vec<f64>,
}

impl BarSeries {
    /// A bar series.
    pub fn new(name: impl Into<String>, values: Vec<f64>) -> Self {
        BarSeries { name: name.into(), values }
    }
}
