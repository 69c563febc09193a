//! Minimal PNG line charts for the sweep example.
//!
//! Dependency-light on purpose: only the `png` crate is used. Everything else
//! (rasterising, a built-in 5x7 bitmap font drawn at 2x, "nice" 1-2-5 axis
//! ticks) lives in this file.
//!
//! ```ignore
//! let chart = Chart {
//!     title: "Distance vs frequency".into(),
//!     x_label: "frequency (Hz)".into(),
//!     y_label: "distance (m)".into(),
//!     series: vec![Series { label: "a".into(), points, color: [31, 119, 180], markers: true }],
//! };
//! write_png(Path::new("out.png"), &[chart], 1, 640, 420)?;
//! ```
//!
//! Axis ranges are fitted to the finite data (NaN and infinite points are
//! skipped, breaking the line) and stretched to include zero when the data come
//! close to it. Lines are anti-aliased, 2 px wide; markers are filled discs.

#[path = "../common/font.rs"]
mod font;

use font::glyph;
use std::fs::File;
use std::io::{self, BufWriter};
use std::path::Path;

/// One line on a chart.
#[derive(Clone, Debug, Default)]
pub struct Series {
    /// Legend text; series with an empty label are left out of the legend.
    pub label: String,
    /// Data points `(x, y)`; non-finite points are skipped and break the line.
    pub points: Vec<(f32, f32)>,
    /// Line colour (RGB).
    pub color: [u8; 3],
    /// Draw a disc at every data point.
    pub markers: bool,
}

/// One chart: a title, two axis labels and any number of series.
#[derive(Clone, Debug, Default)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// One unit is as long on both axes (shapes keep their proportions).
    pub equal_aspect: bool,
}

/// Renders several charts side by side, `cols` per row, each `chart_w` x
/// `chart_h` pixels, into one RGB PNG at `path`.
pub fn write_png(
    path: &Path,
    charts: &[Chart],
    cols: usize,
    chart_w: u32,
    chart_h: u32,
) -> io::Result<()> {
    let cols = cols.max(1);
    let rows = charts.len().div_ceil(cols).max(1);
    let (cw, ch) = (chart_w.max(1) as i32, chart_h.max(1) as i32);
    let mut canvas = Canvas::new(cw * cols as i32, ch * rows as i32);
    for (i, chart) in charts.iter().enumerate() {
        let cell = rect((i % cols) as i32 * cw, (i / cols) as i32 * ch, cw, ch);
        draw_chart(&mut canvas, chart, cell);
    }
    canvas.save(path)
}

// ---------------------------------------------------------------------------
// Layout constants

const TEXT: [u8; 3] = [40, 40, 40];
const FRAME: [u8; 3] = [70, 70, 70];
const GRID: [u8; 3] = [228, 228, 228];
const SCALE: i32 = 2;
/// Height of one line of text at `SCALE`.
const TEXT_H: i32 = 7 * SCALE;
const LINE_HALF_W: f32 = 1.0;
const MARKER_R: f32 = 3.5;
const TICK_LEN: i32 = 5;
/// Pixels between ticks we aim for.
const TICK_SPACING: i32 = 60;
/// A legend row's height and its line sample's length.
const LEGEND_ROW: i32 = TEXT_H + 6;
const LEGEND_SWATCH: i32 = 26;

// ---------------------------------------------------------------------------
// Chart drawing

/// Plot area plus the data ranges mapped onto it.
struct Frame {
    plot: Rect,
    x: Axis,
    y: Axis,
}

impl Frame {
    /// Data coordinates to canvas coordinates (pixel centres at +0.5).
    fn to_px(&self, (x, y): (f32, f32)) -> (f32, f32) {
        let p = self.plot;
        let tx = self.x.frac(x as f64) * (p.w - 1) as f64;
        let ty = self.y.frac(y as f64) * (p.h - 1) as f64;
        (
            p.x as f32 + 0.5 + tx as f32,
            (p.y + p.h) as f32 - 0.5 - ty as f32,
        )
    }
}

fn draw_chart(cv: &mut Canvas, chart: &Chart, cell: Rect) {
    let finite = || chart.series.iter().flat_map(|s| finite_points(&s.points));
    let Some(mut f) = layout(chart, cell, data_range(finite().map(|p| p.1))) else {
        return;
    };
    // Where every corner of the plot would hide data under the legend, raise the top of
    // the y axis until the legend's band above the data is clear.
    if let Some((w, h)) = legend_size(&chart.series)
        && !chart.equal_aspect
    {
        let covered = |f: &Frame| {
            let r = legend_corner(f, &chart.series, w, h);
            chart
                .series
                .iter()
                .map(|s| samples_in(f, &s.points, &r))
                .sum::<usize>()
        };
        let (_, hi) = data_range(finite().map(|p| p.1));
        let clear = ((h + 20) as f64 / f.plot.h as f64).min(0.6);
        for _ in 0..3 {
            if covered(&f) == 0 {
                break;
            }
            let raised = f.y.min + (hi - f.y.min) / (1.0 - clear);
            match layout(chart, cell, (f.y.min, raised.max(f.y.max + f.y.step))) {
                Some(g) => f = g,
                None => break,
            }
        }
    }
    let y_ticks = tick_labels(&f.y);
    draw_grid(cv, &f, &y_ticks);
    for s in &chart.series {
        draw_series(cv, &f, s);
    }
    cv.outline(f.plot, FRAME);
    draw_legend(cv, &f, &chart.series);
    draw_labels(cv, &f, chart, cell);
}

/// The plot area and axes of `chart` in `cell` with its y axis fitted to `y_range`; none
/// where the cell is too small to plot in.
fn layout(chart: &Chart, cell: Rect, y_range: (f64, f64)) -> Option<Frame> {
    let finite = || chart.series.iter().flat_map(|s| finite_points(&s.points));
    let top = 12 + TEXT_H + 12;
    let bottom = TICK_LEN + 6 + TEXT_H + 10 + TEXT_H + 10;
    let y_target = (cell.h - top - bottom) / TICK_SPACING;
    let y = Axis::fit(y_range, y_target);
    let y_label_w = tick_labels(&y)
        .iter()
        .map(|(_, s)| text_width(s, SCALE))
        .max()
        .unwrap_or(0);
    let left = 10 + TEXT_H + 10 + y_label_w + 6 + TICK_LEN;
    let right = 24;
    let x_target = (cell.w - left - right) / TICK_SPACING;
    let x = Axis::fit(data_range(finite().map(|p| p.0)), x_target);
    let plot = rect(
        cell.x + left,
        cell.y + top,
        cell.w - left - right,
        cell.h - top - bottom,
    );
    if plot.w < 16 || plot.h < 16 {
        return None;
    }
    let (mut x, mut y) = (x, y);
    if chart.equal_aspect {
        // Widen the axis with fewer units per pixel about its centre.
        let (ux, uy) = (
            (x.max - x.min) / plot.w as f64,
            (y.max - y.min) / plot.h as f64,
        );
        // Keep about as many ticks per pixel as the fitted axes had.
        let widen = |a: &mut Axis, span: f64, target: i32| {
            let c = 0.5 * (a.min + a.max);
            (a.min, a.max) = (c - 0.5 * span, c + 0.5 * span);
            a.step = nice_step(span / target.clamp(2, 10) as f64);
        };
        if ux < uy {
            widen(&mut x, uy * plot.w as f64, x_target);
        } else {
            widen(&mut y, ux * plot.h as f64, y_target);
        }
    }
    Some(Frame { plot, x, y })
}

/// Grid lines, tick marks and tick labels for both axes.
fn draw_grid(cv: &mut Canvas, f: &Frame, y_ticks: &[(f64, String)]) {
    let p = f.plot;
    for (v, label) in tick_labels(&f.x) {
        let px = f.to_px((v as f32, 0.0)).0 as i32;
        cv.fill(rect(px, p.y, 1, p.h), GRID);
        cv.fill(rect(px, p.y + p.h, 1, TICK_LEN), FRAME);
        let tx = px - text_width(&label, SCALE) / 2;
        draw_text(cv, tx, p.y + p.h + TICK_LEN + 6, &label, SCALE, TEXT, false);
    }
    for (v, label) in y_ticks {
        let py = f.to_px((0.0, *v as f32)).1 as i32;
        cv.fill(rect(p.x, py, p.w, 1), GRID);
        cv.fill(rect(p.x - TICK_LEN, py, TICK_LEN, 1), FRAME);
        let tx = p.x - TICK_LEN - 6 - text_width(label, SCALE);
        draw_text(cv, tx, py - TEXT_H / 2, label, SCALE, TEXT, false);
    }
}

/// One series as an anti-aliased polyline with optional markers, clipped to the plot.
fn draw_series(cv: &mut Canvas, f: &Frame, s: &Series) {
    // Markers at the plot edge may overhang the frame.
    let mut mask = Mask::new(f.plot.grow(MARKER_R.ceil() as i32 + 1));
    for pair in s.points.windows(2) {
        if finite_point(pair[0]) && finite_point(pair[1]) {
            mask.segment(f.to_px(pair[0]), f.to_px(pair[1]), LINE_HALF_W);
        }
    }
    for (i, &p) in s.points.iter().enumerate() {
        let linked = |j: Option<usize>| {
            j.and_then(|j| s.points.get(j))
                .is_some_and(|&q| finite_point(q))
        };
        if !finite_point(p) {
            continue;
        } else if s.markers {
            mask.disc(f.to_px(p), MARKER_R);
        } else if !linked(i.checked_sub(1)) && !linked(Some(i + 1)) {
            mask.disc(f.to_px(p), LINE_HALF_W + 0.5); // isolated point: keep it visible
        }
    }
    mask.composite(cv, s.color);
}

/// Legend box in the plot corner that covers the fewest data points.
fn draw_legend(cv: &mut Canvas, f: &Frame, series: &[Series]) {
    const ROW: i32 = LEGEND_ROW;
    const SWATCH: i32 = LEGEND_SWATCH;
    let entries: Vec<&Series> = series.iter().filter(|s| !s.label.is_empty()).collect();
    let Some((w, h)) = legend_size(series) else {
        return;
    };
    let r = legend_corner(f, series, w, h);
    cv.fill(r, [255, 255, 255]);
    cv.outline(r, [190, 190, 190]);
    for (i, s) in entries.iter().enumerate() {
        let y = r.y + 6 + ROW * i as i32;
        let mid = (y + TEXT_H / 2) as f32; // on a pixel boundary: a crisp 2 px line
        let mut mask = Mask::new(r);
        let (x0, x1) = ((r.x + 8) as f32, (r.x + 8 + SWATCH) as f32);
        mask.segment((x0, mid), (x1, mid), LINE_HALF_W);
        if s.markers {
            mask.disc(((x0 + x1) / 2.0, mid), MARKER_R);
        }
        mask.composite(cv, s.color);
        draw_text(cv, r.x + 16 + SWATCH, y, &s.label, SCALE, TEXT, false);
    }
}

/// The legend box's width and height; none without labelled series.
fn legend_size(series: &[Series]) -> Option<(i32, i32)> {
    let labels: Vec<&str> = series
        .iter()
        .filter(|s| !s.label.is_empty())
        .map(|s| s.label.as_str())
        .collect();
    let text_w = labels.iter().map(|l| text_width(l, SCALE)).max()?;
    Some((
        8 + LEGEND_SWATCH + 8 + text_w + 8,
        6 + LEGEND_ROW * labels.len() as i32 + 2,
    ))
}

fn legend_corner(f: &Frame, series: &[Series], w: i32, h: i32) -> Rect {
    let p = f.plot;
    let (l, t) = (p.x + 8, p.y + 8);
    let (r, b) = (p.x + p.w - 8 - w, p.y + p.h - 8 - h);
    let corners = [(r, t), (l, t), (r, b), (l, b)].map(|(x, y)| rect(x, y, w, h));
    let covered = |c: &Rect| {
        series
            .iter()
            .map(|s| samples_in(f, &s.points, c))
            .sum::<usize>()
    };
    corners.into_iter().min_by_key(covered).unwrap()
}

/// How many points sampled along the drawn polyline fall inside `r` (grown by a margin).
fn samples_in(f: &Frame, points: &[(f32, f32)], r: &Rect) -> usize {
    let r = r.grow(4);
    let inside = |a: (f32, f32), b: (f32, f32), t: f32| {
        r.contains((a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t))
    };
    let mut n = finite_points(points)
        .filter(|&q| r.contains(f.to_px(q)))
        .count();
    for pair in points
        .windows(2)
        .filter(|w| finite_point(w[0]) && finite_point(w[1]))
    {
        let (a, b) = (f.to_px(pair[0]), f.to_px(pair[1]));
        n += (1..8).filter(|&k| inside(a, b, k as f32 / 8.0)).count();
    }
    n
}

/// Title above, x label below, y label rotated along the left edge.
fn draw_labels(cv: &mut Canvas, f: &Frame, chart: &Chart, cell: Rect) {
    let p = f.plot;
    let s = fit_scale(&chart.title, cell.w - 8);
    let tx = p.x + p.w / 2 - text_width(&chart.title, s) / 2;
    draw_text(
        cv,
        tx.max(cell.x + 4),
        cell.y + 12,
        &chart.title,
        s,
        TEXT,
        false,
    );
    let s = fit_scale(&chart.x_label, cell.w - 8);
    let tx = p.x + p.w / 2 - text_width(&chart.x_label, s) / 2;
    let ty = p.y + p.h + TICK_LEN + 6 + TEXT_H + 10;
    draw_text(cv, tx.max(cell.x + 4), ty, &chart.x_label, s, TEXT, false);
    let s = fit_scale(&chart.y_label, cell.h - 8);
    let ty = p.y + p.h / 2 + text_width(&chart.y_label, s) / 2;
    draw_text(
        cv,
        cell.x + 10,
        ty.min(cell.y + cell.h - 4),
        &chart.y_label,
        s,
        TEXT,
        true,
    );
}

// ---------------------------------------------------------------------------
// Data ranges and ticks

fn finite_point(p: (f32, f32)) -> bool {
    p.0.is_finite() && p.1.is_finite()
}

fn finite_points(points: &[(f32, f32)]) -> impl Iterator<Item = (f32, f32)> + '_ {
    points.iter().copied().filter(|&p| finite_point(p))
}

/// Range of the finite values, stretched to zero when the data come near it and
/// padded when degenerate. `(0, 1)` when there is no finite value.
fn data_range(values: impl Iterator<Item = f32>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v as f64);
        hi = hi.max(v as f64);
    }
    if lo > hi {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if lo > 0.0 && lo <= 0.5 * span {
        lo = 0.0;
    } else if hi < 0.0 && -hi <= 0.5 * span {
        hi = 0.0;
    }
    if hi - lo <= hi.abs().max(lo.abs()) * 1e-9 {
        let pad = if hi == 0.0 { 1.0 } else { hi.abs() * 0.1 };
        (lo - pad, hi + pad)
    } else {
        (lo, hi)
    }
}

/// 1, 2 or 5 times a power of ten, at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let e = 10f64.powf(raw.log10().floor());
    let m = raw / e;
    let n = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .find(|&n| m <= n * (1.0 + 1e-9))
        .unwrap_or(10.0);
    n * e
}

/// An axis range snapped outward to whole multiples of a nice step.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Axis {
    min: f64,
    max: f64,
    step: f64,
}

impl Axis {
    /// Fits `range` with about `target` intervals (at least 2).
    fn fit((lo, hi): (f64, f64), target: i32) -> Axis {
        let step = nice_step((hi - lo) / target.clamp(2, 10) as f64);
        let min = (lo / step + 1e-9).floor() * step;
        let max = (hi / step - 1e-9).ceil() * step;
        Axis { min, max, step }
    }

    fn frac(&self, v: f64) -> f64 {
        (v - self.min) / (self.max - self.min)
    }

    fn ticks(&self) -> Vec<f64> {
        let (a, b) = (
            (self.min / self.step - 1e-9).ceil() as i64,
            (self.max / self.step + 1e-9).floor() as i64,
        );
        (a..=b).map(|i| i as f64 * self.step).collect()
    }
}

fn tick_labels(axis: &Axis) -> Vec<(f64, String)> {
    axis.ticks()
        .into_iter()
        .map(|v| (v, format_tick(v, axis.step)))
        .collect()
}

/// Formats a tick value with just the precision its step needs.
fn format_tick(v: f64, step: f64) -> String {
    if v.abs() < step * 1e-6 {
        return "0".into();
    }
    let step_exp = step.log10().floor() as i32;
    if step_exp >= 5 || step_exp <= -4 {
        let digits = (v.abs().log10().floor() as i32 - step_exp).max(0) as usize;
        let s = format!("{v:.digits$e}");
        let (mant, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mant = if mant.contains('.') {
            mant.trim_end_matches('0').trim_end_matches('.')
        } else {
            mant
        };
        return format!("{mant}e{exp}");
    }
    let decimals = (-step_exp).max(0) as usize;
    format!("{v:.decimals$}")
}

// ---------------------------------------------------------------------------
// Raster

#[derive(Clone, Copy, Debug)]
struct Rect {
    x: i32,
    y: i32,
    w: i32,
    h: i32,
}

const fn rect(x: i32, y: i32, w: i32, h: i32) -> Rect {
    Rect { x, y, w, h }
}

impl Rect {
    /// `m` pixels larger on every side.
    fn grow(self, m: i32) -> Rect {
        rect(self.x - m, self.y - m, self.w + 2 * m, self.h + 2 * m)
    }

    fn contains(&self, (x, y): (f32, f32)) -> bool {
        x >= self.x as f32
            && x < (self.x + self.w) as f32
            && y >= self.y as f32
            && y < (self.y + self.h) as f32
    }
}

/// White RGB8 image.
struct Canvas {
    w: i32,
    h: i32,
    px: Vec<u8>,
}

impl Canvas {
    fn new(w: i32, h: i32) -> Canvas {
        Canvas {
            w,
            h,
            px: vec![255; w as usize * h as usize * 3],
        }
    }

    /// Mixes colour `c` into pixel `(x, y)` with coverage `a` in 0..=1.
    fn blend(&mut self, x: i32, y: i32, c: [u8; 3], a: f32) {
        if x < 0 || y < 0 || x >= self.w || y >= self.h || a <= 0.0 {
            return;
        }
        let i = ((y * self.w + x) * 3) as usize;
        for (dst, src) in self.px[i..i + 3].iter_mut().zip(c) {
            *dst = (*dst as f32 + (src as f32 - *dst as f32) * a.min(1.0)).round() as u8;
        }
    }

    fn fill(&mut self, r: Rect, c: [u8; 3]) {
        for y in r.y..r.y + r.h {
            for x in r.x..r.x + r.w {
                self.blend(x, y, c, 1.0);
            }
        }
    }

    /// 1 px border just inside `r`.
    fn outline(&mut self, r: Rect, c: [u8; 3]) {
        let (right, bottom) = (r.x + r.w - 1, r.y + r.h - 1);
        self.fill(rect(r.x, r.y, r.w, 1), c);
        self.fill(rect(r.x, bottom, r.w, 1), c);
        self.fill(rect(r.x, r.y, 1, r.h), c);
        self.fill(rect(right, r.y, 1, r.h), c);
    }

    fn save(&self, path: &Path) -> io::Result<()> {
        let file = BufWriter::new(File::create(path)?);
        let mut enc = png::Encoder::new(file, self.w as u32, self.h as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header()?;
        writer.write_image_data(&self.px)?;
        writer.finish()?;
        Ok(())
    }
}

/// Coverage buffer over a clip rectangle. Shapes combine by `max`, so joints of
/// a polyline are not blended twice; the result is composited in one colour.
struct Mask {
    r: Rect,
    a: Vec<f32>,
}

impl Mask {
    fn new(r: Rect) -> Mask {
        Mask {
            r,
            a: vec![0.0; (r.w.max(0) * r.h.max(0)) as usize],
        }
    }

    /// Raises coverage to `cov(pixel centre)` over the box `lo..hi`.
    fn stamp(&mut self, lo: (f32, f32), hi: (f32, f32), cov: impl Fn(f32, f32) -> f32) {
        let r = self.r;
        let x0 = (lo.0.floor() as i32).max(r.x);
        let x1 = (hi.0.ceil() as i32).min(r.x + r.w - 1);
        let y0 = (lo.1.floor() as i32).max(r.y);
        let y1 = (hi.1.ceil() as i32).min(r.y + r.h - 1);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = cov(x as f32 + 0.5, y as f32 + 0.5).clamp(0.0, 1.0);
                let i = ((y - r.y) * r.w + (x - r.x)) as usize;
                self.a[i] = self.a[i].max(c);
            }
        }
    }

    /// Segment `a`-`b` of half-width `hw`, with a one-pixel anti-aliased edge.
    fn segment(&mut self, a: (f32, f32), b: (f32, f32), hw: f32) {
        let m = hw + 1.0;
        let lo = (a.0.min(b.0) - m, a.1.min(b.1) - m);
        let hi = (a.0.max(b.0) + m, a.1.max(b.1) + m);
        self.stamp(lo, hi, |x, y| hw + 0.5 - dist_to_segment((x, y), a, b));
    }

    fn disc(&mut self, c: (f32, f32), radius: f32) {
        let m = radius + 1.0;
        self.stamp((c.0 - m, c.1 - m), (c.0 + m, c.1 + m), |x, y| {
            radius + 0.5 - ((x - c.0).powi(2) + (y - c.1).powi(2)).sqrt()
        });
    }

    fn composite(&self, cv: &mut Canvas, color: [u8; 3]) {
        for (i, &a) in self.a.iter().enumerate() {
            let (x, y) = (i as i32 % self.r.w, i as i32 / self.r.w);
            cv.blend(self.r.x + x, self.r.y + y, color, a);
        }
    }
}

fn dist_to_segment(p: (f32, f32), a: (f32, f32), b: (f32, f32)) -> f32 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (cx, cy) = (a.0 + t * dx, a.1 + t * dy);
    ((p.0 - cx).powi(2) + (p.1 - cy).powi(2)).sqrt()
}

// ---------------------------------------------------------------------------
// Text

fn text_width(s: &str, scale: i32) -> i32 {
    (s.chars().count() as i32 * 6 - 1).max(0) * scale
}

/// 2 when the text fits in `max_w` at double size, else 1.
fn fit_scale(s: &str, max_w: i32) -> i32 {
    if text_width(s, SCALE) <= max_w {
        SCALE
    } else {
        1
    }
}

/// Draws `s` with its top-left corner at `(x, y)`; when `vertical`, the text is
/// rotated a quarter turn anticlockwise and `(x, y)` is its bottom-left corner.
fn draw_text(cv: &mut Canvas, x: i32, y: i32, s: &str, scale: i32, c: [u8; 3], vertical: bool) {
    for (i, ch) in s.chars().enumerate() {
        for (col, bits) in glyph(ch).iter().enumerate() {
            for row in (0..9).filter(|r| bits >> r & 1 == 1) {
                let (gx, gy) = ((i as i32 * 6 + col as i32) * scale, row * scale);
                let r = if vertical {
                    rect(x + gy, y - gx - scale, scale, scale)
                } else {
                    rect(x + gx, y + gy, scale, scale)
                };
                cv.fill(r, c);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps_are_1_2_5() {
        assert_eq!(nice_step(1.0), 1.0);
        assert_eq!(nice_step(1.3), 2.0);
        assert_eq!(nice_step(3.0), 5.0);
        assert_eq!(nice_step(7.0), 10.0);
        assert!((nice_step(0.013) - 0.02).abs() < 1e-12);
        assert_eq!(nice_step(420.0), 500.0);
    }

    #[test]
    fn axis_snaps_to_ticks() {
        let a = Axis::fit((0.0, 9.3), 5);
        assert_eq!((a.min, a.max, a.step), (0.0, 10.0, 2.0));
        assert_eq!(a.ticks(), vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        let a = Axis::fit((-0.33, 0.71), 6);
        assert!((a.step - 0.2).abs() < 1e-12);
        assert!((a.min + 0.4).abs() < 1e-9 && (a.max - 0.8).abs() < 1e-9);
    }

    #[test]
    fn range_skips_non_finite_and_includes_zero() {
        let v = [f32::NAN, 1.0, f32::INFINITY, 3.0, f32::NEG_INFINITY];
        assert_eq!(data_range(v.into_iter()), (0.0, 3.0));
        assert_eq!(data_range([10.0, 12.0].into_iter()), (10.0, 12.0));
        assert_eq!(data_range([-3.0, -1.0].into_iter()), (-3.0, 0.0));
        assert_eq!(data_range([f32::NAN].into_iter()), (0.0, 1.0));
        let (lo, hi) = data_range([5.0, 5.0].into_iter());
        assert!(lo < 5.0 && hi > 5.0);
    }

    #[test]
    fn tick_labels_use_needed_precision() {
        assert_eq!(format_tick(0.5, 0.5), "0.5");
        assert_eq!(format_tick(-0.2, 0.1), "-0.2");
        assert_eq!(format_tick(40.0, 20.0), "40");
        assert_eq!(format_tick(1e-17, 0.1), "0");
        assert_eq!(format_tick(1.2e6, 2e5), "1.2e6");
    }

    #[test]
    fn writes_decodable_png_of_right_size() {
        let line = |label: &str, markers| Series {
            label: label.into(),
            points: vec![
                (0.0, 1.0),
                (1.0, f32::NAN),
                (2.0, 3.0),
                (3.0, 2.5),
                (f32::INFINITY, 0.0),
            ],
            color: [200, 30, 30],
            markers,
        };
        let empty = Series {
            label: "empty".into(),
            ..Series::default()
        };
        let charts = [
            Chart {
                title: "A".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                series: vec![line("a", true), empty],
                ..Chart::default()
            },
            Chart {
                title: "B".into(),
                series: vec![line("b", false)],
                ..Chart::default()
            },
            Chart::default(),
        ];
        let path = std::env::temp_dir().join(format!("plot_test_{}.png", std::process::id()));
        write_png(&path, &charts, 2, 160, 120).unwrap();
        let file = io::BufReader::new(File::open(&path).unwrap());
        let mut reader = png::Decoder::new(file).read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!((info.width, info.height), (320, 240));
        assert!(buf.iter().any(|&b| b != 255), "something was drawn");
    }
}
