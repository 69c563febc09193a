//! The water's response to the bell over one step, as the bell's implicit solve sees it.
//!
//! A force on a point is spread to the faces around it, moves that water over the step,
//! and the points read the water back: each one moves by `dt²/ρ` times the overlap of its
//! stencil with the pushed one's. Those overlaps are this matrix `G` (a point's
//! displacement for a unit force on each solved point and its mirror image). The solve
//! `(W + K·G) f = F` then finds forces the water can actually take up, where a lone mass a
//! point (`G = dt²/m`) let the wall stretch under its own stroke by 11–15% at a species'
//! own step (`docs/numerics.md`, "A coupling that sees the water's response"). Only the
//! stencils' overlaps are here, not the pressure's or the viscosity's reply: four fifths of
//! the give, for a banded matrix the solve can afford.

/// Points further apart than this in the solver's order are not coupled through the
/// water: the kernel reaches a few cells and the points lie half a cell apart along the
/// chain (twice as far apart in a planar bell's alternating order).
const MOST_APART: usize = 24;
/// A row's entries: both components of every point within [`MOST_APART`].
const WIDTH: usize = 2 * (2 * MOST_APART + 1);

/// `G` over the bell solver's points, in its order: component by component (the overlaps
/// carry a force's x to displacements' x only, and so does the relaxation), banded, the
/// two components of each entry side by side.
#[derive(Clone, Default)]
pub(crate) struct Response {
    /// Each solved point (a body index), in the solver's order.
    points: Vec<usize>,
    /// Whether the point has a mirror image past the axis that moves with it.
    imaged: Vec<bool>,
    /// The widest coupling set since the last [`Self::clear`], in the solver's order.
    band: usize,
    /// Row `p` from `p − MOST_APART` to `p + MOST_APART`, each entry's x and y side by
    /// side (the order the solve's unknowns interleave them in).
    entries: Vec<f32>,
}

impl Response {
    /// An empty response over `points` (in the solver's order), `imaged[p]` where point
    /// `p` has a mirror image.
    pub(crate) fn new(points: Vec<usize>, imaged: Vec<bool>) -> Self {
        let size = points.len() * WIDTH;
        Self {
            points,
            imaged,
            band: 0,
            entries: vec![0.0; size],
        }
    }

    /// How many solved points.
    pub(crate) fn len(&self) -> usize {
        self.points.len()
    }

    /// The solved points, as body indices, in the solver's order.
    pub(crate) fn points(&self) -> &[usize] {
        &self.points
    }

    /// Whether solved point `p` has a mirror image past the axis.
    pub(crate) fn imaged(&self, p: usize) -> bool {
        self.imaged[p]
    }

    /// How far apart in the solver's order two coupled points may be.
    pub(crate) fn reach(&self) -> usize {
        MOST_APART.min(self.len().saturating_sub(1))
    }

    /// The widest coupling added since the last clear.
    pub(crate) fn band(&self) -> usize {
        self.band
    }

    /// No response at all (only the band last written needs clearing).
    pub(crate) fn clear(&mut self) {
        let band = self.band;
        for row in self.entries.chunks_exact_mut(WIDTH) {
            row[2 * (MOST_APART - band)..2 * (MOST_APART + band + 1)].fill(0.0);
        }
        self.band = 0;
    }

    /// Adds `value` to component `c`'s displacement of point `p` for a unit force on `q`.
    pub(crate) fn add(&mut self, c: usize, p: usize, q: usize, value: f32) {
        let apart = p.abs_diff(q);
        if apart > MOST_APART || value == 0.0 {
            return;
        }
        self.band = self.band.max(apart);
        self.entries[p * WIDTH + 2 * (q + MOST_APART - p) + c] += value;
    }

    /// Point `p`'s displacements for a unit force on each of `forced` (within
    /// [`Self::reach`] of `p`), x and y of each side by side.
    #[inline]
    pub(crate) fn row(&self, p: usize, forced: std::ops::Range<usize>) -> &[f32] {
        let start = p * WIDTH + 2 * (MOST_APART - p);
        &self.entries[start + 2 * forced.start..start + 2 * forced.end]
    }
}
