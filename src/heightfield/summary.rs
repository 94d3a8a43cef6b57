//! One line that tells the user what was loaded.

use super::{place, Quantisation, Terrain};

impl Terrain {
    /// Size, height range, quantisation step and holes, e.g. `513x513 samples, heights
    /// 0.00 .. 120.00 (step 0.00183, 16-bit), no holes`; for a georeferenced field also its
    /// heights in metres, cell size and extent.
    pub fn summary(&self) -> String {
        let field = self.field();
        let (lo, hi) = self.z_range();
        let source = match field.quantisation() {
            Quantisation::Maxval(maxval) => format!("maxval {maxval}"),
            Quantisation::Offset { lowest, step } => {
                format!("values {lowest} + sample x {step:.3e}")
            }
        };
        let holes = match field.nodata_count() {
            0 => "no holes".to_owned(),
            n => format!("{n} no-data samples (holes)"),
        };
        let heights = match (
            place::elevation_metres(field, lo),
            place::elevation_metres(field, hi),
        ) {
            (Some(lo_m), Some(hi_m)) => format!("{lo_m:.1} .. {hi_m:.1} m ({lo:.2} .. {hi:.2})"),
            _ => format!("{lo:.2} .. {hi:.2}"),
        };
        let line = format!(
            "{}x{} samples, heights {heights} (step {:.3e}, {source}), {holes}",
            field.width(),
            field.height(),
            field.step(),
        );
        match place::describe_georeferencing(field) {
            Some(georef) => format!("{line}; {georef}"),
            None => line,
        }
    }
}
