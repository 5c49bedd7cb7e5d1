//! Zeroed storage in whole cache lines, on the operating system's large pages where it offers
//! them: what a bottom level's [`crate::node::Arena`] keeps its nodes and blocks in.
//!
//! A walk on a mesh larger than the caches reads lines scattered over tens of megabytes, and
//! with 4 KiB pages most of those reads also miss the processor's address translation cache
//! (2048 entries on AMD Zen 3, 8 MiB of 4 KiB pages), each miss a walk of the page tables
//! before the line itself is asked for. A storage of at least [`ADVISE_FROM`] bytes is
//! therefore aligned to [`HUGE`] and, on Linux, advised as a candidate for transparent huge
//! pages (`madvise(MADV_HUGEPAGE)`, which the kernel honours in its `always` and `madvise`
//! modes) before it is first written, so the pages are 2 MiB from the first fault. Embree's
//! process holds its hierarchy on them too (61–65 MB of them while it traces the terrain).
//! Measured (`scripts/paired_passes.py`, single rays, the scenes of BENCHMARKS.md's Embree
//! section, AMD Zen 3, medians of 3 or 4 rounds): the 1M-triangle terrain's bounce rays +4 to
//! +6 % (its packets +4 %), the 3.3M-triangle blobs' primary, bounce and shadow rays +7 to
//! +9 %, the terrain's primary and shadow rays unchanged. Elsewhere, or where the kernel
//! declines, the storage is ordinary pages and nothing else differs.
//!
//! A storage of a few megabytes gains too, though the second-level translation cache holds
//! its 4 KiB pages: the first level's (64 entries on Zen 3, 256 KiB) does not, and the caches
//! are indexed by physical address, so a storage on scattered 4 KiB pages meets a different
//! pattern of conflicting lines in every process. On large pages the pattern is the layout's
//! own. The blob's hierarchy (3.8 MB; Embree's holds its own on two large pages), 12 fresh
//! processes of each build alternated, median pass: primary rays 32.6 → 31.9 ms, bounce rays
//! 26.3 → 24.6 ms, shadow rays 21.3 → 21.1 ms. Its last, partial large page is taken whole
//! where that adds at most an eighth to the storage ([`Lines::layout`]).

use std::alloc::{alloc, dealloc, handle_alloc_error, Layout};
use std::ptr::NonNull;

/// One cache line of storage.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct Line(pub [u8; 64]);

/// A large page: 2 MiB, the x86-64 and AArch64 transparent huge page.
pub(crate) const HUGE: usize = 2 << 20;

/// Bytes from which a storage is aligned to, and advised onto, large pages: one large page.
pub(crate) const ADVISE_FROM: usize = HUGE;

/// Zeroed cache lines in one allocation, on large pages from [`ADVISE_FROM`] bytes (see the
/// module); read and written as a slice of lines, like the `Vec<Line>` it replaces.
pub(crate) struct Lines {
    ptr: NonNull<Line>,
    len: usize,
}

// SAFETY: `Lines` owns plain bytes, like a `Vec<Line>`.
unsafe impl Send for Lines {}
// SAFETY: as above; shared access only reads.
unsafe impl Sync for Lines {}

impl Lines {
    /// `len` zeroed lines.
    pub(crate) fn zeroed(len: usize) -> Lines {
        let Some(layout) = Lines::layout(len) else {
            return Lines { ptr: NonNull::dangling(), len: 0 };
        };
        // SAFETY: the layout's size is non-zero.
        let ptr = unsafe { alloc(layout) };
        let Some(ptr) = NonNull::new(ptr as *mut Line) else { handle_alloc_error(layout) };
        if layout.align() == HUGE {
            advise_huge(ptr.as_ptr() as *mut u8, layout.size());
        }
        // SAFETY: the allocation holds `len` lines; writing zeros is what first touches the
        // pages (after the advice, so they fault in large).
        unsafe { std::ptr::write_bytes(ptr.as_ptr(), 0, len) };
        Lines { ptr, len }
    }

    /// The allocation's layout for `len` lines (`None` for none): aligned to [`HUGE`] from
    /// [`ADVISE_FROM`] bytes, to a line below. A large storage's size is rounded up to whole
    /// large pages where that adds at most an eighth (the kernel backs only whole aligned
    /// large pages of an advised range; the rest of a partial one stays on 4 KiB pages).
    fn layout(len: usize) -> Option<Layout> {
        let bytes = len.checked_mul(64).expect("storage size overflows");
        let (bytes, align) = if bytes >= ADVISE_FROM {
            let whole = bytes.checked_next_multiple_of(HUGE).expect("storage size overflows");
            (if whole - bytes <= bytes / 8 { whole } else { bytes }, HUGE)
        } else {
            (bytes, 64)
        };
        (len > 0).then(|| Layout::from_size_align(bytes, align).expect("storage size overflows"))
    }
}

impl std::ops::Deref for Lines {
    type Target = [Line];

    #[inline(always)]
    fn deref(&self) -> &[Line] {
        // SAFETY: `ptr` holds `len` initialised lines (or is dangling with `len` 0).
        unsafe { std::slice::from_raw_parts(self.ptr.as_ptr(), self.len) }
    }
}

impl std::ops::DerefMut for Lines {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut [Line] {
        // SAFETY: as in `deref`, and `self` is borrowed uniquely.
        unsafe { std::slice::from_raw_parts_mut(self.ptr.as_ptr(), self.len) }
    }
}

impl Default for Lines {
    fn default() -> Lines {
        Lines::zeroed(0)
    }
}

impl Clone for Lines {
    fn clone(&self) -> Lines {
        let mut copy = Lines::zeroed(self.len);
        copy.copy_from_slice(self);
        copy
    }
}

impl Drop for Lines {
    fn drop(&mut self) {
        if let Some(layout) = Lines::layout(self.len) {
            // SAFETY: allocated in `zeroed` with this layout.
            unsafe { dealloc(self.ptr.as_ptr() as *mut u8, layout) };
        }
    }
}

/// Asks the kernel to back `[ptr, ptr + bytes)` with transparent huge pages. Only advice: a
/// refusal (an older kernel, huge pages off) leaves ordinary pages.
#[cfg(target_os = "linux")]
fn advise_huge(ptr: *mut u8, bytes: usize) {
    // SAFETY: the range is one live allocation of ours; the advice changes no contents.
    let _ = unsafe { libc::madvise(ptr as *mut libc::c_void, bytes, libc::MADV_HUGEPAGE) };
}

/// Elsewhere: no advice to give.
#[cfg(not(target_os = "linux"))]
fn advise_huge(_ptr: *mut u8, _bytes: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_of_any_size_is_zeroed_aligned_and_copies() {
        for len in [0, 1, 3, ADVISE_FROM / 64 - 1, ADVISE_FROM / 64, ADVISE_FROM / 64 + 5] {
            let mut s = Lines::zeroed(len);
            assert_eq!(s.len(), len);
            assert!(s.iter().all(|l| l.0 == [0; 64]));
            let align = if len * 64 >= ADVISE_FROM { HUGE } else { 64 };
            assert_eq!(s.as_ptr() as usize % align, 0, "{len} lines");
            if let Some(last) = s.last_mut() {
                last.0[63] = 7;
            }
            let c = s.clone();
            assert_eq!(c.len(), len);
            assert_eq!(c.last().map(|l| l.0[63]), (len > 0).then_some(7));
        }
    }

    /// A large storage is rounded up to whole large pages where that adds at most an eighth,
    /// and a small one is never rounded.
    #[test]
    fn large_storage_takes_whole_large_pages_at_small_cost() {
        let lines = |bytes: usize| bytes / 64;
        let size = |bytes: usize| Lines::layout(lines(bytes)).map(|l| (l.size(), l.align()));
        assert_eq!(size(HUGE - 64), Some((HUGE - 64, 64)));
        assert_eq!(size(HUGE), Some((HUGE, HUGE)));
        // 3.8 MB (the blob's hierarchy) → two large pages; 2.1 MiB stays as it is.
        assert_eq!(size(3_800_000 / 64 * 64), Some((2 * HUGE, HUGE)));
        assert_eq!(size(HUGE + HUGE / 16), Some((HUGE + HUGE / 16, HUGE)));
        assert_eq!(size(8 * HUGE + 64), Some((9 * HUGE, HUGE)));
    }
}
