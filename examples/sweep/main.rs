//! The paper's Fig. 5: how far the paper's moon jelly ([`Species::paper`]) swims in a
//! fixed time at contraction frequencies from 0.2 to 1.6 Hz (0.1 Hz apart), with staggered
//! and with unison re-expansion, and with a bell twice as stiff, whose resonance (and so
//! its best frequency) lies higher; beside it the calibrated moon jelly
//! ([`Species::aurelia`], same size) and crystal jelly ([`Species::aequorea`], 60 mm),
//! whose own peaks should sit near the rates their animals pulse at.
//!
//! Prints a table and the peaks, writes `sweep.csv` and `sweep.png` (distance against
//! frequency; trajectories against time) into `--out` (default `docs/`).
//!
//! `cargo run --release --no-default-features --example sweep -- [--seconds 20] [--grid G] [--out docs]`

mod plot;

use bevy_jellyfish::{SliceSim, Species};
use plot::{Chart, Series};
use std::io::Write;
use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// One line of the sweep: a label and how it changes the paper's species.
struct Variant {
    label: &'static str,
    color: [u8; 3],
    apply: fn(&mut Species),
}

const VARIANTS: [Variant; 5] = [
    Variant {
        label: "staggered",
        color: [31, 119, 180],
        apply: |_| {},
    },
    Variant {
        label: "unison",
        color: [214, 39, 40],
        apply: |s| s.expansion_stagger = 0.0,
    },
    Variant {
        label: "staggered, bell 2x stiffer",
        color: [44, 160, 44],
        apply: |s| s.elastic_modulus *= 2.0,
    },
    Variant {
        label: "moon jelly, calibrated (0.7 Hz)",
        color: [148, 103, 189],
        apply: |s| *s = Species::aurelia(),
    },
    Variant {
        label: "crystal jelly, calibrated (0.6 Hz)",
        color: [255, 127, 14],
        apply: |s| *s = Species::aequorea(),
    },
];

fn frequencies() -> Vec<f32> {
    (2..=16).map(|k| k as f32 / 10.0).collect()
}

struct Run {
    variant: usize,
    frequency: f32,
    /// The bell's diameter, m.
    diameter: f32,
    /// (time s, distance m)
    trajectory: Vec<(f32, f32)>,
    recoveries: u32,
}

struct Options {
    seconds: f32,
    grid: Option<u32>,
    out: PathBuf,
}

fn parse_options() -> Result<Options, String> {
    let mut o = Options {
        seconds: 20.0,
        grid: None,
        out: PathBuf::from("docs"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let mut value = || args.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--seconds" => o.seconds = value()?.parse().map_err(|e| format!("--seconds: {e}"))?,
            "--grid" => o.grid = Some(value()?.parse().map_err(|e| format!("--grid: {e}"))?),
            "--out" => o.out = PathBuf::from(value()?),
            other => return Err(format!("unknown argument {other}")),
        }
    }
    Ok(o)
}

fn species(variant: usize, frequency: f32, o: &Options) -> Species {
    let mut s = Species::paper();
    (VARIANTS[variant].apply)(&mut s);
    s.contraction_frequency = frequency;
    if let Some(grid) = o.grid {
        s.grid_resolution = grid;
    }
    s
}

fn simulate(variant: usize, frequency: f32, o: &Options) -> Result<Run, String> {
    let species = species(variant, frequency, o);
    let mut sim = SliceSim::new(&species).map_err(|e| e.to_string())?;
    let mut trajectory = vec![(0.0, 0.0)];
    while sim.time() < o.seconds - 1e-4 {
        sim.advance(0.1);
        trajectory.push((sim.time(), sim.swim_distance()));
    }
    Ok(Run {
        variant,
        frequency,
        diameter: species.diameter,
        trajectory,
        recoveries: sim.recoveries(),
    })
}

fn main() {
    let o = match parse_options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("sweep: {e}");
            std::process::exit(2);
        }
    };
    let jobs: Vec<(usize, f32)> = (0..VARIANTS.len())
        .flat_map(|v| frequencies().into_iter().map(move |f| (v, f)))
        .collect();
    let (next, done) = (AtomicUsize::new(0), AtomicUsize::new(0));
    let runs = Mutex::new(Vec::new());
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
    progress(0, jobs.len());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                while let Some(&(v, f)) = jobs.get(next.fetch_add(1, Ordering::SeqCst)) {
                    let run = simulate(v, f, &o);
                    runs.lock().unwrap().push(run);
                    progress(done.fetch_add(1, Ordering::SeqCst) + 1, jobs.len());
                }
            });
        }
    });
    eprintln!();
    let mut runs: Vec<Run> = match runs.into_inner().unwrap().into_iter().collect() {
        Ok(runs) => runs,
        Err(e) => {
            eprintln!("sweep: {e}");
            std::process::exit(1);
        }
    };
    runs.sort_by(|a, b| {
        (a.variant, a.frequency)
            .partial_cmp(&(b.variant, b.frequency))
            .unwrap()
    });
    report(&runs, &o);
}

fn progress(done: usize, total: usize) {
    let width = 40;
    let filled = width * done / total.max(1);
    eprint!(
        "\r[{}{}] {done}/{total} runs",
        "#".repeat(filled),
        "-".repeat(width - filled)
    );
    let _ = std::io::stderr().flush();
}

fn final_distance(run: &Run) -> f32 {
    run.trajectory.last().map_or(0.0, |p| p.1)
}

/// Distance against frequency for one variant, in its own diameters.
fn curve(runs: &[Run], variant: usize) -> Vec<(f32, f32)> {
    runs.iter()
        .filter(|r| r.variant == variant)
        .map(|r| (r.frequency, final_distance(r) / r.diameter))
        .collect()
}

fn report(runs: &[Run], o: &Options) {
    let grid = o.grid.unwrap_or(Species::paper().grid_resolution);
    println!(
        "distance swum in {} s (grid {grid}), in bell diameters",
        o.seconds
    );
    let curves: Vec<Vec<(f32, f32)>> = (0..VARIANTS.len()).map(|v| curve(runs, v)).collect();
    print!("{:>8}", "freq Hz");
    for v in &VARIANTS {
        print!("  {:>26}", v.label);
    }
    println!();
    for (k, f) in frequencies().iter().enumerate() {
        print!("{f:8.1}");
        for c in &curves {
            print!("  {:>26.3}", c.get(k).map_or(f32::NAN, |p| p.1));
        }
        println!();
    }
    for (v, c) in VARIANTS.iter().zip(&curves) {
        let (Some(peak), Some(low), Some(high)) = (
            c.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1)),
            c.first(),
            c.last(),
        ) else {
            continue;
        };
        println!(
            "{}: peak at {} Hz, {:+.0}% over the {} Hz end, {:+.0}% over the {} Hz end",
            v.label,
            peak.0,
            100.0 * (peak.1 / low.1 - 1.0),
            low.0,
            100.0 * (peak.1 / high.1 - 1.0),
            high.0
        );
    }
    let ratio = |f: f32| {
        let at = |c: &Vec<(f32, f32)>| c.iter().find(|p| (p.0 - f).abs() < 1e-4).map(|p| p.1);
        Some(at(&curves[0])? / at(&curves[1])?)
    };
    if let Some(r) = ratio(0.7) {
        println!(
            "staggered over unison at 0.7 Hz: {:+.0}%",
            100.0 * (r - 1.0)
        );
    }
    let recoveries: u32 = runs.iter().map(|r| r.recoveries).sum();
    println!("blow-ups recovered: {recoveries}");

    if let Err(e) = std::fs::create_dir_all(&o.out) {
        eprintln!("sweep: cannot create {}: {e}", o.out.display());
        return;
    }
    let csv = o.out.join("sweep.csv");
    let mut text = String::from("variant,frequency_hz,time_s,distance_m\n");
    for r in runs {
        for (t, d) in &r.trajectory {
            text += &format!(
                "{},{},{t:.3},{d:.6}\n",
                VARIANTS[r.variant].label, r.frequency
            );
        }
    }
    match std::fs::write(&csv, text) {
        Ok(()) => println!("wrote {}", csv.display()),
        Err(e) => eprintln!("sweep: cannot write {}: {e}", csv.display()),
    }
    let distance = Chart {
        title: format!("Distance in {} s against frequency", o.seconds),
        x_label: "contraction frequency (Hz)".into(),
        y_label: "distance (bell diameters)".into(),
        series: VARIANTS
            .iter()
            .zip(&curves)
            .map(|(v, c)| Series {
                label: v.label.to_string(),
                points: c.clone(),
                color: v.color,
                markers: true,
            })
            .collect(),
        ..Default::default()
    };
    let palette = [
        [68, 1, 84],
        [59, 82, 139],
        [33, 145, 140],
        [94, 201, 98],
        [253, 231, 37],
        [230, 120, 20],
        [200, 30, 60],
        [120, 60, 20],
    ];
    let shown = [0.2, 0.4, 0.6, 0.7, 0.8, 1.0, 1.2, 1.6];
    let trajectories = Chart {
        title: "Trajectories, staggered".into(),
        x_label: "time (s)".into(),
        y_label: "distance (bell diameters)".into(),
        series: runs
            .iter()
            .filter(|r| r.variant == 0 && shown.iter().any(|f| (f - r.frequency).abs() < 1e-4))
            .zip(palette.iter().cycle())
            .map(|(r, color)| Series {
                label: format!("{} Hz", r.frequency),
                points: r
                    .trajectory
                    .iter()
                    .map(|(t, d)| (*t, d / r.diameter))
                    .collect(),
                color: *color,
                markers: false,
            })
            .collect(),
        ..Default::default()
    };
    let png = o.out.join("sweep.png");
    match plot::write_png(&png, &[distance, trajectories], 2, 640, 440) {
        Ok(()) => println!("wrote {}", png.display()),
        Err(e) => eprintln!("sweep: cannot write {}: {e}", png.display()),
    }
}
