//! The arguments of `render --ortho` (map products) and of TIFF output.

/// Products made straight down over the map, and how TIFFs are written.
#[derive(clap::Args, Debug)]
pub struct OrthoArgs {
    /// Render straight down, one pixel per cell of the map's own grid (or per --cell): a
    /// product, written as a GeoTIFF (.tif: georeferenced where the map is) or a PNG picture.
    #[arg(long, conflicts_with_all = ["frames", "tile", "tiles", "stats", "size"])]
    pub ortho: bool,
    /// With --ortho: shaded (the scene's shading with cast shadows, colour), sky-view (the
    /// sky-view factor, 0 to 1) or sunlight-hours (hours of direct sun on --date); the last
    /// two as 32-bit float values.
    #[arg(long, requires = "ortho", default_value = "shaded", value_parser = ["shaded", "sky-view", "sunlight-hours"])]
    pub product: String,
    /// With --ortho: pixel size in the map's units (metres or feet of a projected map,
    /// degrees of a geographic one, cells of a plain image); default: the map's own cells.
    #[arg(
        long,
        requires = "ortho",
        value_name = "SIZE",
        allow_hyphen_values = true
    )]
    pub cell: Option<f64>,
    /// With --product sunlight-hours: the day, YYYY-MM-DD, midnight to midnight on the map's
    /// local clocks.
    #[arg(long, requires = "ortho", value_name = "YYYY-MM-DD", value_parser = parse_date)]
    pub date: Option<chrono::NaiveDate>,
    /// With --product sunlight-hours: minutes between the sun's positions (divides 60).
    #[arg(long, requires = "ortho", default_value_t = 10, value_name = "MINUTES")]
    pub sun_step: u32,
    /// With --product sunlight-hours: whether each sun's strip bounds settle rays without a
    /// walk where they prove them clear (the same hours; off to measure what they save).
    #[arg(long, requires = "ortho", default_value = "on", value_parser = ["on", "off"])]
    pub strip_bounds: String,
    /// With --product sky-view: compass directions searched for the horizon.
    #[arg(long, requires = "ortho", default_value_t = heightray::products::sky_view::DEFAULT_DIRECTIONS)]
    pub svf_directions: u32,
    /// With --product sky-view: how far the horizon is searched, in cells (along y where
    /// cells are not square).
    #[arg(long, requires = "ortho", default_value_t = heightray::products::sky_view::DEFAULT_RADIUS_CELLS, value_name = "CELLS")]
    pub svf_radius: f64,
    /// With --ortho: contour lines every HEIGHT (the map's height unit), index lines labelled
    /// with their height; replaces the scene's `[overlay] contours`. Drawn on pictures only
    /// (--product shaded, or a .png of any product), never into sky-view or sunlight-hours
    /// values.
    #[arg(long, requires = "ortho", value_name = "HEIGHT")]
    pub contours: Option<f64>,
    /// With --contours: every N-th line is a wider, labelled index line (default: the scene's
    /// `index_every`, else 5; 0 for none).
    #[arg(long, requires = "ortho", value_name = "N")]
    pub index_every: Option<u32>,
    /// Bits per channel of a colour TIFF (-o out.tif): 8 or 16. At 16 the picture is made
    /// from the renderer's linear colours, far finer than the PNG's bytes (not for tiles or
    /// frames, which are PNGs).
    #[arg(long, default_value = "8", value_parser = ["8", "16"])]
    pub depth: String,
    /// Resolution written into a TIFF, in dots per inch.
    #[arg(long)]
    pub dpi: Option<f64>,
}

fn parse_date(text: &str) -> Result<chrono::NaiveDate, super::knobs::ValueError> {
    chrono::NaiveDate::parse_from_str(text.trim(), "%Y-%m-%d").map_err(|reason| {
        super::knobs::ValueError::Date {
            text: text.to_owned(),
            reason,
        }
    })
}
