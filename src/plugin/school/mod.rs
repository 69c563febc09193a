//! Schools: [`JellyfishSchool`] spawns many jellyfish of one species in a box, each with its
//! own seed, phase and size, placed apart; it keeps them inside by steering (never by
//! moving them) and apart from every other school's members, and despawns them with it.
//! Members are not transform children: a jellyfish's `Transform` is its world pose.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_jellyfish::plugin::JellyfishSchool;
//! use bevy_jellyfish::JellyfishPlugin;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, JellyfishPlugin::default()))
//!     .add_systems(Startup, |mut commands: Commands, assets: Res<AssetServer>| {
//!         // Forty moon jellies in a box 8 × 6 × 8 units around (0, 4, 0).
//!         let species = assets.load("species/aurelia.species.ron");
//!         commands.spawn((
//!             JellyfishSchool::new(species, 40, Vec3::new(4.0, 3.0, 4.0)),
//!             Transform::from_xyz(0.0, 4.0, 0.0),
//!         ));
//!     })
//!     .run();
//! ```

mod grid;
mod place;
mod steer;

use super::jellyfish::Jellyfish;
use super::schedule::JellyfishSystems;
use super::swimming::Steering;
use crate::species::Species;
use bevy::prelude::*;

/// Spawns, steers and despawns schools.
#[derive(Clone, Copy, Debug, Default)]
pub struct SchoolPlugin;

impl Plugin for SchoolPlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<JellyfishSchool>()
            .register_type::<MemberOf>()
            .register_type::<SchoolMembers>()
            .add_systems(
                PreUpdate,
                place::fill_schools.in_set(JellyfishSystems::Prepare),
            )
            .add_systems(
                FixedUpdate,
                steer::steer_schools.in_set(JellyfishSystems::SteerSchools),
            );
    }
}

/// A school of one species in a box: spawn it with a `Transform` (the box's centre and
/// orientation) and the plugin spawns its members once the species has loaded, 64 a
/// frame (a school of thousands fills in a few frames, none of them long). Changing it
/// spawns the school again.
#[derive(Component, Clone, Debug, Reflect)]
#[reflect(Component)]
#[require(Transform)]
pub struct JellyfishSchool {
    /// The members' species.
    pub species: Handle<Species>,
    /// How many members.
    pub count: usize,
    /// Half the box the school keeps to, along the school's own axes, world units.
    pub half_extents: Vec3,
    /// World units per metre of the species: a member's scale before its size spread.
    pub scale: f32,
    /// Each member is up to this fraction larger or smaller than `scale` makes it.
    pub size_spread: f32,
    /// Places, seeds, phases, sizes and wanders follow from it: the same school every run.
    pub seed: u64,
    /// How sharply members turn (`Steering::agility`): radians per bell diameter surged.
    pub agility: f32,
}

impl JellyfishSchool {
    /// `count` jellyfish of `species` in a box of `half_extents`, at 20 world units per
    /// metre (a 40 mm moon jelly 0.8 units across), sizes within ±15 %.
    pub fn new(species: Handle<Species>, count: usize, half_extents: Vec3) -> Self {
        Self {
            species,
            count,
            half_extents,
            scale: 20.0,
            size_spread: 0.15,
            seed: 1,
            agility: 2.0 * Steering::DEFAULT_AGILITY,
        }
    }

    /// The same school placed and seeded differently.
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
}

/// A member of a school: the school entity.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Reflect)]
#[reflect(Component)]
#[relationship(relationship_target = SchoolMembers)]
pub struct MemberOf(pub Entity);

/// A school's members, kept by Bevy: despawning the school despawns them.
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component)]
#[relationship_target(relationship = MemberOf, linked_spawn)]
pub struct SchoolMembers(Vec<Entity>);

impl SchoolMembers {
    /// The members' entities.
    pub fn entities(&self) -> &[Entity] {
        &self.0
    }
}

/// What a member steers by: its own wander and how far it keeps from others.
#[derive(Component, Clone, Copy, Debug, Default)]
pub(crate) struct Swimmer {
    /// Phases of its slow wander, one per axis.
    wander: Vec3,
    /// How far its bell and fringe reach, world units.
    radius: f32,
    /// Its number in the school: which fixed ticks it steers in ([`steer::STEER_EVERY`]).
    number: u32,
}

/// Members by place, x then y then z: one order every run, whatever the entities.
fn by_position(a: &(Vec3, f32), b: &(Vec3, f32)) -> std::cmp::Ordering {
    a.0.to_array()
        .partial_cmp(&b.0.to_array())
        .unwrap_or(std::cmp::Ordering::Equal)
}

/// One member as spawned: a jellyfish of the school's species placed by `transform`
/// (world), number `number` in its school.
fn member(
    school: Entity,
    spec: &JellyfishSchool,
    transform: Transform,
    radius: f32,
    number: u32,
    rng: &mut place::SplitMix,
) -> impl Bundle {
    (
        Jellyfish::new(spec.species.clone())
            .with_seed(rng.next_u32())
            .with_phase(rng.unit()),
        MemberOf(school),
        Swimmer {
            wander: Vec3::new(rng.unit(), rng.unit(), rng.unit()) * 100.0,
            radius,
            number,
        },
        Steering::heading(transform.rotation * Vec3::Y).with_agility(spec.agility),
        transform,
    )
}
