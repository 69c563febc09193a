//! The schools: `count` jellyfish of each shipped species, one library
//! [`JellyfishSchool`] per species filling the tank's water, each member with its own
//! seed, phase and size, kept in the tank and apart by the plugin's steering.

use crate::tank::{HALF_DEPTH, HALF_WIDTH, SURFACE};
use bevy::prelude::*;
use bevy::transform::StaticTransformOptimizations;
use bevy_jellyfish::Species;
use bevy_jellyfish::plugin::JellyfishSchool;

/// Scene units per metre: a 40 mm moon jelly is 0.8 units across, so a school of
/// hundreds has room in the tank.
pub const SCALE: f32 = 20.0;
/// The species shipped in `assets/species/`.
pub const SPECIES: [&str; 3] = ["aurelia", "aequorea", "sarsia"];
/// The water the schools keep to: clear of the glass by this much, scene units…
const GLASS: f32 = 1.0;
/// …above the floor by this much (the tentacles hang a body length below the bell)…
const FLOOR: f32 = 2.0;
/// …and below the surface by this much.
const TOP: f32 = 1.0;

/// How many jellyfish of each species; changing it respawns the schools.
#[derive(Resource, Clone, Copy, Debug)]
pub struct School {
    pub per_species: usize,
    pub seed: u32,
}

pub fn plugin(app: &mut App) {
    app.add_systems(
        Update,
        respawn.run_if(resource_exists_and_changed::<School>),
    )
    // Everything in the tank swims: Bevy's marking of unmoved subtrees would find none
    // and cost 2% of the 10,002 frame (`docs/benchmarks.md`).
    .insert_resource(StaticTransformOptimizations::Disabled);
}

/// The tank's water the schools keep to: its centre and half extents.
pub fn water_box() -> (Vec3, Vec3) {
    let (bottom, top) = (FLOOR, SURFACE - TOP);
    (
        Vec3::new(0.0, 0.5 * (bottom + top), 0.0),
        Vec3::new(HALF_WIDTH - GLASS, 0.5 * (top - bottom), HALF_DEPTH - GLASS),
    )
}

/// One school per species, all in the same water (the plugin keeps members of different
/// schools apart too); the old ones despawn with their members.
fn respawn(
    mut commands: Commands,
    school: Res<School>,
    assets: Res<AssetServer>,
    existing: Query<Entity, With<JellyfishSchool>>,
) {
    for e in &existing {
        commands.entity(e).despawn();
    }
    let (centre, half) = water_box();
    for (k, name) in SPECIES.iter().enumerate() {
        let species: Handle<Species> = assets.load(format!("species/{name}.species.ron"));
        commands.spawn((
            // The library's school: sizes within ±15 %, turning twice as sharply as a lone
            // jellyfish (away from the glass within two or three strokes).
            JellyfishSchool {
                scale: SCALE,
                ..JellyfishSchool::new(species, school.per_species, half)
                    .with_seed(u64::from(school.seed) * 3 + k as u64)
            },
            Transform::from_translation(centre),
        ));
    }
    info!(
        "{} jellyfish: {} of each of {}",
        school.per_species * SPECIES.len(),
        school.per_species,
        SPECIES.join(", ")
    );
}
