//! [`Jellyfish`]: the one component a game spawns. Each part of the plugin registers what
//! it needs on a jellyfish as a component `Jellyfish` requires, so a part left out of
//! [`JellyfishPlugins`](super::JellyfishPlugins) adds nothing to it.

use crate::species::Species;
use bevy::prelude::*;

/// A jellyfish of a species. One line spawns one:
/// `commands.spawn((Jellyfish::new(species), Transform::from_xyz(0.0, 1.0, 0.0)))`.
///
/// It swims along its local +Y axis, scaled by its `Transform::scale` (the mesh is in
/// metres). Rotate it to steer.
#[derive(Component, Clone, Debug, Reflect)]
#[reflect(Component)]
#[require(Transform, Visibility)]
pub struct Jellyfish {
    /// Its species: a loaded file or a `Species` added to `Assets<Species>`.
    pub species: Handle<Species>,
    /// Picks the individual's surface noise; `None` derives one from the entity.
    pub seed: Option<u32>,
    /// Where in its stroke it starts, in cycles [0, 1); `None` derives one from the seed,
    /// so a school spawned together does not beat in unison.
    pub phase: Option<f32>,
}

impl Jellyfish {
    /// A jellyfish of `species`, its seed and phase derived from the entity.
    pub fn new(species: Handle<Species>) -> Self {
        Self {
            species,
            seed: None,
            phase: None,
        }
    }

    /// Picks its surface noise (two with one seed look alike).
    pub fn with_seed(mut self, seed: u32) -> Self {
        self.seed = Some(seed);
        self
    }

    /// Starts it at `phase` of its stroke, in cycles [0, 1).
    pub fn with_phase(mut self, phase: f32) -> Self {
        self.phase = Some(phase);
        self
    }

    /// The seed, explicit or derived from the entity (stable within an app).
    pub fn seed_for(&self, entity: Entity) -> u32 {
        self.seed.unwrap_or_else(|| hash(entity.index_u32()))
    }

    /// The phase, explicit or derived from the seed.
    pub fn phase_for(&self, seed: u32) -> f32 {
        self.phase
            .unwrap_or_else(|| hash(seed ^ 0x9e37_79b9) as f32 / u32::MAX as f32)
            .rem_euclid(1.0)
    }
}

/// Lets systems filter on `AssetChanged<Jellyfish>`: its species asset changed.
impl bevy::asset::AsAssetId for Jellyfish {
    type Asset = Species;

    fn as_asset_id(&self) -> AssetId<Species> {
        self.species.id()
    }
}

/// A small integer hash (lowbias32), so neighbouring entities get unrelated seeds.
fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}
