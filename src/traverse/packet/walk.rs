//! The packet's walk: depth first down the mipmap, each block's four children tested together
//! and the ones a ray may touch pushed far first, so that the near one is walked first.

use super::lanes::{Kernel, Packet};
use super::{PacketClearance, HANDOFF, LANES};
use crate::traverse::Clearance;

/// A block some lanes may touch, waiting on the stack: level `k`, frame block `(bu, bv)`, the
/// lanes that may touch it, and where each lane enters it.
#[derive(Clone, Copy)]
struct Node {
    k: u32,
    bu: i64,
    bv: i64,
    may: u32,
    enter: [f64; LANES],
}

/// Walks the packet and writes where each of its rays starts its own walk into `out`.
#[inline(always)]
pub(super) fn walk<K: Kernel>(p: &Packet<'_>, out: &mut PacketClearance) {
    let f = &p.frame;
    let top = p.terrain.mipmap().top();
    // Three siblings wait at each level at most, and the top block.
    let mut stack: Vec<Node> = Vec::with_capacity(3 * top as usize + 2);
    // The top block covers the grid.
    let root = (f.cols.0 >> top, f.rows.0 >> top);
    stack.extend(test::<K>(p, top, root, p.members, out));
    let mut alive = p.members;
    while let Some(node) = stack.pop() {
        let lanes = node.may & alive;
        if lanes == 0 {
            continue;
        }
        let leaving = if node.k == 0 || (few(alive) && !few(p.members)) {
            lanes
        } else {
            0
        };
        for l in each(leaving) {
            let t = stack
                .iter()
                .filter(|waiting| waiting.may & (1 << l) != 0)
                .fold(node.enter[l], |t, waiting| t.min(waiting.enter[l]));
            out.lanes[l] = Some(Clearance { t, level: node.k });
        }
        alive &= !leaving;
        let down = lanes & !leaving;
        if down == 0 {
            continue;
        }
        let (k, bu, bv) = (node.k - 1, 2 * node.bu, 2 * node.bv);
        for (du, dv) in [(1, 1), (0, 1), (1, 0), (0, 0)] {
            stack.extend(test::<K>(p, k, (bu + du, bv + dv), down, out));
        }
    }
    // Every block these rays cross was cleared: they touch nothing (`f64::MAX`, not infinity,
    // which the walk's own start could not move down by its rounding).
    for l in each(alive) {
        out.lanes[l] = Some(Clearance {
            t: f64::MAX,
            level: 0,
        });
    }
}

/// The node test of frame block `(bu, bv)` of level `k` for `lanes`: the block as a node to
/// walk if some lane may touch it. Counted in `out` where some lane crosses it.
#[inline(always)]
fn test<K: Kernel>(
    p: &Packet<'_>,
    k: u32,
    (bu, bv): (i64, i64),
    lanes: u32,
    out: &mut PacketClearance,
) -> Option<Node> {
    let (f, terrain) = (&p.frame, p.terrain);
    let side = 1i64 << k;
    let (cu, cv) = (bu << k, bv << k);
    let outside = cu > f.cols.1 || cv > f.rows.1 || cu + side <= f.cols.0;
    if outside || cv + side <= f.rows.0 {
        return None;
    }
    // (Frame blocks are aligned like the grid's: any cell of the block names it.)
    let (i, j) = f.cell(cu.max(f.cols.0), cv.max(f.rows.0));
    let sample = if k == 0 {
        terrain.cell_sample_range(i, j).1
    } else {
        terrain.mipmap().highest(k, i >> k, j >> k)
    };
    let (u, v, width) = (cu as f64, cv as f64, side as f64);
    let highest = terrain.field().height_of(sample);
    let test = K::test(&p.lanes, p.room, [u, u + width, v, v + width], highest);
    if test.touch & lanes == 0 {
        return None;
    }
    let may = test.may & lanes;
    out.tests.record(may != 0);
    (may != 0).then_some(Node {
        k,
        bu,
        bv,
        may,
        enter: test.enter,
    })
}

/// Whether the lanes of a mask are few enough to walk on their own (a packet that began with
/// as few walks to the end: a lone ray's packet stands for its walk in the tests).
fn few(lanes: u32) -> bool {
    lanes.count_ones() <= HANDOFF
}

/// The lanes of a mask, lowest first.
fn each(mask: u32) -> impl Iterator<Item = usize> {
    (0..LANES).filter(move |l| mask & (1 << l) != 0)
}
