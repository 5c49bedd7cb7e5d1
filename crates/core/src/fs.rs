//! Bounded file reading: the one way renderlab reads an input file whole.
//!
//! A file's size as reported by the file system is not a bound on what reading it returns:
//! `/dev/zero` and `/dev/urandom` report 0 and never end, a FIFO blocks its reader until a
//! writer appears (possibly forever), and a regular file may grow while it is read. So
//! [`read_bounded`] follows symbolic links, refuses anything that is not a regular file
//! before reading a byte (FIFO, character or block device, socket, directory), and reads
//! through [`std::io::Read::take`] with one byte more than the limit, so that a file larger
//! than the limit is refused with a message however its size was reported.
//!
//! On Unix the file is opened with `O_NONBLOCK` and checked again through the open handle,
//! so a regular file swapped for a FIFO between the check and the open cannot block the
//! reader either (the flag has no effect on reading a regular file).
//!
//! Errors are [`std::io::Error`]s whose message says what was wrong, without the path (the
//! caller names the file): kind [`ErrorKind::NotFound`] and the like as the system reports
//! them, [`ErrorKind::InvalidInput`] for what is not a regular file and
//! [`ErrorKind::FileTooLarge`] for a file over the limit.

use std::fs::{File, Metadata};
use std::io::{ErrorKind, Read};
use std::path::Path;

/// One mebibyte, the unit limits are stated in.
pub const MIB: u64 = 1 << 20;

/// Largest image file read (PNG, JPEG, TGA, EXR): 1 GiB. The largest image accepted
/// (64 Mpixels, see [`crate::image::MAX_PIXELS`]) as uncompressed RGBA float EXR is 1 GiB
/// of pixel data; every other format stores such an image in less.
pub const MAX_IMAGE_FILE_BYTES: u64 = 1024 * MIB;

/// Largest small configuration or bookkeeping file (the viewer's settings and the like):
/// 1 MiB, a thousand times what such a file holds.
pub const MAX_SETTINGS_FILE_BYTES: u64 = MIB;

/// Reads the whole regular file at `path` (symbolic links followed), refusing anything that
/// is not a regular file before reading it and any file of more than `limit` bytes, whatever
/// size the file system reports for it.
pub fn read_bounded(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    check_regular(&meta)?;
    let file = open_nonblocking(path)?;
    // The handle may not be the file that was checked (it can be replaced in between).
    let meta = file.metadata()?;
    check_regular(&meta)?;
    // Reserve what the file says it holds (within the limit) so that a large file is read
    // without the vector doubling past it; the reservation, like the growth while reading,
    // fails with an error (ErrorKind::OutOfMemory) instead of aborting when memory is short.
    let mut bytes = Vec::new();
    let hint = usize::try_from(meta.len().min(limit)).unwrap_or(usize::MAX).saturating_add(1);
    bytes.try_reserve_exact(hint).map_err(|_| {
        std::io::Error::new(ErrorKind::OutOfMemory, format!("cannot reserve {hint} bytes to read it"))
    })?;
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(limit));
    }
    Ok(bytes)
}

/// [`read_bounded`] for text: the file must be UTF-8 (refused with
/// [`ErrorKind::InvalidData`] otherwise).
pub fn read_bounded_to_string(path: &Path, limit: u64) -> std::io::Result<String> {
    let bytes = read_bounded(path, limit)?;
    String::from_utf8(bytes)
        .map_err(|e| std::io::Error::new(ErrorKind::InvalidData, format!("not UTF-8 text ({e})")))
}

/// The error for a file over `limit` bytes, stating the limit in MiB (or bytes, below one).
fn too_large(limit: u64) -> std::io::Error {
    let (mib, rest) = (limit / MIB, limit % MIB);
    let stated = if mib > 0 && rest == 0 { format!("{mib} MiB") } else { format!("{limit} bytes") };
    std::io::Error::new(ErrorKind::FileTooLarge, format!("file is larger than {stated}"))
}

/// Refuses what is not a regular file, naming what it is.
fn check_regular(meta: &Metadata) -> std::io::Result<()> {
    let ft = meta.file_type();
    if ft.is_file() {
        return Ok(());
    }
    let what = if ft.is_dir() { "a directory" } else { special_kind(&ft) };
    Err(std::io::Error::new(ErrorKind::InvalidInput, format!("not a regular file (it is {what})")))
}

#[cfg(unix)]
fn special_kind(ft: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if ft.is_fifo() {
        "a FIFO"
    } else if ft.is_char_device() {
        "a character device"
    } else if ft.is_block_device() {
        "a block device"
    } else if ft.is_socket() {
        "a socket"
    } else {
        "not a file"
    }
}

#[cfg(not(unix))]
fn special_kind(_: &std::fs::FileType) -> &'static str {
    "a special file"
}

#[cfg(unix)]
fn open_nonblocking(path: &Path) -> std::io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path)
}

#[cfg(not(unix))]
fn open_nonblocking(path: &Path) -> std::io::Result<File> {
    File::open(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limit_is_stated_in_mib_or_bytes() {
        assert_eq!(too_large(MIB).to_string(), "file is larger than 1 MiB");
        assert_eq!(too_large(1024 * MIB).to_string(), "file is larger than 1024 MiB");
        assert_eq!(too_large(100).to_string(), "file is larger than 100 bytes");
    }

    #[test]
    fn a_file_of_exactly_the_limit_is_read_and_one_byte_more_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f");
        std::fs::write(&path, [7u8; 10]).unwrap();
        assert_eq!(read_bounded(&path, 10).unwrap(), vec![7u8; 10]);
        let err = read_bounded(&path, 9).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::FileTooLarge);
    }
}
