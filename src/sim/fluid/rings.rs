//! The axisymmetric slice (r–z, no swirl): the same MAC grid, read as a meridian
//! half-plane of a body of revolution mirrored about its axis.
//!
//! The axis runs through the centre of the middle column of cells (as the planar slice's
//! mirror line does), so that column's cells are discs of radius h/2 and the others
//! annuli; `u` faces sit at r = h/2, 3h/2, … The mirrored half stays in the grid, so
//! advection traces across the axis by reading it (semi-Lagrangian tracing reflected at
//! the axis), and everything that reads the planar slice reads this one. Each field is
//! solved on the half from the left wall to the axis and mirrored (`u` odd, `v` even), so
//! no radial velocity crosses the axis and the axial velocity is even there.
//!
//! What changes from the plane (`docs/numerics.md`, "The axisymmetric slice"):
//! - volumes are weighted by r: a cell's divergence is `(r₊u₊ − r₋u₋)/(r·h) + ∂v/∂z`,
//!   each ring's weight r its volume per radian over h² (the mirrored grid holds every
//!   annulus twice and the axis disc once, so the disc weighs twice its h/8: h/4);
//! - the pressure equation is the same r-weighted operator, solved exactly
//!   ([`RingPoissonSolver`]);
//! - viscosity carries the hoop term: `∇²u − u/r² = ∂/∂r((1/r)∂(ru)/∂r) + ∂²u/∂z²`, the
//!   radial gradient of the same r-weighted divergence, exact for solid-body expansion
//!   u ∝ r; `v` diffuses by the r-weighted Laplacian;
//! - a point of the bell is a ring: its force (per radian) spreads onto each face over the
//!   face's volume per radian `r·h²`, so the total force is exact and spreading is the
//!   adjoint of interpolation in the r-weighted inner product.
//!
//! A planar slice held mirror-symmetric is solved on the same half with every weight 1
//! ([`Rings::mirrored_plane`]): the plane's divergence, viscosity and pressure, the axis
//! a mirror.

use super::Fluid;
use super::symmetry::{mirror_u_row, mirror_v_row};
use crate::sim::pressure::{Across, RingPoissonSolver};

/// The radii of an axisymmetric slice's faces and cells, and its pressure solve (every
/// radius 1 for a planar slice's mirrored half).
#[derive(Clone)]
pub(crate) struct Rings {
    /// |x − axis| of each column of `u` faces, m (`n + 1`).
    pub(crate) face: Vec<f32>,
    /// |x − axis| of each column of cells, m (`n`); the axis column's h/4, the disc's
    /// area over its circumference: a cell's volume per radian is `cell · h²`.
    pub(crate) cell: Vec<f32>,
    /// `1 / cell`, for the loops (a multiply where a divide costs several).
    inverse_cell: Vec<f32>,
    /// Columns solved: from the left wall to the axis column, `n/2 + 1`.
    pub(crate) solved: usize,
    /// Where the axis is, m from the left wall; the span a point is held within for the
    /// test, half a cell inside the walls (a stencil is located inside the box, so this
    /// only brings a point past a wall nearer the axis); and the least radius of a
    /// wall's faces or cells: what [`Rings::within_reach_of_axis`] reads.
    axis: f32,
    located: (f32, f32),
    wall: f32,
    /// A no-slip outer wall for the viscous term (a pipe: test set-ups only; the slice's
    /// wall is free-slip, as the plane's are).
    pub(crate) no_slip_wall: bool,
    /// The operator across: r-weighted rings, or the plane's mirrored half.
    across_operator: Across,
    solver: RingPoissonSolver,
    /// φ row by row across the radius, the wall first (the projection's work space).
    across: Vec<f32>,
    /// One row of the viscous sweep's fluxes (its work space).
    flux: Vec<f32>,
}

/// Largest `ν·dt/h²` of one explicit sweep of the r–z viscous operator: its stiffest mode,
/// the first `u` face off the axis (hoop term included), is about 13/h², so 0.1 keeps a
/// sweep stable where the plane's 0.2 would not.
pub(crate) const RINGS_SWEEP_LIMIT: f32 = 0.1;

impl Rings {
    /// The radii for `n` cells of size `h` about the centre of column `n/2`.
    pub(crate) fn new(n: usize, h: f32) -> Self {
        let c = n / 2;
        let face: Vec<f32> = (0..=n)
            .map(|i| (i as f32 - c as f32 - 0.5).abs() * h)
            .collect();
        let cell: Vec<f32> = (0..n)
            .map(|i| {
                if i == c {
                    0.25 * h
                } else {
                    (i as f32 - c as f32).abs() * h
                }
            })
            .collect();
        let wall = [face[0], face[n], cell[0], cell[n - 1]]
            .into_iter()
            .fold(f32::MAX, f32::min);
        Self {
            face,
            inverse_cell: cell.iter().map(|r| 1.0 / r).collect(),
            cell,
            solved: c + 1,
            axis: (c as f32 + 0.5) * h,
            located: (0.5 * h, (n as f32 - 0.5) * h),
            wall,
            no_slip_wall: false,
            across_operator: Across::Rings,
            solver: RingPoissonSolver::new(c + 1, n, h),
            across: vec![0.0; (c + 1) * n],
            flux: vec![0.0; c + 1],
        }
    }

    /// The half of a planar slice held mirror-symmetric about the centre of column `n/2`:
    /// every weight 1, so the same passes are the plane's operators. On an even grid the
    /// mirrored half is a box one cell wider than the grid: the image of its wall lies a
    /// column past the grid's (whose faces just inside it hold the mirror images all the
    /// same; nothing the step reads lies there).
    pub(crate) fn mirrored_plane(n: usize, h: f32) -> Self {
        let c = n / 2;
        Self {
            face: vec![1.0; n + 1],
            cell: vec![1.0; n],
            inverse_cell: vec![1.0; n],
            solved: c + 1,
            axis: (c as f32 + 0.5) * h,
            located: (0.5 * h, (n as f32 - 0.5) * h),
            wall: 1.0,
            no_slip_wall: false,
            across_operator: Across::MirroredPlane,
            solver: RingPoissonSolver::across(Across::MirroredPlane, c + 1, n, h),
            across: vec![0.0; (c + 1) * n],
            flux: vec![0.0; c + 1],
        }
    }

    /// Whether a stencil of a point `x` (m from the left wall) may reach a face within
    /// `reach` (m) of the axis, so that [`Self::weigh_by_volume_near_axis`] could change
    /// it: its taps lie within `reach` of `x` (held inside the box, as the stencil's
    /// position is), so none does from `2·reach` or further out, unless the box itself is
    /// narrower than that. A cheap test first, for the points far from the axis.
    #[inline]
    pub(crate) fn within_reach_of_axis(&self, x: f32, reach: f32) -> bool {
        let x = x.clamp(self.located.0, self.located.1);
        (x - self.axis).abs() < 2.0 * reach || self.wall < reach
    }

    /// Weighs the taps of a stencil of component `c` that fall within `reach` (m) of the
    /// axis by their faces' volume, not their rings': a share `r / reach` each, the
    /// stencil renormalised (`Stencil::reweigh_across`). A ring spread over faces of
    /// volume `r·h²` puts a force density ∝ 1/r on the faces nearest the axis; water
    /// answers such a force with an axial jet as narrow as the grid's first column, one
    /// that grew without bound as the grid was refined (the paper's model in r–z: 0.07,
    /// 0.27 and 0.57 m/s at 10, 20 and 30 cells a diameter, where its margin closes at
    /// 0.03). Weighed by volume there, a ring on the axis is a point spread by the
    /// kernel in three dimensions, smooth across the axis; a ring `2·reach` or further
    /// out is untouched. Kept out of line: only the stencils near the axis call it, and
    /// inlined it would sit in `Fluid::locate`'s loop over every point.
    #[inline(never)]
    pub(crate) fn weigh_by_volume_near_axis(
        &self,
        c: super::Component,
        stencil: &mut crate::sim::kernel::Stencil,
        reach: f32,
    ) {
        let radii = match c {
            super::Component::U => &self.face,
            super::Component::V => &self.cell,
        };
        // The radii fall towards the axis column (`solved − 1`) from either side: the
        // stencil's nearest column to it is its nearest to the axis.
        let (columns, axis) = (stencil.columns(), self.solved - 1);
        let nearest = axis.clamp(columns.start, columns.end.saturating_sub(1));
        if radii.get(nearest).is_none_or(|&r| r >= reach) {
            return;
        }
        stencil.reweigh_across(|column| (radii[column] / reach).min(1.0));
    }

    /// Whether these are an axisymmetric slice's rings (not a planar half).
    pub(crate) fn axisymmetric(&self) -> bool {
        self.across_operator == Across::Rings
    }

    /// Heap bytes.
    pub(crate) fn bytes(&self) -> usize {
        let rows = self.face.len() + self.cell.len() + self.inverse_cell.len();
        (rows + self.across.len() + self.flux.len()) * 4 + self.solver.bytes()
    }
}

impl Fluid {
    /// The rings, if this slice is axisymmetric.
    pub(crate) fn rings(&self) -> Option<&Rings> {
        self.rings.as_deref()
    }

    /// The half this slice is solved on: an axisymmetric slice's rings, or a planar
    /// slice's mirrored half while it is held mirror-symmetric in the channel; `None` for
    /// a planar slice free to tilt, or a closed test box.
    pub(crate) fn half(&self) -> Option<&Rings> {
        if self.rings.is_some() {
            self.rings.as_deref()
        } else if self.mirror && !self.walls.is_closed() {
            self.plane_half.as_deref()
        } else {
            None
        }
    }

    /// [`Fluid::half`], taken out for a pass that also borrows the fields (give it back
    /// with [`Fluid::put_half`]).
    pub(super) fn take_half(&mut self) -> Option<Box<Rings>> {
        self.half()?;
        self.rings.take().or_else(|| self.plane_half.take())
    }

    /// Puts back what [`Fluid::take_half`] took.
    pub(super) fn put_half(&mut self, half: Box<Rings>) {
        if half.axisymmetric() {
            self.rings = Some(half);
        } else {
            self.plane_half = Some(half);
        }
    }

    /// The r-weighted divergence of cell `(i, j)`, 1/s.
    pub(super) fn ring_divergence(&self, rings: &Rings, i: usize, j: usize) -> f32 {
        let (n, h) = (self.n, self.h);
        let (u, r) = (&self.u[j * (n + 1)..][..n + 1], &rings.face);
        let radial = (r[i + 1] * u[i + 1] - r[i] * u[i]) / (rings.cell[i] * h);
        radial + (self.v[(j + 1) * n + i] - self.v[j * n + i]) / h
    }

    /// The projection of a mirror-symmetric slice: the (r-weighted) divergence of the
    /// solved half, the exact solve, its gradient subtracted, the half mirrored. Its
    /// loops run eight wide where the processor has AVX.
    pub(super) fn project_half(&mut self, rings: &mut Rings) {
        let fluid = self;
        eight_wide!(Fluid::project_half_passes, (fluid: &mut Fluid, rings: &mut Rings))
    }

    /// [`Self::project_half`]'s passes, inlined into each of its callers' codegen.
    #[inline(always)]
    fn project_half_passes(&mut self, rings: &mut Rings) {
        let (n, c) = (self.n, rings.solved - 1);
        let inverse_h = 1.0 / self.h;
        let (r, inverse) = (&rings.face[..c + 2], &rings.inverse_cell[..c + 1]);
        // The divergence row by row (`across`: row j, ring k at c − k); the solve reads
        // and writes each ring's column of it along the axis.
        let across = &mut rings.across;
        for (j, row) in across.chunks_exact_mut(c + 1).enumerate() {
            let u = &self.u[j * (n + 1)..][..c + 2];
            let (v0, v1) = (&self.v[j * n..][..c + 1], &self.v[(j + 1) * n..][..c + 1]);
            // Zipped slices of one length, so that it vectorises (each cell as written).
            let (outer, inner) = (r[1..].iter().zip(&u[1..]), r.iter().zip(u));
            let axial = v1.iter().zip(v0);
            for ((d, ((ro, uo), (ri, ui))), (inv, (v1, v0))) in row
                .iter_mut()
                .zip(outer.zip(inner))
                .zip(inverse.iter().zip(axial))
            {
                let radial = (ro * uo - ri * ui) * inv;
                *d = (radial + (v1 - v0)) * inverse_h;
            }
        }
        rings
            .solver
            .solve_across(across, &mut self.phi[..(c + 1) * n]);
        for j in 0..n {
            let phi = &across[j * (c + 1)..][..c + 1];
            let u = &mut self.u[j * (n + 1)..][..c + 1];
            for (u, (p1, p0)) in u[1..].iter_mut().zip(phi[1..].iter().zip(&phi[..c])) {
                *u -= (p1 - p0) * inverse_h;
            }
            let v = &mut self.v[j * n..][..c + 1];
            if j == 0 {
                // The open wake end: φ = 0 on its face; the inflow keeps the stream.
                for (v, p) in v.iter_mut().zip(phi) {
                    *v -= 2.0 * p * inverse_h;
                }
            } else {
                let below = &across[(j - 1) * (c + 1)..][..c + 1];
                for ((v, p), q) in v.iter_mut().zip(phi).zip(below) {
                    *v -= (p - q) * inverse_h;
                }
            }
            // Mirrored while the rows are at hand (what `symmetry::mirror` would write).
            mirror_u_row(&mut self.u[j * (n + 1)..][..n + 1]);
            mirror_v_row(&mut self.v[j * n..][..n]);
        }
        // The inflow's row, which the projection leaves as it is.
        mirror_v_row(&mut self.v[n * n..][..n]);
    }

    /// One explicit sweep of the r–z viscous operator, `a = ν·dt/h²`, on the solved half:
    /// `u` by the radial gradient of its r-weighted divergence (the hoop term included),
    /// `v` by the r-weighted Laplacian; free slip at the outer wall, zero gradient at the
    /// open ends, as in the plane. Only the faces just past the axis are mirrored after
    /// it (the next sweep reads them); the projection mirrors the rest. Eight wide where
    /// the processor has AVX.
    pub(super) fn ring_viscosity_sweep(&mut self, rings: &mut Rings, a: f32) {
        let fluid = self;
        eight_wide!(
            Fluid::ring_viscosity_passes,
            (fluid: &mut Fluid, rings: &mut Rings, a: f32)
        )
    }

    /// [`Self::ring_viscosity_sweep`]'s passes, inlined into each of its callers' codegen.
    #[inline(always)]
    fn ring_viscosity_passes(&mut self, rings: &mut Rings, a: f32) {
        let (n, c) = (self.n, rings.solved - 1);
        let (r, inverse) = (&rings.face[..c + 2], &rings.inverse_cell[..c + 1]);
        // Each loop over slices of one length, without a branch, an index check or a
        // carried value, so that it vectorises (each face's arithmetic as written).
        let flux = &mut rings.flux[..c + 1];
        for j in 0..n {
            let (jm, jp) = (j.saturating_sub(1), (j + 1).min(n - 1));
            let below = &self.u[jm * (n + 1)..][..c + 2];
            let here = &self.u[j * (n + 1)..][..c + 2];
            let above = &self.u[jp * (n + 1)..][..c + 2];
            let out = &mut self.scratch_u[j * (n + 1)..][..c + 2];
            // (1/r)·∂(r u)/∂r of each cell, times h.
            let (outer, inner) = (r[1..].iter().zip(&here[1..]), r.iter().zip(here));
            for ((f, ((ro, uo), (ri, ui))), inv) in
                flux.iter_mut().zip(outer.zip(inner)).zip(inverse)
            {
                *f = (ro * uo - ri * ui) * inv;
            }
            out[0] = here[0];
            let faces = (&below[1..=c], &here[1..=c], &above[1..=c]);
            let fluxes = flux[1..].iter().zip(&flux[..c]);
            let rows = faces.0.iter().zip(faces.1).zip(faces.2);
            for ((o, ((b, h), t)), (f1, f0)) in out[1..=c].iter_mut().zip(rows).zip(fluxes) {
                let axial = b + t - 2.0 * h;
                *o = h + a * (f1 - f0 + axial);
            }
            out[c + 1] = -out[c];
        }
        for j in 0..=n {
            let (jm, jp) = (j.saturating_sub(1), (j + 1).min(n));
            let below = &self.v[jm * n..][..c + 2];
            let here = &self.v[j * n..][..c + 2];
            let above = &self.v[jp * n..][..c + 2];
            let out = &mut self.scratch_v[j * n..][..c + 2];
            // The outer wall's face: free slip (no flux through it), or no slip in a pipe.
            let wall = if rings.no_slip_wall {
                2.0 * here[0]
            } else {
                0.0
            };
            let radial = (r[1] * (here[1] - here[0]) - r[0] * wall) * inverse[0];
            let axial = below[0] + above[0] - 2.0 * here[0];
            out[0] = here[0] + a * (radial + axial);
            // Faces 1..=c: each with its neighbours out (i + 1) and in (i − 1).
            let radii = r[2..=c + 1].iter().zip(&r[1..=c]).zip(&inverse[1..=c]);
            let across = here[2..=c + 1].iter().zip(&here[1..=c]).zip(&here[..c]);
            let along = below[1..=c].iter().zip(&above[1..=c]);
            for ((o, ((ro, ri), inv)), (((ho, h), hi), (b, t))) in
                out[1..=c].iter_mut().zip(radii).zip(across.zip(along))
            {
                let radial = (ro * (ho - h) - ri * (h - hi)) * inv;
                let axial = b + t - 2.0 * h;
                *o = h + a * (radial + axial);
            }
            out[c + 1] = out[c - 1];
        }
        std::mem::swap(&mut self.u, &mut self.scratch_u);
        std::mem::swap(&mut self.v, &mut self.scratch_v);
        self.enforce_walls();
    }

    /// max |div u| over the solved half, 1/s.
    pub(super) fn ring_divergence_max(&self, rings: &Rings) -> f32 {
        let n = self.n;
        (0..n)
            .flat_map(|j| (0..rings.solved).map(move |i| (i, j)))
            .map(|(i, j)| self.ring_divergence(rings, i, j).abs())
            .fold(0.0, f32::max)
    }
}
