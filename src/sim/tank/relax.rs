//! The tank's pressure: Gauss–Seidel sweeps over its cells, several in flight at once.

use glam::UVec3;

/// Gauss–Seidel sweeps of the pressure solve: the grid is coarse and the water slow, and
/// what is left of the divergence is damped away within a few steps.
pub(super) const PRESSURE_SWEEPS: usize = 20;

/// Gauss–Seidel sweeps towards the pressure whose Laplacian is `div` (cells `h2 = h²`
/// apart; Neumann walls). Each cell's update waits on its neighbour's just before it, so
/// one sweep is a chain of dependent divisions; the sweeps run [`SWEEPS_IN_FLIGHT`] at a
/// time instead, each a plane behind the one before and stepped cell by cell with it, so
/// the processor works on several chains at once. Every cell still sees its neighbours as
/// one sweep after another leaves them: the same pressure, bit for bit.
/// `sweeps` of them (a step takes [`PRESSURE_SWEEPS`], perhaps in two calls: two calls
/// whose first takes a whole number of flights are one call of both counts, bit for bit).
pub(super) fn relax_sweeps(p: &mut [f32], div: &[f32], size: UVec3, h2: f32, sweeps: usize) {
    let [sx, sy, sz] = [size.x, size.y, size.z].map(|n| n as usize);
    let (dy, dz) = (sx, sx * sy);
    let cell = |p: &mut [f32], i: usize, j: usize, k: usize| {
        let idx = (k * sy + j) * sx + i;
        let here = p[idx];
        // Neumann: no pressure gradient through a wall.
        let at = |ok: bool, n: usize| if ok { p[n] } else { here };
        let l = at(i > 0, idx.wrapping_sub(1));
        let r = at(i + 1 < sx, idx + 1);
        let d = at(j > 0, idx.wrapping_sub(dy));
        let u = at(j + 1 < sy, idx + dy);
        let b = at(k > 0, idx.wrapping_sub(dz));
        let f = at(k + 1 < sz, idx + dz);
        p[idx] = (l + r + d + u + b + f - h2 * div[idx]) / 6.0;
    };
    let mut done = 0;
    while done < sweeps {
        let flight = SWEEPS_IN_FLIGHT.min(sweeps - done);
        // Sweep q of the flight is at plane `t - q`: the earlier sweeps lead, and at each
        // cell of a row go first, so a later one reads what they left.
        for t in 0..sz + flight - 1 {
            let planes = (0..flight).filter_map(|q| t.checked_sub(q).filter(|&k| k < sz));
            let (mut ks, mut n) = ([0; SWEEPS_IN_FLIGHT], 0);
            for k in planes {
                ks[n] = k;
                n += 1;
            }
            for j in 0..sy {
                for i in 0..sx {
                    for &k in &ks[..n] {
                        cell(p, i, j, k);
                    }
                }
            }
        }
        done += flight;
    }
}

/// Pressure sweeps [`relax_sweeps`] runs side by side.
pub(super) const SWEEPS_IN_FLIGHT: usize = 4;

/// Visits every cell of a grid of `size` in memory order with its index and its six
/// neighbours' (−x, +x, −y, +y, −z, +z; none past a wall). Inside, the neighbours are
/// plain offsets, found without a test per neighbour.
#[inline(always)]
pub(super) fn for_each_cell(size: UVec3, mut visit: impl FnMut(usize, [Option<usize>; 6])) {
    let [sx, sy, sz] = [size.x, size.y, size.z].map(|n| n as usize);
    let (dy, dz) = (sx, sx * sy);
    for k in 0..sz {
        for j in 0..sy {
            let row = (k * sy + j) * sx;
            let edge = |i: usize| {
                let idx = row + i;
                let step = |ok: bool, n: usize| ok.then_some(n);
                [
                    step(i > 0, idx.wrapping_sub(1)),
                    step(i + 1 < sx, idx + 1),
                    step(j > 0, idx.wrapping_sub(dy)),
                    step(j + 1 < sy, idx + dy),
                    step(k > 0, idx.wrapping_sub(dz)),
                    step(k + 1 < sz, idx + dz),
                ]
            };
            if j == 0 || j + 1 == sy || k == 0 || k + 1 == sz {
                for i in 0..sx {
                    visit(row + i, edge(i));
                }
                continue;
            }
            visit(row, edge(0));
            for idx in row + 1..row + sx - 1 {
                visit(
                    idx,
                    [
                        Some(idx - 1),
                        Some(idx + 1),
                        Some(idx - dy),
                        Some(idx + dy),
                        Some(idx - dz),
                        Some(idx + dz),
                    ],
                );
            }
            visit(row + sx - 1, edge(sx - 1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweeps in flight leave the pressure one sweep after another leaves it, bit for
    /// bit, on grids thinner than the flight too.
    #[test]
    fn sweeps_in_flight_are_the_sweeps_one_after_another() {
        for size in [
            UVec3::new(19, 12, 14),
            UVec3::new(5, 4, 3),
            UVec3::new(3, 3, 1),
        ] {
            let n = (size.x * size.y * size.z) as usize;
            let div: Vec<f32> = (0..n).map(|c| ((c * 7919) % 23) as f32 - 11.0).collect();
            let h2 = 0.75f32 * 0.75;
            let mut flight = vec![0.0; n];
            relax_sweeps(&mut flight, &div, size, h2, PRESSURE_SWEEPS);
            // The same sweeps in two calls, the first of whole flights.
            let mut split = vec![0.0; n];
            relax_sweeps(&mut split, &div, size, h2, 2 * SWEEPS_IN_FLIGHT);
            relax_sweeps(
                &mut split,
                &div,
                size,
                h2,
                PRESSURE_SWEEPS - 2 * SWEEPS_IN_FLIGHT,
            );
            let mut one = vec![0.0f32; n];
            for _ in 0..PRESSURE_SWEEPS {
                for_each_cell(size, |idx, near| {
                    let here = one[idx];
                    let [l, r, d, u, b, f] = near.map(|m| m.map_or(here, |m| one[m]));
                    one[idx] = (l + r + d + u + b + f - h2 * div[idx]) / 6.0;
                });
            }
            assert!(one.iter().any(|p| *p != 0.0));
            let bits = |p: &[f32]| p.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&flight), bits(&one), "grid {size}");
            assert_eq!(bits(&split), bits(&one), "grid {size}, in two calls");
        }
    }
}
