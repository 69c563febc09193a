//! The water of a slice: incompressible Navier–Stokes on a staggered (MAC) grid in a
//! channel that follows the bell: free-slip side walls, still water streaming in at the
//! top (ahead of the bell) and an open bottom (zero pressure) where the wake leaves.
//!
//! `u` lives on vertical faces, `v` on horizontal faces, so the discrete divergence of a
//! projected field vanishes to round-off. Velocities are relative to the frame; far from
//! the bell the water streams past at [`Fluid::stream`].
//!
//! One idea per file, so that another slice geometry can share them:
//! - `advection`: the velocity carried along itself (semi-Lagrangian,
//!   MacCormack or limited bicubic), on the samplers of `sampling` (and of `window`,
//!   eight feet near their faces at a time);
//! - `immersed`: where the bell meets the grid: points read velocities and spread forces
//!   through one stencil;
//! - `diffusion`: viscosity;
//! - `projection`: the pressure that makes the flow divergence-free;
//! - `boundaries`: the side walls, the inflow, the open wake end and its absorbing layer;
//! - `frame`: the co-moving box (Galilean changes of frame, whole-cell shifts);
//! - `symmetry`: the mirror about the bell's axis;
//! - `rings`: the axisymmetric slice's r-weighted operators (see [`SliceGeometry`]), and
//!   the same passes with unit weights on a planar slice's mirrored half;
//! - `measure`: divergence, speeds, energy;
//! - `walls`: the channel, or a closed box for the textbook flows (`textbook`) that
//!   check the fluid on its own.

mod advection;
mod boundaries;
mod diffusion;
mod frame;
mod immersed;
mod measure;
mod projection;
#[cfg(test)]
mod ring_tests;
mod rings;
mod sampling;
mod symmetry;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod textbook;
mod walls;
mod window;

pub(crate) use crate::species::{Advection, Kernel, SliceGeometry};
pub(crate) use rings::{RINGS_SWEEP_LIMIT, Rings};
pub(crate) use walls::Walls;

use super::pressure::PoissonSolver;

/// The water of one slice: a staggered (MAC) grid of velocities with pressure solved
/// exactly (see `Fluid::step` for the order of a step).
#[derive(Clone)]
pub struct Fluid {
    /// Cells per side.
    pub n: usize,
    /// Cell size, m.
    pub h: f32,
    /// Horizontal velocity on vertical faces, `(n + 1) × n`, index `j * (n + 1) + i`.
    pub u: Vec<f32>,
    /// Vertical velocity on horizontal faces, `n × (n + 1)`, index `j * n + i`.
    pub v: Vec<f32>,
    /// Force density accumulated for the next step, N/m³, on the `u` faces.
    pub(crate) force_u: Vec<f32>,
    /// Force density accumulated for the next step, N/m³, on the `v` faces.
    pub(crate) force_v: Vec<f32>,
    /// The rows of faces (`j`, of either component) that may hold force: the rest are
    /// zero, and the step adds and clears these only. Whoever writes force widens it
    /// ([`Fluid::force_in_rows`]).
    pub(crate) force_rows: std::ops::Range<usize>,
    /// Kinematic viscosity, m²/s.
    pub(crate) nu: f32,
    /// Density, kg/m³.
    pub(crate) rho: f32,
    /// How velocities are carried along (see [`Advection`]).
    pub(crate) advection: Advection,
    /// How points read and spread onto the faces (see [`Kernel`]).
    pub(crate) kernel: Kernel,
    /// Hold the flow mirror-symmetric about [`Fluid::axis`] (averaged before each
    /// projection, so what the projection leaves is divergence-free).
    pub(crate) mirror: bool,
    /// How many times wider than three cells the kernel is (at least 1): the bell's
    /// `boundary_width` over the grid's three cells.
    pub(crate) kernel_stretch: f32,
    /// Vertical velocity of still water relative to the frame, m/s (minus the frame's
    /// velocity): what enters at the top, and what the absorbing layer relaxes towards.
    pub(crate) stream: f32,
    /// The walls around the grid: the channel, or a closed box in tests.
    walls: Walls,
    /// Absorbing layer at the bottom (wake) end: damping rate (1/s) per face.
    sponge_u: Vec<f32>,
    sponge_v: Vec<f32>,
    scratch_u: Vec<f32>,
    scratch_v: Vec<f32>,
    back_u: Vec<f32>,
    back_v: Vec<f32>,
    bounds_u: Vec<(f32, f32)>,
    bounds_v: Vec<(f32, f32)>,
    phi: Vec<f32>,
    /// The whole grid's pressure solve: a planar slice free to tilt, or a closed test
    /// box; built when first needed (a slice held symmetric never is).
    poisson: Option<PoissonSolver>,
    /// The radii and pressure solve of an axisymmetric slice; `None` for a planar one.
    rings: Option<Box<Rings>>,
    /// A planar slice's mirrored half, solved while the slice is held mirror-symmetric in
    /// the channel (see [`Fluid::take_half`]).
    plane_half: Option<Box<Rings>>,
    /// What a unit of spread force adds to the force density of each column of `u` and
    /// `v` faces: `1/h²` in the plane, `1/(r·h²)` for rings (a face's volume per unit of
    /// the slice's depth).
    pub(crate) spread_u: Vec<f32>,
    pub(crate) spread_v: Vec<f32>,
}

/// Which staggered component a sample refers to.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Component {
    /// Horizontal velocity, on the vertical faces.
    U,
    /// Vertical velocity, on the horizontal faces.
    V,
}

impl Fluid {
    /// Still water on `n`×`n` cells of side `h` (m), kinematic viscosity `nu` (m²/s),
    /// density `rho` (kg/m³).
    pub(crate) fn new(n: usize, h: f32, nu: f32, rho: f32) -> Self {
        let faces = (n + 1) * n;
        Self {
            n,
            h,
            u: vec![0.0; faces],
            v: vec![0.0; faces],
            force_u: vec![0.0; faces],
            force_v: vec![0.0; faces],
            force_rows: 0..0,
            nu,
            rho,
            advection: Advection::default(),
            kernel: Kernel::default(),
            mirror: false,
            kernel_stretch: 1.0,
            stream: 0.0,
            walls: Walls::Channel,
            sponge_u: vec![0.0; faces],
            sponge_v: vec![0.0; faces],
            scratch_u: vec![0.0; faces],
            scratch_v: vec![0.0; faces],
            back_u: vec![0.0; faces],
            back_v: vec![0.0; faces],
            bounds_u: vec![(0.0, 0.0); faces],
            bounds_v: vec![(0.0, 0.0); faces],
            phi: vec![0.0; n * n],
            poisson: None,
            rings: None,
            plane_half: Some(Box::new(Rings::mirrored_plane(n, h))),
            spread_u: vec![1.0 / (h * h); n + 1],
            spread_v: vec![1.0 / (h * h); n],
        }
    }

    /// Makes this the slice of `geometry`: planar, or axisymmetric about [`Fluid::axis`]
    /// (which holds the flow mirror-symmetric, as a meridian of a body of revolution is).
    pub(crate) fn set_geometry(&mut self, geometry: SliceGeometry) {
        let (n, h) = (self.n, self.h);
        match geometry {
            SliceGeometry::Planar => {
                self.rings = None;
                if self.plane_half.is_none() {
                    self.plane_half = Some(Box::new(Rings::mirrored_plane(n, h)));
                }
                self.phi = vec![0.0; n * n];
                self.spread_u.fill(1.0 / (h * h));
                self.spread_v.fill(1.0 / (h * h));
            }
            SliceGeometry::Axisymmetric => {
                let rings = Rings::new(n, h);
                for (s, r) in self.spread_u.iter_mut().zip(&rings.face) {
                    *s = 1.0 / (r * h * h);
                }
                for (s, r) in self.spread_v.iter_mut().zip(&rings.cell) {
                    *s = 1.0 / (r * h * h);
                }
                self.phi = vec![0.0; rings.solved * n];
                self.rings = Some(Box::new(rings));
                self.plane_half = None;
                self.mirror = true;
            }
        }
    }

    /// Side of the domain, m.
    pub fn size(&self) -> f32 {
        self.n as f32 * self.h
    }

    /// Heap bytes of the fields and scratch buffers.
    pub(crate) fn bytes(&self) -> usize {
        let f32s = [
            &self.u,
            &self.v,
            &self.force_u,
            &self.force_v,
            &self.sponge_u,
            &self.sponge_v,
            &self.scratch_u,
            &self.scratch_v,
            &self.back_u,
            &self.back_v,
            &self.phi,
        ];
        f32s.iter().map(|v| v.len() * 4).sum::<usize>()
            + (self.bounds_u.len() + self.bounds_v.len()) * 8
            + self.poisson.as_ref().map_or(0, |p| p.bytes())
            + self.rings.as_ref().map_or(0, |r| r.bytes())
            + self.plane_half.as_ref().map_or(0, |r| r.bytes())
            + (self.spread_u.len() + self.spread_v.len()) * 4
    }

    /// One step of `dt` seconds, in this order:
    /// 1. [`advect`](Fluid::advect): the velocity carried along itself;
    /// 2. [`apply_force`](Fluid::apply_force): the force the bell spread since the last
    ///    step, then cleared;
    /// 3. [`diffuse`](Fluid::diffuse): viscosity;
    /// 4. [`absorb`](Fluid::absorb): the wake's absorbing layer;
    /// 5. [`project`](Fluid::project): the pressure that leaves the flow divergence-free.
    ///
    /// A mirror-symmetric slice (axisymmetric, or planar and held symmetric) is solved on
    /// its half and mirrored by the projection; only a closed test box held symmetric is
    /// [`symmetrise`](Fluid::symmetrise)d before it.
    ///
    /// Stam's stable fluids (1999) add the force first and then advect; here advection
    /// comes first, so the force acts on the faces it was spread to and is not carried
    /// downstream before the projection sees it. The sponge and the mirror come before the
    /// projection so that what the step leaves is divergence-free.
    pub(crate) fn step(&mut self, dt: f32) {
        self.advect(dt);
        self.apply_force(dt);
        self.diffuse(dt);
        self.absorb(dt);
        if self.mirror && self.half().is_none() {
            self.symmetrise();
        }
        self.project();
    }

    /// Still water: every velocity the stream's, no pending forces.
    pub(crate) fn clear(&mut self) {
        for f in [&mut self.u, &mut self.force_u, &mut self.force_v] {
            f.fill(0.0);
        }
        self.force_rows = 0..0;
        self.v.fill(self.stream);
    }
}
