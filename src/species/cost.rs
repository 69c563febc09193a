//! The slice's cost model: what a simulated second of a species costs one core of the
//! reference machine, estimated from its cells, its viscosity's sweeps and its body
//! points, so that validation can refuse a species too slow to run before it runs.

use super::{Advection, BellCoupling, SliceGeometry, Species};

/// Most seconds of one core one simulated second may cost by [`simulation_cost`]'s
/// estimate, on the reference machine (a 2-core x86 here, release). The estimate can be
/// half the truth when the flow runs faster than expected and steps split; with the mesh
/// at its budget, 60 frames then still take under the 2 s the limits promise.
pub const MAX_COST_PER_SECOND: f64 = 0.5;

/// Cost of one step on the reference machine: per fluid cell (semi-Lagrangian), per cell
/// and diffusion sweep, and per body point. Fitted 2026-12-05 by `examples/cost_fit.rs`
/// (which prints every run's cost beside this estimate) over 216 runs: every shipped
/// species and the paper's model, and the moon jelly in water ten and a hundred times as
/// viscous (more sweeps a step), in both geometries, with the three advection schemes, on
/// grids 40 to 160, the least of three runs each, on the relative error; then raised by
/// half, so that every run costs no more than its estimate (at most 0.82 of it, the
/// shipped species at their own grids 0.63–0.75) but the paper's r–z dome on fine grids,
/// whose fast flow splits its steps (up to 1.14). The fit before (2026-12-03) had costed a
/// cell and a body point half again as much as the slice's passes since leave of them,
/// and a sweep five times: the shipped species cost 0.37–0.45 of it.
const COST_PER_CELL: f64 = 5.1e-9;
const COST_PER_CELL_SWEEP: f64 = 1.2e-9;
const COST_PER_POINT: f64 = 0.42e-6;

/// What a cell costs with an advection scheme against the semi-Lagrangian step, from the
/// same fit: MacCormack's two traces and its limiter 3.7 times, the bicubic trace (eight
/// lanes wide, `fluid::window`) 1.85 times.
fn advection_cost(advection: Advection) -> f64 {
    match advection {
        Advection::SemiLagrangian => 1.0,
        Advection::MacCormack => 3.7,
        Advection::Cubic => 1.85,
    }
}

/// What a body point costs with a bell coupling against the added mass. The water's
/// response (its overlaps, and a non-symmetric solve in a band three to four times as
/// wide) added 45%, 33% and 42% to the moon jelly's, *Aequorea*'s and *Sarsia*'s r–z
/// slices (callgrind, `numerics fingerprint`, 2026-12-07), 0.6 of what their points are
/// estimated to cost; 1.8 keeps the estimate above it.
fn coupling_cost(coupling: BellCoupling) -> f64 {
    match coupling {
        BellCoupling::AddedMass => 1.0,
        BellCoupling::WaterResponse => 1.8,
    }
}

/// Estimated seconds of one core per simulated second: steps per second times the cost
/// of a step (its cells and its body points) on the reference machine.
pub fn simulation_cost(s: &Species) -> f64 {
    let [cells, sweeps, points] = simulation_cost_terms(s);
    COST_PER_CELL * cells + COST_PER_CELL_SWEEP * sweeps + COST_PER_POINT * points
}

/// What [`simulation_cost`] counts in a simulated second: fluid cells stepped (each
/// weighted by what its advection scheme costs against the semi-Lagrangian step), cells
/// swept by the explicit viscosity, and body points stepped (each weighted by what its
/// bell coupling costs against the added mass). Its constants price them.
pub fn simulation_cost_terms(s: &Species) -> [f64; 3] {
    let cells = (s.grid_resolution as f64).powi(2);
    // Body points half a kernel cell apart (`Species::kernel_stretch_at`).
    let spacing = 0.5 * (s.cell_size() * s.kernel_stretch_at(s.cell_size())) as f64;
    // Half an ellipse's perimeter (Ramanujan's approximation) and two tentacle chains.
    let (a, b) = (0.5 * s.diameter as f64, s.height as f64);
    let half_perimeter =
        0.5 * std::f64::consts::PI * (3.0 * (a + b) - ((3.0 * a + b) * (a + 3.0 * b)).sqrt());
    let points = (half_perimeter + 2.0 * s.tentacle_length as f64) / spacing;
    let steps = s.contraction_frequency as f64 * s.steps_per_cycle() as f64;
    // Explicit viscosity: one sweep per 0.2 of ν·dt/h², up to the fluid's cap, over the
    // half of the grid either slice solves (mirror-symmetric); r–z sweeps are half as long
    // (its hoop term is stiffer), twice as many.
    let h = s.cell_size() as f64;
    let alpha = s.kinematic_viscosity() as f64 * s.step_length() as f64 / (h * h);
    let (sweep, most) = match s.slice_geometry {
        SliceGeometry::Planar => (0.2, 32.0),
        SliceGeometry::Axisymmetric => (0.1, 64.0),
    };
    let sweeps = (alpha / sweep).ceil().clamp(1.0, most) * 0.5;
    [
        steps * cells * advection_cost(s.advection),
        steps * cells * sweeps,
        steps * points * coupling_cost(s.bell_coupling),
    ]
}
