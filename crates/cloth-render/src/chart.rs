//! Charts for reports: series of points as lines or bars over labelled axes (linear, or
//! logarithmic in y), with a legend, vertical marks (where a run's stages begin), and
//! several charts stacked in one picture.

use super::image::Image;
use super::legend::INK;
use super::text::{draw_text, fit_text, text_width, GLYPH};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    /// Points joined in order; a point that cannot be shown (not finite, or not positive
    /// on a log axis) breaks the line.
    Line,
    /// A bar from 0 to each point's y, `width` wide in x units, its middle `offset` from
    /// the point's x (side-by-side series of one histogram).
    Bars { width: f64, offset: f64 },
}

#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub colour: [u8; 3],
    pub style: Style,
}

/// One chart: its series over axes that span them all.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// A logarithmic y axis (powers of ten), for quantities spanning decades.
    pub log_y: bool,
    pub series: Vec<Series>,
    /// Labelled vertical lines at these x.
    pub marks: Vec<(f64, String)>,
}

const FRAME: [u8; 3] = [150, 155, 165];
const GRID: [u8; 3] = [232, 234, 238];
const BACKGROUND: [u8; 3] = [255, 255, 255];

/// `charts` one above the other in a `width` x `height` picture, each given an equal
/// share of the height.
pub fn charts(charts: &[Chart], width: u32, height: u32) -> Image {
    let mut image = Image::new(width, height, BACKGROUND);
    let n = charts.len().max(1) as i64;
    let share = height as i64 / n;
    let scale = if width < 480 || share < 200 { 1 } else { 2 };
    for (k, chart) in charts.iter().enumerate() {
        let area = Area {
            x: 0,
            y: k as i64 * share,
            w: width as i64,
            h: share,
        };
        draw_chart(&mut image, area, chart, scale);
    }
    image
}

#[derive(Debug, Clone, Copy)]
struct Area {
    x: i64,
    y: i64,
    w: i64,
    h: i64,
}

/// The range of an axis and how values map onto it.
#[derive(Debug, Clone, Copy)]
struct Axis {
    lo: f64,
    hi: f64,
    log: bool,
}

impl Axis {
    /// Spanning `values` (with 0 for a linear axis that has bars), padded by a twentieth
    /// on a linear axis, to whole decades on a log one; `None` with nothing to show.
    fn spanning(values: impl Iterator<Item = f64>, log: bool, from_zero: bool) -> Option<Self> {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if lo > hi {
            return None;
        }
        if log {
            // A little room, so a series at a power of ten is not drawn on the frame.
            let (a, b) = ((lo.log10() - 0.02).floor(), (hi.log10() + 0.02).ceil());
            let b = if b <= a { a + 1.0 } else { b };
            return Some(Self { lo: a, hi: b, log });
        }
        if from_zero {
            lo = lo.min(0.0);
            hi = hi.max(0.0);
        }
        if hi - lo <= f64::EPSILON * hi.abs().max(1.0) {
            let pad = if hi == 0.0 { 1.0 } else { 0.1 * hi.abs() };
            return Some(Self {
                lo: lo - pad,
                hi: hi + pad,
                log,
            });
        }
        let pad = 0.05 * (hi - lo);
        Some(Self {
            lo: if from_zero && lo == 0.0 { 0.0 } else { lo - pad },
            hi: hi + pad,
            log,
        })
    }

    /// Where `v` is from 0 (low end) to 1 (high end); `None` where it cannot be shown.
    fn place(&self, v: f64) -> Option<f64> {
        let v = if self.log {
            (v > 0.0).then(|| v.log10())?
        } else {
            v
        };
        v.is_finite().then(|| (v - self.lo) / (self.hi - self.lo))
    }

    /// Tick values and their labels.
    fn ticks(&self) -> Vec<(f64, String)> {
        if self.log {
            let decades = (self.hi - self.lo).round() as i64;
            let every = (decades + 5) / 6;
            return (self.lo as i64..=self.hi as i64)
                .filter(|k| (k - self.lo as i64) % every.max(1) == 0)
                .map(|k| (10f64.powi(k as i32), power_label(k)))
                .collect();
        }
        let step = nice_step((self.hi - self.lo) / 6.0);
        let decimals = (-step.log10().floor()).max(0.0) as usize;
        let first = (self.lo / step).ceil() as i64;
        let last = (self.hi / step).floor() as i64;
        (first..=last)
            .map(|k| {
                let v = k as f64 * step;
                (v, format!("{:.*}", decimals, if v == 0.0 { 0.0 } else { v }))
            })
            .collect()
    }
}

/// 1, 2 or 5 times a power of ten, at least `rough`.
fn nice_step(rough: f64) -> f64 {
    let power = 10f64.powf(rough.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .find(|s| *s >= rough)
        .unwrap_or(10.0 * power)
}

fn power_label(k: i64) -> String {
    match k {
        0..=3 => format!("{}", 10i64.pow(k as u32)),
        _ => format!("1e{k}"),
    }
}

fn draw_chart(image: &mut Image, area: Area, chart: &Chart, scale: u32) {
    let glyph = (GLYPH * scale) as i64;
    let points = || chart.series.iter().flat_map(|s| s.points.iter());
    let has_bars = chart.series.iter().any(|s| matches!(s.style, Style::Bars { .. }));
    let x_values = chart.series.iter().flat_map(|s| {
        let (width, offset) = match s.style {
            Style::Bars { width, offset } => (width, offset),
            Style::Line => (0.0, 0.0),
        };
        s.points
            .iter()
            .flat_map(move |p| [p.0 + offset - width / 2.0, p.0 + offset + width / 2.0])
    });
    let x_axis = Axis::spanning(x_values, false, false);
    let y_axis = Axis::spanning(points().map(|p| p.1), chart.log_y, has_bars);

    // Room for the title above, the tick labels and axis labels left and below.
    let y_ticks = y_axis.map(|a| a.ticks()).unwrap_or_default();
    let widest = y_ticks
        .iter()
        .map(|(_, l)| text_width(l, scale) as i64)
        .max()
        .unwrap_or(0);
    let plot = Area {
        x: area.x + widest + 2 * glyph,
        y: area.y + 3 * glyph + glyph / 2,
        w: area.w - widest - 3 * glyph,
        h: area.h - 6 * glyph - glyph / 2,
    };
    let title = fit_text(&chart.title, area.w.max(0) as u32, scale);
    let centred = |text: &str| area.x + (area.w - text_width(text, scale) as i64) / 2;
    draw_text(image, centred(&title), area.y + glyph / 2, &title, scale, INK);
    if plot.w < 4 * glyph || plot.h < 2 * glyph {
        return;
    }
    let (Some(x_axis), Some(y_axis)) = (x_axis, y_axis) else {
        let text = "nothing to plot";
        draw_text(image, centred(text), plot.y + plot.h / 2, text, scale, FRAME);
        return;
    };
    let to_x = |v: f64| {
        x_axis
            .place(v)
            .map(|t| plot.x + (t * plot.w as f64).round() as i64)
    };
    let to_y = |v: f64| {
        y_axis
            .place(v)
            .map(|t| plot.y + plot.h - (t * plot.h as f64).round() as i64)
    };

    for (v, label) in &y_ticks {
        if let Some(y) = to_y(*v) {
            image.fill_rect(plot.x, y, plot.w, 1, GRID);
            let x = plot.x - glyph / 2 - text_width(label, scale) as i64;
            draw_text(image, x, y - glyph / 2, label, scale, INK);
        }
    }
    for (v, label) in x_axis.ticks() {
        if let Some(x) = to_x(v) {
            image.fill_rect(x, plot.y, 1, plot.h, GRID);
            let w = text_width(&label, scale) as i64;
            draw_text(image, x - w / 2, plot.y + plot.h + glyph / 2, &label, scale, INK);
        }
    }
    let x_label = fit_text(&chart.x_label, plot.w as u32, scale);
    let x = plot.x + (plot.w - text_width(&x_label, scale) as i64) / 2;
    draw_text(image, x, plot.y + plot.h + 2 * glyph, &x_label, scale, INK);
    let y_label = fit_text(&chart.y_label, plot.w as u32, scale);
    draw_text(image, plot.x, plot.y - glyph - glyph / 4, &y_label, scale, FRAME);

    for (v, label) in &chart.marks {
        if let Some(x) = to_x(*v) {
            for y in (plot.y..plot.y + plot.h).step_by(6) {
                image.fill_rect(x, y, 1, 3, FRAME);
            }
            draw_text(image, x + glyph / 4, plot.y + glyph / 4, label, scale, FRAME);
        }
    }

    let base = if y_axis.log { None } else { to_y(0.0) };
    for series in &chart.series {
        match series.style {
            Style::Line => {
                let mut last: Option<(i64, i64)> = None;
                for &(vx, vy) in &series.points {
                    let here = to_x(vx).zip(to_y(vy));
                    if let (Some(a), Some(b)) = (last, here) {
                        line(image, a, b, series.colour);
                    }
                    last = here;
                }
            }
            Style::Bars { width, offset } => {
                let bottom = base.unwrap_or(plot.y + plot.h);
                for &(vx, vy) in &series.points {
                    let left = to_x(vx + offset - width / 2.0);
                    let right = to_x(vx + offset + width / 2.0);
                    if let (Some(l), Some(r), Some(top)) = (left, right, to_y(vy)) {
                        let (y0, y1) = (top.min(bottom), top.max(bottom));
                        image.fill_rect(l, y0, (r - l).max(1), (y1 - y0).max(1), series.colour);
                    }
                }
            }
        }
    }
    // The frame last, over the bars' ends.
    image.fill_rect(plot.x, plot.y, plot.w, 1, FRAME);
    image.fill_rect(plot.x, plot.y + plot.h, plot.w + 1, 1, FRAME);
    image.fill_rect(plot.x, plot.y, 1, plot.h, FRAME);
    image.fill_rect(plot.x + plot.w, plot.y, 1, plot.h, FRAME);

    // The legend, top right inside the plot.
    let named: Vec<&Series> = chart.series.iter().filter(|s| !s.name.is_empty()).collect();
    let room = named
        .iter()
        .map(|s| text_width(&s.name, scale) as i64)
        .max()
        .unwrap_or(0);
    for (k, s) in named.iter().enumerate() {
        let y = plot.y + glyph / 2 + k as i64 * (glyph + glyph / 2);
        let x = plot.x + plot.w - room - 3 * glyph;
        image.fill_rect(x, y + glyph / 4, glyph + glyph / 2, glyph / 2, s.colour);
        draw_text(image, x + 2 * glyph, y, &s.name, scale, INK);
    }
}

/// A line two pixels wide from `a` to `b`.
fn line(image: &mut Image, a: (i64, i64), b: (i64, i64), colour: [u8; 3]) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let steps = dx.abs().max(dy.abs()).max(1);
    for k in 0..=steps {
        let x = a.0 + (dx * k) / steps;
        let y = a.1 + (dy * k) / steps;
        image.fill_rect(x, y, 2, 2, colour);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn count(image: &Image, colour: [u8; 3]) -> usize {
        image.rgb.chunks_exact(3).filter(|p| *p == colour).count()
    }

    #[test]
    fn ticks_are_round_numbers_inside_the_axis() {
        let axis = Axis::spanning([0.13, 4.7].into_iter(), false, false).unwrap();
        let ticks = axis.ticks();
        assert!(ticks.len() >= 4 && ticks.len() <= 12, "{ticks:?}");
        for (v, label) in &ticks {
            assert!(*v >= axis.lo && *v <= axis.hi);
            assert_eq!(label.parse::<f64>().unwrap(), *v);
        }
        let log = Axis::spanning([3e-7, 0.02].into_iter(), true, false).unwrap();
        assert_eq!((log.lo, log.hi), (-7.0, -1.0));
        let labels: Vec<String> = log.ticks().into_iter().map(|(_, l)| l).collect();
        assert_eq!(labels, ["1e-7", "1e-6", "1e-5", "1e-4", "1e-3", "1e-2", "1e-1"]);
        assert_eq!(nice_step(0.7), 1.0);
        assert_eq!(nice_step(0.013), 0.02);
        assert_eq!(nice_step(3.0), 5.0);
    }

    #[test]
    fn a_falling_line_is_drawn_high_on_the_left_and_low_on_the_right() {
        let red = [220, 30, 30];
        let chart = Chart {
            title: "energy".into(),
            x_label: "step".into(),
            y_label: "J".into(),
            log_y: true,
            series: vec![Series {
                name: String::new(),
                points: (1..=100)
                    .map(|k| (k as f64, 10f64.powf(-(k as f64) / 20.0)))
                    .collect(),
                colour: red,
                style: Style::Line,
            }],
            marks: vec![],
        };
        let image = charts(&[chart], 400, 300);
        let (mut left, mut right) = ((0u32, 0u32), (0u32, 0u32));
        for y in 0..300 {
            for x in 0..400 {
                if image.pixel(x, y) == Some(red) {
                    if x < 200 {
                        left = (left.0 + y, left.1 + 1);
                    } else {
                        right = (right.0 + y, right.1 + 1);
                    }
                }
            }
        }
        assert!(left.1 > 20 && right.1 > 20, "{left:?} {right:?}");
        // Rows count down: the left half is higher up, so its mean row is smaller.
        assert!(left.0 / left.1 + 40 < right.0 / right.1, "{left:?} {right:?}");
    }

    #[test]
    fn bars_are_as_tall_as_their_values() {
        let blue = [30, 60, 220];
        let bars = |values: &[f64]| Chart {
            title: "histogram".into(),
            x_label: "x".into(),
            y_label: "share".into(),
            log_y: false,
            series: vec![Series {
                name: String::new(),
                points: values.iter().enumerate().map(|(k, &v)| (k as f64, v)).collect(),
                colour: blue,
                style: Style::Bars {
                    width: 0.8,
                    offset: 0.0,
                },
            }],
            marks: vec![(1.0, "mark".into())],
        };
        let image = charts(&[bars(&[1.0, 2.0])], 400, 300);
        // Each bar's height in pixels: the blue rows of its half of the picture.
        let height = |xs: std::ops::Range<u32>| {
            (0..300)
                .filter(|&y| xs.clone().any(|x| image.pixel(x, y) == Some(blue)))
                .count() as f64
        };
        let (low, high) = (height(0..200), height(200..400));
        assert!(low > 50.0, "{low}");
        assert!((low / high - 0.5).abs() < 0.03, "{low} and {high} pixels");
        assert_eq!(count(&charts(&[bars(&[])], 400, 300), blue), 0, "nothing plotted");
    }
}
