//! The 2D slice simulation (paper sections 3.2–3.3).
//!
//! The physical model, its units and the published figures it is checked against are in
//! `docs/physics.md`; the numerical choices and what they measured in `docs/numerics.md`.

/// Calls `$passes($args…)` (returning nothing) compiled for AVX where the processor has
/// it, else as built: the passes' loops then run eight lanes wide with the same
/// operations in the same order (no FMA), so the same bits. `$passes` must be
/// `#[inline(always)]`, so that it is compiled into each caller. Returns from the
/// enclosing function on the AVX path.
macro_rules! eight_wide {
    ($passes:path, ($($arg:ident: $ty:ty),*)) => {{
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            #[target_feature(enable = "avx")]
            fn avx($($arg: $ty),*) {
                $passes($($arg),*)
            }
            // SAFETY: this processor has AVX (asked above).
            return unsafe { avx($($arg),*) };
        }
        $passes($($arg),*)
    }};
}

mod banded;
mod banded_lu;
pub(crate) mod body;
pub mod clock;
pub(crate) mod coupling;
pub mod cycle;
pub mod escape;
pub(crate) mod fluid;
pub mod guides;
pub mod inspect;
pub(crate) mod kernel;
pub(crate) mod muscle;
pub(crate) mod oral_arms;
pub(crate) mod pressure;
pub(crate) mod response;
mod slice;
pub mod tank;
pub(crate) mod trilinear;

pub use cycle::{CycleCache, CycleRecorder};
pub use slice::SliceSim;

use glam::Vec2;

/// A read-only view of one slice, as the renderer needs it.
///
/// Frame: the slice plane, x across the bell, y along its axis with the apex towards +y
/// at rest. Metres.
#[derive(Clone, Copy, Debug)]
pub struct SliceView<'a> {
    /// Subumbrellar surface points, from the left margin over the apex to the right margin.
    /// An odd count: point `i` and point `len - 1 - i` are an opposite pair, the middle one
    /// is the apex.
    pub bell: &'a [Vec2],
    /// The same points at rest (uncontracted), for measuring contraction per pair.
    pub rest_bell: &'a [Vec2],
    /// Left and right tentacle chains; each starts at its margin point (`bell[0]`, resp.
    /// `bell[len-1]`) and hangs away from the bell.
    pub tentacles: [&'a [Vec2]; 2],
    /// Left and right chains of the manubrium and oral arms, from beside
    /// the subumbrellar apex down; empty for a species without them.
    pub oral_arms: [&'a [Vec2]; 2],
    /// The fringe's offsets in the 3D water the slice does not see (the plugin's guide
    /// chains); [`Trail::NONE`](guides::Trail::NONE) for the slice alone.
    pub trail: guides::Trail<'a>,
    /// The manubrium's and the oral arms' offsets in the same water, one guide per tube in
    /// the surface's order (the manubrium first, if the species has one).
    pub oral_trail: guides::Trail<'a>,
}
