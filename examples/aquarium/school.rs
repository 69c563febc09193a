//! The schools: `count` jellyfish of each shipped species, placed without overlap, each
//! with its own seed and phase, kept in the tank by steering.
//!
//! Each jellyfish carries the plugin's [`Steering`]: this module only says where it wants
//! to go (a slow wander of its own, biased upwards, bent away from the walls, the floor,
//! the surface and close neighbours); the plugin turns it towards that while it strokes,
//! never while it coasts. Decided in fixed ticks, so a replay steers the same.

use crate::tank::{HALF_DEPTH, HALF_WIDTH, SURFACE};
use bevy::prelude::*;
use bevy_jellyfish::plugin::{JellyfishSlice, Steering, SwimMotion};
use bevy_jellyfish::{Jellyfish, JellyfishSystems, Species};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

/// Scene units per metre: a 40 mm moon jelly is 0.8 units across, so a school of
/// hundreds has room in the tank.
pub const SCALE: f32 = 20.0;
/// The species shipped in `assets/species/`, with a radius that keeps neighbours apart
/// (bell and tentacles, scene units).
pub const SPECIES: [(&str, f32); 3] = [("aurelia", 0.6), ("aequorea", 0.75), ("sarsia", 0.65)];
/// Steering starts this far from a wall, scene units.
const MARGIN: f32 = 2.5;
/// Below and above these heights jellyfish turn away from the floor (felt early: the
/// tentacles hang a body length below the bell) and from the surface; they start between.
const FLOOR_ZONE: f32 = 2.0;
const SURFACE_ZONE: f32 = 2.0;

/// Radians turned per bell diameter surged while contracting: twice the plugin's default,
/// so a school turns away from the glass within two or three strokes.
const AGILITY: f32 = 6.0;

/// How many jellyfish of each species; changing it respawns the schools.
#[derive(Resource, Clone, Copy, Debug)]
pub struct School {
    pub per_species: usize,
    pub seed: u32,
}

/// One member of a school, with its own wander.
#[derive(Component)]
pub struct Swimmer {
    radius: f32,
    wander: Vec3,
}

pub fn plugin(app: &mut App) {
    app.add_systems(
        Update,
        respawn.run_if(resource_exists_and_changed::<School>),
    )
    .add_systems(FixedUpdate, steer.before(JellyfishSystems::StepSlices));
}

/// Where jellyfish may be placed: clear of the walls, the floor and the surface.
pub fn place(rng: &mut StdRng) -> Vec3 {
    Vec3::new(
        rng.random_range(-HALF_WIDTH + 1.5..HALF_WIDTH - 1.5),
        rng.random_range(FLOOR_ZONE..SURFACE - SURFACE_ZONE),
        rng.random_range(-HALF_DEPTH + 1.5..HALF_DEPTH - 1.5),
    )
}

/// Rejection sampling: each new jellyfish is at least the sum of the two radii away from
/// every other; after many failures the spacing is relaxed a little.
pub fn positions(radii: &[f32], rng: &mut StdRng) -> Vec<Vec3> {
    let mut placed: Vec<Vec3> = Vec::with_capacity(radii.len());
    for &r in radii {
        let mut spacing = 1.0;
        let p = 'search: loop {
            for _ in 0..300 {
                let p = place(rng);
                if placed
                    .iter()
                    .zip(radii)
                    .all(|(q, rq)| p.distance(*q) >= spacing * (r + rq))
                {
                    break 'search p;
                }
            }
            spacing *= 0.9;
        };
        placed.push(p);
    }
    placed
}

fn respawn(
    mut commands: Commands,
    school: Res<School>,
    assets: Res<AssetServer>,
    existing: Query<Entity, With<Swimmer>>,
) {
    for e in &existing {
        commands.entity(e).despawn();
    }
    // Seeded, so a seed gives the same aquarium every run (with the same `rand`).
    let mut rng = StdRng::seed_from_u64(school.seed.into());
    let members: Vec<(&str, f32)> = SPECIES
        .iter()
        .flat_map(|s| std::iter::repeat_n(*s, school.per_species))
        .collect();
    let radii: Vec<f32> = members.iter().map(|(_, r)| *r).collect();
    for ((name, radius), at) in members.iter().zip(positions(&radii, &mut rng)) {
        commands.spawn(member(&assets, name, *radius, at, &mut rng));
    }
    info!(
        "{} jellyfish: {} of each of {}",
        members.len(),
        school.per_species,
        SPECIES.map(|s| s.0).join(", ")
    );
}

/// A jellyfish of the species file `name` at `at`, keeping `radius` from its neighbours,
/// with its own seed, phase, lean and wander.
pub fn member(
    assets: &AssetServer,
    name: &str,
    radius: f32,
    at: Vec3,
    rng: &mut StdRng,
) -> impl Bundle {
    let species: Handle<Species> = assets.load(format!("species/{name}.species.ron"));
    // Mostly upright, leaning up to ~25 degrees in a random direction.
    let lean = Quat::from_rotation_y(rng.random_range(0.0..std::f32::consts::TAU))
        * Quat::from_rotation_x(rng.random_range(0.0..0.45));
    (
        Jellyfish::new(species)
            .with_seed(rng.random())
            .with_phase(rng.random()),
        Swimmer {
            radius,
            wander: Vec3::from_array(rng.random()) * 100.0,
        },
        Steering::heading(Vec3::Y).with_agility(AGILITY),
        Transform::from_translation(at)
            .with_rotation(lean)
            .with_scale(Vec3::splat(SCALE)),
    )
}

/// How strongly the walls push at `p`: zero beyond the margin, one at the wall, per axis.
fn wall_push(p: Vec3) -> Vec3 {
    let near = |d: f32| ((MARGIN - d) / MARGIN).clamp(0.0, 1.5);
    Vec3::new(
        near(HALF_WIDTH + p.x) - near(HALF_WIDTH - p.x),
        near(p.y - (FLOOR_ZONE - MARGIN)) - near(SURFACE - SURFACE_ZONE + MARGIN - p.y),
        near(HALF_DEPTH + p.z) - near(HALF_DEPTH - p.z),
    )
}

/// Where each jellyfish wants to go: a slowly wandering heading (biased upwards, as
/// jellyfish mostly swim), bent away from walls and neighbours. The plugin turns it only
/// while it strokes, harder the harder it strokes.
fn steer(
    time: Res<Time<Fixed>>,
    mut swimmers: Query<(&Swimmer, &JellyfishSlice, &SwimMotion, &mut Steering)>,
) {
    let t = time.elapsed_secs();
    // Where they are in the simulation (not where the last frame drew them).
    let mut all: Vec<(Vec3, f32)> = swimmers
        .iter()
        .filter(|(_, slice, ..)| slice.started())
        .map(|(s, _, motion, _)| (motion.pose.position, s.radius))
        .collect();
    // The same order every run: the steering is part of the replay.
    all.sort_by(|a, b| {
        a.0.to_array()
            .partial_cmp(&b.0.to_array())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for (swimmer, _, motion, mut steering) in &mut swimmers {
        let p = motion.pose.position;
        let w = swimmer.wander;
        let heading = Vec3::new(
            0.6 * (0.11 * t + w.x).sin(),
            1.2 + 0.5 * (0.07 * t + w.y).sin(),
            0.6 * (0.09 * t + w.z).cos(),
        );
        let mut push = wall_push(p);
        for (q, rq) in &all {
            let d = p - *q;
            let reach = 1.3 * (swimmer.radius + rq);
            let len = d.length();
            if len > 1e-4 && len < reach {
                push += d / len * (1.0 - len / reach);
            }
        }
        let desired = (heading.normalize() + 3.0 * push).normalize_or(Vec3::Y);
        steering.target = bevy_jellyfish::plugin::SteeringTarget::Heading(desired);
    }
}
