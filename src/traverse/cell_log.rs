//! What a walk tells of the cells it reaches: nothing ([`Unrecorded`]), or their list in
//! order ([`Recorded`], `trace --cells`). Every walk runs the same either way: the log is a
//! type, not a flag, so a walk that records nothing does no work for it.

/// Where a walk notes the cells it reaches at the cell level.
pub(super) trait CellLog: Default {
    /// Whether anything is noted: without, a walk does not work out which cells it passed.
    const RECORDS: bool;
    /// Cell `(i, j)` was reached.
    fn reached(&mut self, cell: (usize, usize));
    /// The cells noted, in order.
    fn into_cells(self) -> Vec<[usize; 2]>;
}

/// Notes nothing.
#[derive(Default)]
pub(super) struct Unrecorded;

impl CellLog for Unrecorded {
    const RECORDS: bool = false;
    #[inline(always)]
    fn reached(&mut self, _cell: (usize, usize)) {}
    #[inline(always)]
    fn into_cells(self) -> Vec<[usize; 2]> {
        Vec::new()
    }
}

/// Lists the cells reached, in order.
#[derive(Default)]
pub(super) struct Recorded(Vec<[usize; 2]>);

impl CellLog for Recorded {
    const RECORDS: bool = true;
    fn reached(&mut self, (i, j): (usize, usize)) {
        self.0.push([i, j]);
    }
    fn into_cells(self) -> Vec<[usize; 2]> {
        self.0
    }
}
