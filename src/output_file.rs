//! Writing a file a user names. The path is checked before any work is done (its folder
//! exists and takes new files, it names no directory or device, an image's format is known
//! from its extension), and the bytes go to a temporary file in the same folder that is
//! renamed over the target only once complete: a failed write (a full disk) leaves the old
//! file as it was, and a reader never sees half a file.

use image::{ImageFormat, Rgb, RgbImage};
use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use thiserror::Error;

/// Distinguishes the temporary files of one process.
static NEXT: AtomicU64 = AtomicU64::new(0);

/// Why a path cannot be written.
#[derive(Debug, Error)]
pub enum PathError {
    /// The path names a folder.
    #[error(
        "{} is a directory; give a file name in it, such as {}",
        path.display(),
        suggestion.display()
    )]
    Directory {
        /// The path.
        path: PathBuf,
        /// A file in that folder.
        suggestion: PathBuf,
    },
    /// The path names a device, a FIFO or a socket.
    #[error(
        "{} is {what}, not a file: output is written to a new file and renamed into place; \
         give a file name in a folder",
        path.display()
    )]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it names.
        what: &'static str,
    },
    /// The folder is missing.
    #[error("cannot write {}: the folder {} does not exist", path.display(), folder.display())]
    NoFolder {
        /// The path.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
    },
    /// The folder refuses new files.
    #[error(
        "cannot write {}: the folder {} does not take new files ({reason})",
        path.display(),
        folder.display()
    )]
    FolderRefuses {
        /// The path.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
        /// Why a file could not be made there.
        reason: io::Error,
    },
    /// The extension names no image format written.
    #[error(
        "cannot write {}: its extension names no image format written (use .png, .jpg, .tif \
         or .ppm)",
        .0.display()
    )]
    Extension(PathBuf),
}

/// A file that could not be made, written, flushed or renamed into place.
#[derive(Debug, Error)]
#[error("cannot write {}: {reason}", path.display())]
pub struct FileError {
    /// The file.
    pub path: PathBuf,
    /// Why not.
    pub reason: io::Error,
}

/// Why [`write()`] failed: the content's own error, or the file's.
#[derive(Debug, Error)]
pub enum WriteError<E> {
    /// The content could not be made or written; its error says so.
    #[error("{0}")]
    Content(E),
    /// The file could not be made, flushed or renamed into place.
    #[error(transparent)]
    File(#[from] FileError),
}

/// Why an image could not be saved.
#[derive(Debug, Error)]
pub enum SaveError {
    /// The path cannot be written.
    #[error(transparent)]
    Path(#[from] PathError),
    /// The file could not be written.
    #[error(transparent)]
    File(#[from] FileError),
    /// The image could not be encoded.
    #[error("cannot write {}: {reason}", path.display())]
    Encode {
        /// The file.
        path: PathBuf,
        /// The encoder's error.
        reason: image::ImageError,
    },
}

/// Checks that `path` can be written as a new or replaced file, or says why not; where it
/// names a folder, the message suggests `example` (a file name, `out.png`) in it.
pub fn check(path: &Path, example: &str) -> Result<(), PathError> {
    match std::fs::metadata(path) {
        Ok(metadata) if metadata.is_dir() => {
            return Err(PathError::Directory {
                path: path.to_owned(),
                suggestion: path.join(example),
            })
        }
        Ok(metadata) if !metadata.is_file() => {
            return Err(PathError::NotAFile {
                path: path.to_owned(),
                what: crate::regular_file::kind(&metadata),
            })
        }
        _ => {}
    }
    let folder = folder_of(path);
    if !folder.is_dir() {
        return Err(PathError::NoFolder {
            path: path.to_owned(),
            folder,
        });
    }
    // Made and removed again: the only sure test that the folder takes new files.
    let (probe, probe_path) = temporary(path).map_err(|reason| PathError::FolderRefuses {
        path: path.to_owned(),
        folder,
        reason,
    })?;
    drop(probe);
    let _ = std::fs::remove_file(probe_path);
    Ok(())
}

/// Checks that `path` can be written, and that its extension names an image format that
/// can be written; returns the format.
pub fn check_image(path: &Path) -> Result<ImageFormat, PathError> {
    check(path, "out.png")?;
    ImageFormat::from_path(path)
        .ok()
        .filter(ImageFormat::writing_enabled)
        .ok_or_else(|| PathError::Extension(path.to_owned()))
}

/// Writes `path` through `write`, atomically: into a temporary file beside it, flushed to
/// disk, then renamed over it. On any failure the temporary file is removed and the old file
/// left as it was.
pub fn write<E>(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), E>,
) -> Result<(), WriteError<E>> {
    let cannot = |reason| {
        WriteError::File(FileError {
            path: path.to_owned(),
            reason,
        })
    };
    let (file, partial) = temporary(path).map_err(cannot)?;
    let mut out = BufWriter::new(file);
    let written = write(&mut out)
        .map_err(WriteError::Content)
        .and_then(|()| {
            out.into_inner()
                .map_err(|e| cannot(e.into_error()))
                .and_then(|file| file.sync_all().map_err(cannot))
        })
        .and_then(|()| std::fs::rename(&partial, path).map_err(cannot));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written
}

/// Writes `bytes` as `path`, atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    write(path, |out| out.write_all(bytes)).map_err(|error| match error {
        WriteError::Content(reason) => FileError {
            path: path.to_owned(),
            reason,
        },
        WriteError::File(error) => error,
    })
}

/// Writes 0x00RRGGBB pixels, row by row from the top, as an image in the format of `path`'s
/// extension, atomically.
pub fn save_rgb(path: &Path, pixels: &[u32], (width, height): (u32, u32)) -> Result<(), SaveError> {
    let format = check_image(path)?;
    let image = RgbImage::from_fn(width, height, |x, y| {
        let rgb = pixels[(y * width + x) as usize];
        Rgb([(rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8])
    });
    write(path, |out| image.write_to(out, format)).map_err(|error| match error {
        WriteError::Content(reason) => SaveError::Encode {
            path: path.to_owned(),
            reason,
        },
        WriteError::File(error) => error.into(),
    })
}

/// The folder `path` lies in (the current one for a bare file name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_owned(),
        _ => PathBuf::from("."),
    }
}

/// A new, hidden file beside `path`.
fn temporary(path: &Path) -> io::Result<(File, PathBuf)> {
    let name = path
        .file_name()
        .map_or("output".into(), |n| n.to_string_lossy());
    let folder = folder_of(path);
    loop {
        let number = NEXT.fetch_add(1, Ordering::Relaxed);
        let partial = folder.join(format!(".{name}.{}-{number}.partial", std::process::id()));
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&partial)
        {
            Ok(file) => return Ok((file, partial)),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_partial_one() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        std::fs::write(&path, "old").unwrap();
        let failed = write(&path, |out| {
            out.write_all(b"half").map_err(|e| e.to_string())?;
            Err("the disk is full".to_owned())
        });
        assert_eq!(failed.unwrap_err().to_string(), "the disk is full");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        write_bytes(&path, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn paths_that_cannot_be_written_say_why() {
        let dir = tempfile::tempdir().unwrap();
        let folder = check(dir.path(), "stats.json").unwrap_err().to_string();
        let suggested = dir.path().join("stats.json").display().to_string();
        assert!(folder.contains("is a directory"), "{folder}");
        assert!(
            folder.ends_with(&format!("such as {suggested}")),
            "{folder}"
        );
        let image_folder = check_image(dir.path()).unwrap_err().to_string();
        assert!(image_folder.contains("out.png"), "{image_folder}");
        let device = check(Path::new("/dev/full"), "out.txt")
            .unwrap_err()
            .to_string();
        assert!(device.contains("character device"), "{device}");
        let missing = check(&dir.path().join("no/such/out.png"), "out.png")
            .unwrap_err()
            .to_string();
        assert!(missing.contains("does not exist"), "{missing}");
        let extension = check_image(&dir.path().join("out.xyz"))
            .unwrap_err()
            .to_string();
        assert!(extension.contains("extension"), "{extension}");
        assert_eq!(
            check_image(&dir.path().join("out.png")).ok(),
            Some(ImageFormat::Png)
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
