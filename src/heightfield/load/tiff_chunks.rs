//! A GeoTIFF read a row of strips or tiles at a time, for maps larger than memory: the samples
//! and holes a whole-file load makes of it come out row by row, the same values, while no more
//! than one row of chunks is held decoded. Its size, no-data value and georeferencing are read
//! as the whole-file load reads them (see `tiff::describe`), but it may hold any number of
//! samples.

use super::raster::{has_data, nodata_value, placed, ValueRange};
use super::tiff::{describe, limits, unsupported_type, ChunkError};
use super::{decode_error, open_regular, LoadError, LoadOptions};
use crate::heightfield::georef::Georeferencing;
use crate::heightfield::{mapping, HeightfieldError, Quantisation};
use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use std::rc::Rc;
use tiff::decoder::{ChunkType, Decoder, DecodingResult};
use tiff::tags::Tag;

/// A chunk's offset and bytes in the file and the size of its data: chunks alike in these
/// decode to the same samples (writers point the many tiles of one value at one tile's bytes).
type Key = (u64, u64, usize, usize);

/// A chunk's or a row's values, widened: unsigned samples as they are, others as `f64`.
enum Samples {
    Unsigned(Vec<u16>),
    Values(Vec<f64>),
}

impl Samples {
    fn len(&self) -> usize {
        match self {
            Samples::Unsigned(v) => v.len(),
            Samples::Values(v) => v.len(),
        }
    }

    /// The value at `k`, as the whole-file load reads it.
    fn value(&self, k: usize) -> f64 {
        match self {
            Samples::Unsigned(v) => f64::from(v[k]),
            Samples::Values(v) => v[k],
        }
    }
}

/// What one pass over a map finds.
#[derive(Clone, Copy, Debug)]
pub struct Survey {
    /// The range of its values with data.
    pub range: ValueRange,
    /// Its samples without data.
    pub holes: u64,
}

/// A TIFF's first image, read by rows of chunks.
pub struct ChunkedTiff {
    decoder: Decoder<BufReader<File>>,
    name: String,
    width: usize,
    height: usize,
    /// A chunk's width and height (a strip's: the image's width and its rows per strip).
    chunk: [usize; 2],
    /// "strip" or "tile", for messages.
    what: &'static str,
    /// Bits per sample.
    bits: u16,
    /// Chunks along x.
    across: usize,
    /// Chunks along y.
    down: usize,
    /// Each chunk's offset and bytes.
    places: Vec<(u64, u64)>,
    /// The raster value that means no data.
    nodata: Option<f64>,
    /// The largest value of unsigned samples; none for values quantised over their range.
    maxval: Option<u16>,
    georef: Georeferencing,
    /// The chunk decoded last.
    last: Option<(Key, Rc<Samples>)>,
}

impl ChunkedTiff {
    /// Opens the TIFF at `path`, to be read as `options` say, and decodes its first chunk for
    /// the type of its samples.
    pub fn open(path: &Path, options: &LoadOptions) -> Result<Self, LoadError> {
        let (file, len) = open_regular(path)?;
        let name = path.display().to_string();
        let mut decoder = Decoder::new(BufReader::new(file)).map_err(|e| decode_error(&name, e))?;
        let described = describe(&mut decoder, len, &name, false)?;
        let (width, height) = (described.width as usize, described.height as usize);
        let (what, offsets, counts) = match decoder.get_chunk_type() {
            ChunkType::Tile => ("tile", Tag::TileOffsets, Tag::TileByteCounts),
            ChunkType::Strip => ("strip", Tag::StripOffsets, Tag::StripByteCounts),
        };
        let mut tag = |tag| {
            decoder
                .get_tag_u64_vec(tag)
                .map_err(|e| decode_error(&name, e))
        };
        let (offsets, counts) = (tag(offsets)?, tag(counts)?);
        let (w, h) = decoder.chunk_dimensions();
        let chunk = [w as usize, h as usize];
        let (across, down) = match chunk {
            [0, _] | [_, 0] => (0, 0),
            [w, h] => (width.div_ceil(w), height.div_ceil(h)),
        };
        let needed = across * down;
        if needed == 0 || offsets.len() < needed || counts.len() < needed {
            let got = offsets.len().min(counts.len());
            return Err(decode_error(&name, ChunkError::Count { what, got, needed }));
        }
        let mut chunked = ChunkedTiff {
            decoder: decoder.with_limits(limits()),
            name,
            width,
            height,
            chunk,
            what,
            bits: described.bits,
            across,
            down,
            places: offsets.into_iter().zip(counts).collect(),
            nodata: None,
            maxval: None,
            georef: placed(&described.georef, options, width, height),
            last: None,
        };
        if let Samples::Unsigned(_) = *chunked.decode(0)? {
            chunked.maxval = Some(match described.bits {
                8 => u8::MAX.into(),
                _ => u16::MAX,
            });
        }
        chunked.nodata = nodata_value(options, chunked.maxval.is_some(), described.file_nodata);
        Ok(chunked)
    }

    /// Samples along x and y.
    pub fn size(&self) -> [u64; 2] {
        [self.width as u64, self.height as u64]
    }

    /// Where the file says its samples lie, as the whole-file load reads it.
    pub fn georeferencing(&self) -> &Georeferencing {
        &self.georef
    }

    /// The size of chunk `index`'s data: its chunk's, but at the right and bottom edges.
    fn data_size(&self, index: usize) -> [usize; 2] {
        let (i, j) = (index % self.across, index / self.across);
        [
            self.chunk[0].min(self.width - i * self.chunk[0]),
            self.chunk[1].min(self.height - j * self.chunk[1]),
        ]
    }

    fn key(&self, index: usize) -> Key {
        let (offset, bytes) = self.places[index];
        let [w, h] = self.data_size(index);
        (offset, bytes, w, h)
    }

    /// The values of chunk `index`, decoded unless it is the chunk decoded last.
    fn decode(&mut self, index: usize) -> Result<Rc<Samples>, LoadError> {
        let key = self.key(index);
        if let Some((last, samples)) = &self.last {
            if *last == key {
                return Ok(samples.clone());
            }
        }
        let decoded = u32::try_from(index)
            .map_err(|_| tiff::TiffError::IntSizeError)
            .and_then(|k| self.decoder.read_chunk(k))
            .map_err(|e| decode_error(&self.name, e))?;
        let widened = |v: Vec<f64>| Samples::Values(v);
        let samples = match decoded {
            DecodingResult::U8(v) => Samples::Unsigned(v.into_iter().map(u16::from).collect()),
            DecodingResult::U16(v) => Samples::Unsigned(v),
            DecodingResult::I8(v) => widened(v.into_iter().map(f64::from).collect()),
            DecodingResult::I16(v) => widened(v.into_iter().map(f64::from).collect()),
            DecodingResult::I32(v) => widened(v.into_iter().map(f64::from).collect()),
            DecodingResult::U32(v) => widened(v.into_iter().map(f64::from).collect()),
            DecodingResult::F32(v) => widened(v.into_iter().map(f64::from).collect()),
            DecodingResult::F64(v) => widened(v),
            _ => return Err(unsupported_type(&self.name, self.bits)),
        };
        let (what, [w, h]) = (self.what, [key.2, key.3]);
        if samples.len() != w * h {
            let error = ChunkError::Size { what, index, w, h };
            return Err(decode_error(&self.name, error));
        }
        let samples = Rc::new(samples);
        self.last = Some((key, samples.clone()));
        Ok(samples)
    }

    /// Reads every chunk once for the range of the values with data and the count of those
    /// without (a chunk like the one before it taken as read again), calling `step` with the
    /// fraction done at each row of chunks.
    pub fn survey<E: From<LoadError>>(
        &mut self,
        mut step: impl FnMut(f64) -> Result<(), E>,
    ) -> Result<Survey, E> {
        let mut survey = Survey {
            range: ValueRange::EMPTY,
            holes: 0,
        };
        let mut last: Option<(Key, Survey)> = None;
        for index in 0..self.across * self.down {
            if index % self.across == 0 {
                step(index as f64 / (self.across * self.down) as f64)?;
            }
            let key = self.key(index);
            let found = match last {
                Some((k, found)) if k == key => found,
                _ => {
                    let samples = self.decode(index)?;
                    let mut found = Survey {
                        range: ValueRange::EMPTY,
                        holes: 0,
                    };
                    for v in (0..samples.len()).map(|k| samples.value(k)) {
                        match has_data(v, self.nodata) {
                            true => found.range.include(v),
                            false => found.holes += 1,
                        }
                    }
                    last = Some((key, found));
                    found
                }
            };
            survey.range = survey.range.join(found.range);
            survey.holes += found.holes;
        }
        Ok(survey)
    }

    /// The quantisation of the field the whole-file load makes of a map of `survey`: unsigned
    /// samples as they are, other values over their range.
    pub fn quantisation(&self, survey: &Survey) -> Result<Quantisation, LoadError> {
        let refuse = |source| LoadError::Field {
            name: self.name.clone(),
            source,
        };
        if survey.range.is_empty() {
            return Err(refuse(HeightfieldError::AllNoData));
        }
        let q = match self.maxval {
            Some(maxval) => Quantisation::Maxval(maxval),
            None => Quantisation::Offset {
                lowest: survey.range.lo,
                step: survey.range.step(),
            },
        };
        mapping(q, 1.0).map_err(refuse)?;
        Ok(q)
    }

    /// The range of the heights (at z scale 1) the field of a map of `survey`, quantised as
    /// `q`, holds where it has data: its lowest and highest values quantised, and whether all
    /// are whole numbers (read again, unless the quantisation says so).
    pub fn heights<E: From<LoadError>>(
        &mut self,
        survey: &Survey,
        q: Quantisation,
        step: impl FnMut(f64) -> Result<(), E>,
    ) -> Result<ValueRange, E> {
        let Quantisation::Offset { lowest, step: unit } = q else {
            return Ok(survey.range);
        };
        let height = |v| lowest + f64::from(ValueRange::sample(v, lowest, unit)) * unit;
        let mut range = ValueRange {
            lo: height(survey.range.lo),
            hi: height(survey.range.hi),
            whole: unit == 1.0 && lowest.fract() == 0.0,
        };
        if !range.whole {
            range.whole = self.all(step, |v| height(v).fract() == 0.0)?;
        }
        Ok(range)
    }

    /// Whether `holds` holds of every value with data, read until one it does not hold of.
    fn all<E: From<LoadError>>(
        &mut self,
        mut step: impl FnMut(f64) -> Result<(), E>,
        holds: impl Fn(f64) -> bool,
    ) -> Result<bool, E> {
        let mut last = None;
        for index in 0..self.across * self.down {
            if index % self.across == 0 {
                step(index as f64 / (self.across * self.down) as f64)?;
            }
            let key = self.key(index);
            if last == Some(key) {
                continue;
            }
            let samples = self.decode(index)?;
            let nodata = self.nodata;
            if (0..samples.len())
                .map(|k| samples.value(k))
                .any(|v| has_data(v, nodata) && !holds(v))
            {
                return Ok(false);
            }
            last = Some(key);
        }
        Ok(true)
    }

    /// Calls `row` with each row of the field the whole-file load makes of the map, quantised
    /// as `q`, with holes where the value means no data (their samples `lowest`): its row
    /// number (y up), its samples and which have data; and `step` with the fraction done at
    /// each row of chunks. Rows come from the top (the northern edge) down.
    pub fn rows<E: From<LoadError>>(
        &mut self,
        (q, lowest): (Quantisation, u16),
        mut step: impl FnMut(f64) -> Result<(), E>,
        mut row: impl FnMut(usize, &[u16], &[bool]) -> Result<(), E>,
    ) -> Result<(), E> {
        let (w, nodata) = (self.width, self.nodata);
        let (mut samples, mut valid) = (vec![0u16; w], vec![false; w]);
        for cj in 0..self.down {
            step(cj as f64 / self.down as f64)?;
            let rows = self.data_size(cj * self.across)[1];
            let band = self.band(cj, rows)?;
            for r in 0..rows {
                for i in 0..w {
                    let v = band.value(r * w + i);
                    valid[i] = has_data(v, nodata);
                    samples[i] = match (valid[i], q) {
                        (false, _) => lowest,
                        (true, Quantisation::Maxval(_)) => v as u16,
                        (true, Quantisation::Offset { lowest, step }) => {
                            ValueRange::sample(v, lowest, step)
                        }
                    };
                }
                row(self.height - 1 - (cj * self.chunk[1] + r), &samples, &valid)?;
            }
        }
        Ok(())
    }

    /// The `rows` image rows of chunk row `cj`, `width` values each.
    fn band(&mut self, cj: usize, rows: usize) -> Result<Samples, LoadError> {
        let w = self.width;
        let mut band = match self.maxval {
            Some(_) => Samples::Unsigned(vec![0; w * rows]),
            None => Samples::Values(vec![0.0; w * rows]),
        };
        for ci in 0..self.across {
            let index = cj * self.across + ci;
            let [cw, ch] = self.data_size(index);
            let chunk = self.decode(index)?;
            let x0 = ci * self.chunk[0];
            for r in 0..ch.min(rows) {
                let (to, from) = (r * w + x0..r * w + x0 + cw, r * cw..(r + 1) * cw);
                match (&mut band, &*chunk) {
                    (Samples::Unsigned(b), Samples::Unsigned(c)) => b[to].copy_from_slice(&c[from]),
                    (Samples::Values(b), Samples::Values(c)) => b[to].copy_from_slice(&c[from]),
                    _ => {
                        let error = ChunkError::Size {
                            what: self.what,
                            index,
                            w: cw,
                            h: ch,
                        };
                        return Err(decode_error(&self.name, error));
                    }
                }
            }
        }
        Ok(band)
    }

    /// The field's largest unsigned sample, or none for values quantised over their range.
    pub fn maxval(&self) -> Option<u16> {
        self.maxval
    }
}
