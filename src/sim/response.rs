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

/// `G` over the bell solver's points, in its order: component by component (the overlaps
/// carry a force's x to displacements' x only, and so does the relaxation), banded.
#[derive(Clone, Default)]
pub(crate) struct Response {
    /// Each solved point (a body index), in the solver's order.
    points: Vec<usize>,
    /// Whether the point has a mirror image past the axis that moves with it.
    imaged: Vec<bool>,
    /// The widest coupling set since the last [`Self::clear`], in the solver's order.
    band: usize,
    /// Per component, row `p` from `p − MOST_APART` to `p + MOST_APART`.
    entries: [Vec<f32>; 2],
}

impl Response {
    /// An empty response over `points` (in the solver's order), `imaged[p]` where point
    /// `p` has a mirror image.
    pub(crate) fn new(points: Vec<usize>, imaged: Vec<bool>) -> Self {
        let size = points.len() * (2 * MOST_APART + 1);
        Self {
            points,
            imaged,
            band: 0,
            entries: [vec![0.0; size], vec![0.0; size]],
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
        let (width, band) = (2 * MOST_APART + 1, self.band);
        for entries in &mut self.entries {
            for row in entries.chunks_exact_mut(width) {
                row[MOST_APART - band..=MOST_APART + band].fill(0.0);
            }
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
        self.entries[c][p * (2 * MOST_APART + 1) + q + MOST_APART - p] += value;
    }

    /// Component `c`'s displacements of point `p` for a unit force on each of `forced`
    /// (within [`Self::reach`] of `p`).
    #[inline]
    pub(crate) fn row(&self, c: usize, p: usize, forced: std::ops::Range<usize>) -> &[f32] {
        let start = p * (2 * MOST_APART + 1) + MOST_APART - p;
        &self.entries[c][start + forced.start..start + forced.end]
    }
}
