//! One line that tells the user what was loaded.

use super::{place, Quantisation, Terrain};

impl Terrain {
    /// Size, height range, quantisation and holes, e.g. `513x513 samples, heights 0.00 ..
    /// 120.00 grid units (16-bit steps of 0.00183), no holes`; a georeferenced field's
    /// heights are in metres, followed by its cells, extent and coordinate system.
    pub fn summary(&self) -> String {
        let field = self.field();
        let (lo, hi) = self.z_range();
        let bits = match field.quantisation() {
            Quantisation::Maxval(maxval) if maxval <= u16::from(u8::MAX) => 8,
            _ => 16,
        };
        let holes = match field.nodata_count() {
            0 => "no holes".to_owned(),
            n => format!("{n} no-data samples (holes)"),
        };
        let heights = match (
            place::elevation_metres(field, lo),
            place::elevation_metres(field, hi),
            place::elevation_metres(field, field.step()),
        ) {
            (Some(lo_m), Some(hi_m), Some(step_m)) => {
                format!("{lo_m:.1} .. {hi_m:.1} m ({bits}-bit steps of {step_m:.3e} m)")
            }
            _ => format!(
                "{lo:.2} .. {hi:.2} grid units ({bits}-bit steps of {:.3e}{})",
                field.step(),
                match field.quantisation() {
                    Quantisation::Offset { lowest, .. } => format!(", the file's {lowest} at 0"),
                    Quantisation::Maxval(_) => String::new(),
                }
            ),
        };
        let mut line = format!(
            "{}x{} samples, heights {heights}, {holes}",
            field.width(),
            field.height(),
        );
        if let Some(bytes) = field.store_bytes() {
            line += &format!(
                ", mapped from a tile store of {:.2} GB (memory budget {:.1} GB)",
                bytes as f64 / 1e9,
                super::store::residency::budget() as f64 / 1e9
            );
        }
        match place::describe_georeferencing(field) {
            Some(georef) => format!("{line}; {georef}"),
            None => line,
        }
    }
}
