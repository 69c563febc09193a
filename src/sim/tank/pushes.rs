//! The pushes a tank's water takes: each a ball of velocity, applied in the order it came,
//! over the whole tank or over slabs of its z-planes side by side.

use super::TankFluid;
use glam::{UVec3, Vec3};

/// A push given to the water: within `radius` of `at`, towards `velocity`, smoothly less
/// towards the edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Impulse {
    /// Centre.
    pub at: Vec3,
    /// Reach.
    pub radius: f32,
    /// Velocity given at the centre.
    pub velocity: Vec3,
}

/// What a slab of pushes needs to know of the tank's grid.
#[derive(Clone, Copy, Debug)]
struct Slab {
    min: Vec3,
    cell: f32,
    size: UVec3,
}

impl Slab {
    fn of(tank: &TankFluid) -> Self {
        Self {
            min: tank.min,
            cell: tank.cell,
            size: tank.size,
        }
    }

    fn centre(&self, i: i64, j: i64, k: i64) -> Vec3 {
        self.min + (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * self.cell
    }
}

/// The tank's pending pushes over one slab of its z-planes ([`TankFluid::push_slabs`]).
#[derive(Debug)]
pub struct PushSlab<'a> {
    tank: Slab,
    /// The slab's first z-plane.
    first: i64,
    /// The slab's cells, x fastest, then y, then z.
    velocity: &'a mut [Vec3],
    pending: &'a [Impulse],
}

impl PushSlab<'_> {
    /// Applies every pending push to the slab's cells, in the order they came.
    pub fn apply(self) {
        let Self {
            tank,
            first,
            velocity,
            pending,
        } = self;
        let s = tank.size.as_i64vec3();
        let last = first + (velocity.len() as i64 / (s.x * s.y)) - 1;
        for imp in pending {
            // The ball in cell-centre units, and the planes, rows and cells that can hold a
            // centre within it: a bound a hundredth of a cell and a thousandth of the
            // radius wide of it, for rounding. Each cell is still checked exactly: such a
            // bound only skips what fails `d < 1` too.
            let at = (imp.at - tank.min) / tank.cell - 0.5;
            let reach = imp.radius / tank.cell * 1.001 + 0.01;
            let span = |c: f32, lo: i64, hi: i64| {
                ceil_to_i64(c - reach).max(lo)..=floor_to_i64(c + reach).min(hi)
            };
            let planes = span(at.z, first, last);
            if planes.is_empty() {
                continue;
            }
            // Surely outside (a squared distance beyond it): skipped row by row and then
            // cell by cell before the root.
            let outside = imp.radius * imp.radius * 1.0001;
            let slack = 1e-3 * imp.radius;
            for k in planes {
                for j in span(at.y, 0, s.y - 1) {
                    let off = tank.centre(0, j, k) - imp.at;
                    let across = off.y * off.y + off.z * off.z;
                    if across > outside {
                        continue;
                    }
                    // Only the ball's chord along this row.
                    let half = ((outside - across).sqrt() + slack) / tank.cell + 0.01;
                    let row = (((k - first) * s.y + j) * s.x) as usize;
                    let along =
                        ceil_to_i64(at.x - half).max(0)..=floor_to_i64(at.x + half).min(s.x - 1);
                    for i in along {
                        let centre = tank.centre(i, j, k);
                        if centre.distance_squared(imp.at) > outside {
                            continue;
                        }
                        let d = centre.distance(imp.at) / imp.radius;
                        if d < 1.0 {
                            let w = (1.0 - d * d).powi(2);
                            let v = &mut velocity[row + i as usize];
                            *v += (imp.velocity - *v) * w;
                        }
                    }
                }
            }
        }
    }
}

impl TankFluid {
    /// Applies the pending pushes, in the order they came.
    pub(super) fn push(&mut self) {
        self.push_slabs(1).into_iter().for_each(PushSlab::apply);
        self.pending.clear();
    }

    /// The pending pushes cut into at most `parts` slabs of whole z-planes, to be applied
    /// side by side ([`PushSlab::apply`]) before [`TankFluid::step_pushed`]. A cell lies in
    /// one slab and takes its pushes there in the order they came, so the water is the
    /// same, bit for bit, however many parts it is cut into.
    pub fn push_slabs(&mut self, parts: usize) -> Vec<PushSlab<'_>> {
        let plane = (self.size.x * self.size.y) as usize;
        let planes = self.size.z as usize;
        let per = planes.div_ceil(parts.clamp(1, planes.max(1)));
        let (tank, pending) = (Slab::of(self), &self.pending);
        self.velocity
            .chunks_mut(per * plane)
            .enumerate()
            .map(|(n, velocity)| PushSlab {
                tank,
                first: (n * per) as i64,
                velocity,
                pending,
            })
            .collect()
    }
}

// Floors and ceilings by truncation, the same integers as `floor`/`ceil` and a cast (each
// a library call on x86-64's baseline, without SSE4.1): two for every row a push crosses.

/// `v.floor() as i64`.
fn floor_to_i64(v: f32) -> i64 {
    let t = v as i64;
    if (t as f32) > v {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// `v.ceil() as i64`.
fn ceil_to_i64(v: f32) -> i64 {
    let t = v as i64;
    if (t as f32) < v {
        t.saturating_add(1)
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::tank::tests::{tank, uniform};

    /// The pushes skip what is surely outside each ball, and nothing else: the water is
    /// the same, bit for bit, as from visiting the whole cube around it, for balls of
    /// every size, anywhere (across the walls and outside the tank too).
    #[test]
    fn pushes_reach_exactly_the_cells_in_their_balls() {
        let mut fast = tank();
        let mut every = tank();
        let mut next = uniform(7);
        for n in 0..400 {
            let mut at = Vec3::new(
                next() * 10.0 - 5.0,
                next() * 10.0 - 1.0,
                next() * 10.0 - 5.0,
            );
            let mut radius = 0.05 + 2.5 * next() * next();
            // And balls with a cell centre just inside their edge, along an axis, across a
            // row or through a corner: the bounds that skip cells must not skip it.
            if n >= 300 {
                let centre = (at / fast.cell).floor() * fast.cell + fast.min + 0.5 * fast.cell;
                let towards = [
                    Vec3::X,
                    -Vec3::Y,
                    Vec3::Z,
                    Vec3::new(1.0, -2.0, 0.0),
                    Vec3::ONE,
                ];
                radius = 0.1 + 2.0 * next();
                at = centre + towards[n % 5].normalize() * radius * (1.0 - 1e-4);
            }
            let velocity = Vec3::new(next() - 0.5, next(), next() - 0.5);
            fast.stir(at, radius, velocity);
            every.stir(at, radius, velocity);
        }
        fast.push();
        for imp in std::mem::take(&mut every.pending) {
            let reach = ((imp.radius / every.cell).ceil() as i64 + 1).max(1);
            let c = ((imp.at - every.min) / every.cell).floor().as_ivec3();
            let s = every.size.as_i64vec3();
            for k in c.z as i64 - reach..=c.z as i64 + reach {
                for j in c.y as i64 - reach..=c.y as i64 + reach {
                    for i in c.x as i64 - reach..=c.x as i64 + reach {
                        if i < 0 || j < 0 || k < 0 || i >= s.x || j >= s.y || k >= s.z {
                            continue;
                        }
                        let (i, j, k) = (i as u32, j as u32, k as u32);
                        let d = every.centre(i, j, k).distance(imp.at) / imp.radius;
                        if d < 1.0 {
                            let w = (1.0 - d * d).powi(2);
                            let idx = every.index(i, j, k);
                            let v = &mut every.velocity[idx];
                            *v += (imp.velocity - *v) * w;
                        }
                    }
                }
            }
        }
        let moved = every.velocity.iter().filter(|v| **v != Vec3::ZERO).count();
        assert!(moved > 500, "the pushes reach the water: {moved} cells");
        for (a, b) in fast.velocity.iter().zip(&every.velocity) {
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits)
            );
        }
    }

    /// Cut into slabs of z-planes and applied in any order, the pushes give the water
    /// they give in one piece, bit for bit, and a whole step after them is `step`'s.
    #[test]
    fn pushes_in_slabs_are_the_pushes_in_one_piece() {
        let stirred = || {
            let mut t = tank();
            let mut next = uniform(11);
            for _ in 0..400 {
                let at = Vec3::new(next() * 9.0 - 4.5, next() * 9.0 - 0.5, next() * 9.0 - 4.5);
                let velocity = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
                t.stir(at, 0.1 + 2.0 * next(), velocity);
            }
            t
        };
        let bits = |t: &TankFluid| -> Vec<[u32; 3]> {
            t.velocity
                .iter()
                .map(|v| v.to_array().map(f32::to_bits))
                .collect()
        };
        let mut whole = stirred();
        whole.step(1.0 / 64.0);
        let planes = whole.size.z as usize;
        for parts in [1, 2, 3, 5, planes - 1, planes, planes + 7] {
            let mut cut = stirred();
            let mut slabs = cut.push_slabs(parts);
            assert!(
                slabs.len() <= parts,
                "{} slabs for {parts} parts",
                slabs.len()
            );
            // Last first: no slab leans on another.
            slabs.reverse();
            slabs.into_iter().for_each(PushSlab::apply);
            cut.step_pushed(1.0 / 64.0);
            assert!(cut.pending.is_empty());
            assert!(bits(&cut) == bits(&whole), "{parts} parts differ");
        }
        let moved = whole.velocity.iter().filter(|v| **v != Vec3::ZERO).count();
        assert!(
            moved > whole.velocity.len() / 2,
            "the pushes reach the water: {moved}"
        );
    }

    /// The truncating floors and ceilings are the library's, from far below to far
    /// above, at every quarter near zero and an ulp either side, and at the infinities.
    #[test]
    fn truncated_floors_and_ceilings_are_the_librarys() {
        let mut values = vec![f32::INFINITY, f32::NEG_INFINITY, f32::NAN, 0.0, -0.0];
        for q in -400..=400 {
            let v = q as f32 * 0.25;
            values.extend([v, v.next_up(), v.next_down()]);
        }
        for e in [10, 20, 31, 32, 40, 63, 64, 100] {
            let v = 2f32.powi(e);
            values.extend([
                v,
                -v,
                v.next_up(),
                -v.next_up(),
                v.next_down(),
                -v.next_down(),
            ]);
        }
        for v in values {
            assert_eq!(floor_to_i64(v), v.floor() as i64, "floor of {v}");
            assert_eq!(ceil_to_i64(v), v.ceil() as i64, "ceil of {v}");
        }
    }
}
