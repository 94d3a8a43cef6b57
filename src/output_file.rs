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

/// Distinguishes the temporary files of one process.
static NEXT: AtomicU64 = AtomicU64::new(0);

/// Checks that `path` can be written as a new or replaced file, or says why not; where it
/// names a folder, the message suggests `example` (a file name, `out.png`) in it.
pub fn check(path: &Path, example: &str) -> Result<(), String> {
    let shown = path.display();
    match std::fs::metadata(path) {
        Ok(metadata) if metadata.is_dir() => {
            return Err(format!(
                "{shown} is a directory; give a file name in it, such as {}",
                path.join(example).display()
            ))
        }
        Ok(metadata) if !metadata.is_file() => {
            return Err(format!(
                "{shown} is {}, not a file: output is written to a new file and renamed \
                 into place; give a file name in a folder",
                crate::regular_file::kind(&metadata)
            ))
        }
        _ => {}
    }
    let folder = folder_of(path);
    if !folder.is_dir() {
        return Err(format!(
            "cannot write {shown}: the folder {} does not exist",
            folder.display()
        ));
    }
    // Made and removed again: the only sure test that the folder takes new files.
    let (probe, probe_path) = temporary(path).map_err(|e| {
        format!(
            "cannot write {shown}: the folder {} does not take new files ({e})",
            folder.display()
        )
    })?;
    drop(probe);
    let _ = std::fs::remove_file(probe_path);
    Ok(())
}

/// Checks that `path` can be written, and that its extension names an image format that
/// can be written; returns the format.
pub fn check_image(path: &Path) -> Result<ImageFormat, String> {
    check(path, "out.png")?;
    ImageFormat::from_path(path)
        .ok()
        .filter(ImageFormat::writing_enabled)
        .ok_or_else(|| {
            format!(
                "cannot write {}: its extension names no image format written (use .png, \
                 .jpg, .tif or .ppm)",
                path.display()
            )
        })
}

/// Writes `path` through `write`, atomically: into a temporary file beside it, flushed to
/// disk, then renamed over it. On any failure the temporary file is removed and the old file
/// left as it was.
pub fn write(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), String>,
) -> Result<(), String> {
    let cannot = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
    let (file, partial) = temporary(path).map_err(|e| cannot(&e))?;
    let mut out = BufWriter::new(file);
    let written = write(&mut out)
        .and_then(|()| {
            out.into_inner()
                .map_err(|e| cannot(&e.into_error()))
                .and_then(|file| file.sync_all().map_err(|e| cannot(&e)))
        })
        .and_then(|()| std::fs::rename(&partial, path).map_err(|e| cannot(&e)));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written
}

/// Writes `bytes` as `path`, atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), String> {
    write(path, |out| {
        out.write_all(bytes)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))
    })
}

/// Writes 0x00RRGGBB pixels, row by row from the top, as an image in the format of `path`'s
/// extension, atomically.
pub fn save_rgb(path: &Path, pixels: &[u32], (width, height): (u32, u32)) -> Result<(), String> {
    let format = check_image(path)?;
    let image = RgbImage::from_fn(width, height, |x, y| {
        let rgb = pixels[(y * width + x) as usize];
        Rgb([(rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8])
    });
    write(path, |out| {
        image
            .write_to(out, format)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))
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
            Err("the disk is full".into())
        });
        assert_eq!(failed, Err("the disk is full".into()));
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        write_bytes(&path, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn paths_that_cannot_be_written_say_why() {
        let dir = tempfile::tempdir().unwrap();
        let folder = check(dir.path(), "stats.json").unwrap_err();
        let suggested = dir.path().join("stats.json").display().to_string();
        assert!(folder.contains("is a directory"), "{folder}");
        assert!(
            folder.ends_with(&format!("such as {suggested}")),
            "{folder}"
        );
        let image_folder = check_image(dir.path()).unwrap_err();
        assert!(image_folder.contains("out.png"), "{image_folder}");
        let device = check(Path::new("/dev/full"), "out.txt").unwrap_err();
        assert!(device.contains("character device"), "{device}");
        let missing = check(&dir.path().join("no/such/out.png"), "out.png").unwrap_err();
        assert!(missing.contains("does not exist"), "{missing}");
        let extension = check_image(&dir.path().join("out.xyz")).unwrap_err();
        assert!(extension.contains("extension"), "{extension}");
        assert_eq!(
            check_image(&dir.path().join("out.png")),
            Ok(ImageFormat::Png)
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
