//! Who is near whom: a uniform hash grid over the members' places, so that placing and
//! steering a school of thousands asks each member about its few neighbours instead of
//! every other member (a pass over all pairs made 10,000 jellyfish cost a hundred times
//! what 1,000 do). Answers are exact: the same members a pass over all would find.

use bevy::platform::collections::HashMap;
use bevy::prelude::*;

/// Indices of points, bucketed by the cube of side `cell` they fall in.
pub(super) struct Neighbours {
    cell: f32,
    buckets: HashMap<IVec3, Vec<usize>>,
}

/// `cell`, or a unit cube where it is not a usable side.
fn usable(cell: f32) -> f32 {
    if cell.is_finite() && cell > 1e-6 {
        cell
    } else {
        1.0
    }
}

impl Default for Neighbours {
    fn default() -> Self {
        Self::new(1.0)
    }
}

impl Neighbours {
    /// An empty grid of cubes of side `cell` (world units; a typical query's range keeps
    /// a query to a few cubes).
    fn new(cell: f32) -> Self {
        Self {
            cell: usable(cell),
            buckets: HashMap::default(),
        }
    }

    /// A grid of `points` by their index.
    pub(super) fn of(points: &[(Vec3, f32)], cell: f32) -> Self {
        let mut grid = Self::new(cell);
        grid.refill(points, cell);
        grid
    }

    /// Files `points` by their index anew, in cubes of side `cell`, keeping the lists of
    /// the cubes still in use: a school's grid is made again every tick, and ten thousand
    /// pushes into fresh lists were most of the making. Cubes left empty are dropped.
    pub(super) fn refill(&mut self, points: &[(Vec3, f32)], cell: f32) {
        let cell = usable(cell);
        if cell != self.cell {
            self.buckets.clear();
            self.cell = cell;
        }
        self.buckets.values_mut().for_each(Vec::clear);
        for (i, (p, _)) in points.iter().enumerate() {
            self.insert(i, *p);
        }
        self.buckets.retain(|_, indices| !indices.is_empty());
    }

    /// Whether cube `key` can hold a point within `reach` of `p`: its box comes that near
    /// (with a little slack for rounding). The outermost cubes hold every place beyond
    /// them (see `key`), so they always can.
    fn may_hold(&self, key: IVec3, p: Vec3, reach: f32) -> bool {
        if key.abs().max_element() >= 1_000_000 {
            return true;
        }
        let lo = key.as_vec3() * self.cell;
        let hi = lo + Vec3::splat(self.cell);
        let gap = (lo - p).max(p - hi).max(Vec3::ZERO);
        let reach = reach + 1e-3 * self.cell;
        // A place that is not finite is never ruled out.
        let d2 = gap.length_squared();
        d2 <= reach * reach || d2.is_nan()
    }

    fn key(&self, p: Vec3) -> IVec3 {
        // Far-off or non-finite places share the outermost cubes: still found, never lost.
        (p / self.cell)
            .floor()
            .clamp(Vec3::splat(-1e6), Vec3::splat(1e6))
            .as_ivec3()
    }

    /// Files point `index` at `p`.
    pub(super) fn insert(&mut self, index: usize, p: Vec3) {
        let key = self.key(p);
        self.buckets.entry(key).or_default().push(index);
    }

    /// Whether `hit` holds for any index filed within the cube of half-side `range`
    /// around `p` (a superset of those within `range` of it), asking in no particular
    /// order and stopping at the first: placing a member in a crowded box rejects most
    /// places at their first neighbour.
    pub(super) fn any_around(
        &self,
        p: Vec3,
        range: f32,
        mut hit: impl FnMut(usize) -> bool,
    ) -> bool {
        let range = if range.is_finite() {
            range.max(0.0)
        } else {
            0.0
        };
        let lo = self.key(p - Vec3::splat(range));
        let hi = self.key(p + Vec3::splat(range));
        // A range of many cubes is cheaper read bucket by bucket than cube by cube.
        let cubes = (hi - lo + IVec3::ONE).as_i64vec3();
        if cubes.x * cubes.y * cubes.z > self.buckets.len() as i64 {
            return self.buckets.iter().any(|(key, indices)| {
                key.cmpge(lo).all() && key.cmple(hi).all() && indices.iter().any(|i| hit(*i))
            });
        }
        // `p`'s own cube first: in a crowded box most places are ruled out by a neighbour
        // there, and the answer does not depend on the order.
        let own = self.key(p);
        let mut ask = |key: IVec3| {
            self.buckets
                .get(&key)
                .is_some_and(|indices| indices.iter().any(|i| hit(*i)))
        };
        if ask(own) {
            return true;
        }
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    let key = IVec3::new(x, y, z);
                    if key != own && ask(key) {
                        return true;
                    }
                }
            }
        }
        false
    }
}

impl Neighbours {
    /// The `k` nearest of the points `near(i)` accepts, each with the distance it gives
    /// (at most `most`), into `out` by distance, ties by index: what a pass over all of
    /// them, sorted, would keep. Cubes are read shell by shell outwards from `p`'s and
    /// the search stops once no farther cube can hold anything nearer than the `k`-th.
    pub(super) fn nearest(
        &self,
        p: Vec3,
        most: f32,
        k: usize,
        mut near: impl FnMut(usize) -> Option<f32>,
        out: &mut Vec<(f32, usize)>,
    ) {
        out.clear();
        if k == 0 {
            return;
        }
        let most = if most.is_finite() { most.max(0.0) } else { 0.0 };
        let mut offer = |out: &mut Vec<(f32, usize)>, i: usize| {
            if let Some(d) = near(i) {
                let at = out.partition_point(|&(e, j)| (e, j) < (d, i));
                if at < k {
                    out.insert(at, (d, i));
                    out.truncate(k);
                }
            }
        };
        let shells = (most / self.cell).ceil().min(1e6) as i32 + 1;
        let side = 2 * shells as i64 + 1;
        // Many cubes over few buckets (a sparse school) are cheaper read bucket by bucket.
        if side * side * side > 4 * self.buckets.len() as i64 {
            let (lo, hi) = (
                self.key(p - Vec3::splat(most)),
                self.key(p + Vec3::splat(most)),
            );
            for (key, indices) in &self.buckets {
                if key.cmpge(lo).all() && key.cmple(hi).all() {
                    indices.iter().for_each(|i| offer(out, *i));
                }
            }
            return;
        }
        let centre = self.key(p);
        for r in 0..=shells {
            // The nearest a point in shell r can be is r - 1 cubes away.
            let gap = (r - 1).max(0) as f32 * self.cell;
            let full = out.len() == k && out.last().is_some_and(|&(d, _)| gap > d);
            if full || gap > most {
                break;
            }
            for x in -r..=r {
                for y in -r..=r {
                    let rim = x.abs() == r || y.abs() == r;
                    // Inside the shell's rim only its two faces along z.
                    let step = if rim { 1 } else { 2 * r as usize };
                    for z in (-r..=r).step_by(step) {
                        // A cube wholly beyond the reach, or beyond the k-th found, holds
                        // nothing to keep (the shell's corners reach √3 times as far).
                        let key = centre + IVec3::new(x, y, z);
                        let reach = match out.len() == k {
                            true => out.last().map_or(most, |&(d, _)| d.min(most)),
                            false => most,
                        };
                        if !self.may_hold(key, p, reach) {
                            continue;
                        }
                        if let Some(indices) = self.buckets.get(&key) {
                            indices.iter().for_each(|i| offer(out, *i));
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `count` points spread through a box of half-extents `half`, deterministically.
    fn scattered(count: usize, half: Vec3) -> Vec<(Vec3, f32)> {
        (0..count)
            .map(|i| {
                let f = i as f32;
                let unit = Vec3::new((f * 0.37).sin(), (f * 0.71).cos(), (f * 0.13).sin());
                (unit * half, 0.0)
            })
            .collect()
    }

    /// The grid finds exactly the points a pass over all of them finds, for ranges
    /// smaller and larger than its cubes, and for far and non-finite places.
    #[test]
    fn finds_what_a_pass_over_all_finds() {
        let mut points = scattered(400, Vec3::new(9.0, 4.0, 12.0));
        points.push((Vec3::splat(1e12), 0.0));
        points.push((Vec3::new(f32::NAN, 0.0, 0.0), 0.0));
        for cell in [0.3, 1.0, 7.5] {
            let grid = Neighbours::of(&points, cell);
            for range in [0.2, 1.0, 2.5, 40.0] {
                for (p, _) in points.iter().take(60) {
                    let mut found = Vec::new();
                    let any = grid.any_around(*p, range, |i| {
                        if points[i].0.distance(*p) < range {
                            found.push(i);
                        }
                        false
                    });
                    assert!(!any);
                    found.sort_unstable();
                    let all: Vec<usize> = (0..points.len())
                        .filter(|&i| points[i].0.distance(*p) < range)
                        .collect();
                    assert_eq!(found, all, "cell {cell}, range {range}, at {p}");
                }
            }
        }
    }

    /// A grid filled again (from other points, in cubes of the same or another size)
    /// holds what a new one holds: the same points in the same cubes, none left over.
    #[test]
    fn a_refilled_grid_is_a_new_one() {
        let before = scattered(300, Vec3::new(20.0, 2.0, 3.0));
        let points = scattered(500, Vec3::new(4.0, 6.0, 5.0));
        let listed = |grid: &Neighbours| {
            let mut cubes: Vec<(IVec3, Vec<usize>)> =
                grid.buckets.iter().map(|(k, v)| (*k, v.clone())).collect();
            cubes.sort_by_key(|(k, _)| k.to_array());
            cubes
        };
        for (first, then) in [(0.5, 0.5), (2.0, 0.5), (0.5, 3.0)] {
            let mut grid = Neighbours::of(&before, first);
            grid.refill(&points, then);
            assert_eq!(listed(&grid), listed(&Neighbours::of(&points, then)));
        }
    }

    /// The k nearest within reach, as a pass over all sorted by distance then index would
    /// keep them: for dense and sparse grids, k below and above the number within reach,
    /// ties included (points on a lattice).
    #[test]
    fn nearest_are_what_a_sorted_pass_over_all_keeps() {
        let mut points = scattered(600, Vec3::new(5.0, 3.0, 6.0));
        // A lattice: many equal distances.
        points.extend((0..125).map(|i| {
            (
                Vec3::new((i % 5) as f32, ((i / 5) % 5) as f32, (i / 25) as f32) * 0.5,
                0.0,
            )
        }));
        for cell in [0.25, 0.8, 3.0, 40.0] {
            let grid = Neighbours::of(&points, cell);
            for (range, k) in [(0.6, 3), (1.5, 7), (1.5, 1000), (9.0, 7), (0.0, 7)] {
                for (p, _) in points.iter().step_by(11) {
                    let near = |i: usize| {
                        let d = points[i].0.distance(*p);
                        (d > 1e-6 && d < range).then_some(d)
                    };
                    let mut found = Vec::new();
                    grid.nearest(*p, range, k, near, &mut found);
                    let mut all: Vec<(f32, usize)> = (0..points.len())
                        .filter_map(|i| near(i).map(|d| (d, i)))
                        .collect();
                    all.sort_by(|a, b| a.partial_cmp(b).unwrap());
                    all.truncate(k);
                    assert_eq!(found, all, "cell {cell}, range {range}, k {k}, at {p}");
                }
            }
        }
    }
}
