//! A coarse stand-in for a map read from a tile store, made from the mipmap's upper levels
//! (which stay resident): a frame of it can be shown at once, while the pages the real frame's
//! rays touch are still being read from the disk.
//!
//! Each corner of a level-`k` block becomes a sample: the mean of the midpoints between the
//! highest and lowest sample of the blocks around it. The preview's grid is the map's scaled
//! down by `2^k` in every axis (heights too), so a view of the map is a view of the preview
//! through a camera scaled the same way. A corner whose own sample holds no data holds none.

use super::mipmap::blocks;
use super::{Heightfield, NoDataMask, Terrain};

/// The preview's samples along its longer side, at most; a map of at most this many cells
/// along each side is shown as it is.
const MOST_SIDE: usize = 2048;

/// A coarse terrain in place of a map, and where it lies in the map's world.
#[derive(Debug)]
pub struct Preview {
    /// The coarse terrain.
    pub terrain: Terrain,
    /// World coordinates of the map per grid coordinate of the preview (see
    /// [`Terrain::world_from_grid`]).
    pub world_from_grid: [f64; 3],
    /// The mipmap level its samples come from: one sample per `2^level` of the map's.
    pub level: u32,
}

impl Preview {
    /// The preview of `terrain`, or `None` where the map is small enough to need none.
    pub(super) fn of(terrain: &Terrain) -> Option<Preview> {
        let (field, mipmap) = (terrain.field(), terrain.mipmap());
        let (w, h) = (field.width(), field.height());
        if w.max(h) - 1 <= MOST_SIDE {
            return None;
        }
        let level = (2..=mipmap.top()).find(|&k| {
            let (nx, ny) = blocks(k, w, h);
            nx.max(ny) < MOST_SIDE
        })?;
        let (nx, ny) = blocks(level, w, h);
        // (Each block's midpoint once: up to four corners share it.)
        let midpoints: Vec<f64> = (0..ny)
            .flat_map(|bj| (0..nx).map(move |bi| (bi, bj)))
            .map(|(bi, bj)| {
                let (hi, lo) = (mipmap.highest(level, bi, bj), mipmap.lowest(level, bi, bj));
                (u32::from(hi) + u32::from(lo)) as f64 / 2.0
            })
            .collect();
        let corner = |i: usize, j: usize| {
            let around = |n: usize, k: usize| k.saturating_sub(1)..(k + 1).min(n);
            let (mut sum, mut count) = (0.0, 0.0);
            for bj in around(ny, j) {
                for bi in around(nx, i) {
                    sum += midpoints[bj * nx + bi];
                    count += 1.0;
                }
            }
            (sum / count).round() as u16
        };
        let (pw, ph) = (nx + 1, ny + 1);
        let samples = (0..ph)
            .flat_map(|j| (0..pw).map(move |i| (i, j)))
            .map(|(i, j)| corner(i, j))
            .collect();
        let on_map = |k: usize, n: usize| (k << level).min(n - 1);
        let nodata = (field.nodata_count() > 0).then(|| {
            let mut mask = NoDataMask::new(pw * ph);
            for j in 0..ph {
                for i in 0..pw {
                    if field.is_nodata(on_map(i, w), on_map(j, h)) {
                        mask.insert(j * pw + i);
                    }
                }
            }
            mask
        });
        let scale = f64::from(1u32 << level);
        let z_scale = field.z_scale() / scale;
        let coarse =
            Heightfield::new(pw, ph, samples, field.quantisation(), z_scale, nodata).ok()?;
        // The map's height range, scaled: colours by height come out as the map's.
        let (lo, hi) = terrain.z_range();
        let terrain_of_preview = Terrain::new(coarse).with_z_range(lo / scale, hi / scale);
        let stretch = terrain.world_from_grid().unwrap_or([1.0; 3]);
        Some(Preview {
            terrain: terrain_of_preview,
            world_from_grid: stretch.map(|s| s * scale),
            level,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each preview sample, scaled back to the map, is the mean of the midpoints of the level's
    /// blocks around its corner, worked out from the map's own samples; it lies where that
    /// corner lies in the world.
    #[test]
    fn a_preview_sample_is_the_mean_midpoint_of_the_blocks_around_its_corner() {
        let wave = |i: usize, j: usize| {
            (500.0 + 400.0 * ((i as f64 / 37.0).sin() + (j as f64 / 5.0).cos())) as u16
        };
        let field = Heightfield::from_fn(4103, 23, 2000, 50.0, wave).unwrap();
        let terrain = Terrain::new(field.clone());
        let preview = Preview::of(&terrain).unwrap();
        let k = preview.level;
        assert_eq!(k, 2);
        let size = 1usize << k;
        let coarse = preview.terrain.field();
        assert_eq!(
            (coarse.width(), coarse.height()),
            (4102 / size + 2, 22 / size + 2)
        );
        let scale = preview.world_from_grid;
        assert_eq!(scale, [4.0; 3]);
        let midpoint = |bi: usize, bj: usize| {
            let cells = |b: usize, n: usize| b * size..((b + 1) * size).min(n - 1) + 1;
            let samples: Vec<u16> = cells(bj, 23)
                .flat_map(|j| cells(bi, 4103).map(move |i| wave(i, j)))
                .collect();
            let (lo, hi) = (samples.iter().min().unwrap(), samples.iter().max().unwrap());
            (f64::from(*lo) + f64::from(*hi)) / 2.0
        };
        let (nx, ny) = (coarse.width() - 1, coarse.height() - 1);
        for (i, j) in [(0, 0), (1, 0), (7, 3), (nx, ny), (nx - 1, 2), (512, ny)] {
            let around: Vec<f64> = (j.saturating_sub(1)..(j + 1).min(ny))
                .flat_map(|bj| (i.saturating_sub(1)..(i + 1).min(nx)).map(move |bi| (bi, bj)))
                .map(|(bi, bj)| midpoint(bi, bj))
                .collect();
            let mean = around.iter().sum::<f64>() / around.len() as f64;
            assert_eq!(
                coarse.sample(i, j),
                mean.round() as u16,
                "corner ({i}, {j})"
            );
            let in_world = coarse.z(i, j) * scale[2];
            assert!((in_world - field.height_of(mean.round() as u16)).abs() < 1e-9);
        }
        let (lo, hi) = terrain.z_range();
        assert_eq!(preview.terrain.z_range(), (lo / 4.0, hi / 4.0));
    }

    /// A map small enough to show at once has no preview.
    #[test]
    fn a_small_map_has_no_preview() {
        let field = Heightfield::from_fn(2049, 300, 10, 1.0, |i, j| ((i + j) % 7) as u16).unwrap();
        assert!(Preview::of(&Terrain::new(field)).is_none());
    }
}
