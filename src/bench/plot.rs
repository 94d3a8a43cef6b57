//! The time-against-error plot: SVG drawn by plotters, rasterised to PNG by resvg with a font
//! embedded in the binary (no system fonts needed).

use anyhow::Context;
use plotters::prelude::*;
use std::path::Path;

/// One method and arithmetic: its time per ray and the share of answers that differ from exact.
#[derive(Clone, Debug)]
pub struct Point {
    /// The method and arithmetic, e.g. `mipmap f64`.
    pub label: String,
    /// The method alone (its colour in the plot).
    pub method: String,
    /// Time per ray in nanoseconds (x axis).
    pub ns_per_ray: f64,
    /// Share of answers that differ from exact, 0 to 1 (y axis).
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
    crate::output_file::write_bytes(path, &bytes).map_err(anyhow::Error::msg)
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
        // One colour per method (matplotlib's first four), so every method has its own.
        let palette = [
            RGBColor(31, 119, 180),
            RGBColor(214, 39, 40),
            RGBColor(44, 160, 44),
            RGBColor(255, 127, 14),
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
        }
        // One label per arithmetic (the colours tell the methods apart), under its leftmost
        // point (above, on the floor), as near as it fits without covering a label placed
        // before it: the bounded rationals sit close together.
        let mut ariths: Vec<(String, f64, f64)> = Vec::new();
        for p in points {
            let name = short_name(p.label.trim_start_matches(p.method.as_str()).trim());
            let (x, y) = (p.ns_per_ray, p.error_rate.max(FLOOR));
            match ariths.iter_mut().find(|a| a.0 == name) {
                Some(a) if x < a.1 => (a.1, a.2) = (x, y),
                Some(_) => {}
                None => ariths.push((name, x, y)),
            }
        }
        ariths.sort_by(|a, b| a.1.total_cmp(&b.1));
        // What a label must not cover, as (left, right, top) of a box 14 high: every point
        // and every label placed before it.
        let mut placed: Vec<(i32, i32, i32)> = points
            .iter()
            .map(|p| {
                let (cx, cy) = chart.backend_coord(&(p.ns_per_ray, p.error_rate.max(FLOOR)));
                (cx - 7, cx + 7, cy - 7)
            })
            .collect();
        let mut labels = Vec::new();
        for (name, x, y) in &ariths {
            let (px, py) = chart.backend_coord(&(x * 0.92, *y));
            let width = 6 * name.len() as i32 + 4;
            let down = *y > FLOOR;
            let clear = |dy: i32| {
                let top = if down { py + dy } else { py - dy - 14 };
                let free = placed
                    .iter()
                    .all(|&(x0, x1, t)| px + width < x0 || px > x1 || top + 14 < t || top > t + 14);
                free.then_some(top)
            };
            let (first, top) = (1..16)
                .find_map(|k| clear(12 * k).map(|top| (k == 1, top)))
                .unwrap_or((true, py + 12));
            placed.push((px, px + width, top));
            // A label pushed away from its point by others is tied to it by a line.
            if !first {
                let (ax, ay) = chart.backend_coord(&(*x, *y));
                let end = if down { top } else { top + 14 };
                let line = PathElement::new(vec![(ax, ay), (px + 3, end)], BLACK.mix(0.4));
                root.draw(&line)?;
            }
            labels.push((name, px, top, width));
        }
        // Labels over every line and grid line, each on a pale ground.
        for (name, px, top, width) in labels {
            let ground = [(px - 2, top - 1), (px + width + 2, top + 14)];
            root.draw(&Rectangle::new(ground, WHITE.mix(0.85).filled()))?;
            let font = ("sans-serif", 13).into_font().color(&BLACK);
            root.draw(&Text::new(name.clone(), (px, top), font))?;
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
    let options = crate::render::annotate::svg_options();
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
