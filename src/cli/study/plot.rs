//! The study plots: log-log error against samples and against time, drawn with plotters into
//! PNG bytes with a bundled font.

use image::ImageEncoder;
use raytracer::sampling::Method;

use super::runs::*;

/// The font the plots' text is drawn with, bundled so that no system font is needed (DejaVu Sans
/// Mono, Bitstream Vera licence: `assets/fonts/DejaVu-LICENSE.txt`).
static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSansMono.ttf");

/// Registers [`FONT`] as plotters' `sans-serif`, once.
pub(super) fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let _ =
            plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, FONT);
    });
}

/// Colour of a sampler's line.
pub(super) fn colour(m: Method) -> plotters::style::RGBColor {
    match m {
        Method::Random => plotters::style::RGBColor(214, 39, 40),
        Method::Jittered => plotters::style::RGBColor(31, 119, 180),
        Method::Sobol => plotters::style::RGBColor(44, 160, 44),
    }
}

/// Draws the log-log plot of the region MSE against samples (left) and against seconds (right),
/// one line per sampler with its fitted slope in the legend, as a `width × height` RGB8 buffer.
pub fn plot_rgb(
    runs: &[Run],
    title: &str,
    counted: &str,
    width: u32,
    height: u32,
) -> Result<Vec<u8>, String> {
    use plotters::prelude::*;
    register_font();
    let mut buf = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root = root
            .titled(title, ("sans-serif", 18))
            .map_err(|e| e.to_string())?;
        let panels = root.split_evenly((1, 2));
        let samplers: Vec<Method> = SAMPLERS
            .into_iter()
            .filter(|&m| runs.iter().any(|r| r.sampler == m))
            .collect();
        let positive = |v: f64| v.is_finite() && v > 0.0;
        let ys: Vec<f64> = runs
            .iter()
            .map(|r| r.mse_region)
            .filter(|&v| positive(v))
            .collect();
        let (ymin, ymax) = bounds(&ys);
        for (panel, by_time) in panels.iter().zip([false, true]) {
            let xs: Vec<f64> = runs
                .iter()
                .map(|r| if by_time { r.seconds } else { r.samples as f64 })
                .filter(|&v| positive(v))
                .collect();
            let (xmin, xmax) = bounds(&xs);
            let mut chart = ChartBuilder::on(panel)
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .caption(
                    if by_time {
                        "MSE vs render time".to_string()
                    } else {
                        format!("MSE vs {counted}")
                    },
                    ("sans-serif", 16),
                )
                .build_cartesian_2d((xmin..xmax).log_scale(), (ymin..ymax).log_scale())
                .map_err(|e| e.to_string())?;
            draw_axes(&mut chart, if by_time { "seconds" } else { counted })?;
            for &m in &samplers {
                let c = colour(m);
                let pts: Vec<(f64, f64)> = runs_of(runs, m)
                    .iter()
                    .map(|r| {
                        (
                            if by_time { r.seconds } else { r.samples as f64 },
                            r.mse_region,
                        )
                    })
                    .filter(|&(x, y)| positive(x) && positive(y))
                    .collect();
                let label = match mse_slope(runs, m) {
                    Some(s) => format!("{m} (slope {s:.2})"),
                    None => m.to_string(),
                };
                chart
                    .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
                    .map_err(|e| e.to_string())?
                    .label(label)
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                    });
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
                    .map_err(|e| e.to_string())?;
            }
            draw_legend(&mut chart)?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(buf)
}

/// A log-log chart drawn into an RGB buffer.
type LogChart<'a, 'b> = plotters::chart::ChartContext<
    'a,
    plotters::backend::BitMapBackend<'b>,
    plotters::coord::cartesian::Cartesian2d<
        plotters::coord::combinators::LogCoord<f64>,
        plotters::coord::combinators::LogCoord<f64>,
    >,
>;

/// The axes and grid of the studies' plots: `x` described as `x_desc`, `y` the MSE, log ticks.
pub(super) fn draw_axes<'a, 'b: 'a>(
    chart: &mut LogChart<'a, 'b>,
    x_desc: &str,
) -> Result<(), String> {
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("MSE")
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(|e| e.to_string())
}

/// The legend of the studies' plots: lower left, on a pale box.
pub(super) fn draw_legend<'a, 'b: 'a>(chart: &mut LogChart<'a, 'b>) -> Result<(), String> {
    use plotters::prelude::*;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .label_font(("sans-serif", 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| e.to_string())
}

/// A `width × height` RGB8 buffer as PNG bytes.
pub(super) fn encode_png(buf: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(buf, width, height, image::ExtendedColorType::Rgb8)
        .map_err(|e| format!("cannot encode the plot: {e}"))?;
    Ok(png)
}

/// A log-axis tick label: only 1, 2 and 5 times a power of ten are written, so labels do not
/// crowd.
fn tick(v: f64) -> String {
    if v <= 0.0 {
        return String::new();
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    if [1.0, 2.0, 5.0].iter().any(|&k| (m - k).abs() < 1e-6 * k) {
        if (-2.0..=4.0).contains(&e) {
            format!("{v}")
        } else {
            format!("{m:.0}e{e}")
        }
    } else {
        String::new()
    }
}

/// Log-scale axis bounds around `v` with some room (a decade around 1 for no values).
pub(super) fn bounds(v: &[f64]) -> (f64, f64) {
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(0.0f64, f64::max);
    if !lo.is_finite() || hi <= 0.0 {
        return (0.1, 10.0);
    }
    let (lo, hi) = if lo == hi {
        (lo / 2.0, hi * 2.0)
    } else {
        (lo, hi)
    };
    (lo / 1.5, hi * 1.5)
}

/// The plot of [`plot_rgb`] as PNG bytes.
pub fn plot_png(runs: &[Run], title: &str, counted: &str) -> Result<Vec<u8>, String> {
    let (w, h) = (1200, 520);
    encode_png(&plot_rgb(runs, title, counted, w, h)?, w, h)
}
