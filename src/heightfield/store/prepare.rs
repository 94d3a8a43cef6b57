//! Preparing a store from its inputs: planned (each input read once for where it lies and the
//! range of its heights), written input by input, then its acceleration data built. The
//! header says how far it has come, so a store stopped part way is finished by running the
//! same preparation again.

use super::build::build;
use super::chunked;
use super::header::{Header, Input};
use super::write::{Placing, Writer};
use super::StoreError;
use crate::heightfield::georef::{Georef, Georeferencing};
use crate::heightfield::load::is_tiff;
use crate::heightfield::load::mosaic::{one_grid, tile_offsets, value};
use crate::heightfield::load::raster::ValueRange;
use crate::heightfield::{load_with, Heightfield, LoadOptions, Quantisation};
use std::fs::{File, OpenOptions};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

/// What preparing is doing, for a progress bar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Reading the inputs for where they lie.
    Planning,
    /// Writing their samples.
    Writing,
    /// Building the mipmap.
    Building,
}

/// Prepares the store `output` from `inputs` (one map, or the tiles of a mosaic on one grid),
/// loaded as `options` say (its z scale aside: a store holds heights at z scale 1), going on
/// from where an earlier run on the same inputs stopped; `progress` is told the stage and the
/// fraction of it done, and breaking cancels. Returns the store's header.
pub fn prepare(
    inputs: &[PathBuf],
    output: &Path,
    options: &LoadOptions,
    progress: &dyn Fn(Stage, f64) -> ControlFlow<()>,
) -> Result<Header, StoreError> {
    let options = LoadOptions {
        z_scale: 1.0,
        ..*options
    };
    let cancelled = || StoreError::Cancelled {
        path: output.to_owned(),
    };
    refuse_overwriting(output)?;
    let (file, mut header, room) = match resume(inputs, output) {
        Some(kept) => kept,
        None => {
            let header = plan(inputs, &options, &|f| progress(Stage::Planning, f), output)?;
            let (file, room) = create(output, &header)?;
            (file, header, room)
        }
    };
    let sections = header.sections(room);
    let n = header.inputs.len();
    // The last input first: an earlier one then writes over it where both have data.
    for k in (0..n).rev() {
        if header.inputs[k].written {
            continue;
        }
        let step =
            |f: f64| match progress(Stage::Writing, (n - 1 - k) as f64 / n as f64 + f / n as f64) {
                ControlFlow::Break(()) => Err(cancelled()),
                ControlFlow::Continue(()) => Ok(()),
            };
        step(0.0)?;
        let input = &header.inputs[k];
        let writer = Writer::of((&file, output), &header, &sections);
        let (q, whole) = (header.quantisation, n == 1);
        if is_tiff(&input.path) {
            let how = (q, whole, header.holes.is_some());
            chunked::write(
                (&input.path, &options),
                &writer,
                (input.at, input.size),
                how,
                step,
            )?;
        } else {
            let field = load_with(&input.path, &options, &|_| ControlFlow::Continue(()))?;
            let own = field.quantisation();
            writer.field(
                &field,
                &Placing {
                    at: input.at,
                    own,
                    store: q,
                    whole,
                },
            )?;
        }
        header.inputs[k].written = true;
        header.write(&file, room, output)?;
    }
    let mut covered = vec![false; header.height as usize];
    for input in &header.inputs {
        let rows = input.at[1] as usize..(input.at[1] + input.size[1]) as usize;
        covered[rows].fill(true);
    }
    finish((&file, output), (&mut header, room), &covered, progress)?;
    Ok(header)
}

/// Writes `field`, its samples and holes as they are, as the store `output`.
pub fn save(field: &Heightfield, output: &Path) -> Result<Header, StoreError> {
    refuse_overwriting(output)?;
    let (w, h) = (field.width() as u64, field.height() as u64);
    let mut header = Header::new(w, h, field.quantisation());
    header.georef = field.georef().copied();
    header.holes = (field.nodata_count() > 0).then_some(0);
    let (file, room) = create(output, &header)?;
    let sections = header.sections(room);
    let writer = Writer::of((&file, output), &header, &sections);
    let q = header.quantisation;
    writer.field(
        field,
        &Placing {
            at: [0, 0],
            own: q,
            store: q,
            whole: true,
        },
    )?;
    let covered = vec![true; field.height()];
    let keep_going = |_, _| ControlFlow::Continue(());
    finish((&file, output), (&mut header, room), &covered, &keep_going)?;
    Ok(header)
}

/// A new store at `output` with `header` and room for it to grow, as long as its sections
/// make it (sparse: what is never written reads as zeros and takes no room).
fn create(output: &Path, header: &Header) -> Result<(File, u64), StoreError> {
    let room = header.room();
    let file = OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(true)
        .open(output)
        .map_err(StoreError::io(output))?;
    header.write(&file, room, output)?;
    file.set_len(header.sections(room).end)
        .map_err(StoreError::io(output))?;
    Ok((file, room))
}

/// Builds the written store's acceleration data (its sample rows that `covered` holds some
/// input) and marks it complete.
fn finish(
    (file, output): (&File, &Path),
    (header, room): (&mut Header, u64),
    covered: &[bool],
    progress: &dyn Fn(Stage, f64) -> ControlFlow<()>,
) -> Result<(), StoreError> {
    let size = (header.width as usize, header.height as usize);
    let sections = header.sections(room);
    let stage = |f| progress(Stage::Building, f);
    let built = build(file, output, size, (&sections, covered), &stage)?;
    header.holes = header.holes.map(|_| built.holes);
    header.steepest = Some(built.steepest);
    header.write(file, room, output)?;
    file.sync_all().map_err(StoreError::io(output))
}

/// Refuses an `output` that exists and is not a store, an input among them: preparing
/// truncates what it writes to.
fn refuse_overwriting(output: &Path) -> Result<(), StoreError> {
    let Ok(file) = File::open(output) else {
        return Ok(());
    };
    let empty = file.metadata().is_ok_and(|m| m.is_file() && m.len() == 0);
    match empty || super::is_store(&file) {
        true => Ok(()),
        false => Err(StoreError::NotAStore {
            path: output.to_owned(),
        }),
    }
}

/// The store at `output` to go on with, where it was planned for these inputs (the same files,
/// of the same lengths) and not finished.
fn resume(inputs: &[PathBuf], output: &Path) -> Option<(File, Header, u64)> {
    let file = OpenOptions::new()
        .read(true)
        .write(true)
        .open(output)
        .ok()?;
    let len = file.metadata().ok()?.len();
    let (header, room) = Header::read(&file, len, output).ok()?;
    let same = header.inputs.len() == inputs.len()
        && header.inputs.iter().zip(inputs).all(|(kept, path)| {
            kept.path == *path && std::fs::metadata(path).is_ok_and(|m| m.len() == kept.bytes)
        });
    (same && header.steepest.is_none() && len >= header.sections(room).end)
        .then_some((file, header, room))
}

/// The header of a store of `inputs`: each input read once for its size, its place and the
/// range of its heights.
fn plan(
    inputs: &[PathBuf],
    options: &LoadOptions,
    progress: &dyn Fn(f64) -> ControlFlow<()>,
    output: &Path,
) -> Result<Header, StoreError> {
    let mut read = Vec::with_capacity(inputs.len());
    let n = inputs.len();
    for (k, path) in inputs.iter().enumerate() {
        let step = |f: f64| match progress((k as f64 + f) / n as f64) {
            ControlFlow::Break(()) => Err(StoreError::Cancelled {
                path: output.to_owned(),
            }),
            ControlFlow::Continue(()) => Ok(()),
        };
        step(0.0)?;
        if is_tiff(path) {
            read.push(chunked::plan(path, options, n > 1, step)?);
            continue;
        }
        let field = load_with(path, options, &|_| ControlFlow::Continue(()))?;
        let bytes = std::fs::metadata(path).map_err(StoreError::io(path))?.len();
        let mut range = ValueRange::EMPTY;
        for j in 0..field.height() {
            for i in (0..field.width()).filter(|&i| !field.is_nodata(i, j)) {
                range.include(value(&field, i, j));
            }
        }
        read.push(Planned {
            path: path.clone(),
            bytes,
            size: [field.width() as u64, field.height() as u64],
            range,
            holes: field.nodata_count() as u64,
            quantisation: field.quantisation(),
            georef: field.georeferencing().clone(),
        });
    }
    let [one] = &read[..] else {
        return plan_mosaic(&read);
    };
    let mut header = Header::new(one.size[0], one.size[1], one.quantisation);
    header.georef = one.georef.georef().copied();
    header.holes = (one.holes > 0).then_some(0);
    header.inputs.push(one.input([0, 0]));
    Ok(header)
}

/// What planning reads of an input.
pub(super) struct Planned {
    pub path: PathBuf,
    /// The file's length.
    pub bytes: u64,
    /// Samples along x and y.
    pub size: [u64; 2],
    /// The range of its heights with data.
    pub range: ValueRange,
    /// Samples without data.
    pub holes: u64,
    pub quantisation: Quantisation,
    pub georef: Georeferencing,
}

impl Planned {
    /// The input, to be written at `at`.
    fn input(&self, at: [u64; 2]) -> Input {
        Input {
            path: self.path.clone(),
            bytes: self.bytes,
            at,
            size: self.size,
            written: false,
        }
    }
}

/// The header of a mosaic of the inputs `read`, joined as a mosaic loads them.
fn plan_mosaic(read: &[Planned]) -> Result<Header, StoreError> {
    let refuse = |why: String| StoreError::Inputs(why);
    let georefs = read
        .iter()
        .map(|input| match &input.georef {
            Georeferencing::Map(g) => Ok((input.path.as_path(), *g)),
            _ => Err(refuse(format!(
                "{} is not georeferenced, so where it lies beside the others is unknown",
                input.path.display()
            ))),
        })
        .collect::<Result<Vec<(&Path, Georef)>, _>>()?;
    let first = georefs
        .first()
        .map(|(_, g)| *g)
        .ok_or_else(|| refuse("no inputs given".into()))?;
    for (path, georef) in &georefs[1..] {
        one_grid(&first, georef).map_err(|why| {
            refuse(format!(
                "{} and {} {why}",
                read[0].path.display(),
                path.display()
            ))
        })?;
    }
    let offsets = tile_offsets(georefs.iter().map(|(p, g)| (*p, g)), &first)
        .map_err(|e| refuse(e.to_string()))?;
    let (mut lo, mut hi) = ([i64::MAX; 2], [i64::MIN; 2]);
    let mut range = ValueRange::EMPTY;
    for (input, offset) in read.iter().zip(&offsets) {
        range = range.join(input.range);
        for axis in 0..2 {
            lo[axis] = lo[axis].min(offset[axis]);
            hi[axis] = hi[axis].max(offset[axis] + input.size[axis] as i64 - 1);
        }
    }
    if range.is_empty() {
        return Err(refuse("every sample of every input is no-data".into()));
    }
    let quantisation = Quantisation::Offset {
        lowest: range.lo,
        step: range.step(),
    };
    let (width, height) = ((hi[0] - lo[0] + 1) as u64, (hi[1] - lo[1] + 1) as u64);
    let mut header = Header::new(width, height, quantisation);
    let origin = [0, 1].map(|axis| first.origin[axis] + lo[axis] as f64 * first.spacing[axis]);
    header.georef = Some(
        Georef::new(origin, first.spacing, first.units)
            .map_err(|e| refuse(e.to_string()))?
            .with_crs(first.crs)
            .with_height_unit(first.height_unit),
    );
    header.holes = Some(0);
    header.inputs = read
        .iter()
        .zip(&offsets)
        .map(|(input, offset)| input.input([0, 1].map(|axis| (offset[axis] - lo[axis]) as u64)))
        .collect();
    Ok(header)
}
