//! Opening a file a user names (a height map, a scene): only a regular file is opened, so
//! that a directory, a device such as `/dev/zero`, a FIFO or a socket is refused at once
//! instead of blocking in `open` (a FIFO waits for a writer) or streaming without end.

use std::fs::{File, Metadata, OpenOptions};
use std::io;
use std::path::Path;

/// Why a path could not be opened as a regular file.
#[derive(Debug)]
pub enum OpenError {
    /// It names something else; the words say what ("a directory", "a FIFO (named pipe)", ...).
    NotAFile(&'static str),
    /// It could not be looked at or opened.
    Io(io::Error),
}

/// Opens `path` (following links) for reading if it is a regular file; returns the file and
/// its length.
pub fn open(path: &Path) -> Result<(File, u64), OpenError> {
    // Looked at before opening: opening a FIFO for reading blocks until a writer appears.
    let metadata = std::fs::metadata(path).map_err(OpenError::Io)?;
    regular(&metadata)?;
    let file = options().open(path).map_err(OpenError::Io)?;
    // Looked at again through the open file: the path may have been replaced in between.
    let metadata = file.metadata().map_err(OpenError::Io)?;
    regular(&metadata)?;
    if kernel_pseudo_file(&file) {
        return Err(OpenError::NotAFile(
            "a kernel pseudo-file (/proc or /sys), whose size says nothing of its contents",
        ));
    }
    Ok((file, metadata.len()))
}

/// Read-only; on Unix also non-blocking, so that a FIFO put in place of the file between the
/// look and the open cannot block the open (reads of a regular file ignore the flag).
fn options() -> OpenOptions {
    let mut options = OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options
}

fn regular(metadata: &Metadata) -> Result<(), OpenError> {
    if metadata.is_file() {
        Ok(())
    } else {
        Err(OpenError::NotAFile(kind(metadata)))
    }
}

/// What a path that is not a regular file names, in words.
pub(crate) fn kind(metadata: &Metadata) -> &'static str {
    let kind = metadata.file_type();
    if kind.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if kind.is_char_device() {
            return "a character device";
        }
        if kind.is_block_device() {
            return "a block device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    "a special file"
}

/// Whether `file` lies on /proc or /sys: "regular" files there say they are empty (or 4096
/// bytes) whatever they hold, and some never end.
#[cfg(target_os = "linux")]
fn kernel_pseudo_file(file: &File) -> bool {
    use std::os::fd::AsRawFd;
    let mut stat = std::mem::MaybeUninit::<libc::statfs>::zeroed();
    // SAFETY: `stat` has room for a `statfs`, and the descriptor is open for the call.
    if unsafe { libc::fstatfs(file.as_raw_fd(), stat.as_mut_ptr()) } != 0 {
        return false;
    }
    // SAFETY: `fstatfs` succeeded, so it filled `stat`.
    let kind = unsafe { stat.assume_init() }.f_type;
    kind == libc::PROC_SUPER_MAGIC || kind == libc::SYSFS_MAGIC
}

#[cfg(not(target_os = "linux"))]
fn kernel_pseudo_file(_: &File) -> bool {
    false
}
