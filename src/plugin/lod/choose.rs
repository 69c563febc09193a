//! Which tier each jellyfish should have: ranked by size on screen, within the counts of
//! [`DetailLevels`], with hysteresis.

use crate::plugin::render::JellyfishMeshes;
use crate::plugin::settings::DetailLevels;
use crate::plugin::slice::{JellyfishSlice, Tier};
use bevy::prelude::*;

/// A jellyfish's claim to detail: its size on screen, boosted for the tier it holds.
pub(super) struct Rank {
    pub entity: Entity,
    pub size: f32,
    pub tier: Tier,
}

/// Where sizes on screen are measured from: the first active camera's eye and lens,
/// worked out once a frame rather than for each of ten thousand jellyfish.
#[derive(Clone, Copy)]
pub(super) struct Eye(Option<(Vec3, Lens)>);

impl Eye {
    pub(super) fn of(cameras: &Query<(Entity, &Camera, &GlobalTransform, &Projection)>) -> Self {
        Self(
            cameras
                .iter()
                .filter(|(_, c, ..)| c.is_active)
                .min_by_key(|(e, c, ..)| (c.order, *e))
                .map(|(_, _, eye, projection)| {
                    let lens = match projection {
                        Projection::Perspective(p) => Lens::Perspective((0.5 * p.fov).tan()),
                        Projection::Orthographic(o) => {
                            Lens::Orthographic(o.area.height().max(1e-6))
                        }
                        _ => Lens::Other,
                    };
                    (eye.translation(), lens)
                }),
        )
    }

    /// A started jellyfish's size on screen (none for one not started): infinite without
    /// a camera, nothing where no camera sees it.
    pub(super) fn rank(
        self,
        entity: Entity,
        slice: &JellyfishSlice,
        meshes: Option<&JellyfishMeshes>,
        transform: &GlobalTransform,
    ) -> Option<Rank> {
        if !slice.started() {
            return None;
        }
        let diameter = slice.species.diameter * transform.scale().max_element();
        let unseen = meshes.is_some_and(|m| !m.seen() && m.bounds.is_some());
        let size = match self.0 {
            None => f32::INFINITY,
            Some(_) if unseen => 0.0,
            Some((eye, lens)) => {
                let distance = eye.distance(transform.translation());
                match lens {
                    Lens::Perspective(tan_half) => diameter / (2.0 * distance.max(1e-6) * tan_half),
                    Lens::Orthographic(height) => diameter / height,
                    Lens::Other => 1.0,
                }
            }
        };
        Some(Rank {
            entity,
            size: if size.is_finite() || size == f32::INFINITY {
                size
            } else {
                0.0
            },
            tier: slice.tier,
        })
    }
}

/// What a size on screen is measured through.
#[derive(Clone, Copy)]
enum Lens {
    /// The tangent of half the vertical field of view.
    Perspective(f32),
    /// The height of the view, world units.
    Orthographic(f32),
    Other,
}

/// The jellyfish whose tier should change, with the tier each should have, in
/// [`assign`]'s order: read from the ranks, not looked up again for each jellyfish.
pub(super) fn changes(ranks: Vec<Rank>, levels: &DetailLevels) -> Vec<(Entity, Tier)> {
    assign(ranks, levels)
        .into_iter()
        .filter(|(_, tier, from)| tier != from)
        .map(|(e, tier, _)| (e, tier))
        .collect()
}

/// The tier each jellyfish should have: the `near` largest (with hysteresis) of at least
/// `near_size`, then the `mid` largest of the rest, then far. Near and mid come largest
/// first; of the far, those not far now (the changes) come as the mid tier's claims rank
/// them, the rest in no order.
///
/// Only each tier's budget is put in order, after a selection, and the far changes: ten
/// thousand jellyfish sorted twice a frame, in a serial system, were 1.5% of the 10,002
/// bench's CPU. What is selected and sorted are whole numbers ([`order_key`]), not the
/// ranks with a comparison that worked out both claims each time (1.6% of the frame
/// still). Each comes with the tier it holds now.
fn assign(ranks: Vec<Rank>, levels: &DetailLevels) -> Vec<(Entity, Tier, Tier)> {
    let boost = 1.0 + levels.hysteresis.max(0.0);
    let claim = |r: &Rank, tier: Tier| {
        if r.tier <= tier {
            r.size * boost
        } else {
            r.size
        }
    };
    let key = |i: usize, tier: Tier| order_key(claim(&ranks[i], tier), ranks[i].entity, i);
    let rank = |k: &u128| &ranks[*k as u32 as usize];
    let mut chosen = Vec::with_capacity(ranks.len());
    let mut left: Vec<usize> = (0..ranks.len()).collect();
    for (tier, budget, least) in [
        (Tier::Near, levels.near, levels.near_size),
        (Tier::Mid, levels.mid, levels.mid_size),
    ] {
        let mut keys: Vec<u128> = left.iter().map(|&i| key(i, tier)).collect();
        if budget < keys.len() {
            keys.select_nth_unstable(budget);
            keys[..budget].sort_unstable();
        } else {
            keys.sort_unstable();
        }
        let taken = keys
            .iter()
            .take(budget)
            .take_while(|k| claim(rank(k), tier) >= least)
            .count();
        chosen.extend(
            keys[..taken]
                .iter()
                .map(rank)
                .map(|r| (r.entity, tier, r.tier)),
        );
        left = keys[taken..].iter().map(|k| *k as u32 as usize).collect();
    }
    let mut moved: Vec<u128> = left
        .iter()
        .filter(|&&i| ranks[i].tier != Tier::Far)
        .map(|&i| key(i, Tier::Mid))
        .collect();
    moved.sort_unstable();
    chosen.extend(
        moved
            .iter()
            .map(rank)
            .map(|r| (r.entity, Tier::Far, r.tier)),
    );
    let stay = left
        .iter()
        .map(|&i| &ranks[i])
        .filter(|r| r.tier == Tier::Far);
    chosen.extend(stay.map(|r| (r.entity, Tier::Far, Tier::Far)));
    chosen
}

/// A rank's place in a tier's order as one whole number that orders as the order does:
/// its claim, largest first (the float's bits turned so that they order as `total_cmp`
/// does, then reversed), then its entity, smallest first, and its index below them, to
/// find it again.
fn order_key(claim: f32, entity: Entity, index: usize) -> u128 {
    let b = claim.to_bits();
    let ascending = if b >> 31 == 1 { !b } else { b | 1 << 31 };
    u128::from(!ascending) << 96 | u128::from(entity.to_bits()) << 32 | index as u128
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tier each jellyfish should have ([`assign`]).
    fn choose(ranks: Vec<Rank>, levels: &DetailLevels) -> Vec<(Entity, Tier)> {
        assign(ranks, levels)
            .into_iter()
            .map(|(e, tier, _)| (e, tier))
            .collect()
    }

    fn ranks(sizes: &[(u32, f32, Tier)]) -> Vec<Rank> {
        sizes
            .iter()
            .map(|&(i, size, tier)| Rank {
                entity: Entity::from_raw_u32(i).unwrap(),
                size,
                tier,
            })
            .collect()
    }

    fn tier_of(chosen: &[(Entity, Tier)], i: u32) -> Tier {
        chosen
            .iter()
            .find(|(e, _)| *e == Entity::from_raw_u32(i).unwrap())
            .unwrap()
            .1
    }

    #[test]
    fn the_largest_are_near_within_the_budgets() {
        let levels = DetailLevels {
            near: 2,
            mid: 1,
            hysteresis: 0.0,
            ..default()
        };
        let far = Tier::Far;
        let chosen = choose(
            ranks(&[(1, 0.1, far), (2, 0.5, far), (3, 0.3, far), (4, 0.2, far)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 2), Tier::Near);
        assert_eq!(tier_of(&chosen, 3), Tier::Near);
        assert_eq!(tier_of(&chosen, 4), Tier::Mid);
        assert_eq!(tier_of(&chosen, 1), Tier::Far);
    }

    #[test]
    fn a_tier_is_kept_until_another_clearly_outranks_it() {
        let levels = DetailLevels {
            near: 1,
            mid: 0,
            hysteresis: 0.25,
            ..default()
        };
        // 2 is near; 1 is a little larger, not enough to take its place.
        let chosen = choose(
            ranks(&[(1, 0.11, Tier::Far), (2, 0.1, Tier::Near)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 2), Tier::Near);
        assert_eq!(tier_of(&chosen, 1), Tier::Far);
        // Clearly larger: it takes the place.
        let chosen = choose(
            ranks(&[(1, 0.13, Tier::Far), (2, 0.1, Tier::Near)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 1), Tier::Near);
        assert_eq!(tier_of(&chosen, 2), Tier::Far);
    }

    #[test]
    fn ties_and_sizes_below_the_threshold() {
        let levels = DetailLevels {
            near: 5,
            mid: 5,
            near_size: 0.2,
            mid_size: 0.05,
            hysteresis: 0.0,
            ..default()
        };
        let far = Tier::Far;
        let chosen = choose(
            ranks(&[(7, 0.3, far), (3, 0.3, far), (5, 0.1, far), (6, 0.01, far)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 3), Tier::Near);
        assert_eq!(tier_of(&chosen, 7), Tier::Near);
        assert_eq!(tier_of(&chosen, 5), Tier::Mid);
        assert_eq!(tier_of(&chosen, 6), Tier::Far);
        // The order of the input changes nothing.
        let again = choose(
            ranks(&[(6, 0.01, far), (5, 0.1, far), (3, 0.3, far), (7, 0.3, far)]),
            &levels,
        );
        let mut a = chosen.clone();
        let mut b = again;
        a.sort();
        b.sort();
        assert_eq!(a, b);
    }

    /// The tiers as sorting every rank for each tier chose them: the same tier for each,
    /// and the changes (those whose tier is not what they hold) in the same order, which
    /// decides the promotions a frame allows.
    #[test]
    fn the_tiers_and_their_changes_are_what_sorting_all_chose() {
        fn sorted_all(mut ranks: Vec<Rank>, levels: &DetailLevels) -> Vec<(Entity, Tier)> {
            let boost = 1.0 + levels.hysteresis.max(0.0);
            let mut chosen = Vec::new();
            for (tier, budget, least) in [
                (Tier::Near, levels.near, levels.near_size),
                (Tier::Mid, levels.mid, levels.mid_size),
            ] {
                let claim = |r: &Rank| {
                    if r.tier <= tier {
                        r.size * boost
                    } else {
                        r.size
                    }
                };
                ranks.sort_by(|a, b| claim(b).total_cmp(&claim(a)).then(a.entity.cmp(&b.entity)));
                let taken = ranks
                    .iter()
                    .take(budget)
                    .take_while(|r| claim(r) >= least)
                    .count();
                chosen.extend(ranks.drain(..taken).map(|r| (r.entity, tier)));
            }
            chosen.extend(ranks.into_iter().map(|r| (r.entity, Tier::Far)));
            chosen
        }
        let tiers = [Tier::Near, Tier::Mid, Tier::Far];
        for (count, near, mid) in [
            (0, 3, 2),
            (5, 10, 10),
            (40, 3, 5),
            (300, 20, 7),
            (300, 0, 0),
        ] {
            // Sizes with ties, tiers held at random.
            let input: Vec<(u32, f32, Tier)> = (0..count)
                .map(|i| {
                    let size = ((i * 7919 % 97) / 3) as f32 * 0.01;
                    (i * 31 % 1009, size, tiers[(i * 13 % 7 % 3) as usize])
                })
                .collect();
            let levels = DetailLevels {
                near,
                mid,
                near_size: 0.05,
                mid_size: 0.02,
                hysteresis: 0.25,
                ..default()
            };
            let (a, b) = (
                choose(ranks(&input), &levels),
                sorted_all(ranks(&input), &levels),
            );
            let held = |e: Entity| {
                input
                    .iter()
                    .find(|r| Entity::from_raw_u32(r.0).unwrap() == e)
                    .unwrap()
                    .2
            };
            let changes = |c: &[(Entity, Tier)]| -> Vec<(Entity, Tier)> {
                c.iter().copied().filter(|(e, t)| held(*e) != *t).collect()
            };
            assert_eq!(
                changes(&a),
                changes(&b),
                "{count} ranks, budgets {near}, {mid}"
            );
            // As the levels of detail take them, from the ranks' own tiers.
            assert_eq!(super::changes(ranks(&input), &levels), changes(&b));
            let (mut a, mut b) = (a, b);
            a.sort();
            b.sort();
            assert_eq!(a, b);
        }
    }

    #[test]
    fn the_mid_tier_is_a_compact_box_of_the_same_cells_and_step() {
        use crate::plugin::slice::tier_species;
        use crate::species::Species;
        let species = Species::default();
        let mid = tier_species(&species, Tier::Mid);
        assert!(mid.grid_resolution < species.grid_resolution);
        assert!((mid.cell_size() - species.cell_size()).abs() < 1e-6 * species.cell_size());
        assert_eq!(mid.steps_per_cycle(), species.steps_per_cycle());
        assert_eq!(tier_species(&species, Tier::Far), species);
    }
}
