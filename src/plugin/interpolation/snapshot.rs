//! One slice step as the frames see it: shapes relative to the bell's centroid, the
//! distance swum, the time and the jellyfish's pose.

use crate::plugin::swimming::Pose;
use crate::sim::cycle::{CycleCache, Reach};
use crate::sim::guides::{GUIDE_NODES, THIN_NODES, Trail};
use crate::sim::{SliceSim, SliceView};
use bevy::math::{Vec2, Vec3};
use std::sync::Arc;

/// One step's slice, relative to the bell's centroid so that the box following the bell
/// never shows.
///
/// Laid out for ten thousand far jellyfish, whose histories no cache holds: what a far
/// step writes and a frame reads (its recorded step, time, swim and pose) fills the first
/// cache line, its trail's header the second; the points of a shape of its own follow.
#[derive(Clone, Debug, Default)]
#[repr(C, align(64))]
pub(crate) struct Snapshot {
    /// The recorded cycle and the step of it this shape is, exactly (a far jellyfish's,
    /// not faded into another shape): its points are read from the cycle, not copied, and
    /// far jellyfish showing it share its packed shape.
    pub recorded: Option<(Arc<CycleCache>, u32)>,
    /// Slice time of the state, s.
    pub time: f64,
    pub swim: f32,
    /// Whether the fringe's trail is thinned (`Trail::thin_into`): a far jellyfish's step
    /// keeps only what it draws, a fifth of the trail, and its frames need not thin it
    /// again.
    pub thin_trail: bool,
    /// The jellyfish's pose in the world after the step.
    pub pose: Pose,
    /// The fringe's guide offsets after the step (`TentacleGuides`), body frame: every
    /// node, or as a far jellyfish draws them where `thin_trail` says so; unless `shared`.
    trail: Vec<Vec3>,
    /// The oral tubes' guide offsets after the step, body frame.
    pub oral_trail: Vec<Vec3>,
    /// A far step's thinned trail, shared with its guides and the steps before it (it
    /// changes a few times a second): each step holds it, none copies it.
    shared: Option<Arc<[Vec3]>>,
    /// The shape's own points; not read while it is a `recorded` step, whose points are
    /// the cycle's (kept for the next shape of its own, so a step allocates nothing).
    own: Points,
}

/// A slice's points, relative to the bell's centroid, and the centroid in the slice.
#[derive(Clone, Debug, Default)]
struct Points {
    bell: Vec<Vec2>,
    tentacles: [Vec<Vec2>; 2],
    oral_arms: [Vec<Vec2>; 2],
    centroid: Vec2,
}

/// The points of a shape, wherever they are kept.
#[derive(Clone, Copy)]
pub(crate) struct Shape<'a> {
    pub bell: &'a [Vec2],
    pub tentacles: [&'a [Vec2]; 2],
    pub oral_arms: [&'a [Vec2]; 2],
    pub centroid: Vec2,
}

impl Snapshot {
    /// The shape's points: its own, or its recorded step's.
    pub fn shape(&self) -> Shape<'_> {
        match &self.recorded {
            Some((cycle, index)) => {
                let f = cycle.frame(*index);
                Shape {
                    bell: &f.bell,
                    tentacles: [&f.tentacles[0], &f.tentacles[1]],
                    oral_arms: [&f.oral_arms[0], &f.oral_arms[1]],
                    centroid: f.centroid,
                }
            }
            None => {
                let p = &self.own;
                Shape {
                    bell: &p.bell,
                    tentacles: [&p.tentacles[0], &p.tentacles[1]],
                    oral_arms: [&p.oral_arms[0], &p.oral_arms[1]],
                    centroid: p.centroid,
                }
            }
        }
    }

    /// How far the shape reaches from its centroid: a recorded step's as it was measured
    /// once, when recorded.
    pub fn reach(&self) -> Option<Reach> {
        if let Some((cycle, index)) = &self.recorded {
            return cycle.frame(*index).reach;
        }
        let own = &self.own;
        let chains = own.tentacles.iter().chain(&own.oral_arms).flatten();
        Reach::of(own.bell.iter().chain(chains))
    }

    /// The bell's centroid in the slice, m.
    pub fn centroid(&self) -> Vec2 {
        self.shape().centroid
    }

    pub fn capture(&mut self, sim: &SliceSim) {
        let view = sim.view();
        let c = view.bell.iter().sum::<Vec2>() / view.bell.len() as f32;
        self.recorded = None;
        let own = &mut self.own;
        own.centroid = c;
        own.bell.clear();
        own.bell.extend(view.bell.iter().map(|p| *p - c));
        let chains = view.tentacles.into_iter().chain(view.oral_arms);
        for (out, chain) in own
            .tentacles
            .iter_mut()
            .chain(&mut own.oral_arms)
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
        let (sa, sb, own) = (a.shape(), b.shape(), &mut self.own);
        lerp(&mut own.bell, sa.bell, sb.bell);
        let lerp3 = |out: &mut Vec<Vec3>, a: &[Vec3], b: &[Vec3], alike: bool| {
            out.clear();
            // (A far jellyfish's trail changes every few steps only.)
            if alike && a.len() == b.len() && a != b {
                out.extend(a.iter().zip(b).map(|(a, b)| a.lerp(*b, t)));
            } else {
                out.extend_from_slice(b);
            }
        };
        // A whole trail and a thinned one (at a change of tier) are not alike.
        let alike = a.thin_trail == b.thin_trail;
        let (ta, tb) = (a.fringe_trail().offsets, b.fringe_trail().offsets);
        lerp3(&mut self.trail, ta, tb, alike);
        self.shared = None;
        self.thin_trail = b.thin_trail;
        lerp3(&mut self.oral_trail, &a.oral_trail, &b.oral_trail, true);
        for side in 0..2 {
            lerp(
                &mut own.tentacles[side],
                sa.tentacles[side],
                sb.tentacles[side],
            );
            lerp(
                &mut own.oral_arms[side],
                sa.oral_arms[side],
                sb.oral_arms[side],
            );
        }
        own.centroid = Vec2::ZERO;
        self.recorded = None;
        self.swim = a.swim + t * (b.swim - a.swim);
        self.time = a.time + t as f64 * (b.time - a.time);
        self.pose = a.pose.blend(&b.pose, t);
    }

    /// Step `index` of the recorded `cycle`, at slice time `time` and swim distance
    /// `swim`: its points are the cycle's, not copied.
    pub fn copy_frame(&mut self, cycle: &Arc<CycleCache>, index: u32, time: f64, swim: f32) {
        self.recorded = Some((cycle.clone(), index));
        self.swim = swim;
        self.time = time;
    }

    /// The fringe's and the oral tubes' guide offsets after the step.
    pub fn set_trail(&mut self, fringe: &[Vec3], oral: &[Vec3]) {
        self.trail.clear();
        self.trail.extend_from_slice(fringe);
        self.shared = None;
        self.thin_trail = false;
        self.oral_trail.clear();
        self.oral_trail.extend_from_slice(oral);
    }

    /// The fringe's trail as a far jellyfish draws it (`render::recorded::drawn_view`):
    /// `thin`, already thinned and rounded to halves (`TentacleGuides::thin_trail`), held
    /// not copied (none: no fringe); no oral trail, which a far jellyfish does not draw.
    pub fn set_thin_trail(&mut self, thin: Option<&Arc<[Vec3]>>) {
        match thin {
            // (Mostly the one it holds already: not written again.)
            Some(thin) if self.shared.as_ref().is_some_and(|s| Arc::ptr_eq(s, thin)) => {}
            Some(thin) => self.shared = Some(thin.clone()),
            None => {
                self.trail.clear();
                self.shared = None;
            }
        }
        self.thin_trail = true;
        // (Mostly empty already: not written, so a far step touches one line less.)
        if !self.oral_trail.is_empty() {
            self.oral_trail.clear();
        }
    }

    /// The thinned trail a far step shares with its guides (`set_thin_trail`), if any.
    pub fn shared_trail(&self) -> Option<&Arc<[Vec3]>> {
        self.shared.as_ref()
    }

    /// The fringe's trail as stored.
    pub fn fringe_trail(&self) -> Trail<'_> {
        Trail {
            offsets: self.shared.as_deref().unwrap_or(&self.trail),
            nodes: if self.thin_trail {
                THIN_NODES
            } else {
                GUIDE_NODES
            },
        }
    }

    /// `self += weight · other`, point by point, where the shapes match. A recorded step
    /// changed becomes a shape of its own.
    pub fn add(&mut self, other: &Snapshot, weight: f32) {
        if weight == 0.0 {
            return;
        }
        if self.recorded.is_some() {
            let shape = self.shape();
            let own = Points {
                bell: shape.bell.to_vec(),
                tentacles: shape.tentacles.map(<[Vec2]>::to_vec),
                oral_arms: shape.oral_arms.map(<[Vec2]>::to_vec),
                centroid: shape.centroid,
            };
            self.own = own;
            self.recorded = None;
        }
        let add = |a: &mut Vec<Vec2>, b: &[Vec2]| {
            if a.len() == b.len() {
                a.iter_mut().zip(b).for_each(|(a, b)| *a += weight * *b);
            }
        };
        let (own, other) = (&mut self.own, other.shape());
        add(&mut own.bell, other.bell);
        for side in 0..2 {
            add(&mut own.tentacles[side], other.tentacles[side]);
            add(&mut own.oral_arms[side], other.oral_arms[side]);
        }
    }

    pub fn view<'a>(&'a self, rest_bell: &'a [Vec2]) -> SliceView<'a> {
        let shape = self.shape();
        SliceView {
            bell: shape.bell,
            rest_bell,
            tentacles: shape.tentacles,
            oral_arms: shape.oral_arms,
            trail: self.fringe_trail(),
            oral_trail: Trail::new(&self.oral_trail),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::offset_of;

    #[test]
    fn what_a_far_step_writes_fills_one_cache_line() {
        assert_eq!(align_of::<Snapshot>(), 64);
        let ends = [
            offset_of!(Snapshot, recorded) + size_of::<Option<(Arc<CycleCache>, u32)>>(),
            offset_of!(Snapshot, time) + size_of::<f64>(),
            offset_of!(Snapshot, swim) + size_of::<f32>(),
            offset_of!(Snapshot, thin_trail) + size_of::<bool>(),
            offset_of!(Snapshot, pose) + size_of::<Pose>(),
        ];
        assert!(ends.iter().all(|&end| end <= 64), "{ends:?}");
    }

    #[test]
    fn a_far_step_holds_its_thinned_trail_and_a_whole_one_replaces_it() {
        let thin: Arc<[Vec3]> = Arc::from(vec![Vec3::X; 2 * THIN_NODES]);
        let mut step = Snapshot::default();
        step.set_trail(&[Vec3::Y; GUIDE_NODES], &[Vec3::Z]);
        step.set_thin_trail(Some(&thin));
        let trail = step.fringe_trail();
        assert_eq!((trail.offsets, trail.nodes), (&thin[..], THIN_NODES));
        assert!(step.oral_trail.is_empty(), "a far step draws no oral trail");
        // Blended between two far steps: the trails lerped, and the blend its own.
        let mut other = Snapshot::default();
        let moved: Arc<[Vec3]> = Arc::from(vec![Vec3::NEG_X; 2 * THIN_NODES]);
        other.set_thin_trail(Some(&moved));
        let mut blended = Snapshot::default();
        blended.blend(&step, &other, 0.25);
        let trail = blended.fringe_trail();
        assert_eq!(trail.nodes, THIN_NODES);
        assert!(
            trail.offsets.iter().all(|o| *o == Vec3::X * 0.5),
            "{:?}",
            trail.offsets
        );
        // A whole trail replaces the shared one; no fringe leaves none.
        step.set_trail(&[Vec3::Y; GUIDE_NODES], &[]);
        let trail = step.fringe_trail();
        assert_eq!(
            (trail.offsets, trail.nodes),
            (&[Vec3::Y; GUIDE_NODES][..], GUIDE_NODES)
        );
        step.set_thin_trail(None);
        assert!(step.fringe_trail().offsets.is_empty());
    }
}
