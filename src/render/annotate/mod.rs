//! Annotations drawn into a finished picture at its output resolution, so text and marks are
//! crisp at any size: a scale bar, a north arrow, a height legend, a title and attribution,
//! and vector layers' places and lines, shown only where the terrain lets the eye see them.
//!
//! They are written as one SVG document of the whole image and rasterised by resvg with the
//! viewer's font; a window of the image (a poster's tile) rasterises its part of the same
//! document, so merged tiles show the whole picture's annotations.

#[cfg(feature = "annotate")]
mod fonts;
mod layout;
mod measure;
mod place_names;
#[cfg(feature = "annotate")]
mod raster;
mod sheet;
mod sight;
mod svg;
mod vectors;

#[cfg(feature = "annotate")]
pub use fonts::svg_options;
pub use layout::{north_angle_deg, trimmed, ScaleBar};
pub use measure::TextWidth;
pub use place_names::PlacedName;
#[cfg(feature = "annotate")]
pub use raster::{DrawError, Marked};
pub use sheet::{Annotations, AnnotationsSection, Sheet};
pub use sight::Sight;
pub use svg::{escaped, round_marks};
pub use vectors::{
    from_geojson, from_gpx, Coordinates, Place, VectorError, VectorFile, VectorFileError,
    VectorLayer, VectorProblem, VectorSection,
};
