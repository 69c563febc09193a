//! Each shipped species started from rest, beside the records of its animal: the speed and
//! distance of its first strokes, and the moon jelly's shape through one stroke under way
//! against the 15.5 cm *Aurelia* Dabiri recorded (`docs/records/`), at the model's own
//! size and scaled to the recorded animal's. The paper's Fig. 12 model runs beside them.
//!
//! Prints, per species: distance per stroke from rest and under way, the slowest speed
//! while the bell refills once under way (negative: it drifts backwards), the contracted
//! margin, outline (the exumbrella's widest, as a video shows the bell, over its own width
//! at rest as a video measures it) and height, and the
//! subumbrella's depth over its width (the cavity alone, as `SliceSim::bell_points` gives
//! it); then each shipped species at other sizes, every length scaled and the pulse rate
//! set to the animal's at that size, with its refill's slowest speed too, and the smallest
//! size at which each still glides while it refills; then how far the
//! moon jelly's stroke stays from the record's (root mean square). Writes
//! `kinematics.csv` and `kinematics.png` into `--out` (default `docs/`).
//!
//! `cargo run --release --no-default-features --example kinematics -- [--strokes 20 (at least 3)] [--out docs] [--finer N] [--set field=value …]`
//! (`--set` changes every species, the paper's and the resized moon jellies too; `--finer`
//! takes N times each species' steps, to see what its own step does to the stroke).

#[path = "common/species.rs"]
mod common;

#[path = "sweep/plot.rs"]
mod plot;

use bevy_jellyfish::shape::profile::Profile;
use bevy_jellyfish::sim::clock::FixedClock;
use bevy_jellyfish::sim::inspect::cavity;
use bevy_jellyfish::{SliceSim, Species};
use common::{overrides, shipped_species, with_overrides};
use plot::{Chart, Series};
use std::io::Write;
use std::path::{Path, PathBuf};

/// One sample after a fixed step; lengths over the rest diameter.
#[derive(Clone, Copy)]
struct Sample {
    time: f32,
    /// Cycles since the start (time × pulse rate).
    cycles: f32,
    distance: f32,
    /// Over the last step, diameters per second.
    speed: f32,
    margin: f32,
    /// The bell's outline (its exumbrella) at its widest, over its widest at rest: what a
    /// video of the animal measures (at rest the mesoglea of the flanks stands past the
    /// margin, so over the rest diameter it reads larger).
    widest: f32,
    height: f32,
    /// The subumbrella alone, as [`SliceSim::bell_points`] gives it: its depth (apex to
    /// the margins' midpoint) over its width at its widest.
    cavity: f32,
    /// The subumbrella's strain ([`SliceSim::meridian_strain`]).
    strain: f32,
}

/// The margin's width, the outline's widest (the subumbrella given its mesoglea, as the
/// renderer draws the exumbrella) and the bell's height from apex to margin (the
/// subumbrella's plus the apex's mesoglea), m; and the subumbrella's depth over its width.
fn shape(sim: &SliceSim, profile: &mut Profile) -> (f32, f32, f32, f32) {
    let b = sim.bell_points();
    let (left, right, apex) = (b[0], b[b.len() - 1], b[b.len() / 2]);
    let margin = (right - left).length();
    profile.build(b, b, sim.species(), b.len() / 2);
    let widest = profile.widest();
    let height = apex.y - 0.5 * (left.y + right.y) + sim.species().thickness;
    (margin, widest, height, cavity(b).0)
}

/// `strokes` strokes from rest, a sample after every fixed step (`finer` times the
/// species' own steps a cycle). A slice that had to recover from a blow-up or a crossed
/// outline is said on stderr.
fn from_rest(species: &Species, strokes: u32, finer: u32) -> Vec<Sample> {
    let mut sim = SliceSim::new(species).expect("valid species");
    if finer > 1 {
        let steps = SliceSim::steps_per_cycle(species) * finer;
        sim.set_clock(FixedClock::new(species.period(), steps));
    }
    let d = species.diameter;
    let mut samples = Vec::new();
    let mut profile = Profile::default();
    let rest_widest = shape(&sim, &mut profile).1;
    let (mut time, mut distance) = (0.0f32, 0.0f32);
    let end = strokes as f32 * species.period();
    while sim.time() < end {
        sim.advance_with(1.0 / 60.0, |sim| {
            let (margin, widest, height, cavity) = shape(sim, &mut profile);
            let x = sim.swim_distance() / d;
            let dt = sim.time() - time;
            samples.push(Sample {
                time: sim.time(),
                cycles: sim.time() * species.contraction_frequency,
                distance: x,
                speed: if dt > 0.0 { (x - distance) / dt } else { 0.0 },
                margin: margin / d,
                widest: widest / rest_widest,
                height: height / d,
                cavity,
                strain: sim.meridian_strain(),
            });
            time = sim.time();
            distance = x;
        });
    }
    if sim.recoveries() > 0 {
        eprintln!("{}: {} recoveries", species.name, sim.recoveries());
    }
    samples
}

/// Each of `species` from rest for `strokes` strokes, one thread each.
fn from_rest_all(species: Vec<Species>, strokes: u32, finer: u32) -> Vec<(Species, Vec<Sample>)> {
    std::thread::scope(|scope| {
        let handles: Vec<_> = species
            .into_iter()
            .map(|s| {
                scope.spawn(move || {
                    let samples = from_rest(&s, strokes, finer);
                    (s, samples)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    })
}

/// Mean distance per stroke over the last five strokes, diameters.
fn under_way_per_stroke(samples: &[Sample]) -> f32 {
    let strokes = per_stroke(samples);
    let late = &strokes[strokes.len().saturating_sub(5)..];
    late.iter().sum::<f32>() / late.len().max(1) as f32
}

/// Distance per stroke over each whole cycle.
fn per_stroke(samples: &[Sample]) -> Vec<f32> {
    let mut starts = vec![0.0f32];
    for pair in samples.windows(2) {
        if pair[1].cycles.floor() > pair[0].cycles.floor() {
            starts.push(pair[1].distance);
        }
    }
    starts.windows(2).map(|w| w[1] - w[0]).collect()
}

/// The samples of cycle `k`, phase 0..1.
fn cycle(samples: &[Sample], k: u32) -> impl Iterator<Item = (f32, &Sample)> {
    samples
        .iter()
        .filter(move |s| s.cycles.floor() as u32 == k)
        .map(move |s| (s.cycles - k as f32, s))
}

/// The narrowest margin and outline and the greatest height over stroke `k`, over the
/// rest diameter.
fn contracted(samples: &[Sample], k: u32) -> (f32, f32, f32) {
    cycle(samples, k).fold((f32::MAX, f32::MAX, 0.0f32), |(m, w, h), (_, x)| {
        (m.min(x.margin), w.min(x.widest), h.max(x.height))
    })
}

/// The subumbrella's greatest depth over its width over stroke `k`.
fn deepest(samples: &[Sample], k: u32) -> f32 {
    cycle(samples, k).fold(0.0f32, |c, (_, x)| c.max(x.cavity))
}

/// The subumbrella's greatest strain over stroke `k`.
fn stretched(samples: &[Sample], k: u32) -> f32 {
    cycle(samples, k).fold(f32::MIN, |m, (_, x)| m.max(x.strain))
}

/// A species with every length times `scale`, beating at its animal's pulse rate for that
/// size ([`Species::resized`]; the rate as the diameter to the −1/2, `docs/physics.md`
/// section 5).
fn resized(base: &Species, scale: f32) -> Species {
    let diameter = base.diameter * scale;
    Species {
        name: format!("{} {:.0} mm", base.name, diameter * 1000.0),
        ..base.resized(diameter)
    }
}

/// The slowest speed while the bell refills (after its contraction) in stroke `stroke`,
/// diameters per second: negative where it drifts backwards.
fn slowest_in_refill(species: &Species, samples: &[Sample], stroke: u32) -> f32 {
    cycle(samples, stroke)
        .filter(|(phase, _)| *phase > species.contraction_share())
        .map(|(_, x)| x.speed)
        .fold(f32::MAX, f32::min)
}

/// The smallest size at which each species, every length scaled and beating at its
/// animal's rate for that size, still glides forwards while its bell refills once under
/// way: smaller, the water's viscosity takes the glide its contraction gave and the
/// refill draws it back. Bisected on the scale's logarithm between an eighth and one
/// (the shipped size, which glides), to about 2%.
fn glide_thresholds(species: &[&Species], strokes: u32, finer: u32, under_way: u32) {
    let glides = |scales: &[f32]| -> Vec<bool> {
        let runs = species
            .iter()
            .zip(scales)
            .map(|(s, &k)| resized(s, k))
            .collect();
        from_rest_all(runs, strokes, finer)
            .iter()
            .map(|(s, samples)| slowest_in_refill(s, samples, under_way) > 0.0)
            .collect()
    };
    let mut bounds: Vec<(f32, f32)> = vec![(0.125, 1.0); species.len()];
    let at_own_size = glides(&vec![1.0; species.len()]);
    for _ in 0..7 {
        let middle: Vec<f32> = bounds.iter().map(|(lo, hi)| (lo * hi).sqrt()).collect();
        for ((b, m), g) in bounds.iter_mut().zip(&middle).zip(glides(&middle)) {
            *b = if g { (b.0, *m) } else { (*m, b.1) };
        }
    }
    println!("\n| species | smallest size that glides while it refills (mm) | its own size (mm) |");
    println!("|---|---|---|");
    for ((s, (lo, hi)), own) in species.iter().zip(&bounds).zip(at_own_size) {
        let size = if !own {
            "none: drawn back at its own size".to_string()
        } else if *lo <= 0.125 {
            format!("below {:.1}", 0.125 * s.diameter * 1000.0)
        } else {
            format!(
                "{:.1}–{:.1}",
                lo * s.diameter * 1000.0,
                hi * s.diameter * 1000.0
            )
        };
        println!("| {} | {size} | {:.0} |", s.name, s.diameter * 1000.0);
    }
}

/// The record: (phase, margin, widest, height), lengths over the rest diameter.
fn record(path: &Path) -> Vec<(f32, f32, f32, f32)> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("time"))
        .filter_map(|l| {
            let v: Vec<f32> = l.split(',').filter_map(|x| x.parse().ok()).collect();
            (v.len() == 5).then(|| (v[1], v[2], v[3], v[4]))
        })
        .collect()
}

/// `record` at `phase`, linear between its samples: `pick` chooses the column.
fn recorded_at(
    rec: &[(f32, f32, f32, f32)],
    phase: f32,
    pick: fn(&(f32, f32, f32, f32)) -> f32,
) -> f32 {
    let after = rec
        .iter()
        .position(|r| r.0 >= phase)
        .unwrap_or(rec.len() - 1);
    if after == 0 {
        return pick(&rec[0]);
    }
    let (a, b) = (&rec[after - 1], &rec[after]);
    let t = ((phase - a.0) / (b.0 - a.0).max(1e-6)).clamp(0.0, 1.0);
    pick(a) + t * (pick(b) - pick(a))
}

/// The root-mean-square distance over stroke `k` of the model's `model` from the record's
/// `recorded`, sample by sample at the model's phases.
fn rms_from_record(
    samples: &[Sample],
    k: u32,
    rec: &[(f32, f32, f32, f32)],
    model: fn(&Sample) -> f32,
    recorded: fn(&(f32, f32, f32, f32)) -> f32,
) -> f32 {
    let (sum, n) = cycle(samples, k).fold((0.0f32, 0u32), |(sum, n), (phase, x)| {
        let d = model(x) - recorded_at(rec, phase, recorded);
        (sum + d * d, n + 1)
    });
    (sum / n.max(1) as f32).sqrt()
}

const COLORS: [[u8; 3]; 5] = [
    [31, 119, 180],
    [44, 160, 44],
    [214, 39, 40],
    [148, 103, 189],
    [255, 127, 14],
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |name: &str| common::value(&args, name);
    // At least three: the first strokes from rest and one under way.
    let strokes: u32 = value("--strokes")
        .and_then(|v| v.parse().ok())
        .unwrap_or(20)
        .max(3);
    let out = PathBuf::from(value("--out").map_or("docs", |v| v.as_str()));
    let under_way = strokes.saturating_sub(2).max(1);
    // The species' own steps, or that many times more (a time-step check: see
    // `docs/numerics.md`, "Time step").
    let finer: u32 = value("--finer")
        .and_then(|v| v.parse().ok())
        .unwrap_or(1)
        .max(1);

    let overrides = overrides(&args);
    let mut species = shipped_species();
    species.push(Species::paper());
    let species: Vec<Species> = species
        .into_iter()
        .map(|s| with_overrides(s, &overrides))
        .collect();
    let runs = from_rest_all(species, strokes, finer);

    println!(
        "| species | strokes 1-3 from rest (D) | D per stroke, under way | slowest in the refill (D/s) | margin contracted | outline contracted | height contracted (rest) | subumbrella depth / width contracted (rest) | subumbrella stretched |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (s, samples) in &runs {
        let strokes = per_stroke(samples);
        let steady = under_way_per_stroke(samples);
        let refill = slowest_in_refill(s, samples, under_way);
        let (margin, widest, height) = contracted(samples, under_way);
        let first: Vec<String> = strokes.iter().take(3).map(|d| format!("{d:.3}")).collect();
        println!(
            "| {} | {} | {steady:.3} | {refill:+.3} | {margin:.2} | {widest:.2} | {height:.2} ({:.2}) | {:.2} ({:.2}) | {:+.0}% |",
            s.name,
            first.join(", "),
            samples[0].height,
            deepest(samples, under_way),
            samples[0].cavity,
            100.0 * stretched(samples, under_way),
        );
    }

    // The moon jelly at other sizes and at the recorded animal's; Sarsia over the sizes
    // Katija et al. (2015) found to swim the same diameters per stroke; Aequorea from half
    // to twice its size.
    let aurelia = with_overrides(Species::aurelia(), &overrides);
    let sarsia = with_overrides(Species::sarsia(), &overrides);
    let aequorea = with_overrides(Species::aequorea(), &overrides);
    let sizes = [0.5, 1.0, 2.0, 155.0 / 40.0];
    let resized_runs = from_rest_all(
        sizes
            .iter()
            .map(|&k| resized(&aurelia, k))
            .chain([0.25, 0.5, 1.0].map(|k| resized(&sarsia, k)))
            .chain([0.5, 1.0, 2.0].map(|k| resized(&aequorea, k)))
            .collect(),
        strokes,
        finer,
    );
    println!(
        "\n| at another size | pulse rate (Hz) | D per stroke, under way | speed (mm/s) | slowest in the refill (D/s) | margin contracted | outline contracted | height contracted |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (s, samples) in &resized_runs {
        let steady = under_way_per_stroke(samples);
        let refill = slowest_in_refill(s, samples, under_way);
        let (margin, widest, height) = contracted(samples, under_way);
        println!(
            "| {} | {:.2} | {steady:.3} | {:.1} | {refill:+.3} | {margin:.2} | {widest:.2} | {height:.2} |",
            s.name,
            s.contraction_frequency,
            steady * s.diameter * s.contraction_frequency * 1000.0
        );
    }

    glide_thresholds(&[&aurelia, &aequorea, &sarsia], strokes, finer, under_way);

    let rec =
        record(&Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/records/aurelia_dabiri2011.csv"));
    let moon = &runs
        .iter()
        .find(|(s, _)| s.name == aurelia.name)
        .expect("the moon jelly is shipped")
        .1;
    let recorded_size = &resized_runs[sizes.len() - 1];
    println!(
        "\nThe moon jelly's stroke {under_way} against the record, root-mean-square over the stroke (over the rest diameter; the outline over its own widest at rest):\n\n| | margin | outline | height |\n|---|---|---|---|"
    );
    for (label, samples) in [("40 mm", moon), ("scaled to 155 mm", &recorded_size.1)] {
        let rms = |model: fn(&Sample) -> f32, recorded: fn(&(f32, f32, f32, f32)) -> f32| {
            rms_from_record(samples, under_way, &rec, model, recorded)
        };
        println!(
            "| {label} | {:.3} | {:.3} | {:.3} |",
            rms(|x| x.margin, |r| r.1),
            rms(|x| x.widest, |r| r.2),
            rms(|x| x.height, |r| r.3),
        );
    }
    let under = |samples: &[Sample], f: fn(&Sample) -> f32| -> Vec<(f32, f32)> {
        cycle(samples, under_way).map(|(p, x)| (p, f(x))).collect()
    };
    let gray = [90, 90, 90];
    let shape_chart =
        |title: &str, y: &str, f: fn(&Sample) -> f32, recorded: Vec<(f32, f32)>| Chart {
            title: title.into(),
            x_label: "phase of the stroke".into(),
            y_label: y.into(),
            series: vec![
                Series {
                    label: "record: 155 mm, Dabiri 2011".into(),
                    points: recorded,
                    color: gray,
                    markers: true,
                },
                Series {
                    label: "model, 40 mm".into(),
                    points: under(moon, f),
                    color: COLORS[0],
                    markers: false,
                },
                Series {
                    label: "model scaled to 155 mm".into(),
                    points: under(&recorded_size.1, f),
                    color: COLORS[4],
                    markers: false,
                },
            ],
            equal_aspect: false,
        };
    let in_time = |f: fn(&Sample) -> f32| -> Vec<Series> {
        runs.iter()
            .zip(COLORS)
            .map(|((s, samples), color)| Series {
                label: s.name.clone(),
                points: samples.iter().map(|x| (x.cycles, f(x))).collect(),
                color,
                markers: false,
            })
            .collect()
    };
    let mut distance = in_time(|x| x.distance);
    // The recorded moon jelly's range once under way (Xu & Dabiri 2020), from where the
    // model's is eight strokes before the end.
    let start = strokes.saturating_sub(8) as f32;
    let from = moon
        .iter()
        .find(|x| x.cycles >= start)
        .map_or(0.0, |x| x.distance);
    for per_cycle in [0.3f32, 0.7] {
        distance.push(Series {
            label: if per_cycle < 0.5 {
                "record: Aurelia 0.3-0.7 D per cycle".into()
            } else {
                String::new()
            },
            points: vec![
                (start, from),
                (strokes as f32, from + (strokes as f32 - start) * per_cycle),
            ],
            color: gray,
            markers: false,
        });
    }
    let charts = [
        shape_chart(
            "Moon jelly, a stroke under way: margin",
            "margin width / rest diameter",
            |x| x.margin,
            rec.iter().map(|r| (r.0, r.1)).collect(),
        ),
        shape_chart(
            "Moon jelly, under way: outline",
            "widest / widest at rest",
            |x| x.widest,
            rec.iter().map(|r| (r.0, r.2)).collect(),
        ),
        shape_chart(
            "Moon jelly, a stroke under way: height",
            "height / rest diameter",
            |x| x.height,
            rec.iter().map(|r| (r.0, r.3)).collect(),
        ),
        Chart {
            title: "Speed from rest".into(),
            x_label: "strokes".into(),
            y_label: "speed (diameters per second)".into(),
            series: in_time(|x| x.speed),
            equal_aspect: false,
        },
        Chart {
            title: "Distance from rest".into(),
            x_label: "strokes".into(),
            y_label: "distance (diameters)".into(),
            series: distance,
            equal_aspect: false,
        },
        Chart {
            title: "At other sizes, pulse rate as diameter^-1/2".into(),
            x_label: "bell diameter (mm)".into(),
            y_label: "diameters per stroke, under way".into(),
            series: [&aequorea, &aurelia, &sarsia]
                .into_iter()
                .zip([COLORS[0], COLORS[1], COLORS[2]])
                .map(|(base, color)| Series {
                    label: base.name.clone(),
                    points: resized_runs
                        .iter()
                        .filter(|(s, _)| s.name.starts_with(base.name.as_str()))
                        .map(|(s, samples)| (s.diameter * 1000.0, under_way_per_stroke(samples)))
                        .collect(),
                    color,
                    markers: true,
                })
                .collect(),
            equal_aspect: false,
        },
    ];
    let png = out.join("kinematics.png");
    match plot::write_png(&png, &charts, 2, 640, 420) {
        Ok(()) => println!("\nwrote {}", png.display()),
        Err(e) => eprintln!("kinematics: cannot write {}: {e}", png.display()),
    }
    let csv = out.join("kinematics.csv");
    let written = std::fs::File::create(&csv).and_then(|mut f| {
        writeln!(
            f,
            "species,diameter_m,time_s,strokes,distance_d,speed_d_per_s,margin_d,widest_of_rest,height_d"
        )?;
        for (s, samples) in runs.iter().chain(&resized_runs) {
            for x in samples {
                writeln!(
                    f,
                    "{},{},{:.4},{:.4},{:.5},{:.5},{:.4},{:.4},{:.4}",
                    s.name,
                    s.diameter,
                    x.time,
                    x.cycles,
                    x.distance,
                    x.speed,
                    x.margin,
                    x.widest,
                    x.height
                )?;
            }
        }
        Ok(())
    });
    match written {
        Ok(()) => println!("wrote {}", csv.display()),
        Err(e) => eprintln!("kinematics: cannot write {}: {e}", csv.display()),
    }
}
