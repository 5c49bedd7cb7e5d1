//! Counting of floating-point arithmetic. The mapping and Jacobian kernels are generic over
//! [`OpCounter`]: timing runs pass [`NoOps`], which compiles to nothing, and analysis runs pass
//! [`OpTally`], which records every addition, subtraction, multiplication and division the
//! kernel performs as written. Integer loop arithmetic and int→float conversions of pixel
//! indices are not counted (the thesis does not count them either).

/// Something that is told which floating-point operations a kernel performed.
pub trait OpCounter {
    /// Records `n` additions.
    fn add(&mut self, n: u32);
    /// Records `n` subtractions (counted apart from additions because the thesis does so).
    fn sub(&mut self, n: u32);
    /// Records `n` multiplications.
    fn mul(&mut self, n: u32);
    /// Records `n` divisions (a reciprocal counts as one division).
    fn div(&mut self, n: u32);
}

/// Counts nothing; the fast path for timing.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoOps;

impl OpCounter for NoOps {
    #[inline(always)]
    fn add(&mut self, _: u32) {}
    #[inline(always)]
    fn sub(&mut self, _: u32) {}
    #[inline(always)]
    fn mul(&mut self, _: u32) {}
    #[inline(always)]
    fn div(&mut self, _: u32) {}
}

/// Sums of every counted operation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpTally {
    /// Additions.
    pub add: u64,
    /// Subtractions.
    pub sub: u64,
    /// Multiplications.
    pub mul: u64,
    /// Divisions.
    pub div: u64,
}

impl OpCounter for OpTally {
    #[inline(always)]
    fn add(&mut self, n: u32) {
        self.add += n as u64;
    }
    #[inline(always)]
    fn sub(&mut self, n: u32) {
        self.sub += n as u64;
    }
    #[inline(always)]
    fn mul(&mut self, n: u32) {
        self.mul += n as u64;
    }
    #[inline(always)]
    fn div(&mut self, n: u32) {
        self.div += n as u64;
    }
}

/// Operation counts as real numbers, for per-pixel averages (a k-stride set-up spread over a
/// row gives fractions).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OpRate {
    /// Additions.
    pub add: f64,
    /// Subtractions.
    pub sub: f64,
    /// Multiplications.
    pub mul: f64,
    /// Divisions.
    pub div: f64,
}

impl OpRate {
    /// Weighted cycle estimate with one cost per addition/subtraction, multiplication and
    /// division — the kind of model the thesis's "CPU clock cycles of basic operations"
    /// output implies (it never gives its table, so the weights are the caller's).
    pub fn cycles(&self, add: f64, mul: f64, div: f64) -> f64 {
        (self.add + self.sub) * add + self.mul * mul + self.div * div
    }
}

/// The cost of a row kernel split into a fixed part and a part per pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RowCost {
    /// Operations done once per row (or per span), whatever its length.
    pub setup: OpRate,
    /// Operations per pixel.
    pub per_pixel: OpRate,
}

/// Measures a kernel's [`RowCost`] by running it on two lengths `n1 < n2` and differencing:
/// the per-pixel rate is `(T(n2) − T(n1)) / (n2 − n1)` and the set-up is what remains of
/// `T(n1)`. Choose lengths that are multiples of any stride the kernel uses. The lengths
/// are taken in either order; equal lengths give an all-zero cost.
pub fn measure_row_cost(n1: usize, n2: usize, mut run: impl FnMut(usize, &mut OpTally)) -> RowCost {
    let (n1, n2) = (n1.min(n2), n1.max(n2));
    if n1 == n2 {
        return RowCost::default();
    }
    let mut t1 = OpTally::default();
    run(n1, &mut t1);
    let mut t2 = OpTally::default();
    run(n2, &mut t2);
    let dn = (n2 - n1) as f64;
    let rate = |a: u64, b: u64| (b as f64 - a as f64) / dn;
    let per_pixel = OpRate {
        add: rate(t1.add, t2.add),
        sub: rate(t1.sub, t2.sub),
        mul: rate(t1.mul, t2.mul),
        div: rate(t1.div, t2.div),
    };
    let fixed = |a: u64, r: f64| a as f64 - r * n1 as f64;
    let setup = OpRate {
        add: fixed(t1.add, per_pixel.add),
        sub: fixed(t1.sub, per_pixel.sub),
        mul: fixed(t1.mul, per_pixel.mul),
        div: fixed(t1.div, per_pixel.div),
    };
    RowCost { setup, per_pixel }
}
