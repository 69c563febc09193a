//! The paper's Fig. 5: how far the default jellyfish swims in a fixed time at contraction
//! frequencies from 0.2 to 1.6 Hz, with staggered and with unison re-expansion.
//!
//! Prints a table, writes `sweep.csv` and `sweep.png` (distance against frequency;
//! trajectories against time) into `--out` (default `docs/`).
//!
//! `cargo run --release --no-default-features --example sweep -- [--seconds 20] [--grid 100] [--out docs]`

mod plot;

use bevy_jellyfish::{SliceSim, Species};
use plot::{Chart, Series};
use std::io::Write;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

const FREQUENCIES: [f32; 8] = [0.2, 0.4, 0.6, 0.7, 0.8, 1.0, 1.2, 1.6];
const STAGGERS: [(f32, &str); 2] = [(1.0, "staggered"), (0.0, "unison")];

struct Run {
    frequency: f32,
    stagger: f32,
    /// (time s, distance m)
    trajectory: Vec<(f32, f32)>,
    recoveries: u32,
}

struct Options {
    seconds: f32,
    grid: u32,
    out: PathBuf,
}

fn parse_options() -> Result<Options, String> {
    let mut o = Options {
        seconds: 20.0,
        grid: 100,
        out: PathBuf::from("docs"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let mut value = || args.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--seconds" => o.seconds = value()?.parse().map_err(|e| format!("--seconds: {e}"))?,
            "--grid" => o.grid = value()?.parse().map_err(|e| format!("--grid: {e}"))?,
            "--out" => o.out = PathBuf::from(value()?),
            other => return Err(format!("unknown argument {other}")),
        }
    }
    Ok(o)
}

fn simulate(frequency: f32, stagger: f32, o: &Options) -> Result<Run, String> {
    let mut species = Species::aurelia();
    species.contraction_frequency = frequency;
    species.expansion_stagger = stagger;
    species.grid_resolution = o.grid;
    let mut sim = SliceSim::new(&species).map_err(|e| e.to_string())?;
    let sample = 0.1;
    let mut trajectory = vec![(0.0, 0.0)];
    while sim.time() < o.seconds - 1e-4 {
        sim.advance(sample);
        trajectory.push((sim.time(), sim.swim_distance()));
    }
    Ok(Run {
        frequency,
        stagger,
        trajectory,
        recoveries: sim.recoveries(),
    })
}

fn main() {
    let o = match parse_options() {
        Ok(o) => Arc::new(o),
        Err(e) => {
            eprintln!("sweep: {e}");
            std::process::exit(2);
        }
    };
    let jobs: Vec<(f32, f32)> = STAGGERS
        .iter()
        .flat_map(|(s, _)| FREQUENCIES.iter().map(move |f| (*f, *s)))
        .collect();
    let total = jobs.len();
    let jobs = Arc::new(Mutex::new(jobs));
    let done = Arc::new(AtomicUsize::new(0));
    let runs = Arc::new(Mutex::new(Vec::new()));
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
    progress(0, total);
    let handles: Vec<_> = (0..workers)
        .map(|_| {
            let (jobs, done, runs, o) = (jobs.clone(), done.clone(), runs.clone(), o.clone());
            std::thread::spawn(move || {
                while let Some((f, s)) = jobs.lock().unwrap().pop() {
                    let run = simulate(f, s, &o);
                    runs.lock().unwrap().push(run);
                    progress(done.fetch_add(1, Ordering::SeqCst) + 1, total);
                }
            })
        })
        .collect();
    for h in handles {
        h.join().expect("sweep worker panicked");
    }
    eprintln!();
    let mut runs: Vec<Run> = match Arc::try_unwrap(runs)
        .ok()
        .unwrap()
        .into_inner()
        .unwrap()
        .into_iter()
        .collect()
    {
        Ok(runs) => runs,
        Err(e) => {
            eprintln!("sweep: {e}");
            std::process::exit(1);
        }
    };
    runs.sort_by(|a, b| {
        (b.stagger, a.frequency)
            .partial_cmp(&(a.stagger, b.frequency))
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

fn report(runs: &[Run], o: &Options) {
    let diameter = Species::aurelia().diameter;
    println!(
        "distance swum in {} s (grid {}), in bell diameters",
        o.seconds, o.grid
    );
    println!(
        "{:>8}  {:>10}  {:>10}  {:>7}",
        "freq Hz", "staggered", "unison", "ratio"
    );
    let find = |f: f32, s: f32| runs.iter().find(|r| r.frequency == f && r.stagger == s);
    for f in FREQUENCIES {
        let (Some(st), Some(un)) = (find(f, 1.0), find(f, 0.0)) else {
            continue;
        };
        let (a, b) = (final_distance(st) / diameter, final_distance(un) / diameter);
        println!("{f:8.2}  {a:10.3}  {b:10.3}  {:7.2}", a / b);
    }
    let staggered: Vec<(f32, f32)> = FREQUENCIES
        .iter()
        .filter_map(|f| find(*f, 1.0).map(|r| (*f, final_distance(r))))
        .collect();
    if let (Some(peak), Some(low), Some(high)) = (
        staggered.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1)),
        staggered.first(),
        staggered.last(),
    ) {
        println!(
            "staggered peak at {} Hz: {:.2}x the {} Hz end, {:.2}x the {} Hz end",
            peak.0,
            peak.1 / low.1,
            low.0,
            peak.1 / high.1,
            high.0
        );
    }
    let recoveries: u32 = runs.iter().map(|r| r.recoveries).sum();
    println!("blow-ups recovered: {recoveries}");

    if let Err(e) = std::fs::create_dir_all(&o.out) {
        eprintln!("sweep: cannot create {}: {e}", o.out.display());
        return;
    }
    let csv = o.out.join("sweep.csv");
    let mut text = String::from("frequency_hz,stagger,time_s,distance_m\n");
    for r in runs {
        for (t, d) in &r.trajectory {
            text += &format!("{},{},{t:.3},{d:.6}\n", r.frequency, r.stagger);
        }
    }
    match std::fs::write(&csv, text) {
        Ok(()) => println!("wrote {}", csv.display()),
        Err(e) => eprintln!("sweep: cannot write {}: {e}", csv.display()),
    }

    let colors = [[31, 119, 180], [214, 39, 40]];
    let distance = Chart {
        title: format!("Distance in {} s against frequency", o.seconds),
        x_label: "contraction frequency (Hz)".into(),
        y_label: "distance (bell diameters)".into(),
        series: STAGGERS
            .iter()
            .zip(colors)
            .map(|((s, label), color)| Series {
                label: label.to_string(),
                points: runs
                    .iter()
                    .filter(|r| r.stagger == *s)
                    .map(|r| (r.frequency, final_distance(r) / diameter))
                    .collect(),
                color,
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
    let trajectories = Chart {
        title: "Trajectories, staggered".into(),
        x_label: "time (s)".into(),
        y_label: "distance (bell diameters)".into(),
        series: runs
            .iter()
            .filter(|r| r.stagger == 1.0)
            .zip(palette.iter().cycle())
            .map(|(r, color)| Series {
                label: format!("{} Hz", r.frequency),
                points: r
                    .trajectory
                    .iter()
                    .map(|(t, d)| (*t, d / diameter))
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
