//! The components of one jellyfish. Spawn [`Jellyfish`]; the rest is required by it.

use super::detail::{Replay, Tier};
use super::surface::SurfacePath;
use crate::shape::packed::ShapePacker;
use crate::shape::{JellyMesh, Resolution};
use crate::sim::clock::FixedClock;
use crate::sim::cycle::CycleFrame;
use crate::sim::{SliceSim, SliceView};
use crate::species::Species;
use bevy::math::Vec2;
use bevy::prelude::*;

/// A jellyfish of a species. One line spawns one:
/// `commands.spawn((Jellyfish::new(species), Transform::from_xyz(0.0, 1.0, 0.0)))`.
///
/// It swims along its local +Y axis, scaled by its `Transform::scale` (the mesh is in
/// metres). Rotate it to steer.
#[derive(Component, Clone, Debug, Reflect)]
#[reflect(Component)]
#[require(Transform, Visibility, JellyfishSlice, SwimMotion, JellyfishMeshes)]
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

/// The simulated slice (or, far from the camera, its species' recorded stroke cycle) and
/// its last few fixed steps, which frames blend between.
///
/// Empty until the species asset has loaded.
#[derive(Component, Default, Reflect)]
#[reflect(Component, Default)]
pub struct JellyfishSlice {
    /// The live slice (near and mid tiers).
    #[reflect(ignore)]
    pub(crate) sim: Option<SliceSim>,
    /// The replayed cycle (far tier).
    #[reflect(ignore)]
    pub(crate) replay: Option<Replay>,
    pub(crate) tier: Tier,
    /// The species as simulated: the last valid one it was given.
    pub(crate) species: Species,
    pub(crate) seed: u32,
    #[reflect(ignore)]
    pub(crate) history: SliceHistory,
    /// The bell at rest, which meshes measure contraction against.
    pub(crate) rest_bell: Vec<Vec2>,
    /// Virtual time and the clock's added time at one moment: the clock is set from the
    /// virtual time elapsed since (an exact count of nanoseconds), so frames that split
    /// the same time differently end at the same state. Reset when the clock is replaced.
    #[reflect(ignore)]
    pub(crate) anchor: Option<(std::time::Duration, f64)>,
}

impl JellyfishSlice {
    /// The live slice, once its species has loaded and while it is near or mid (for debug
    /// overlays and tools); `None` while it replays its species' cycle (far).
    pub fn sim(&self) -> Option<&SliceSim> {
        self.sim.as_ref()
    }

    /// The live slice, mutable: for testing recovery (`SliceSim::poison_for_tests`).
    /// Anything changed here is physics, outside the species' calibration.
    #[doc(hidden)]
    pub fn sim_mut_for_tests(&mut self) -> Option<&mut SliceSim> {
        self.sim.as_mut()
    }

    /// Whether it swims yet: its species has loaded and it has a slice or a replay.
    pub fn started(&self) -> bool {
        self.sim.is_some() || self.replay.is_some()
    }

    /// How much of it is simulated (see [`Tier`]).
    pub fn tier(&self) -> Tier {
        self.tier
    }

    /// The species the slice runs with: the last valid one it was given.
    pub fn species(&self) -> Option<&Species> {
        self.started().then_some(&self.species)
    }

    /// Its clock: the live slice's or the replay's.
    pub(crate) fn clock(&self) -> Option<&FixedClock> {
        match (&self.sim, &self.replay) {
            (Some(sim), _) => Some(sim.clock()),
            (None, Some(replay)) => Some(&replay.clock),
            _ => None,
        }
    }

    /// Where it is in its stroke, in cycles [0, 1).
    pub fn phase(&self) -> Option<f32> {
        self.clock().map(FixedClock::phase)
    }

    /// The seed its surface noise was drawn with.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// Swim distance after the last step, m.
    pub fn swim_distance(&self) -> f32 {
        self.history.newest().map_or(0.0, |s| s.swim)
    }

    /// A domain point of the newest step in the mesh's local frame (metres, origin at the
    /// bell's centroid): for overlays drawn over the jellyfish.
    pub fn to_local(&self, p: Vec2) -> Vec3 {
        let centroid = self.history.newest().map_or(Vec2::ZERO, |s| s.centroid);
        (p - centroid).extend(0.0)
    }

    /// The slice time a frame shows, s: the time added to the slice less one step, so
    /// that two stored steps always bracket it and a frame never waits for a step.
    pub fn display_time(&self) -> f64 {
        self.clock().map_or(0.0, |c| c.added() - c.step())
    }

    /// Starts the slice at `pose`, near; its clock's start (the phase offset) picks the
    /// frames it steps on.
    pub(crate) fn start(&mut self, sim: SliceSim, species: Species, seed: u32, pose: Pose) {
        self.history.restart(&sim, pose);
        self.rest_bell = sim.view().rest_bell.to_vec();
        self.sim = Some(sim);
        self.replay = None;
        self.tier = Tier::Near;
        self.anchor = None;
        self.species = species;
        self.seed = seed;
    }
}

/// The last few fixed steps of a slice, oldest first: enough to bracket any time a frame
/// shows ([`JellyfishSlice::display_time`]).
#[derive(Default)]
pub(crate) struct SliceHistory {
    states: std::collections::VecDeque<Snapshot>,
    /// Recycled snapshots, so a step allocates nothing.
    spare: Vec<Snapshot>,
    /// A shape difference left by a change of tier, faded out over the next steps.
    carry: Option<Carry>,
}

/// What the shape was minus what the new tier shows, at the change; added back to the
/// recorded shapes with a weight falling from 1 to 0 over `steps`.
#[derive(Default)]
struct Carry {
    shape: Snapshot,
    left: u32,
    steps: u32,
}

impl SliceHistory {
    /// Keeps this many states: the bracket for a lag of one step, when one frame can hold
    /// several steps.
    fn capacity(clock: &FixedClock, frame: f64) -> usize {
        3 + (frame / clock.step()).ceil().clamp(0.0, 64.0) as usize
    }

    /// Forgets the past: the slice's present state only (a new or rebuilt slice).
    pub fn restart(&mut self, sim: &SliceSim, pose: Pose) {
        self.spare.extend(self.states.drain(..));
        self.carry = None;
        self.record(sim.clock(), 0.0, pose, |s| s.capture(sim));
    }

    /// Records the state after a step (`fill` writes the shape, time and swim distance)
    /// and the jellyfish's pose, dropping what a frame of `frame` seconds can no longer
    /// show.
    pub fn record(
        &mut self,
        clock: &FixedClock,
        frame: f64,
        pose: Pose,
        fill: impl FnOnce(&mut Snapshot),
    ) {
        let mut snapshot = self.spare.pop().unwrap_or_default();
        fill(&mut snapshot);
        snapshot.pose = pose;
        if let Some(carry) = &mut self.carry {
            let weight = carry.left as f32 / carry.steps.max(1) as f32;
            snapshot.add(&carry.shape, weight);
            carry.left = carry.left.saturating_sub(1);
            if carry.left == 0 {
                self.carry = None;
            }
        }
        self.states.push_back(snapshot);
        while self.states.len() > Self::capacity(clock, frame) {
            if let Some(old) = self.states.pop_front() {
                self.spare.push(old);
            }
        }
    }

    /// A change of tier: the new tier's present shape is `now`, at time `time`. The
    /// stored steps are moved to the new clock's time, and the difference between the
    /// newest stored shape and `now` fades out over `steps` steps, so nothing jumps.
    pub fn change_tier(&mut self, now: &Snapshot, time: f64, steps: u32) {
        let Some(newest) = self.states.back() else {
            return;
        };
        let shift = time - newest.time;
        let mut shape = newest.clone();
        shape.add(now, -1.0);
        for s in &mut self.states {
            s.time += shift;
        }
        self.carry = Some(Carry {
            shape,
            left: steps,
            steps,
        });
    }

    pub fn newest(&self) -> Option<&Snapshot> {
        self.states.back()
    }

    /// The two states around time `t` and how far between them it is, in [0, 1]; held at
    /// the ends if `t` is outside the history.
    pub fn bracket(&self, t: f64) -> Option<(&Snapshot, &Snapshot, f32)> {
        let first = self.states.front()?;
        if t <= first.time {
            return Some((first, first, 0.0));
        }
        for (a, b) in self.states.iter().zip(self.states.iter().skip(1)) {
            if t <= b.time {
                let span = (b.time - a.time).max(1e-12);
                return Some((a, b, ((t - a.time) / span) as f32));
            }
        }
        let last = self.states.back()?;
        Some((last, last, 0.0))
    }

    /// The pose at time `t`, blended between the steps around it.
    pub fn pose_at(&self, t: f64) -> Option<Pose> {
        self.bracket(t).map(|(a, b, f)| a.pose.blend(&b.pose, f))
    }

    /// Moves every stored pose as `edit` moves `from` (a game moved or turned the
    /// jellyfish): what the frames show continues from where it was put.
    pub fn move_poses(&mut self, from: Pose, to: Pose) {
        for s in &mut self.states {
            s.pose = s.pose.moved(from, to);
        }
    }
}

/// Where a jellyfish is and which way it points, world.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct Pose {
    /// World position.
    pub position: Vec3,
    /// World rotation: local +Y is the swimming axis.
    pub rotation: Quat,
}

impl Default for Pose {
    fn default() -> Self {
        Self {
            position: Vec3::ZERO,
            rotation: Quat::IDENTITY,
        }
    }
}

impl Pose {
    /// The pose a transform holds.
    pub fn of(transform: &Transform) -> Self {
        Self {
            position: transform.translation,
            rotation: transform.rotation,
        }
    }

    /// Between `self` (t = 0) and `other` (t = 1).
    pub fn blend(&self, other: &Pose, t: f32) -> Pose {
        Pose {
            position: self.position.lerp(other.position, t),
            // Unturned stays bit for bit unturned.
            rotation: if self.rotation == other.rotation {
                self.rotation
            } else {
                self.rotation.slerp(other.rotation, t)
            },
        }
    }

    /// This pose carried along with a rigid move that takes `from` to `to`.
    pub fn moved(&self, from: Pose, to: Pose) -> Pose {
        let turn = to.rotation * from.rotation.inverse();
        Pose {
            position: to.position + turn * (self.position - from.position),
            rotation: (turn * self.rotation).normalize(),
        }
    }
}

/// One step's slice, relative to the bell's centroid so that the box following the bell
/// never shows.
#[derive(Clone, Debug, Default)]
pub(crate) struct Snapshot {
    pub bell: Vec<Vec2>,
    pub tentacles: [Vec<Vec2>; 2],
    pub oral_arms: [Vec<Vec2>; 2],
    pub centroid: Vec2,
    pub swim: f32,
    /// Slice time of the state, s.
    pub time: f64,
    /// The jellyfish's pose in the world after the step.
    pub pose: Pose,
}

impl Snapshot {
    pub fn capture(&mut self, sim: &SliceSim) {
        let view = sim.view();
        let c = view.bell.iter().sum::<Vec2>() / view.bell.len() as f32;
        self.centroid = c;
        self.bell.clear();
        self.bell.extend(view.bell.iter().map(|p| *p - c));
        let chains = view.tentacles.into_iter().chain(view.oral_arms);
        for (out, chain) in self
            .tentacles
            .iter_mut()
            .chain(&mut self.oral_arms)
            .zip(chains)
        {
            out.clear();
            out.extend(chain.iter().map(|p| *p - c));
        }
        self.swim = sim.swim_distance();
        self.time = sim.clock().time();
    }

    /// `self = a + t·(b − a)`, point by point; `b` alone where the shapes differ.
    pub fn blend(&mut self, a: &Snapshot, b: &Snapshot, t: f32) {
        let lerp = |out: &mut Vec<Vec2>, a: &[Vec2], b: &[Vec2]| {
            out.clear();
            if a.len() == b.len() {
                out.extend(a.iter().zip(b).map(|(a, b)| a.lerp(*b, t)));
            } else {
                out.extend_from_slice(b);
            }
        };
        lerp(&mut self.bell, &a.bell, &b.bell);
        for side in 0..2 {
            lerp(
                &mut self.tentacles[side],
                &a.tentacles[side],
                &b.tentacles[side],
            );
            lerp(
                &mut self.oral_arms[side],
                &a.oral_arms[side],
                &b.oral_arms[side],
            );
        }
        self.centroid = Vec2::ZERO;
        self.swim = a.swim + t * (b.swim - a.swim);
        self.time = a.time + t as f64 * (b.time - a.time);
        self.pose = a.pose.blend(&b.pose, t);
    }

    /// The recorded cycle's frame, at slice time `time` and swim distance `swim`.
    pub fn copy_frame(&mut self, frame: &CycleFrame, time: f64, swim: f32) {
        self.bell.clone_from(&frame.bell);
        let chains = frame.tentacles.iter().chain(&frame.oral_arms);
        for (out, chain) in self
            .tentacles
            .iter_mut()
            .chain(&mut self.oral_arms)
            .zip(chains)
        {
            out.clone_from(chain);
        }
        self.centroid = frame.centroid;
        self.swim = swim;
        self.time = time;
    }

    /// `self += weight · other`, point by point, where the shapes match.
    fn add(&mut self, other: &Snapshot, weight: f32) {
        let add = |a: &mut Vec<Vec2>, b: &[Vec2]| {
            if a.len() == b.len() {
                a.iter_mut().zip(b).for_each(|(a, b)| *a += weight * *b);
            }
        };
        add(&mut self.bell, &other.bell);
        for side in 0..2 {
            add(&mut self.tentacles[side], &other.tentacles[side]);
            add(&mut self.oral_arms[side], &other.oral_arms[side]);
        }
    }

    pub fn view<'a>(&'a self, rest_bell: &'a [Vec2]) -> SliceView<'a> {
        SliceView {
            bell: &self.bell,
            rest_bell,
            tentacles: [&self.tentacles[0], &self.tentacles[1]],
            oral_arms: [&self.oral_arms[0], &self.oral_arms[1]],
        }
    }
}

/// How the jellyfish travels: its pose after the newest slice step (the physics; the
/// `Transform` shows it blended between steps) and its ground velocity. Moving or turning
/// the `Transform` yourself moves this with it: travel continues from where it was put.
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct SwimMotion {
    /// Pose after the newest step, world.
    pub pose: Pose,
    /// Ground velocity over the newest step (the water's plus its own swimming), world
    /// units per second.
    pub velocity: Vec3,
    /// Its own swimming along its axis over the steps of the last frame that took any,
    /// world units per second (negative while the bell recoils).
    pub swim_speed: f32,
    /// Swim distance at the newest step, m.
    #[reflect(ignore)]
    pub(crate) swum: f32,
    /// What the plugin last wrote into the `Transform`, to see a game's own edits.
    #[reflect(ignore)]
    pub(crate) written: Option<Transform>,
}

/// A jellyfish with this holds its stroke: it drifts with the water, its bell at rest,
/// and resumes the stroke where it stopped when the component goes.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct Resting;

/// The jellyfish's meshes and what they are built from each frame.
///
/// The umbrella is the jellyfish entity's own `Mesh3d`; all tentacles are one mesh on a
/// child ([`JellyfishTentacles`]). With CPU meshes these are the jellyfish's own assets,
/// rebuilt every frame (despawning frees them); with templates (see
/// [`SurfaceMode`](super::SurfaceMode)) they are shared by every jellyfish of the same
/// resolution and the vertex shader shapes them from the jellyfish's packed shape.
#[derive(Component, Default, Reflect)]
#[reflect(Component, Default)]
pub struct JellyfishMeshes {
    /// The umbrella's mesh, once set up.
    pub umbrella: Option<Handle<Mesh>>,
    /// The tentacles' mesh, once set up.
    pub tentacles: Option<Handle<Mesh>>,
    /// The child entity drawing the tentacles.
    pub tentacle_entity: Option<Entity>,
    /// The child entity drawing the umbrella's glow layer ([`JellyfishGlow`]).
    pub glow_entity: Option<Entity>,
    /// How it is drawn, once set up.
    pub(crate) path: Option<SurfacePath>,
    /// CPU meshes: the buffers the assets are rebuilt from.
    #[reflect(ignore)]
    pub(crate) buffers: JellyMesh,
    /// Templates: the packed shape (`shape::packed`) and the slot it is uploaded to.
    pub(crate) block: Vec<f32>,
    #[reflect(ignore)]
    pub(crate) packer: ShapePacker,
    pub(crate) slot: Option<u32>,
    #[reflect(ignore)]
    pub(crate) blended: Snapshot,
    /// The topology the mesh assets were written with.
    #[reflect(ignore)]
    pub(crate) written: Option<Resolution>,
    /// Buffers hold a frame not yet copied to the assets.
    pub(crate) dirty: bool,
    /// The blended slice's bounds in the mesh's frame (see `culling`).
    pub(crate) bounds: Option<bevy::camera::primitives::Aabb>,
    /// Whether a camera saw it this frame (meshed) or not (skipped).
    pub(crate) seen: bool,
}

impl JellyfishMeshes {
    /// Whether the last frame meshed it: a camera saw it, or there is no camera.
    pub fn seen(&self) -> bool {
        self.seen
    }

    /// How its surfaces are built, once the plugin has set it up.
    pub fn path(&self) -> Option<SurfacePath> {
        self.path
    }
}

/// Marks the child entity holding a jellyfish's tentacle mesh.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct JellyfishTentacles;

/// Marks the child entity that draws the umbrella a second time, additively: the glow
/// layer (see [`glow_material`](crate::plugin::glow_material)). It shares the umbrella's
/// mesh, so it costs a draw, not a mesh.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct JellyfishGlow;
