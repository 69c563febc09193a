//! The tank's water for a crowded aquarium: one tick of the aquarium's tank (14 × 9 × 10
//! scene units in cells of 0.75) pushed by 10,000 jets, each a ball a bell across, as
//! `TankPlugin` gathers them. The pushes are most of such a tick; printed after the
//! criterion run: the tick and the pushes' share.
//!
//! `cargo bench --no-default-features --bench tank`

use bevy_jellyfish::sim::tank::TankFluid;
use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use std::hint::black_box;
use std::time::Instant;

const JETS: usize = 10_000;

fn tank() -> TankFluid {
    TankFluid::new(Vec3::new(-7.0, 0.0, -5.0), Vec3::new(7.0, 9.0, 5.0), 0.75)
}

/// Ten thousand jets spread through the tank, radii 0.4–1.0 (a bell across), each
/// pushing back and down.
fn jets() -> Vec<(Vec3, f32, Vec3)> {
    let mut seed = 12345u32;
    let mut next = move || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (seed >> 8) as f32 / (1u32 << 24) as f32
    };
    (0..JETS)
        .map(|_| {
            let at = Vec3::new(next() * 13.0 - 6.5, next() * 8.0 + 0.5, next() * 9.0 - 4.5);
            let velocity = Vec3::new(next() - 0.5, -0.2 * next(), next() - 0.5);
            (at, 0.4 + 0.6 * next(), velocity)
        })
        .collect()
}

fn tick(water: &mut TankFluid, jets: &[(Vec3, f32, Vec3)], pushes_only: bool) {
    for &(at, radius, velocity) in jets {
        water.stir(at, radius, velocity);
    }
    if pushes_only {
        water.push_slabs(1).into_iter().for_each(|s| s.apply());
        water.step_pushed(0.0);
    } else {
        water.step(1.0 / 64.0);
    }
}

fn bench(c: &mut Criterion) {
    let jets = jets();
    let mut water = tank();
    c.bench_function("tank_tick/10000_jets", |b| {
        b.iter(|| tick(&mut water, black_box(&jets), false))
    });
    c.bench_function("tank_pushes/10000_jets", |b| {
        b.iter(|| tick(&mut water, black_box(&jets), true))
    });
    let time = |pushes_only: bool| {
        let mut water = tank();
        let n = 50;
        let start = Instant::now();
        (0..n).for_each(|_| tick(&mut water, &jets, pushes_only));
        start.elapsed().as_secs_f64() * 1e3 / n as f64
    };
    let (whole, pushes) = (time(false), time(true));
    println!(
        "tank tick with {JETS} jets: {whole:.2} ms on one core, the pushes {pushes:.2} ms ({:.0}%)",
        100.0 * pushes / whole
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
