//! The fringe's guide chains: one step of a moon jelly's eight guides and the five of its
//! manubrium and oral arms (where the slice draws them, the bell as a solid, the water
//! read at three points a guide, the filament steps), what a near jellyfish pays per slice step for a fringe and arms that trail in
//! the 3D water. A frame at 60 Hz takes about 0.6 of the moon jelly's steps. Prints the
//! cost per step and per 60 Hz frame.

use bevy_jellyfish::Species;
use bevy_jellyfish::shape::SliceOutline;
use bevy_jellyfish::shape::oral::{self, OralStyle};
use bevy_jellyfish::shape::tentacles::{TentacleLayout, guide_reference};
use bevy_jellyfish::sim::guides::{
    Filament, GUIDE_NODES, GuideChains, GuideStep, Hanging, Solid, read_along,
};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::{Quat, Vec2, Vec3};
use std::hint::black_box;
use std::time::Instant;

fn step(c: &mut Criterion) {
    for (name, species) in [
        ("aurelia", Species::aurelia()),
        ("aequorea", Species::aequorea()),
        ("sarsia", Species::sarsia()),
    ] {
        species_step(c, name, species);
    }
}

fn species_step(c: &mut Criterion, name: &str, species: Species) {
    let guides = species.guide_count();
    // A bell half contracted, its fringe in a cross stream that keeps the guides moving.
    let slice = SliceOutline::contracted(&species, 61, 30, 0.5);
    let view = slice.view();
    let centroid = view.bell.iter().sum::<Vec2>() / view.bell.len() as f32;
    let roots = [view.bell[0], view.bell[view.bell.len() - 1]];
    let (mut chains, mut reference, mut solid) =
        (GuideChains::new(guides), Vec::new(), Solid::default());
    let mut water = Vec::new();
    // The manubrium's guide and the arms', from the apex.
    let tubes = species.oral_guide_count();
    let layout = TentacleLayout {
        count: tubes,
        sides: oral::ORAL_SIDES,
        points: 2,
    };
    let (style, apex) = (OralStyle::of(&species), view.bell[view.bell.len() / 2]);
    // None where the tubes hang within the cavity (*Aequorea*'s lips).
    let stalks = (tubes > 0 && style.is_manubrium(0)) as usize;
    let mut stalk = GuideChains::hanging(stalks, Hanging::MANUBRIUM);
    let mut arms = GuideChains::hanging(tubes - stalks, Hanging::ORAL_ARM);
    let (mut oral_reference, mut oral_water, mut oral_offsets) =
        (Vec::new(), Vec::new(), Vec::new());
    let dt = species.step_length();
    // The water as the plugin reads it: at each guide's root, middle and tip, each point
    // turned into the world (the jellyfish tilted) and the answer turned back.
    let (tilt, carrying) = (Quat::from_rotation_z(0.3), Vec3::new(0.0, 0.0, 0.002));
    let stream = |t: f32, p: Vec3| {
        let world = tilt * p;
        let water = Vec3::new(0.01 * (t + world.y * 40.0).sin(), 0.0, 0.004);
        tilt.inverse() * (water - carrying)
    };
    let mut one_step = |t: f32| {
        guide_reference(view.tentacles, roots, centroid, guides, &mut reference);
        solid.rebuild(view.bell, centroid, &species);
        read_along(&reference, chains.offsets(), |p| stream(t, p), &mut water);
        chains.step(&GuideStep {
            dt,
            reference: &reference,
            water: &water,
            towing: 0.01,
            filament: Filament::of(&species, 0.01),
            solid: &solid,
        });
        let oral = (view.oral_arms, apex, centroid);
        oral::guide_reference(&layout, &style, oral.0, oral.1, oral.2, &mut oral_reference);
        let (k, chain) = (stalks * GUIDE_NODES, &oral_reference);
        oral_offsets.clear();
        oral_offsets.extend_from_slice(stalk.offsets());
        oral_offsets.extend_from_slice(arms.offsets());
        read_along(chain, &oral_offsets, |p| stream(t, p), &mut oral_water);
        for (guides, range, filament) in [
            (&mut stalk, 0..k, Filament::manubrium(&species, 0.01)),
            (
                &mut arms,
                k..chain.len(),
                Filament::oral_arm(&species, 0.01),
            ),
        ] {
            guides.step(&GuideStep {
                dt,
                reference: &chain[range.clone()],
                water: &oral_water[range],
                towing: 0.01,
                filament,
                solid: &solid,
            });
        }
    };
    let mut t = 0.0;
    c.bench_function(&format!("guides/{name}_step"), |b| {
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
        "guides, {name}: {guides} guides and {tubes} oral ones, {:.2} µs a step, {:.2} µs a 60 Hz frame \
         per near jellyfish",
        per_step * 1e6,
        per_frame * 1e6
    );
    black_box((chains.offsets(), stalk.offsets(), arms.offsets()));
}

criterion_group!(benches, step);
criterion_main!(benches);
