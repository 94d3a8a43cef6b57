//! Lines of equal height over a height field, traced on the surface's own triangles: each
//! cell's two triangles (split along the diagonal from sample `(i, j)` to `(i+1, j+1)`, the
//! surface contract of [`crate::geometry`]) are planes, so a level crosses each in one straight
//! segment and the lines found are exactly where the rendered surface has that height.
//! (Marching squares, on the cell's bilinear patch, would be off the rendered surface by up to
//! a quarter of a cell's relief across the diagonal.)
//!
//! A sample at exactly a level counts as above it, so a level touching a vertex is one line,
//! not two that meet there. Cells with a sample of no data are left out: lines end at holes.

use crate::heightfield::Heightfield;
use std::collections::{BTreeMap, HashMap};

/// A line of one level, in grid coordinates (sample `(i, j)` at `x = i`, `y = j`): open where
/// it ends at the map's edge or a hole, closed (its last point its first) where it rings.
pub type Isoline = Vec<[f64; 2]>;

/// A triangle edge, by its two samples' indices (the smaller first).
type Edge = (usize, usize);

/// A level's segment across a triangle: the edges it crosses, and where.
type Segment = [(Edge, [f64; 2]); 2];

/// The lines of every level `k * interval` (grid height; `k` any integer) the surface
/// crosses, keyed by `k`, each level's lines in a fixed order. Empty unless the interval is
/// finite and above 0.
pub fn isolines(field: &Heightfield, interval: f64) -> BTreeMap<i64, Vec<Isoline>> {
    let mut segments: BTreeMap<i64, Vec<Segment>> = BTreeMap::new();
    if !(interval.is_finite() && interval > 0.0) {
        return BTreeMap::new();
    }
    let (w, h) = (field.width(), field.height());
    let index = |i: usize, j: usize| j * w + i;
    for j in 0..h.saturating_sub(1) {
        for i in 0..w.saturating_sub(1) {
            if field.is_hole_cell(i, j) {
                continue;
            }
            let corner = |di: usize, dj: usize| {
                let (x, y) = (i + di, j + dj);
                (index(x, y), [x as f64, y as f64], field.z(x, y))
            };
            let (p00, p10, p01, p11) = (corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1));
            for triangle in [[p00, p10, p11], [p00, p11, p01]] {
                let zs = triangle.map(|(_, _, z)| z);
                let lo = zs.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                // Levels with a corner below (z < level) and one at or above: lo < level <= hi.
                let first = (lo / interval).floor() as i64 + 1;
                let last = (hi / interval).floor() as i64;
                for k in first..=last {
                    if let Some(segment) = crossing(&triangle, k as f64 * interval) {
                        segments.entry(k).or_default().push(segment);
                    }
                }
            }
        }
    }
    segments
        .into_iter()
        .map(|(k, level)| (k, joined(&level)))
        .collect()
}

/// Where `level` crosses a triangle of `(sample index, point, height)` corners: the segment
/// between its two crossed edges, if it crosses.
fn crossing(corners: &[(usize, [f64; 2], f64); 3], level: f64) -> Option<Segment> {
    let mut found = Vec::with_capacity(2);
    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
        let ((ia, pa, za), (ib, pb, zb)) = (corners[a], corners[b]);
        if (za >= level) == (zb >= level) {
            continue;
        }
        let t = (level - za) / (zb - za);
        let point = [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])];
        found.push(((ia.min(ib), ia.max(ib)), point));
    }
    <[_; 2]>::try_from(found).ok()
}

/// Segments sharing edges joined into lines: open lines walked from an end first, then the
/// rings.
fn joined(segments: &[Segment]) -> Vec<Isoline> {
    let mut at: HashMap<Edge, Vec<usize>> = HashMap::new();
    for (n, segment) in segments.iter().enumerate() {
        for (edge, _) in segment {
            at.entry(*edge).or_default().push(n);
        }
    }
    let mut used = vec![false; segments.len()];
    let mut lines = Vec::new();
    // An edge only one segment crosses is a line's end (at the map's edge or a hole).
    let ends = segments.iter().enumerate().flat_map(|(n, segment)| {
        segment
            .iter()
            .filter(|(edge, _)| at.get(edge).is_some_and(|s| s.len() == 1))
            .map(move |&(edge, _)| (n, edge))
    });
    let starts: Vec<(usize, Edge)> = ends
        .chain(segments.iter().enumerate().map(|(n, s)| (n, s[0].0)))
        .collect();
    for (first, from) in starts {
        if used[first] {
            continue;
        }
        let (mut current, mut edge) = (first, from);
        let start_point = segments[first]
            .iter()
            .find(|(e, _)| *e == from)
            .map_or(segments[first][0].1, |(_, p)| *p);
        let mut line = vec![start_point];
        loop {
            used[current] = true;
            // The segment's other end.
            let Some(&(next_edge, point)) = segments[current].iter().find(|(e, _)| *e != edge)
            else {
                break;
            };
            line.push(point);
            edge = next_edge;
            let next = at
                .get(&edge)
                .and_then(|s| s.iter().copied().find(|&m| !used[m]));
            match next {
                Some(m) => current = m,
                None => break,
            }
        }
        if line.len() >= 2 {
            lines.push(line);
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_gives_straight_lines_at_its_levels() {
        // z = 2x + y on 6 x 5 samples: level 6 runs from (3, 0) to (1, 4).
        let field = Heightfield::from_fn(6, 5, 1000, 1000.0, |i, j| (2 * i + j) as u16).unwrap();
        let lines = isolines(&field, 6.0);
        let level = &lines[&1];
        assert_eq!(level.len(), 1);
        for p in &level[0] {
            assert!((2.0 * p[0] + p[1] - 6.0).abs() < 1e-12, "{p:?}");
        }
        let ends = [level[0][0], level[0][level[0].len() - 1]];
        assert!(
            ends.contains(&[3.0, 0.0]) && ends.contains(&[1.0, 4.0]),
            "{ends:?}"
        );
        // Levels 0 and 14 (the lowest and highest sample) draw no line: nothing lies below 0,
        // and only the corner (5, 4) reaches 14.
        assert_eq!(lines.keys().copied().collect::<Vec<_>>(), vec![1, 2]);
    }

    #[test]
    fn a_peak_gives_a_closed_ring() {
        let field = Heightfield::from_fn(
            5,
            5,
            1000,
            1000.0,
            |i, j| if (i, j) == (2, 2) { 10 } else { 0 },
        )
        .unwrap();
        let lines = isolines(&field, 5.0);
        let ring = &lines[&1];
        assert_eq!(ring.len(), 1);
        assert_eq!(ring[0].first(), ring[0].last());
        // Six triangles meet at the peak's sample (the diagonals run one way): six segments.
        assert_eq!(ring[0].len(), 7);
    }
}
