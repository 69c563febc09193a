//! The fringe's guide chains: one step of a moon jelly's eight guides (where the slice
//! draws them, the bell as a solid, the filament step), what a near jellyfish pays per
//! slice step for a fringe that trails in the 3D water. A frame at 60 Hz takes about 0.6
//! of the moon jelly's steps. Prints the cost per step and per 60 Hz frame.

use bevy_jellyfish::Species;
use bevy_jellyfish::shape::SliceOutline;
use bevy_jellyfish::shape::tentacles::guide_reference;
use bevy_jellyfish::sim::guides::{Filament, GuideChains, GuideStep, Solid};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use std::hint::black_box;
use std::time::Instant;

fn step(c: &mut Criterion) {
    let species = Species::aurelia();
    let guides = species.guide_count();
    // A bell half contracted, its fringe in a cross stream that keeps the guides moving.
    let slice = SliceOutline::contracted(&species, 61, 30, 0.5);
    let view = slice.view();
    let centroid = view.bell.iter().sum::<Vec2>() / view.bell.len() as f32;
    let roots = [view.bell[0], view.bell[view.bell.len() - 1]];
    let (mut chains, mut reference, mut solid) =
        (GuideChains::new(guides), Vec::new(), Solid::default());
    let mut water = Vec::new();
    let dt = species.step_length();
    let mut one_step = |t: f32| {
        guide_reference(view.tentacles, roots, centroid, guides, &mut reference);
        solid.rebuild(view.bell, centroid, &species);
        water.clear();
        water.extend(
            reference
                .iter()
                .map(|p| Vec3::new(0.01 * (t + p.y * 40.0).sin(), 0.0, 0.004)),
        );
        chains.step(&GuideStep {
            dt,
            reference: &reference,
            water: &water,
            towing: 0.01,
            filament: Filament::of(&species, 0.01),
            solid: &solid,
        });
    };
    let mut t = 0.0;
    c.bench_function("guides/aurelia_step", |b| {
        b.iter(|| {
            t += dt;
            one_step(black_box(t));
        })
    });
    let runs = 20_000;
    let start = Instant::now();
    for _ in 0..runs {
        t += dt;
        one_step(t);
    }
    let per_step = start.elapsed().as_secs_f64() / runs as f64;
    let per_frame = per_step * (1.0 / 60.0) / dt as f64;
    println!(
        "guides: {guides} guides, {:.2} µs a step, {:.2} µs a 60 Hz frame per near jellyfish",
        per_step * 1e6,
        per_frame * 1e6
    );
    black_box(chains.offsets());
}

criterion_group!(benches, step);
criterion_main!(benches);
