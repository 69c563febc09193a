//! Which walls enclose the water. The slice always swims in the channel; a closed box is
//! a test set-up, for the textbook flows that check the fluid on its own (`textbook`):
//! the Taylor–Green vortex (free-slip walls) and the lid-driven cavity (no-slip walls).
//!
//! Each step's pieces branch here only for a closed box, so the channel's arithmetic is
//! exactly what it was before the box existed.

use super::Fluid;
use super::diffusion::MAX_DIFFUSION_SWEEPS;
use crate::sim::pressure::PoissonSolver;

/// The walls around the grid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) enum Walls {
    /// The slice's channel: free-slip side walls, the stream entering at the top, the
    /// open wake end at the bottom (p = 0, with its absorbing layer).
    #[default]
    Channel,
    /// A closed box (test set-ups only): zero normal velocity on all four sides and a
    /// pure-Neumann pressure. Free slip (zero tangential stress) unless `no_slip`, where
    /// the tangential velocity on the walls is zero, except on the top wall (the lid),
    /// which moves at `lid` m/s along +x. The no-slip walls enter the viscous term (as
    /// ghost values); advection samples as in the channel, its traces stopping at the
    /// first row inside a wall, where the flow towards the wall is already of order h².
    #[cfg_attr(not(test), allow(dead_code))] // built by the textbook tests only
    ClosedBox {
        /// No-slip walls, instead of free-slip ones.
        no_slip: bool,
        /// Speed of the top wall along +x, m/s (with `no_slip`; ignored otherwise).
        lid: f32,
    },
}

impl Walls {
    /// Whether the box is closed (no stream, no open end).
    pub(crate) fn is_closed(self) -> bool {
        matches!(self, Walls::ClosedBox { .. })
    }
}

impl Fluid {
    /// Encloses the water in `walls`: the pressure solve is rebuilt for them; a closed box
    /// has no stream (still water is at rest) and no absorbing layer.
    #[cfg_attr(not(test), allow(dead_code))] // used by the textbook tests only
    pub(crate) fn set_walls(&mut self, walls: Walls) {
        self.walls = walls;
        let (n, h) = (self.n, self.h);
        self.poisson = Some(if walls.is_closed() {
            self.stream = 0.0;
            self.sponge_u.fill(0.0);
            self.sponge_v.fill(0.0);
            PoissonSolver::closed(n, h)
        } else {
            PoissonSolver::new(n, h)
        });
        self.enforce_walls();
    }

    /// The closed box's normal velocities: zero on all four sides.
    pub(super) fn enforce_box_walls(&mut self) {
        let n = self.n;
        for j in 0..n {
            self.u[j * (n + 1)] = 0.0;
            self.u[j * (n + 1) + n] = 0.0;
        }
        self.v[..n].fill(0.0);
        self.v[n * n..].fill(0.0);
    }

    /// Viscosity in a no-slip box: as [`Fluid::diffuse`] (explicit, the same sub-steps),
    /// with the tangential component's ghost beyond each wall `2·U_wall − value`, so that
    /// the linear profile between them has the wall's velocity on the wall: `−value` on
    /// the stationary walls, `2·lid − value` above the top row of `u`.
    pub(super) fn diffuse_no_slip(&mut self, dt: f32, lid: f32) {
        let alpha = self.nu * dt / (self.h * self.h);
        if alpha.is_nan() || alpha <= 0.0 {
            return;
        }
        let substeps = ((alpha / 0.2).ceil() as usize).clamp(1, MAX_DIFFUSION_SWEEPS);
        let a = (alpha / substeps as f32).min(0.2);
        let n = self.n;
        // u: the side walls' faces are zeroed after each sweep, so their ghosts do not
        // matter; v: likewise the bottom and top faces.
        let u_ghosts = [
            Ghost::MIRROR,
            Ghost::MIRROR,
            Ghost::wall(0.0),
            Ghost::wall(lid),
        ];
        let v_ghosts = [
            Ghost::wall(0.0),
            Ghost::wall(0.0),
            Ghost::MIRROR,
            Ghost::MIRROR,
        ];
        for _ in 0..substeps {
            ghost_sweep(&self.u, &mut self.scratch_u, n + 1, n, a, u_ghosts);
            ghost_sweep(&self.v, &mut self.scratch_v, n, n + 1, a, v_ghosts);
            std::mem::swap(&mut self.u, &mut self.scratch_u);
            std::mem::swap(&mut self.v, &mut self.scratch_v);
            self.enforce_walls();
        }
    }
}

/// The value beyond an edge, from the value next to it: `offset + sign·value`.
#[derive(Clone, Copy)]
struct Ghost {
    sign: f32,
    offset: f32,
}

impl Ghost {
    /// Zero gradient across the edge (free slip for a tangential component).
    const MIRROR: Ghost = Ghost {
        sign: 1.0,
        offset: 0.0,
    };

    /// A no-slip wall moving at `speed` halfway to the ghost.
    fn wall(speed: f32) -> Ghost {
        Ghost {
            sign: -1.0,
            offset: 2.0 * speed,
        }
    }

    fn beyond(self, value: f32) -> f32 {
        self.offset + self.sign * value
    }
}

/// One explicit diffusion sweep `dst = src + a·∇²src` on an `nx × ny` array, with the
/// ghosts `[left, right, below, above]` beyond its edges.
fn ghost_sweep(src: &[f32], dst: &mut [f32], nx: usize, ny: usize, a: f32, ghosts: [Ghost; 4]) {
    let [left, right, below, above] = ghosts;
    for j in 0..ny {
        for i in 0..nx {
            let at = |i: usize, j: usize| src[j * nx + i];
            let c = at(i, j);
            let l = if i > 0 { at(i - 1, j) } else { left.beyond(c) };
            let r = if i + 1 < nx {
                at(i + 1, j)
            } else {
                right.beyond(c)
            };
            let b = if j > 0 { at(i, j - 1) } else { below.beyond(c) };
            let t = if j + 1 < ny {
                at(i, j + 1)
            } else {
                above.beyond(c)
            };
            dst[j * nx + i] = c + a * (l + r + b + t - 4.0 * c);
        }
    }
}
