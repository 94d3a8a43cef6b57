//! The GeoTIFF inputs of a store, read by rows of strips or tiles rather than whole (see
//! `tiff_chunks`): planned from one pass over their chunks, written from another, so that one
//! may hold more samples than a map in memory and take no more memory than a row of its
//! chunks. Their samples, holes and georeferencing are those a whole-file load gives.

use super::prepare::Planned;
use super::write::{Placing, Writer};
use super::StoreError;
use crate::heightfield::load::tiff_chunks::ChunkedTiff;
use crate::heightfield::{LoadOptions, Quantisation};
use std::path::Path;

/// What planning reads of the GeoTIFF at `path`, loaded as `options` say, calling `step` with
/// the fraction done; where it is one `of_mosaic`, the range of its heights as they join
/// other inputs.
pub(super) fn plan(
    path: &Path,
    options: &LoadOptions,
    of_mosaic: bool,
    mut step: impl FnMut(f64) -> Result<(), StoreError>,
) -> Result<Planned, StoreError> {
    let mut tiff = ChunkedTiff::open(path, options)?;
    let survey = tiff.survey(&mut step)?;
    let quantisation = tiff.quantisation(&survey)?;
    let range = match of_mosaic {
        true => tiff.heights(&survey, quantisation, &mut step)?,
        false => survey.range,
    };
    Ok(Planned {
        path: path.to_owned(),
        bytes: std::fs::metadata(path).map_err(StoreError::io(path))?.len(),
        size: tiff.size(),
        range,
        holes: survey.holes,
        quantisation,
        georef: tiff.georeferencing().clone(),
    })
}

/// Writes the GeoTIFF at `path`, loaded as `options` say, of `size` samples, placed at `at` in
/// a store quantised as `store` (`whole` where it is the store's one input, its holes `holes`),
/// calling `step` with the fraction done.
pub(super) fn write(
    (path, options): (&Path, &LoadOptions),
    writer: &Writer<'_>,
    (at, size): ([u64; 2], [u64; 2]),
    (store, whole, holes): (Quantisation, bool, bool),
    mut step: impl FnMut(f64) -> Result<(), StoreError>,
) -> Result<(), StoreError> {
    let mut tiff = ChunkedTiff::open(path, options)?;
    if tiff.size() != size {
        return Err(StoreError::Inputs(format!(
            "{} has changed since the store was planned; prepare it again under a new name",
            path.display()
        )));
    }
    // The input's own quantisation, and the sample its holes hold (its lowest with data): a
    // single input's is the store's, but for the lowest unsigned sample, read again where it
    // has holes; an input of a mosaic's values are read again for their range.
    let (own, lowest) = match (whole, tiff.maxval()) {
        (true, Some(_)) if holes => {
            let survey = tiff.survey(&mut step)?;
            (store, survey.range.lo as u16)
        }
        (true, _) => (store, 0),
        (false, Some(maxval)) => (Quantisation::Maxval(maxval), 0),
        (false, None) => {
            let survey = tiff.survey(&mut step)?;
            (tiff.quantisation(&survey)?, 0)
        }
    };
    let placing = Placing {
        at,
        own,
        store,
        whole,
    };
    let mut row = Vec::new();
    tiff.rows((own, lowest), step, |j, samples, valid| {
        writer.input_row(&placing, j, (samples, valid), &mut row)
    })
}
