//! Filling a school: once its species has loaded, members placed apart in its box.

use super::grid::Neighbours;
use super::{JellyfishSchool, MemberOf, SchoolMembers, Swimmer, member};
use crate::species::Species;
use bevy::asset::LoadState;
use bevy::prelude::*;

/// Rejection tries at one spacing before the spacing is relaxed by a tenth.
const TRIES: usize = 300;

/// A small deterministic generator (SplitMix64): the same school from the same seed.
pub(super) struct SplitMix(u64);

impl SplitMix {
    pub(super) fn new(seed: u64) -> Self {
        Self(seed ^ 0x6a09_e667_f3bc_c908)
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    pub(super) fn next_u32(&mut self) -> u32 {
        (self.next() >> 32) as u32
    }

    /// Uniform in [0, 1).
    pub(super) fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f32 {
        2.0 * self.unit() - 1.0
    }
}

/// How far a jellyfish of `species` at `scale` reaches from its centre: its bell and half
/// its longest hanging part (a neighbour's fringe may brush it, not its bell).
pub(super) fn reach(species: &Species, scale: f32) -> f32 {
    let hanging = species.hanging_length();
    scale * (0.5 * species.diameter + 0.5 * hanging)
}

/// At most this many members are placed and spawned in one frame, over all schools: a
/// school of thousands fills over a few frames instead of in one long one (placing a
/// thousand in a full tank took 7 ms of one thread, spawning them as much again). A count,
/// so the same members appear on the same frames in every run; twice the jellyfish that
/// start in a frame (`NEW_SLICES_PER_FRAME`), so starting is never held up by it.
pub(crate) const MEMBERS_PER_FRAME: usize = 64;

/// A school being filled: where its placement stands between frames.
pub(super) struct Filling {
    school: Entity,
    rng: SplitMix,
    /// The spacing factor the last member needed (see [`place`]).
    spacing: f32,
    /// Members placed so far.
    placed: usize,
}

/// Everyone a fill keeps apart from, held between frames while schools fill: where each
/// was when the fills began, and each member placed since, where it was placed. Gathered
/// again only when a school starts (again), so a fill of thousands does not sort every
/// member each frame, and places do not depend on how far the first members swam before
/// the next were placed (which the frame rate decides).
#[derive(Default)]
pub(super) struct Around {
    kept: Vec<(Vec3, f32)>,
    grid: Neighbours,
    /// The widest reach in `kept`.
    widest: f32,
}

/// Fills every school that is new or changed and whose species has loaded (schools due
/// together wait for each other's species), despawning the members it had,
/// [`MEMBERS_PER_FRAME`] members a frame, the lowest school entities first. Places are drawn in the box and kept at least two reaches apart, within the
/// school and from every member of the other schools, where each was when the fill began
/// or was placed ([`Around`]; the spacing relaxed by a tenth after each [`TRIES`]
/// failures, and kept relaxed for the school's next members: a box too full for one is too
/// full for the next).
pub(super) fn fill_schools(
    mut commands: Commands,
    schools: Query<(
        Entity,
        Ref<JellyfishSchool>,
        &Transform,
        Option<&SchoolMembers>,
    )>,
    others: Query<(&Transform, &Swimmer, &MemberOf)>,
    (species, server): (Res<Assets<Species>>, Res<AssetServer>),
    mut waiting: Local<Vec<Entity>>,
    mut filling: Local<Vec<Filling>>,
    mut around: Local<Option<Around>>,
) {
    let mut due: Vec<Entity> = schools
        .iter()
        .filter(|(_, school, ..)| school.is_changed())
        .map(|(e, ..)| e)
        .chain(waiting.drain(..))
        .collect();
    due.sort_unstable();
    due.dedup();
    // A school is placed around those placed before it, so schools that begin together
    // begin together whatever order their species' files happen to load in (that order is
    // the machine's): while any of them is still coming, all of them wait. A species
    // that failed, or was never asked for, holds up none.
    let coming = |school: &JellyfishSchool| {
        !species.contains(&school.species)
            && matches!(
                server.load_state(school.species.id()),
                LoadState::Loading | LoadState::Loaded
            )
    };
    if due
        .iter()
        .any(|&e| schools.get(e).is_ok_and(|(_, school, ..)| coming(&school)))
    {
        waiting.append(&mut due);
    }
    // Schools (re)started now: their old members go, and a fill under way starts over.
    let mut restarted: Vec<Entity> = Vec::new();
    for entity in due {
        let Ok((entity, spec, _, members)) = schools.get(entity) else {
            continue;
        };
        if !species.contains(&spec.species) {
            waiting.push(entity);
            continue;
        }
        if let Some(members) = members {
            for m in members.entities() {
                commands.entity(*m).despawn();
            }
        }
        filling.retain(|f| f.school != entity);
        filling.push(Filling {
            school: entity,
            rng: SplitMix::new(spec.seed),
            spacing: 1.0,
            placed: 0,
        });
        restarted.push(entity);
    }
    filling.retain(|f| schools.contains(f.school));
    if filling.is_empty() {
        *around = None;
        return;
    }
    filling.sort_unstable_by_key(|f| f.school);
    if around.is_none() || !restarted.is_empty() {
        let coming: Vec<Entity> = filling.iter().map(|f| f.school).collect();
        *around = Some(Around::gather(&others, &restarted, |kept| {
            cube_for(kept, &coming, &schools, &species)
        }));
    }
    let Around { kept, grid, widest } = around.get_or_insert_default();
    let mut budget = MEMBERS_PER_FRAME;
    for fill in filling.iter_mut() {
        let Ok((entity, spec, transform, _)) = schools.get(fill.school) else {
            continue;
        };
        let Some(kind) = species.get(&spec.species) else {
            continue;
        };
        let scale = spec.scale.max(1e-6);
        let (rng, spacing) = (&mut fill.rng, &mut fill.spacing);
        let end = spec.count.min(fill.placed + budget);
        for number in fill.placed..end {
            let size = scale * (1.0 + spec.size_spread.clamp(0.0, 0.9) * rng.signed());
            let radius = reach(kind, size);
            let at = place(
                rng,
                spec.half_extents,
                radius,
                transform,
                spacing,
                |p, spacing| {
                    !grid.any_around(p, spacing * (radius + *widest), |i| {
                        let (q, rq) = kept[i];
                        // Too near, or not comparable (a non-finite place is never clear).
                        let (d, apart) = (p.distance(q), spacing * (radius + rq));
                        d < apart || d.is_nan() || apart.is_nan()
                    })
                },
            );
            grid.insert(kept.len(), at);
            kept.push((at, radius));
            *widest = widest.max(radius);
            // Mostly upright in the school's frame, leaning up to ~25 degrees.
            let lean = Quat::from_rotation_y(std::f32::consts::TAU * rng.unit())
                * Quat::from_rotation_x(0.45 * rng.unit());
            let rotation = transform.rotation * lean;
            let placed = Transform::from_translation(at)
                .with_rotation(rotation)
                .with_scale(Vec3::splat(size));
            commands.spawn(member(entity, &spec, placed, radius, number as u32, rng));
        }
        budget -= end.saturating_sub(fill.placed);
        fill.placed = end.max(fill.placed);
        if budget == 0 {
            break;
        }
    }
    filling.retain(|f| {
        schools
            .get(f.school)
            .is_ok_and(|(_, spec, ..)| f.placed < spec.count)
    });
}

impl Around {
    /// Everyone who stays: members of the schools not started again (those of a school
    /// still filling included), in a grid of cubes of `cube(kept)` to find the near ones:
    /// a school of thousands is placed in milliseconds, not in minutes.
    fn gather(
        others: &Query<(&Transform, &Swimmer, &MemberOf)>,
        restarted: &[Entity],
        cube: impl FnOnce(&[(Vec3, f32)]) -> f32,
    ) -> Self {
        let mut kept: Vec<(Vec3, f32)> = others
            .iter()
            .filter(|(.., of)| !restarted.contains(&of.0))
            .map(|(t, s, _)| (t.translation, s.radius))
            .collect();
        super::sort_by_position(&mut kept);
        let grid = Neighbours::of(&kept, cube(&kept));
        let widest = kept.iter().fold(0.0f32, |r, (_, rq)| r.max(*rq));
        Self { kept, grid, widest }
    }
}

/// The grid's cube: twice the widest reach of anyone kept or about to be placed, so that
/// a query looks at the cubes next to its own.
fn cube_for(
    kept: &[(Vec3, f32)],
    coming: &[Entity],
    schools: &Query<(
        Entity,
        Ref<JellyfishSchool>,
        &Transform,
        Option<&SchoolMembers>,
    )>,
    species: &Assets<Species>,
) -> f32 {
    let coming = coming.iter().filter_map(|e| {
        let (_, spec, ..) = schools.get(*e).ok()?;
        let largest = spec.scale.max(1e-6) * (1.0 + spec.size_spread.clamp(0.0, 0.9));
        Some(reach(species.get(&spec.species)?, largest))
    });
    2.0 * kept
        .iter()
        .map(|(_, r)| *r)
        .chain(coming)
        .fold(0.0, f32::max)
}

/// A world point in the school's box (its centre and orientation the school's; its scale
/// not used), at least a reach from its walls, where `clear` holds at a spacing factor
/// (from `spacing`, relaxed by a tenth after each [`TRIES`] failures and left where it
/// succeeded).
fn place(
    rng: &mut SplitMix,
    half: Vec3,
    radius: f32,
    school: &Transform,
    spacing: &mut f32,
    clear: impl Fn(Vec3, f32) -> bool,
) -> Vec3 {
    let inner = (half - Vec3::splat(radius)).max(0.1 * half.abs());
    loop {
        for _ in 0..TRIES {
            let local = Vec3::new(rng.signed(), rng.signed(), rng.signed()) * inner;
            let at = school.translation + school.rotation * local;
            if clear(at, *spacing) {
                return at;
            }
        }
        *spacing *= 0.9;
        if *spacing < 1e-3 {
            *spacing = 1e-3;
            return school.translation;
        }
    }
}
