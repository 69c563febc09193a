//! Who is near whom: a uniform grid over the members' places, so that placing and
//! steering a school of thousands asks each member about its few neighbours instead of
//! every other member (a pass over all pairs made 10,000 jellyfish cost a hundred times
//! what 1,000 do). Answers are exact: the same members a pass over all would find.

use bevy::platform::collections::HashMap;
use bevy::prelude::*;

/// Indices of points, bucketed by the cube of side `cell` they fall in: those filed
/// together ([`Self::refill`]) laid out cube after cube, those filed one at a time
/// ([`Self::insert`]) in a hash map.
pub(super) struct Neighbours {
    cell: f32,
    filed: Filed,
    buckets: HashMap<IVec3, Vec<usize>>,
}

/// A refill's points cube after cube over the box of cubes they span (a counting sort):
/// a steering tick asks each of a thousand members about a hundred cubes, and an index
/// into one array is cheaper than a hashed lookup and a list apart. Empty where the box
/// would be far larger than the points (a few strays far off): those go to the map.
#[derive(Default)]
struct Filed {
    /// The box's lowest cube, and how many cubes it spans along each axis.
    lo: IVec3,
    dims: IVec3,
    /// Where each cube's indices start in `items` (x fastest, then y, then z), and one
    /// past the last.
    starts: Vec<u32>,
    items: Vec<u32>,
    /// Each item's place, beside it: a search rules most out before asking about them.
    places: Vec<Vec3>,
    /// Cubes holding any.
    occupied: usize,
    /// Each point's cube, and where each cube's next index goes: kept between refills.
    keys: Vec<IVec3>,
    next: Vec<u32>,
}

impl Filed {
    /// The indices filed in cube `key`, ascending.
    fn get(&self, key: IVec3) -> &[u32] {
        &self.items[self.span(key)]
    }

    /// Where cube `key`'s indices lie in `items` (and their places in `places`).
    fn span(&self, key: IVec3) -> std::ops::Range<usize> {
        let d = key - self.lo;
        if d.cmplt(IVec3::ZERO).any() || d.cmpge(self.dims).any() {
            return 0..0;
        }
        let c = ((d.z * self.dims.y + d.y) * self.dims.x + d.x) as usize;
        self.starts[c] as usize..self.starts[c + 1] as usize
    }

    /// Every filed cube in the box from `lo` to `hi` (inclusive), with its indices.
    fn within(&self, lo: IVec3, hi: IVec3) -> impl Iterator<Item = (IVec3, &[u32])> {
        let (lo, hi) = (lo.max(self.lo), hi.min(self.lo + self.dims - IVec3::ONE));
        (lo.z..=hi.z).flat_map(move |z| {
            (lo.y..=hi.y).flat_map(move |y| {
                (lo.x..=hi.x).map(move |x| {
                    let key = IVec3::new(x, y, z);
                    (key, self.get(key))
                })
            })
        })
    }

    /// Lays out the points of cubes `keys`, if their box is not far larger than they are;
    /// otherwise leaves itself empty and says so.
    fn lay_out(&mut self, keys: &[IVec3], points: &[(Vec3, f32)]) -> bool {
        (self.lo, self.dims, self.occupied) = (IVec3::ZERO, IVec3::ZERO, 0);
        self.items.clear();
        self.places.clear();
        self.starts.clear();
        let Some(first) = keys.first() else {
            return true;
        };
        let (lo, hi) = keys
            .iter()
            .fold((*first, *first), |(lo, hi), k| (lo.min(*k), hi.max(*k)));
        let dims = (hi - lo + IVec3::ONE).as_i64vec3();
        let cubes = dims.x * dims.y * dims.z;
        if cubes > 4 * keys.len() as i64 + 4096 || keys.len() >= u32::MAX as usize {
            return false;
        }
        (self.lo, self.dims) = (lo, hi - lo + IVec3::ONE);
        let dims = self.dims;
        let cube = |k: IVec3| {
            let d = k - lo;
            ((d.z * dims.y + d.y) * dims.x + d.x) as usize
        };
        // Counted, summed into starts, then each index put in its place, ascending.
        self.starts.resize(cubes as usize + 1, 0);
        for k in keys {
            self.starts[cube(*k) + 1] += 1;
        }
        self.occupied = self.starts.iter().filter(|&&n| n > 0).count();
        for c in 1..self.starts.len() {
            self.starts[c] += self.starts[c - 1];
        }
        self.items.resize(keys.len(), 0);
        self.places.resize(keys.len(), Vec3::ZERO);
        self.next.clear();
        self.next.extend_from_slice(&self.starts[..cubes as usize]);
        for (i, (k, (p, _))) in keys.iter().zip(points).enumerate() {
            let at = &mut self.next[cube(*k)];
            self.items[*at as usize] = i as u32;
            self.places[*at as usize] = *p;
            *at += 1;
        }
        true
    }
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
            filed: Filed::default(),
            buckets: HashMap::default(),
        }
    }

    /// A grid of `points` by their index.
    pub(super) fn of(points: &[(Vec3, f32)], cell: f32) -> Self {
        let mut grid = Self::new(cell);
        grid.refill(points, cell);
        grid
    }

    /// Files `points` by their index anew, in cubes of side `cell`: everything filed
    /// before is forgotten, and the arrays of the last filing are reused (a school's grid
    /// is made again every tick).
    pub(super) fn refill(&mut self, points: &[(Vec3, f32)], cell: f32) {
        self.cell = usable(cell);
        self.buckets.clear();
        let mut keys = std::mem::take(&mut self.filed.keys);
        keys.clear();
        keys.extend(points.iter().map(|(p, _)| self.key(*p)));
        if !self.filed.lay_out(&keys, points) {
            for (i, key) in keys.iter().enumerate() {
                self.buckets.entry(*key).or_default().push(i);
            }
        }
        self.filed.keys = keys;
    }

    /// The indices filed in cube `key`: those laid out, then those filed one at a time.
    fn cube(&self, key: IVec3) -> impl Iterator<Item = usize> + '_ {
        let hashed = match self.buckets.is_empty() {
            true => None,
            false => self.buckets.get(&key),
        };
        let laid = self.filed.get(key).iter().map(|i| *i as usize);
        laid.chain(hashed.into_iter().flatten().copied())
    }

    /// Every cube holding any within the box of cubes from `lo` to `hi`, as
    /// [`Self::cube`] gives them.
    fn cubes_within(&self, lo: IVec3, hi: IVec3) -> impl Iterator<Item = usize> + '_ {
        let laid = self.filed.within(lo, hi).flat_map(|(_, indices)| indices);
        let hashed = self
            .buckets
            .iter()
            .filter(move |(key, _)| key.cmpge(lo).all() && key.cmple(hi).all())
            .flat_map(|(_, indices)| indices);
        laid.map(|i| *i as usize).chain(hashed.copied())
    }

    /// How many cubes hold any.
    fn occupied(&self) -> usize {
        self.filed.occupied + self.buckets.len()
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
        if cubes.x * cubes.y * cubes.z > self.occupied() as i64 {
            return self.cubes_within(lo, hi).any(hit);
        }
        // `p`'s own cube first: in a crowded box most places are ruled out by a neighbour
        // there, and the answer does not depend on the order.
        let own = self.key(p);
        if self.cube(own).any(&mut hit) {
            return true;
        }
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    let key = IVec3::new(x, y, z);
                    if key != own && self.cube(key).any(&mut hit) {
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
    /// (at most `most`, and no less than the point's own from `p`), into `out` by
    /// distance, ties by index: what a pass over all of them, sorted, would keep. Cubes
    /// are read shell by shell outwards from `p`'s and the search stops once no farther
    /// cube can hold anything nearer than the `k`-th; a point laid out farther than that
    /// is not asked about.
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
        if side * side * side > 4 * self.occupied() as i64 {
            let (lo, hi) = (
                self.key(p - Vec3::splat(most)),
                self.key(p + Vec3::splat(most)),
            );
            self.cubes_within(lo, hi).for_each(|i| offer(out, i));
            return;
        }
        let centre = self.key(p);
        let slack = 1e-3 * self.cell;
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
                        // A laid-out point surely beyond `reach` is not asked about: most of
                        // a cube's are, and asking reads the caller's list out of order.
                        let span = self.filed.span(key);
                        let laid = self.filed.items[span.clone()].iter();
                        let beyond = (reach + slack).powi(2);
                        for (i, q) in laid.zip(&self.filed.places[span]) {
                            if q.distance_squared(p) <= beyond {
                                offer(out, *i as usize);
                            }
                        }
                        if !self.buckets.is_empty() {
                            let hashed = self.buckets.get(&key).into_iter().flatten();
                            hashed.for_each(|i| offer(out, *i));
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

    /// The grids of `points` a school makes: all filed at once, and half filed at once
    /// and the rest one at a time (as a fill places them).
    fn grids(points: &[(Vec3, f32)], cell: f32) -> [Neighbours; 2] {
        let half = points.len() / 2;
        let mut mixed = Neighbours::of(&points[..half], cell);
        for (i, (p, _)) in points.iter().enumerate().skip(half) {
            mixed.insert(i, *p);
        }
        [Neighbours::of(points, cell), mixed]
    }

    /// The grid finds exactly the points a pass over all of them finds, for ranges
    /// smaller and larger than its cubes, for points laid out and filed one at a time,
    /// and with far and non-finite places among them (which leave the cubes to the map).
    #[test]
    fn finds_what_a_pass_over_all_finds() {
        let near = scattered(400, Vec3::new(9.0, 4.0, 12.0));
        let mut strays = near.clone();
        strays.push((Vec3::splat(1e12), 0.0));
        strays.push((Vec3::new(f32::NAN, 0.0, 0.0), 0.0));
        for (points, laid_out) in [(&near, true), (&strays, false)] {
            for cell in [0.3, 1.0, 7.5] {
                // Cubes of 0.3 would be 130,000 for 400 points: left to the map too.
                let all_at_once = Neighbours::of(points, cell);
                let laid_out = laid_out && cell > 0.3;
                assert_eq!(all_at_once.buckets.is_empty(), laid_out, "cell {cell}");
                for grid in grids(points, cell) {
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
        }
    }

    /// Every cube holding any, with its indices ascending.
    fn listed(grid: &Neighbours) -> Vec<(IVec3, Vec<usize>)> {
        let f = &grid.filed;
        let laid = f.within(f.lo, f.lo + f.dims - IVec3::ONE);
        let mut cubes: Vec<(IVec3, Vec<usize>)> = laid
            .filter(|(_, v)| !v.is_empty())
            .map(|(k, v)| (k, v.iter().map(|i| *i as usize).collect()))
            .chain(grid.buckets.iter().map(|(k, v)| (*k, v.clone())))
            .collect();
        cubes.sort_by_key(|(k, _)| k.to_array());
        cubes
    }

    /// A grid filled again (from other points, in cubes of the same or another size, laid
    /// out or not) holds what a new one holds: the same points in the same cubes, none
    /// left over, and each point in the cube of its place.
    #[test]
    fn a_refilled_grid_is_a_new_one() {
        let before = scattered(300, Vec3::new(20.0, 2.0, 3.0));
        let points = scattered(500, Vec3::new(4.0, 6.0, 5.0));
        let mut strays = points.clone();
        strays.push((Vec3::splat(-1e9), 0.0));
        for (first, then) in [(0.5, 0.5), (2.0, 0.5), (0.5, 3.0)] {
            for after in [&points, &strays] {
                for start in [&before, &strays] {
                    let mut grid = Neighbours::of(start, first);
                    grid.insert(7, Vec3::ONE);
                    grid.refill(after, then);
                    let cubes = listed(&grid);
                    assert_eq!(cubes, listed(&Neighbours::of(after, then)));
                    assert_eq!(
                        cubes.iter().map(|(_, v)| v.len()).sum::<usize>(),
                        after.len()
                    );
                    for (key, indices) in cubes {
                        assert!(indices.is_sorted());
                        assert!(indices.iter().all(|i| grid.key(after[*i].0) == key));
                    }
                }
            }
        }
    }

    /// The k nearest within reach, as a pass over all sorted by distance then index would
    /// keep them: for dense and sparse grids, laid out, filed one at a time or left to the
    /// map by a stray far off, k below and above the number within reach, ties included
    /// (points on a lattice).
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
        let mut strays = points.clone();
        strays.push((Vec3::new(0.0, 3e8, 0.0), 0.0));
        for points in [&points, &strays] {
            for cell in [0.25, 0.8, 3.0, 40.0] {
                for grid in grids(points, cell) {
                    let cases = [(0.6, 3), (1.5, 7), (1.5, 1000), (9.0, 7), (0.0, 7)];
                    for (range, k) in cases {
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
    }
}
