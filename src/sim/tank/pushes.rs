//! The pushes a tank's water takes: each a ball of velocity, applied in the order it came,
//! over the whole tank or over slabs of its z-planes side by side. A crowded tank takes
//! ten thousand a tick, a few cells each: the cells of a ball's row are pushed four at a
//! time, each exactly as alone.

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
        let mut lanes = Lanes::of(velocity, tank.size.x as usize);
        push_all(tank, first, &mut lanes, pending);
        lanes.write_back(velocity);
    }
}

/// A slab's velocities by component, each row of cells padded by [`LANES`], so that that
/// many cells from anywhere in a row can be read and written together.
struct Lanes {
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
    /// Cells along x.
    cells: usize,
    /// Where one row starts after the last.
    stride: usize,
}

/// Cells a push weighs at once: four lanes of SSE2, as wide as most balls are across.
const LANES: usize = 4;

impl Lanes {
    fn of(velocity: &[Vec3], cells: usize) -> Self {
        let stride = cells + LANES;
        let rows = velocity.len() / cells.max(1);
        let mut lanes = Self {
            x: vec![0.0; rows * stride],
            y: vec![0.0; rows * stride],
            z: vec![0.0; rows * stride],
            cells,
            stride,
        };
        for (r, row) in velocity.chunks_exact(cells.max(1)).enumerate() {
            for (i, v) in row.iter().enumerate() {
                let at = r * stride + i;
                (lanes.x[at], lanes.y[at], lanes.z[at]) = (v.x, v.y, v.z);
            }
        }
        lanes
    }

    fn write_back(&self, velocity: &mut [Vec3]) {
        for (r, row) in velocity.chunks_exact_mut(self.cells.max(1)).enumerate() {
            for (i, v) in row.iter_mut().enumerate() {
                let at = r * self.stride + i;
                *v = Vec3::new(self.x[at], self.y[at], self.z[at]);
            }
        }
    }
}

/// Every push over a slab's lanes, in the order they came. Each cell a push's ball holds
/// takes `v += (u - v)·w`; the cells of a row are weighed [`LANES`] at a time and those
/// outside keep their velocity (a choice per lane, not a branch a ball's edge would
/// mispredict), with the operations of one cell at a time in the same order: the same bits.
fn push_all(tank: Slab, first: i64, lanes: &mut Lanes, pending: &[Impulse]) {
    let s = tank.size.as_i64vec3();
    let last = first + (lanes.x.len() / lanes.stride) as i64 / s.y - 1;
    for imp in pending {
        // The ball in cell-centre units, and the planes, rows and cells that can hold a
        // centre within it: a bound a hundredth of a cell and a thousandth of the radius
        // wide of it, for rounding. Each cell is still checked exactly: such a bound only
        // skips what fails the ball's own test too.
        let at = (imp.at - tank.min) / tank.cell - 0.5;
        let reach = imp.radius / tank.cell * 1.001 + 0.01;
        let span = |c: f32, lo: i64, hi: i64| {
            ceil_to_i64(c - reach).max(lo)..=floor_to_i64(c + reach).min(hi)
        };
        let planes = span(at.z, first, last);
        if planes.is_empty() {
            continue;
        }
        let inverse_squared = 1.0 / (imp.radius * imp.radius);
        let (rows, along) = (span(at.y, 0, s.y - 1), span(at.x, 0, s.x - 1));
        for k in planes {
            for j in rows.clone() {
                let start = ((k - first) * s.y + j) as usize * lanes.stride;
                let across = across(tank.centre(0, j, k) - imp.at);
                let mut i = *along.start();
                while i <= *along.end() {
                    let row = Row {
                        min: tank.min.x,
                        cell: tank.cell,
                        first: i as f32,
                        count: (along.end() - i + 1).min(LANES as i64) as f32,
                        at: imp.at.x,
                        across,
                        inverse_squared,
                        velocity: imp.velocity,
                    };
                    let at = start + i as usize..start + i as usize + LANES;
                    let (x, y, z) = (
                        &mut lanes.x[at.clone()],
                        &mut lanes.y[at.clone()],
                        &mut lanes.z[at],
                    );
                    row.push(x, y, z);
                    i += LANES as i64;
                }
            }
        }
    }
}

/// The squared distance across a row of cells along x, of `offset` from a push's centre:
/// a cell's squared distance is `offset.x² + across`, summed in that order.
#[inline(always)]
fn across(offset: Vec3) -> f32 {
    offset.y * offset.y + offset.z * offset.z
}

/// How strongly a push takes the water at squared distance `d2` from its centre, with
/// `inverse_squared` its inverse squared radius: `(1 - (d/r)²)²`, smooth to nothing at its
/// edge (and meaningless beyond it, where the second value is false). From the squared
/// distance alone, so a cell costs no root and no division. (On x86-64 the lanes of
/// `sse2::push` take the same steps.)
#[cfg(any(test, not(target_arch = "x86_64")))]
#[inline(always)]
fn weigh(d2: f32, inverse_squared: f32) -> (f32, bool) {
    let q = d2 * inverse_squared;
    ((1.0 - q) * (1.0 - q), q < 1.0)
}

/// One push's cells along one row, up to [`LANES`] of them from a first.
struct Row {
    /// The tank's lower x, its cell size, and the row's first cell (a whole number).
    min: f32,
    cell: f32,
    first: f32,
    /// Cells of the row to weigh, from the first.
    count: f32,
    /// The push's centre along x, the squared distance across the row to it, its ball's
    /// inverse squared radius, and the velocity it gives.
    at: f32,
    across: f32,
    inverse_squared: f32,
    velocity: Vec3,
}

impl Row {
    /// Pushes the row's cells, whose velocities by component are `x`, `y`, `z` (at least
    /// [`LANES`] each; those past `count` are left as they are).
    #[inline(always)]
    fn push(&self, x: &mut [f32], y: &mut [f32], z: &mut [f32]) {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: SSE2 is in every x86-64 target's baseline, so it is always enabled.
        unsafe {
            sse2::push(self, x, y, z)
        }
        #[cfg(not(target_arch = "x86_64"))]
        for l in 0..LANES {
            let centre = self.min + (self.first + l as f32 + 0.5) * self.cell;
            let dx = centre - self.at;
            let (w, inside) = weigh(dx * dx + self.across, self.inverse_squared);
            if inside && (l as f32) < self.count {
                x[l] += (self.velocity.x - x[l]) * w;
                y[l] += (self.velocity.y - y[l]) * w;
                z[l] += (self.velocity.z - z[l]) * w;
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod sse2 {
    use super::{LANES, Row};
    use std::arch::x86_64::*;

    /// [`Row::push`] four cells at once: each step is one cell's, lane by lane
    /// (`centre = min + (i + 0.5)·cell`, `q = ((centre - at)² + across)/r²`,
    /// `v += (u - v)·(1 - q)²` where `q < 1`).
    #[target_feature(enable = "sse2")]
    #[inline]
    pub(super) fn push(row: &Row, x: &mut [f32], y: &mut [f32], z: &mut [f32]) {
        assert!(LANES == 4 && x.len() >= 4 && y.len() >= 4 && z.len() >= 4);
        let lane = _mm_set_ps(3.0, 2.0, 1.0, 0.0);
        let i = _mm_add_ps(_mm_set1_ps(row.first), lane);
        let centre = _mm_add_ps(
            _mm_set1_ps(row.min),
            _mm_mul_ps(_mm_add_ps(i, _mm_set1_ps(0.5)), _mm_set1_ps(row.cell)),
        );
        let dx = _mm_sub_ps(centre, _mm_set1_ps(row.at));
        let d2 = _mm_add_ps(_mm_mul_ps(dx, dx), _mm_set1_ps(row.across));
        let q = _mm_mul_ps(d2, _mm_set1_ps(row.inverse_squared));
        let one = _mm_set1_ps(1.0);
        let inside = _mm_and_ps(
            _mm_cmplt_ps(q, one),
            _mm_cmplt_ps(lane, _mm_set1_ps(row.count)),
        );
        let keep = _mm_sub_ps(one, q);
        let w = _mm_mul_ps(keep, keep);
        for (v, u) in [
            (x, row.velocity.x),
            (y, row.velocity.y),
            (z, row.velocity.z),
        ] {
            // SAFETY: four values within the slice (asserted above).
            let old = unsafe { _mm_loadu_ps(v.as_ptr()) };
            let pushed = _mm_add_ps(old, _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(u), old), w));
            let new = _mm_or_ps(_mm_and_ps(inside, pushed), _mm_andnot_ps(inside, old));
            // SAFETY: as the load.
            unsafe { _mm_storeu_ps(v.as_mut_ptr(), new) };
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
                        let off = every.centre(i, j, k) - imp.at;
                        let d2 = off.x * off.x + across(off);
                        let (w, inside) = weigh(d2, 1.0 / (imp.radius * imp.radius));
                        if inside {
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
