//! The time-against-error plot: SVG drawn by plotters, rasterised to PNG by resvg with a font
//! embedded in the binary (no system fonts needed).

use anyhow::Context;
use plotters::prelude::*;
use std::path::Path;

/// One method and arithmetic: its time per ray and the share of answers that differ from exact.
#[derive(Clone, Debug)]
pub struct Point {
    pub label: String,
    pub method: String,
    pub ns_per_ray: f64,
    pub error_rate: f64,
}

/// Error rates below this are drawn on the axis floor (exact arithmetic is 0 by definition).
const FLOOR: f64 = 1e-5;

/// Writes a log-log plot of time per ray against error rate; PNG or SVG by the extension.
pub fn time_against_error(points: &[Point], path: &Path) -> anyhow::Result<()> {
    let svg = draw_svg(points)?;
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let bytes = if png {
        rasterise(&svg)?
    } else {
        svg.into_bytes()
    };
    std::fs::write(path, bytes).with_context(|| format!("cannot write {}", path.display()))
}

fn draw_svg(points: &[Point]) -> anyhow::Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let (lo, hi) = points.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.ns_per_ray), hi.max(p.ns_per_ray))
        });
        let x_range = (lo.max(1.0) / 2.0)..(hi.max(2.0) * 2.0);
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "What accuracy costs: time per ray against answers differing from exact",
                ("sans-serif", 20),
            )
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(x_range.log_scale(), (FLOOR / 2.0..1.0).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("time per ray (ns, one thread)")
            .y_desc("share of answers differing from exact (0 drawn at 1e-5)")
            .label_style(("sans-serif", 14))
            .draw()?;
        let palette = [
            RGBColor(31, 119, 180),
            RGBColor(214, 39, 40),
            RGBColor(44, 160, 44),
        ];
        let mut methods: Vec<&str> = points.iter().map(|p| p.method.as_str()).collect();
        methods.dedup();
        for (k, method) in methods.iter().enumerate() {
            let colour = palette[k % palette.len()];
            let mine: Vec<&Point> = points.iter().filter(|p| p.method == *method).collect();
            chart
                .draw_series(mine.iter().map(|p| {
                    Circle::new((p.ns_per_ray, p.error_rate.max(FLOOR)), 6, colour.filled())
                }))?
                .label(*method)
                .legend(move |(x, y)| Circle::new((x, y), 6, colour.filled()));
            // Methods sit close together: one labels above its points, the next below.
            let lift = if k % 2 == 0 { 1.3 } else { 0.62 };
            chart.draw_series(mine.iter().map(|p| {
                let name = short_name(p.label.trim_start_matches(*method).trim());
                let at = (p.ns_per_ray * 1.08, p.error_rate.max(FLOOR) * lift);
                Text::new(name, at, ("sans-serif", 13).into_font().color(&colour))
            }))?;
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.9))
            .draw()?;
        root.present()?;
    }
    Ok(svg)
}

fn rasterise(svg: &str) -> anyhow::Result<Vec<u8>> {
    let mut fonts = resvg::usvg::fontdb::Database::new();
    fonts.load_font_data(epaint_default_fonts::UBUNTU_LIGHT.to_vec());
    let family = fonts
        .faces()
        .next()
        .and_then(|f| f.families.first())
        .map(|f| f.0.clone())
        .unwrap_or_default();
    fonts.set_sans_serif_family(family);
    let options = resvg::usvg::Options {
        fontdb: std::sync::Arc::new(fonts),
        ..Default::default()
    };
    let tree = resvg::usvg::Tree::from_str(svg, &options).context("plot SVG")?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).context("plot size")?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    pixmap.encode_png().context("encoding the plot")
}

/// `rational:65536` reads as `rational 2^16`.
fn short_name(arith: &str) -> String {
    match arith
        .strip_prefix("rational:")
        .and_then(|b| b.parse::<u32>().ok())
    {
        Some(bound) if bound.is_power_of_two() => format!("rational 2^{}", bound.trailing_zeros()),
        _ => arith.to_owned(),
    }
}
