//! One line that tells the user what was loaded.

use super::{Quantisation, Terrain};

impl Terrain {
    /// Size, height range, quantisation step and holes, e.g. `513x513 samples, heights
    /// 0.00 .. 120.00 (step 0.00183, 16-bit), no holes`.
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
        format!(
            "{}x{} samples, heights {lo:.2} .. {hi:.2} (step {:.3e}, {source}), {holes}",
            field.width(),
            field.height(),
            field.step(),
        )
    }
}
