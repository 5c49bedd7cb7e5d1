//! Counting of texel and height fetches. Kernels are generic over [`Counter`], so the
//! uncounted fast path ([`NoCount`]) compiles to nothing while measurement runs use [`Tally`].

/// Something that is told how many fetches a kernel made.
pub trait Counter {
    /// Records `n` fetches.
    fn count(&mut self, n: u32);
}

/// A counter that counts nothing, for timing runs.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoCount;

impl Counter for NoCount {
    #[inline(always)]
    fn count(&mut self, _n: u32) {}
}

/// A counter that sums every fetch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally(pub u64);

impl Counter for Tally {
    #[inline(always)]
    fn count(&mut self, n: u32) {
        self.0 += n as u64;
    }
}
