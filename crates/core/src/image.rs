//! A flat, row-major image of any pixel type. Pixel (0,0) is the top-left corner.

use crate::error::{CoreError, Result};

/// Largest width or height accepted anywhere in renderlab.
pub const MAX_DIMENSION: u32 = 16_384;
/// Largest pixel count accepted anywhere in renderlab (64 Mpixels).
pub const MAX_PIXELS: u64 = 64 * 1024 * 1024;

/// Validates image dimensions before anything is allocated.
///
/// `what` names the file or parameter in the error message.
pub fn check_dimensions(what: &str, width: u64, height: u64) -> Result<()> {
    let err = |reason| Err(CoreError::Dimensions { what: what.to_string(), width, height, reason });
    if width == 0 || height == 0 {
        return err("width and height must be at least 1");
    }
    if width > MAX_DIMENSION as u64 || height > MAX_DIMENSION as u64 {
        return err("a side exceeds the limit of 16384 pixels");
    }
    if width * height > MAX_PIXELS {
        return err("more than 64 Mpixels");
    }
    Ok(())
}

/// `i` wrapped into `0..n` (repeat addressing). In-range indices, the common case in texture
/// lookups, skip the integer division.
#[inline(always)]
pub fn wrap_index(i: i64, n: u32) -> usize {
    let n = n as i64;
    if (i as u64) < n as u64 {
        i as usize
    } else if i < 0 && i >= -n {
        (i + n) as usize
    } else if i >= n && i < 2 * n {
        (i - n) as usize
    } else {
        i.rem_euclid(n) as usize
    }
}

/// A `width × height` grid of pixels stored row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct Image<T> {
    width: u32,
    height: u32,
    data: Vec<T>,
}

impl<T: Copy> Image<T> {
    /// An image filled with `value`. Panics only on dimensions that
    /// [`check_dimensions`] would refuse; validate user input first.
    pub fn new(width: u32, height: u32, value: T) -> Self {
        assert!(width > 0 && height > 0, "image dimensions must be positive");
        Self { width, height, data: vec![value; width as usize * height as usize] }
    }

    /// An image whose pixel (x, y) is `f(x, y)`.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> T) -> Self {
        assert!(width > 0 && height > 0, "image dimensions must be positive");
        let mut data = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                data.push(f(x, y));
            }
        }
        Self { width, height, data }
    }

    /// Like [`Image::from_fn`], rows computed in parallel (deterministic: each pixel
    /// depends only on its coordinates).
    pub fn from_fn_par(width: u32, height: u32, f: impl Fn(u32, u32) -> T + Sync) -> Self
    where
        T: Send + Sync + Default,
    {
        use rayon::prelude::*;
        assert!(width > 0 && height > 0, "image dimensions must be positive");
        let mut data = vec![T::default(); width as usize * height as usize];
        data.par_chunks_mut(width as usize).enumerate().for_each(|(y, row)| {
            for (x, px) in row.iter_mut().enumerate() {
                *px = f(x as u32, y as u32);
            }
        });
        Self { width, height, data }
    }

    /// Wraps an existing buffer; errors if its length is not `width * height`.
    pub fn from_vec(width: u32, height: u32, data: Vec<T>) -> Result<Self> {
        check_dimensions("image buffer", width as u64, height as u64)?;
        if data.len() != width as usize * height as usize {
            return Err(CoreError::param(
                "image buffer",
                data.len(),
                format!("length must be {}x{}", width, height),
            ));
        }
        Ok(Self { width, height, data })
    }

    /// Width in pixels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// `(width, height)`.
    #[inline]
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The pixel at (x, y). Panics when out of bounds.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> T {
        self.data[y as usize * self.width as usize + x as usize]
    }

    /// Sets the pixel at (x, y). Panics when out of bounds.
    #[inline]
    pub fn set(&mut self, x: u32, y: u32, value: T) {
        let w = self.width as usize;
        self.data[y as usize * w + x as usize] = value;
    }

    /// The pixel at (x, y) with coordinates wrapped (repeat addressing).
    #[inline]
    pub fn get_wrapped(&self, x: i64, y: i64) -> T {
        self.data[wrap_index(y, self.height) * self.width as usize + wrap_index(x, self.width)]
    }

    /// The pixel at (x, y) with coordinates clamped to the edge.
    #[inline]
    pub fn get_clamped(&self, x: i64, y: i64) -> T {
        let xx = x.clamp(0, self.width as i64 - 1) as usize;
        let yy = y.clamp(0, self.height as i64 - 1) as usize;
        self.data[yy * self.width as usize + xx]
    }

    /// All pixels, row-major.
    #[inline]
    pub fn pixels(&self) -> &[T] {
        &self.data
    }

    /// All pixels, mutable, row-major.
    #[inline]
    pub fn pixels_mut(&mut self) -> &mut [T] {
        &mut self.data
    }

    /// One row of pixels.
    #[inline]
    pub fn row(&self, y: u32) -> &[T] {
        let w = self.width as usize;
        &self.data[y as usize * w..(y as usize + 1) * w]
    }

    /// Consumes the image and returns its buffer.
    pub fn into_vec(self) -> Vec<T> {
        self.data
    }

    /// A new image with `f` applied to every pixel.
    pub fn map<U: Copy>(&self, f: impl FnMut(T) -> U) -> Image<U> {
        Image { width: self.width, height: self.height, data: self.data.iter().copied().map(f).collect() }
    }
}
