//! Test GeoTIFFs written by hand: tiled or stripped, 16-bit or float, Deflate-compressed, whose
//! chunks may share their bytes (as most tiles of a large, mostly constant map do).

use tiff::encoder::compression::{CompressionAlgorithm, Deflate};

/// How a test TIFF's samples are cut into chunks.
#[derive(Clone, Copy)]
pub(super) enum Chunks {
    /// Tiles of this width and height.
    Tiles(u32, u32),
    /// Strips of this many rows.
    Strips(u32),
}

/// The sample type of a test TIFF.
#[derive(Clone, Copy)]
pub(super) enum Sample {
    U16,
    F32,
}

/// A test GeoTIFF: `w x h` samples in 30 m cells from (500000, 4000000) in UTM 33N.
pub(super) struct Spec<'a> {
    pub(super) size: [u32; 2],
    pub(super) chunks: Chunks,
    pub(super) sample: Sample,
    pub(super) nodata: Option<&'a str>,
}

impl Spec<'_> {
    /// Chunks along x and y.
    pub(super) fn grid(&self) -> [u32; 2] {
        match self.chunks {
            Chunks::Tiles(tw, th) => [self.size[0].div_ceil(tw), self.size[1].div_ceil(th)],
            Chunks::Strips(rows) => [1, self.size[1].div_ceil(rows)],
        }
    }

    /// The pixels (column, row; row 0 the northern edge) chunk `index` holds, and how many
    /// columns and rows it stores (tiles whole, padding and all).
    pub(super) fn chunk_pixels(&self, index: u32) -> ([u32; 2], [u32; 2]) {
        let across = self.grid()[0];
        let (ci, cj) = (index % across, index / across);
        match self.chunks {
            Chunks::Tiles(tw, th) => ([ci * tw, cj * th], [tw, th]),
            Chunks::Strips(rows) => (
                [0, cj * rows],
                [self.size[0], rows.min(self.size[1] - cj * rows)],
            ),
        }
    }

    /// Chunk `index` of values `z(column, row)` (padding zeros), Deflate-compressed.
    pub(super) fn chunk(&self, index: u32, z: &dyn Fn(u32, u32) -> f64) -> Vec<u8> {
        let ([x0, y0], [cw, ch]) = self.chunk_pixels(index);
        let mut raw = Vec::new();
        for r in y0..y0 + ch {
            for c in x0..x0 + cw {
                let inside = c < self.size[0] && r < self.size[1];
                let v = if inside { z(c, r) } else { 0.0 };
                match self.sample {
                    Sample::U16 => raw.extend((v as u16).to_le_bytes()),
                    Sample::F32 => raw.extend((v as f32).to_le_bytes()),
                }
            }
        }
        deflate(&raw)
    }

    /// The TIFF of `blobs`, chunk `k` being blob `which[k]`.
    pub(super) fn file(&self, blobs: &[Vec<u8>], which: &[usize]) -> Vec<u8> {
        let mut bytes = b"II*\0\0\0\0\0".to_vec();
        let mut places = Vec::new();
        for blob in blobs {
            places.push((bytes.len() as u32, blob.len() as u32));
            bytes.extend(blob);
        }
        let offsets: Vec<u32> = which.iter().map(|&b| places[b].0).collect();
        let counts: Vec<u32> = which.iter().map(|&b| places[b].1).collect();
        let (bits, format) = match self.sample {
            Sample::U16 => (16u16, 1u16),
            Sample::F32 => (32, 3),
        };
        let short = |v: u16| (3u16, 1u32, v.to_le_bytes().to_vec());
        let long = |v: u32| (4u16, 1u32, v.to_le_bytes().to_vec());
        let longs = |v: &[u32]| {
            (
                4u16,
                v.len() as u32,
                v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            )
        };
        let doubles = |v: &[f64]| {
            (
                12u16,
                v.len() as u32,
                v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            )
        };
        let keys: [u16; 16] = [1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32633];
        let mut entries: Vec<Entry> = vec![
            (256, long(self.size[0])),
            (257, long(self.size[1])),
            (258, short(bits)),
            (259, short(8)),
            (262, short(1)),
            (277, short(1)),
            (339, short(format)),
            (33550, doubles(&[30.0, 30.0, 0.0])),
            (33922, doubles(&[0.0, 0.0, 0.0, 500000.0, 4000000.0, 0.0])),
            (
                34735,
                (3, 16, keys.iter().flat_map(|k| k.to_le_bytes()).collect()),
            ),
        ];
        match self.chunks {
            Chunks::Tiles(tw, th) => entries.extend([
                (322, long(tw)),
                (323, long(th)),
                (324, longs(&offsets)),
                (325, longs(&counts)),
            ]),
            Chunks::Strips(rows) => entries.extend([
                (273, longs(&offsets)),
                (278, long(rows)),
                (279, longs(&counts)),
            ]),
        }
        if let Some(text) = self.nodata {
            let mut ascii = text.as_bytes().to_vec();
            ascii.push(0);
            entries.push((42113, (2, ascii.len() as u32, ascii)));
        }
        entries.sort_by_key(|e| e.0);
        // Values longer than 4 bytes go before the directory.
        let mut fields = Vec::new();
        for (tag, (kind, count, data)) in entries {
            let value = if data.len() <= 4 {
                let mut inline = data.clone();
                inline.resize(4, 0);
                inline
            } else {
                if bytes.len() % 2 == 1 {
                    bytes.push(0);
                }
                let at = bytes.len() as u32;
                bytes.extend(&data);
                at.to_le_bytes().to_vec()
            };
            fields.push((tag, kind, count, value));
        }
        if bytes.len() % 2 == 1 {
            bytes.push(0);
        }
        let ifd = bytes.len() as u32;
        bytes[4..8].copy_from_slice(&ifd.to_le_bytes());
        bytes.extend((fields.len() as u16).to_le_bytes());
        for (tag, kind, count, value) in fields {
            bytes.extend(tag.to_le_bytes());
            bytes.extend(kind.to_le_bytes());
            bytes.extend(count.to_le_bytes());
            bytes.extend(value);
        }
        bytes.extend(0u32.to_le_bytes());
        bytes
    }

    /// The TIFF of values `z(column, row)`, every chunk its own.
    pub(super) fn of(&self, z: &dyn Fn(u32, u32) -> f64) -> Vec<u8> {
        let [a, d] = self.grid();
        let blobs: Vec<Vec<u8>> = (0..a * d).map(|k| self.chunk(k, z)).collect();
        let which: Vec<usize> = (0..blobs.len()).collect();
        self.file(&blobs, &which)
    }
}

/// A directory entry: its tag, and its type, count and value's bytes.
type Entry = (u16, (u16, u32, Vec<u8>));

pub(super) fn deflate(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    Deflate::default().write_to(&mut out, bytes).unwrap();
    out
}
