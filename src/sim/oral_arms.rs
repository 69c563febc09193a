//! The manubrium and the oral arms: two chains hanging from the subumbrellar apex, carried
//! by the slice's water.
//!
//! One-way: they read the water and never push it, so the swimming the bell is calibrated
//! for is exactly the same with or without them (a test holds it bit for bit). Each side of
//! the slice has one chain of [`POINTS`] points a fixed distance apart. A step carries every
//! point with the water around it, as a tracer ([`Fluid::tracer_velocity`]: an arm is
//! neutrally buoyant and light, no inertia of its own), bends it back towards hanging at
//! rest (over [`MANUBRIUM_RELAXATION`] along the stiffer manubrium, over [`ARM_RELAXATION`]
//! along the limp arms), then restores each segment's length from the root down
//! (follow-the-leader). Unconditionally stable and deterministic. The
//! renderer sweeps the pair of chains around the axis, like the tentacles.

use super::fluid::Fluid;
use crate::species::Species;
use glam::Vec2;

/// Points per chain, root to tip.
pub(crate) const POINTS: usize = 16;
/// Time over which a limp arm swings back towards hanging at rest when the water is still,
/// s: long against a stroke, so the pulse's jet and inflow move the arms visibly.
pub(crate) const ARM_RELAXATION: f32 = 0.6;
/// The same for the manubrium, a muscular tube: it sways, but little.
pub(crate) const MANUBRIUM_RELAXATION: f32 = 0.08;
/// The arms' rest direction leans away from the axis by this angle, rad: they hang in a
/// loose cone, as in photographs, rather than in one bundle.
pub(crate) const SPLAY: f32 = 0.3;

/// The two chains and how they hang.
#[derive(Clone, Debug, Default)]
pub(crate) struct OralArms {
    /// Left and right chains; point 0 is the root beside the subumbrellar apex. Empty when
    /// the species has neither manubrium nor arms.
    pub(crate) chains: [Vec<Vec2>; 2],
    /// Distance between neighbouring points, m.
    segment: f32,
    /// The roots' distance from the axis (the manubrium's radius), m.
    root_offset: f32,
    /// Index of the manubrium's last point: points up to it are the stiff stalk.
    stalk: usize,
}

impl OralArms {
    /// Chains hanging at rest from `apex`, with the bell's `axis` pointing from the
    /// aperture to the apex.
    pub(crate) fn new(species: &Species, apex: Vec2, axis: Vec2) -> Self {
        let total = species.manubrium_length + arm_length(species);
        if total <= 0.0 {
            return Self::default();
        }
        let mut arms = Self {
            chains: [vec![Vec2::ZERO; POINTS], vec![Vec2::ZERO; POINTS]],
            segment: total / (POINTS - 1) as f32,
            root_offset: species.manubrium_radius,
            stalk: stalk_index(species),
        };
        for side in 0..2 {
            arms.chains[side][0] = arms.root(side, apex, axis);
            for i in 1..POINTS {
                arms.chains[side][i] =
                    arms.chains[side][i - 1] + arms.segment * arms.rest_direction(side, i, axis);
            }
        }
        arms
    }

    /// One step of `dt` seconds in `fluid`'s water, the bell's apex and axis where they are
    /// now. With `mirror` (the axis line's x), the right chain is the left one's mirror image.
    pub(crate) fn step(
        &mut self,
        fluid: &Fluid,
        apex: Vec2,
        axis: Vec2,
        dt: f32,
        mirror: Option<f32>,
    ) {
        let limp = (dt / ARM_RELAXATION).clamp(0.0, 1.0);
        let stiff = (dt / MANUBRIUM_RELAXATION).clamp(0.0, 1.0);
        let sides = if mirror.is_some() { 1 } else { 2 };
        for side in 0..sides {
            let root = self.root(side, apex, axis);
            let (down, lean) = (
                self.rest_direction(side, 0, axis),
                self.rest_direction(side, POINTS - 1, axis),
            );
            let (segment, stalk) = (self.segment, self.stalk);
            let Some(chain) = self.chains.get_mut(side).filter(|c| !c.is_empty()) else {
                return;
            };
            chain[0] = root;
            for i in 1..POINTS {
                let (rest, stiffness) = if i <= stalk {
                    (down, stiff)
                } else {
                    (lean, limp)
                };
                let carried = chain[i] + dt * fluid.tracer_velocity(chain[i]);
                let hanging = chain[i - 1] + segment * rest;
                let moved = carried + stiffness * (hanging - carried);
                chain[i] = chain[i - 1] + segment * (moved - chain[i - 1]).normalize_or(rest);
            }
        }
        if let Some(centre) = mirror {
            let [left, right] = &mut self.chains;
            for (r, l) in right.iter_mut().zip(left.iter()) {
                *r = Vec2::new(2.0 * centre - l.x, l.y);
            }
        }
    }

    /// Moves every point by `d` (the box shifted under them).
    pub(crate) fn shift(&mut self, d: Vec2) {
        self.chains.iter_mut().flatten().for_each(|p| *p += d);
    }

    /// Whether every point is finite.
    pub(crate) fn is_finite(&self) -> bool {
        self.chains.iter().flatten().all(|p| p.is_finite())
    }

    /// Heap bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.chains.iter().map(|c| c.capacity() * 8).sum()
    }

    fn root(&self, side: usize, apex: Vec2, axis: Vec2) -> Vec2 {
        apex + side_sign(side) * self.root_offset * right_of(axis)
    }

    /// Hanging at rest: straight down the axis along the manubrium, leaning out along the
    /// arms.
    fn rest_direction(&self, side: usize, i: usize, axis: Vec2) -> Vec2 {
        let down = -axis;
        if i <= self.stalk {
            return down;
        }
        let (sin, cos) = SPLAY.sin_cos();
        (cos * down + side_sign(side) * sin * right_of(axis)).normalize_or(down)
    }
}

/// The oral arms' length as the slice carries them: none without arms to carry.
fn arm_length(species: &Species) -> f32 {
    if species.oral_arm_count > 0 {
        species.oral_arm_length
    } else {
        0.0
    }
}

/// Index of the manubrium's last chain point (0 without a manubrium).
fn stalk_index(species: &Species) -> usize {
    let total = species.manubrium_length + arm_length(species);
    if total <= 0.0 {
        return 0;
    }
    ((species.manubrium_length / total * (POINTS - 1) as f32).round() as usize).min(POINTS - 1)
}

/// Where along the chains the manubrium ends and the arms begin, 0 to 1 (the renderer
/// draws the manubrium over `[0, f]` and the arms over `[f, 1]`).
pub(crate) fn stalk_fraction(species: &Species) -> f32 {
    stalk_index(species) as f32 / (POINTS - 1) as f32
}

fn side_sign(side: usize) -> f32 {
    if side == 0 { -1.0 } else { 1.0 }
}

/// The unit vector to the right of `axis` in the slice plane.
fn right_of(axis: Vec2) -> Vec2 {
    Vec2::new(axis.y, -axis.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn still_water() -> Fluid {
        Fluid::new(32, 0.005, 1e-6, 1000.0)
    }

    #[test]
    fn arms_hang_at_rest_with_their_lengths() {
        let s = Species::aurelia();
        let apex = Vec2::new(0.08, 0.1);
        let arms = OralArms::new(&s, apex, Vec2::Y);
        for (side, chain) in arms.chains.iter().enumerate() {
            assert_eq!(chain.len(), POINTS);
            assert!((chain[0].x - apex.x).abs() - s.manubrium_radius < 1e-6);
            let length: f32 = chain.windows(2).map(|w| w[0].distance(w[1])).sum();
            let total = s.manubrium_length + s.oral_arm_length;
            assert!((length - total).abs() < 1e-5, "{side}: {length} vs {total}");
            // Below the apex, the left chain to the left and the right to the right.
            assert!(chain[POINTS - 1].y < apex.y - 0.5 * total);
            assert_eq!(chain[POINTS - 1].x < apex.x, side == 0);
        }
    }

    #[test]
    fn water_carries_the_arms_and_the_segments_keep_their_length() {
        let s = Species::aurelia();
        let apex = Vec2::new(0.08, 0.1);
        let rest = OralArms::new(&s, apex, Vec2::Y);
        let mut arms = rest.clone();
        let mut fluid = still_water();
        // A current from left to right.
        fluid.u.iter_mut().for_each(|u| *u = 0.02);
        let before = arms.chains[0][POINTS - 1];
        for _ in 0..20 {
            arms.step(&fluid, apex, Vec2::Y, 0.02, None);
        }
        let after = arms.chains[0][POINTS - 1];
        assert!(after.x > before.x + 0.002, "{before} -> {after}");
        for (chain, rest) in arms.chains.iter().zip(&rest.chains) {
            for w in chain.windows(2) {
                assert!((w[0].distance(w[1]) - arms.segment).abs() < 1e-6);
            }
            // The manubrium bends less than the arms.
            let moved = |i: usize| chain[i].distance(rest[i]);
            assert!(moved(arms.stalk) < 0.5 * moved(POINTS - 1));
        }
    }

    #[test]
    fn in_still_water_the_arms_stay_hanging() {
        let s = Species::aurelia();
        let apex = Vec2::new(0.08, 0.1);
        let rest = OralArms::new(&s, apex, Vec2::Y);
        let mut arms = rest.clone();
        for _ in 0..100 {
            arms.step(&still_water(), apex, Vec2::Y, 0.02, Some(apex.x));
        }
        for (a, b) in arms
            .chains
            .iter()
            .flatten()
            .zip(rest.chains.iter().flatten())
        {
            assert!(a.distance(*b) < 1e-5, "{a} vs {b}");
        }
    }

    #[test]
    fn no_manubrium_and_no_arms_is_no_chain() {
        let s = Species {
            manubrium_length: 0.0,
            oral_arm_count: 0,
            ..Species::aurelia()
        };
        let mut arms = OralArms::new(&s, Vec2::ZERO, Vec2::Y);
        assert!(arms.chains.iter().all(Vec::is_empty));
        arms.step(&still_water(), Vec2::ZERO, Vec2::Y, 0.02, None);
        assert_eq!(stalk_fraction(&s), 0.0);
        // A manubrium alone is all stalk.
        let stalk = Species {
            oral_arm_count: 0,
            ..Species::aurelia()
        };
        assert_eq!(stalk_fraction(&stalk), 1.0);
    }

    /// One-way: the arms read the water and never push it, so the slice swims exactly as
    /// it does without them; and the stroke's jet and inflow do move them.
    #[test]
    fn arms_never_change_the_swimming_and_the_stroke_moves_them() {
        use crate::sim::SliceSim;
        let with = Species {
            grid_resolution: 40,
            ..Species::aurelia()
        };
        let without = Species {
            manubrium_length: 0.0,
            oral_arm_count: 0,
            ..with.clone()
        };
        let (mut a, mut b) = (
            SliceSim::new(&with).unwrap(),
            SliceSim::new(&without).unwrap(),
        );
        let rest = OralArms::new(&with, Vec2::ZERO, Vec2::Y);
        let rest_tip = rest.chains[1][POINTS - 1] - rest.chains[1][0];
        let (mut swing, mut hang) = (0.0f32, 0.0f32);
        let steps = 3 * a.clock().steps_per_cycle();
        for _ in 0..steps {
            a.step_once();
            b.step_once();
            let view = a.view();
            let arm = view.oral_arms[1];
            swing = swing.max((arm[POINTS - 1] - arm[0]).distance(rest_tip));
            hang += (arm[POINTS - 1] - arm[0]).dot(a.axis()) / rest_tip.length() / steps as f32;
            assert!(arm.iter().all(|p| p.is_finite()));
        }
        // They trail below the apex on the whole (measured: the tip 0.87 of the chain's
        // length down the axis on average, swinging between 0.75 and 0.96).
        assert!(hang < -0.6, "mean hang {hang}");
        assert_eq!(a.swim_distance(), b.swim_distance());
        assert_eq!(a.bell_points(), b.bell_points());
        assert!(b.view().oral_arms[0].is_empty());
        // The tips swing by more than a millimetre but stay within the arm's reach.
        let reach = with.manubrium_length + with.oral_arm_length;
        assert!(swing > 1e-3 && swing < reach, "swing {swing} m");
    }
}
