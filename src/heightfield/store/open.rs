//! Opening a store: its header read and checked, the file mapped read-only, and a height field
//! made of the mapped values with its mipmap ready.

use super::header::{damaged, Header, Sections};
use super::{residency, Prebuilt, StoreError};
use crate::heightfield::georef::Georeferencing;
use crate::heightfield::{Heightfield, LoadOptions, Mipmap, NoDataMask, Values};
use memmap2::{Advice, Mmap};
use std::fs::File;
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

/// The height field of the store `file` (at `path`, `len` bytes long), with the options' z
/// scale and height unit (its no-data samples were chosen when it was prepared).
pub fn open(
    file: &File,
    len: u64,
    path: &Path,
    options: &LoadOptions,
) -> Result<Heightfield, StoreError> {
    let (header, room) = Header::read(file, len, path)?;
    let Some(steepest) = header.steepest else {
        return Err(StoreError::Unfinished {
            path: path.to_owned(),
        });
    };
    let sections = header.sections(room);
    if len < sections.end {
        return Err(StoreError::Truncated {
            path: path.to_owned(),
            len,
            expected: sections.end,
        });
    }
    // SAFETY: the file is mapped read-only and, as the store's contract says, not changed
    // while a map is open from it; every value read from it is checked where it indexes.
    let map = Arc::new(unsafe { Mmap::map(file) }.map_err(StoreError::io(path))?);
    // (Walks read a few samples here and there: reading ahead would only fill memory.)
    let _ = map.advise(Advice::Random);
    let part = |(at, len): (u64, u64)| {
        let (at, len) = (usize::try_from(at).ok(), usize::try_from(len).ok());
        at.zip(len)
    };
    let missing = || damaged(path, "a section lies outside the file".into());
    let (w, h) = (header.width as usize, header.height as usize);
    let values = |section| part(section).and_then(|(at, len)| Values::mapped(&map, at, len));
    let samples = values(sections.samples).ok_or_else(missing)?;
    let (max, min) = (values(sections.max), values(sections.min));
    let mipmap = max
        .zip(min)
        .and_then(|(max, min)| Mipmap::from_values(w, h, max, min))
        .ok_or_else(missing)?;
    let nodata = match (sections.valid, header.holes) {
        (Some(section), Some(count)) => {
            let valid = part(section)
                .and_then(|(at, len)| Values::mapped(&map, at, len))
                .ok_or_else(missing)?;
            Some(NoDataMask::of_valid(valid, count as usize))
        }
        _ => None,
    };
    residency::watch(&map, upper_levels(&map, w, h, &sections));
    let georef = match (header.georef, options.height_unit) {
        (Some(georef), Some(unit)) => Georeferencing::Map(georef.with_height_unit(unit)),
        (Some(georef), None) => Georeferencing::Map(georef),
        (None, _) => Georeferencing::None,
    };
    let prebuilt = Some(Arc::new(Prebuilt { mipmap, steepest }));
    let (q, z_scale) = (header.quantisation, options.z_scale);
    let field =
        Heightfield::of_parts((w, h), samples, q, z_scale, nodata, prebuilt).map_err(|source| {
            StoreError::Field {
                path: path.to_owned(),
                source,
            }
        })?;
    Ok(field.with_georeferencing(georef.with_cells_checked(w, h)))
}

/// The byte ranges of `map` that hold the mipmap's upper levels, which every walk reads: those
/// from the finest level that keeps them within a sixteenth of the memory budget. They are
/// asked of the disk at once, read ahead in whole, and kept.
fn upper_levels(map: &Mmap, w: usize, h: usize, sections: &Sections) -> Vec<Range<usize>> {
    let most = usize::try_from(residency::budget() / 16 / 2).unwrap_or(usize::MAX);
    let (max, min) = Mipmap::layout(w, h).upper_levels(most);
    let range = |(at, len): (u64, u64), from: usize| {
        let (at, len) = (at as usize, len as usize);
        at + 2 * from..at + 2 * len
    };
    let ranges = vec![range(sections.max, max), range(sections.min, min)];
    for range in &ranges {
        let len = range.end.saturating_sub(range.start);
        // (A hint: where it is not taken, the pages come as walks touch them.)
        let _ = map.advise_range(Advice::WillNeed, range.start, len);
    }
    ranges
}
