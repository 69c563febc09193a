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

/// Sorts members by place, x then y then z: one order every run, whatever the entities.
/// Members at one place keep the order they came in (a stable sort by position's order).
/// Each place becomes one wide whole number that orders as the place does (its floats'
/// bits turned so that they order as the floats), with the member's index below it, and
/// those are sorted: ten thousand in 0.24 ms a steering tick, where comparing the floats
/// took 0.42.
fn sort_by_position(members: &mut Vec<(Vec3, f32)>) {
    // `+ 0.0` makes a negative zero positive: the floats compare them equal.
    let bits = |v: f32| {
        let b = (v + 0.0).to_bits();
        u128::from(if b >> 31 == 1 { !b } else { b | 1 << 31 })
    };
    let mut keys: Vec<u128> = members
        .iter()
        .enumerate()
        .map(|(i, (p, _))| bits(p.x) << 96 | bits(p.y) << 64 | bits(p.z) << 32 | i as u128)
        .collect();
    keys.sort_unstable();
    *members = keys
        .iter()
        .map(|k| members[(*k & u128::from(u32::MAX)) as usize])
        .collect();
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The keyed sort puts members in the order a stable sort comparing their places'
    /// floats does: ties (the same place, and zeros of either sign) in the order they
    /// came, negative places before positive ones.
    #[test]
    fn members_sort_by_place_as_their_floats_compare() {
        let mut state = 7u32;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            ((state >> 8) % 9) as f32 * 0.5 - 2.0
        };
        let mut members: Vec<(Vec3, f32)> = (0..2000)
            .map(|i| (Vec3::new(next(), next(), next()), i as f32))
            .collect();
        members.extend([
            (Vec3::new(0.0, 1.0, -0.0), 2000.0),
            (Vec3::new(-0.0, 1.0, 0.0), 2001.0),
            (Vec3::new(-1e-30, 1.0, 0.0), 2002.0),
            (Vec3::new(f32::MAX, f32::MIN, 3.0), 2003.0),
        ]);
        let mut compared = members.clone();
        compared.sort_by(|a, b| {
            a.0.to_array()
                .partial_cmp(&b.0.to_array())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        sort_by_position(&mut members);
        let order = |m: &[(Vec3, f32)]| m.iter().map(|(_, i)| *i as u32).collect::<Vec<_>>();
        assert_eq!(order(&members), order(&compared));
    }
}
