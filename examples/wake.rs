//! The wake of one stroke, planar slice against axisymmetric slice: vorticity and velocity
//! around the bell at six phases of a stroke, written to `docs/wake.png`.
//!
//! The species (Aurelia, or a species file) swims from rest for `--cycles` strokes
//! (default 6) in each geometry, in 1/60 s frames; the next stroke is caught at phases
//! 0, 1/6, ..., 5/6 (the first fixed step at or past each).
//!
//! The picture: two rows, **planar slice on top, axisymmetric slice below** (each row
//! labelled at its top left), six columns, one per phase (labelled above). Each panel is
//! 3 bell diameters wide and 4 tall, the bell near its top, in the box that follows the
//! bell (the wake leaves at the bottom):
//! - colour: vorticity ω = ∂v/∂x − ∂u/∂y at the cell corners, blue clockwise (negative),
//!   white 0, red anticlockwise (positive), saturated at the row's robust maximum (the
//!   99th percentile of |ω| over the row's six panels, printed with the row's label);
//! - arrows: velocity on a lattice of every third cell, in the frame of the still water
//!   far away (the fluid's own velocities are relative to the co-moving box: the box's
//!   velocity is added); the row's robust speed (the 98th percentile over the lattice,
//!   printed) is the arrow drawn beside the row's label, none is longer than a spacing;
//! - black: the bell (subumbrella), thin green: its tentacles, thin orange: manubrium
//!   and oral arms.
//!
//! Per geometry and phase it prints the phase, the peak |ω| (1/s), the distance swum so
//! far and the bell's width (margin to margin), both in bell diameters.
//!
//! `cargo run --release --no-default-features --example wake -- [species.ron] [--cycles 6] [--out docs/wake.png]`

#[path = "common/font.rs"]
mod font;

use bevy_jellyfish::{SliceGeometry, SliceSim, Species};
use font::glyph;
use glam::Vec2;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// Phases caught in the stroke after the run-up.
const PHASES: usize = 6;
/// Frame length the slices are advanced by, s.
const FRAME: f32 = 1.0 / 60.0;
/// Panel size in bell diameters (width, height), and water kept above the apex.
const PANEL_DIAMETERS: (f32, f32) = (3.0, 4.0);
const ABOVE_APEX_DIAMETERS: f32 = 0.5;
/// Target panel width, px (the scale is a whole number of pixels per cell near it).
const PANEL_WIDTH: f32 = 240.0;
/// Arrows on every `ARROW_CELLS`-th cell centre; the row's robust speed is drawn
/// `ARROW_LENGTH` lattice spacings long, and no arrow is longer than one spacing.
const ARROW_CELLS: usize = 3;
const ARROW_LENGTH: f32 = 0.8;

struct Options {
    species: Species,
    cycles: u64,
    out: PathBuf,
}

fn parse_options() -> Result<Options, String> {
    let mut o = Options {
        species: Species::aurelia(),
        cycles: 6,
        out: PathBuf::from("docs/wake.png"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().ok_or(format!("{arg} needs a value"));
        match arg.as_str() {
            "--cycles" => o.cycles = value()?.parse().map_err(|e| format!("--cycles: {e}"))?,
            "--out" => o.out = PathBuf::from(value()?),
            file if !file.starts_with("--") => {
                let text = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
                o.species = Species::from_ron(&text).map_err(|e| format!("{file}: {e}"))?;
            }
            other => return Err(format!("unknown argument {other}")),
        }
    }
    Ok(o)
}

/// What a panel needs of the slice at one phase.
struct Snapshot {
    phase: f32,
    n: usize,
    h: f32,
    /// Face velocities relative to the box, as [`bevy_jellyfish::sim::inspect::Fluid`].
    u: Vec<f32>,
    v: Vec<f32>,
    /// The box's velocity: added to the faces' for the still water's frame.
    frame_velocity: Vec2,
    bell: Vec<Vec2>,
    tentacles: [Vec<Vec2>; 2],
    oral_arms: [Vec<Vec2>; 2],
    /// m
    swim_distance: f32,
}

impl Snapshot {
    fn of(sim: &SliceSim) -> Self {
        let fluid = sim.fluid();
        let (n, h) = (fluid.n, fluid.h);
        assert!(
            fluid.u.len() == (n + 1) * n && fluid.v.len() == n * (n + 1),
            "the MAC grid is not (n + 1) × n faces per component"
        );
        let view = sim.view();
        Self {
            phase: sim.phase(),
            n,
            h,
            u: fluid.u.clone(),
            v: fluid.v.clone(),
            frame_velocity: sim.frame_velocity(),
            bell: view.bell.to_vec(),
            tentacles: view.tentacles.map(<[Vec2]>::to_vec),
            oral_arms: view.oral_arms.map(<[Vec2]>::to_vec),
            swim_distance: sim.swim_distance(),
        }
    }

    /// ω at corner `(i, j)` (position `(i h, j h)`), 1/s; 0 on the box's edge.
    fn vorticity(&self, i: usize, j: usize) -> f32 {
        let n = self.n;
        if i == 0 || j == 0 || i >= n || j >= n {
            return 0.0;
        }
        let dv_dx = self.v[j * n + i] - self.v[j * n + i - 1];
        let du_dy = self.u[j * (n + 1) + i] - self.u[(j - 1) * (n + 1) + i];
        (dv_dx - du_dy) / self.h
    }

    /// ω at domain point `p`, bilinear between the corners; `None` outside the box.
    fn vorticity_at(&self, p: Vec2) -> Option<f32> {
        let g = p / self.h;
        let n = self.n as f32;
        if !(0.0..=n).contains(&g.x) || !(0.0..=n).contains(&g.y) {
            return None;
        }
        let (i, j) = (
            (g.x.floor() as usize).min(self.n - 1),
            (g.y.floor() as usize).min(self.n - 1),
        );
        let (fx, fy) = (g.x - i as f32, g.y - j as f32);
        let w = |a, b| self.vorticity(a, b);
        let bottom = w(i, j) * (1.0 - fx) + w(i + 1, j) * fx;
        let top = w(i, j + 1) * (1.0 - fx) + w(i + 1, j + 1) * fx;
        Some(bottom * (1.0 - fy) + top * fy)
    }

    /// Velocity at the centre of cell `(i, j)` in the still water's frame, m/s.
    fn velocity(&self, i: usize, j: usize) -> Vec2 {
        let n = self.n;
        let u = 0.5 * (self.u[j * (n + 1) + i] + self.u[j * (n + 1) + i + 1]);
        let v = 0.5 * (self.v[j * n + i] + self.v[(j + 1) * n + i]);
        Vec2::new(u, v) + self.frame_velocity
    }

    /// Margin to margin, m.
    fn aperture(&self) -> f32 {
        self.bell[0].distance(self.bell[self.bell.len() - 1])
    }
}

/// One geometry's run: its six snapshots and the part of the box the panels show.
struct Row {
    label: &'static str,
    snapshots: Vec<Snapshot>,
    /// Bottom-left corner and size of the panels' window, domain coordinates, m.
    origin: Vec2,
    size: Vec2,
    /// Robust maxima over the row: |ω| (1/s) and speed (m/s).
    omega_scale: f32,
    speed_scale: f32,
}

fn run(species: &Species, cycles: u64, label: &'static str) -> Result<Row, String> {
    let mut sim = SliceSim::new(species).map_err(|e| e.to_string())?;
    let d = species.diameter;
    // The window, from the bell at rest: centred on its axis, the apex near the top.
    let (apex, size) = (
        sim.view().bell[sim.view().bell.len() / 2],
        sim.fluid().size(),
    );
    let window = Vec2::new(PANEL_DIAMETERS.0, PANEL_DIAMETERS.1) * d;
    let top = (apex.y + ABOVE_APEX_DIAMETERS * d).min(size);
    let origin = Vec2::new(apex.x - 0.5 * window.x, (top - window.y).max(0.0));

    let mut snapshots: Vec<Snapshot> = Vec::with_capacity(PHASES);
    let frames_per_cycle = (species.period() / FRAME).ceil() as u64;
    let mut frames = 0;
    while snapshots.len() < PHASES {
        sim.advance_with(FRAME, |s| {
            let next = snapshots.len();
            if s.cycle() == cycles && next < PHASES && s.phase() >= next as f32 / PHASES as f32 {
                snapshots.push(Snapshot::of(s));
            }
        });
        frames += 1;
        if frames > (cycles + 2) * frames_per_cycle + 10 {
            return Err(format!("{label}: never reached stroke {cycles}"));
        }
    }
    if sim.recoveries() > 0 {
        eprintln!("wake: {label}: {} blow-ups recovered", sim.recoveries());
    }

    let mut omegas = Vec::new();
    let mut speeds = Vec::new();
    for s in &snapshots {
        let (lo, hi) = cells(s, origin, window);
        for j in lo.1..=hi.1 {
            for i in lo.0..=hi.0 {
                omegas.push(s.vorticity(i, j).abs());
            }
        }
        for (i, j) in lattice(s, origin, window) {
            speeds.push(s.velocity(i, j).length());
        }
    }
    Ok(Row {
        label,
        snapshots,
        origin,
        size: window,
        omega_scale: percentile(&mut omegas, 0.99).max(1e-6),
        speed_scale: percentile(&mut speeds, 0.98).max(1e-6),
    })
}

/// Corner index range inside the window (inclusive).
fn cells(s: &Snapshot, origin: Vec2, size: Vec2) -> ((usize, usize), (usize, usize)) {
    let clamp = |x: f32| (x.max(0.0) as usize).min(s.n);
    let lo = (origin / s.h).ceil();
    let hi = ((origin + size) / s.h).floor();
    ((clamp(lo.x), clamp(lo.y)), (clamp(hi.x), clamp(hi.y)))
}

/// Cell centres for the arrows: every [`ARROW_CELLS`]th cell inside the window, placed
/// symmetrically about the window's centre line.
fn lattice(s: &Snapshot, origin: Vec2, size: Vec2) -> Vec<(usize, usize)> {
    let centre = (origin.x + 0.5 * size.x) / s.h - 0.5;
    let first_i = centre.round() as i64;
    let mut out = Vec::new();
    let (lo, hi) = cells(s, origin, size);
    let is = (-(s.n as i64)..=s.n as i64)
        .map(|k| first_i + k * ARROW_CELLS as i64)
        .filter(|&i| i >= lo.0 as i64 && i < hi.0 as i64);
    let is: Vec<usize> = is.map(|i| i as usize).collect();
    let mut j = hi.1 as i64 - 2;
    while j >= lo.1 as i64 {
        out.extend(is.iter().map(|&i| (i, j as usize)));
        j -= ARROW_CELLS as i64;
    }
    out
}

fn percentile(values: &mut Vec<f32>, q: f32) -> f32 {
    values.retain(|v| v.is_finite());
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f32::total_cmp);
    values[((values.len() - 1) as f32 * q).round() as usize]
}

fn main() {
    let o = match parse_options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("wake: {e}");
            std::process::exit(2);
        }
    };
    let d = o.species.diameter;
    println!(
        "{}: {} cycles from rest at {} Hz, then the first fixed step at or past phases \
         0..{}/{} of the next ({} steps a cycle); {}x{} cells, {:.1} cells per diameter",
        o.species.name,
        o.cycles,
        o.species.contraction_frequency,
        PHASES - 1,
        PHASES,
        o.species.steps_per_cycle(),
        o.species.grid_resolution,
        o.species.grid_resolution,
        d / o.species.cell_size(),
    );
    let mut rows = Vec::new();
    for (geometry, label) in [
        (SliceGeometry::Planar, "planar"),
        (SliceGeometry::Axisymmetric, "axisymmetric"),
    ] {
        let species = Species {
            slice_geometry: geometry,
            ..o.species.clone()
        };
        let row = match run(&species, o.cycles, label) {
            Ok(row) => row,
            Err(e) => {
                eprintln!("wake: {e}");
                std::process::exit(1);
            }
        };
        println!(
            "\n{label} (row {}): colour saturates at |ω| = {:.1} 1/s (99th percentile), \
             an arrow {ARROW_LENGTH} lattice spacings long = {:.1} mm/s (98th percentile)",
            rows.len() + 1,
            row.omega_scale,
            row.speed_scale * 1e3,
        );
        println!("  phase  peak |ω| 1/s  swum D  width D");
        for s in &row.snapshots {
            let (lo, hi) = cells(s, row.origin, row.size);
            let peak = (lo.1..=hi.1)
                .flat_map(|j| (lo.0..=hi.0).map(move |i| (i, j)))
                .map(|(i, j)| s.vorticity(i, j).abs())
                .fold(0.0f32, f32::max);
            println!(
                "  {:>5.3}  {:>12.1}  {:>6.3}  {:>7.3}",
                s.phase,
                peak,
                s.swim_distance / d,
                s.aperture() / d,
            );
        }
        rows.push(row);
    }
    if let Err(e) = draw(&rows, &o.out) {
        eprintln!("wake: {}: {e}", o.out.display());
        std::process::exit(1);
    }
    println!("\nwrote {}", o.out.display());
}

// --- Drawing ---

const GAP: i32 = 6;
const MARGIN: i32 = 10;
/// Text is the 5x7 font at twice its size.
const TEXT_SCALE: i32 = 2;
const TEXT_H: i32 = 7 * TEXT_SCALE;
const INK: [u8; 3] = [20, 20, 20];
const ARROW: [u8; 3] = [45, 45, 45];
const TENTACLE: [u8; 3] = [0, 130, 60];
const ORAL_ARM: [u8; 3] = [200, 120, 0];
const OUTSIDE: [u8; 3] = [200, 200, 200];

fn draw(rows: &[Row], path: &Path) -> std::io::Result<()> {
    let first = &rows[0].snapshots[0];
    // Whole pixels per cell, near the target width.
    let px_per_cell = (PANEL_WIDTH / (rows[0].size.x / first.h)).round().max(1.0);
    let scale = px_per_cell / first.h; // px per m
    let (pw, ph) = (
        (rows[0].size.x * scale).round() as i32,
        (rows[0].size.y * scale).round() as i32,
    );
    let header = TEXT_H + 10;
    let legend = 2 * TEXT_H + 24;
    let w = 2 * MARGIN + PHASES as i32 * pw + (PHASES as i32 - 1) * GAP;
    let h = MARGIN + header + rows.len() as i32 * (header + ph + GAP) + legend;
    let mut cv = Canvas::new(w, h);
    for k in 0..PHASES {
        let x = MARGIN + k as i32 * (pw + GAP);
        let phase = rows[0].snapshots[k].phase;
        cv.text(x + 2, MARGIN, &format!("phase {phase:.2}"), INK);
    }
    for (r, row) in rows.iter().enumerate() {
        let y = MARGIN + header + r as i32 * (header + ph + GAP);
        let label = format!(
            "{}: vorticity to +-{:.0} 1/s, arrow",
            row.label, row.omega_scale
        );
        let end = cv.text(MARGIN + 2, y, &label, INK) + 8;
        let length = ARROW_LENGTH * ARROW_CELLS as f32 * px_per_cell;
        let middle = (y + TEXT_H / 2) as f32;
        cv.arrow(Vec2::new(end as f32, middle), Vec2::X * length, ARROW);
        let speed = format!("= {:.0} mm/s", row.speed_scale * 1e3);
        cv.text(end + length.ceil() as i32 + 8, y, &speed, INK);
        for (k, s) in row.snapshots.iter().enumerate() {
            let x = MARGIN + k as i32 * (pw + GAP);
            panel(&mut cv, row, s, (x, y + header), (pw, ph), scale);
        }
    }
    legend_bar(&mut cv, MARGIN, h - legend + 8, pw);
    cv.save(path)
}

fn panel(
    cv: &mut Canvas,
    row: &Row,
    s: &Snapshot,
    (x0, y0): (i32, i32),
    (pw, ph): (i32, i32),
    scale: f32,
) {
    // Domain point -> pixel: y up in the domain, down in the image.
    let top = row.origin.y + row.size.y;
    let to_px = |p: Vec2| {
        (
            x0 as f32 + (p.x - row.origin.x) * scale,
            y0 as f32 + (top - p.y) * scale,
        )
    };
    for py in 0..ph {
        for px in 0..pw {
            let p = Vec2::new(
                row.origin.x + (px as f32 + 0.5) / scale,
                top - (py as f32 + 0.5) / scale,
            );
            let c = match s.vorticity_at(p) {
                Some(w) => diverging(w / row.omega_scale),
                None => OUTSIDE,
            };
            cv.set(x0 + px, y0 + py, c);
        }
    }
    cv.clip = Some((x0, y0, x0 + pw, y0 + ph));
    let spacing = ARROW_CELLS as f32 * s.h * scale;
    for (i, j) in lattice(s, row.origin, row.size) {
        let centre = Vec2::new((i as f32 + 0.5) * s.h, (j as f32 + 0.5) * s.h);
        let u = s.velocity(i, j) / row.speed_scale;
        let length = ARROW_LENGTH * u.length().min(1.25) * spacing;
        let (cx, cy) = to_px(centre);
        if length < 1.5 {
            cv.set(cx.floor() as i32, cy.floor() as i32, ARROW);
            continue;
        }
        cv.arrow(
            Vec2::new(cx, cy),
            Vec2::new(u.x, -u.y).normalize() * length,
            ARROW,
        );
    }
    for arm in &s.oral_arms {
        cv.polyline(arm.iter().map(|&p| to_px(p)), ORAL_ARM, 1.6);
    }
    for tentacle in &s.tentacles {
        cv.polyline(tentacle.iter().map(|&p| to_px(p)), TENTACLE, 1.6);
    }
    cv.polyline(s.bell.iter().map(|&p| to_px(p)), INK, 2.5);
    cv.clip = None;
    cv.frame(x0, y0, pw, ph, [120, 120, 120]);
}

/// The colour bar: −max, 0, +max.
fn legend_bar(cv: &mut Canvas, x: i32, y: i32, w: i32) {
    let bar_h = 12;
    for px in 0..w {
        let t = 2.0 * (px as f32 + 0.5) / w as f32 - 1.0;
        for py in 0..bar_h {
            cv.set(x + px, y + py, diverging(t));
        }
    }
    cv.frame(x, y, w, bar_h, [120, 120, 120]);
    let below = y + bar_h + 4;
    cv.text(x, below, "-max", INK);
    cv.text(x + w / 2 - 5, below, "0", INK);
    cv.text(x + w - 4 * 6 * TEXT_SCALE, below, "+max", INK);
    cv.text(
        x + w + 16,
        y,
        "vorticity: blue clockwise, red anticlockwise. arrows: velocity in still water",
        INK,
    );
    cv.text(
        x + w + 16,
        below,
        "black: bell, green: tentacles, orange: oral arms",
        INK,
    );
}

/// Blue (−1) through white (0) to red (+1), clamped.
fn diverging(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 3] = [
        [247.0, 247.0, 247.0],
        [244.0, 165.0, 130.0],
        [178.0, 24.0, 43.0],
    ];
    const BLUES: [[f32; 3]; 3] = [
        [247.0, 247.0, 247.0],
        [146.0, 197.0, 222.0],
        [33.0, 102.0, 172.0],
    ];
    let stops = if t >= 0.0 { &STOPS } else { &BLUES };
    let a = t.abs().min(1.0) * 2.0;
    let k = (a.floor() as usize).min(1);
    let f = a - k as f32;
    let c = |ch: usize| (stops[k][ch] + (stops[k + 1][ch] - stops[k][ch]) * f).round() as u8;
    [c(0), c(1), c(2)]
}

/// A white RGB8 image.
struct Canvas {
    w: i32,
    h: i32,
    px: Vec<u8>,
    /// Lines are drawn only inside (x0, y0, x1, y1) when set.
    clip: Option<(i32, i32, i32, i32)>,
}

impl Canvas {
    fn new(w: i32, h: i32) -> Self {
        Self {
            w,
            h,
            px: vec![255; (w * h * 3) as usize],
            clip: None,
        }
    }

    fn set(&mut self, x: i32, y: i32, c: [u8; 3]) {
        self.blend(x, y, c, 1.0);
    }

    /// Mixes `c` into pixel `(x, y)` with coverage `a`.
    fn blend(&mut self, x: i32, y: i32, c: [u8; 3], a: f32) {
        if x < 0 || y < 0 || x >= self.w || y >= self.h || a <= 0.0 {
            return;
        }
        if let Some((x0, y0, x1, y1)) = self.clip
            && (x < x0 || y < y0 || x >= x1 || y >= y1)
        {
            return;
        }
        let i = ((y * self.w + x) * 3) as usize;
        for (dst, src) in self.px[i..i + 3].iter_mut().zip(c) {
            *dst = (*dst as f32 + (src as f32 - *dst as f32) * a.min(1.0)).round() as u8;
        }
    }

    /// An antialiased segment `width` px wide; pixel `(x, y)` covers `[x, x + 1) × [y, y + 1)`.
    fn line(&mut self, a: Vec2, b: Vec2, c: [u8; 3], width: f32) {
        let r = 0.5 * width;
        let lo = a.min(b) - Vec2::splat(r + 1.0);
        let hi = a.max(b) + Vec2::splat(r + 1.0);
        for y in lo.y.floor() as i32..=hi.y.ceil() as i32 {
            for x in lo.x.floor() as i32..=hi.x.ceil() as i32 {
                let d = distance_to_segment(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), a, b);
                self.blend(x, y, c, (r + 0.5 - d).clamp(0.0, 1.0));
            }
        }
    }

    /// An arrow from `from` along `along` (px, y down).
    fn arrow(&mut self, from: Vec2, along: Vec2, c: [u8; 3]) {
        let (tip, length) = (from + along, along.length());
        self.line(from, tip, c, 1.0);
        let dir = along / length;
        let side = Vec2::new(-dir.y, dir.x);
        let head = (0.35 * length).clamp(2.0, 5.0);
        self.line(tip, tip - dir * head + side * 0.6 * head, c, 1.0);
        self.line(tip, tip - dir * head - side * 0.6 * head, c, 1.0);
    }

    fn polyline(&mut self, points: impl Iterator<Item = (f32, f32)>, c: [u8; 3], width: f32) {
        let points: Vec<Vec2> = points.map(|(x, y)| Vec2::new(x, y)).collect();
        for pair in points.windows(2) {
            self.line(pair[0], pair[1], c, width);
        }
    }

    /// A 1 px border just inside the rectangle.
    fn frame(&mut self, x: i32, y: i32, w: i32, h: i32, c: [u8; 3]) {
        for i in 0..w {
            self.set(x + i, y, c);
            self.set(x + i, y + h - 1, c);
        }
        for j in 0..h {
            self.set(x, y + j, c);
            self.set(x + w - 1, y + j, c);
        }
    }

    /// `s` with its top-left corner at `(x, y)`, in the 5x7 font at [`TEXT_SCALE`]; returns
    /// where the text ends (x, px).
    fn text(&mut self, x: i32, y: i32, s: &str, c: [u8; 3]) -> i32 {
        for (k, ch) in s.chars().enumerate() {
            for (col, bits) in glyph(ch).iter().enumerate() {
                for row in (0..9).filter(|r| bits >> r & 1 == 1) {
                    let gx = x + (k as i32 * 6 + col as i32) * TEXT_SCALE;
                    let gy = y + row * TEXT_SCALE;
                    for dy in 0..TEXT_SCALE {
                        for dx in 0..TEXT_SCALE {
                            self.set(gx + dx, gy + dy, c);
                        }
                    }
                }
            }
        }
        x + (s.chars().count() as i32 * 6 - 1).max(0) * TEXT_SCALE
    }

    fn save(&self, path: &Path) -> std::io::Result<()> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        let mut encoder = png::Encoder::new(
            BufWriter::new(File::create(path)?),
            self.w as u32,
            self.h as u32,
        );
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&self.px)?;
        writer.finish()?;
        Ok(())
    }
}

fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}
