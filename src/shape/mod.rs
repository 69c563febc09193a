//! Slice to 3D surface (paper sections 3.4–3.5).
//!
//! Per frame, [`build_into`] turns a [`SliceView`](crate::SliceView) into two surfaces of a
//! [`JellyMesh`], in place:
//! - [`profile`]: the 2D rendering model: exumbrella from the mesoglea thickness, cubic
//!   [`spline`] resampling into opposite pairs.
//! - [`discs`]: each pair swept into a disc about its own axis.
//! - [`umbrella`], [`tentacles`], [`oral`] (manubrium and oral arms): discs joined into
//!   closed surfaces in [`buffers`];
//!   the umbrella's normals come from its ring grid (`normals.rs`).
//! - [`pattern`]: the canals and gonads painted on the subumbrella.
//! - [`tissue`]: each vertex's thickness and glow band, for the translucent material.
//! - [`variation`]: structural, compression and unstructured variation (Fig. 9); the noise
//!   is cached per vertex in [`noise_field`].
//! - [`input`]: what a slice must satisfy; [`outline`]: a hand-made slice for tests,
//!   benches and examples.

pub mod buffers;
pub mod discs;
pub mod input;
pub mod mesh;
pub mod noise_field;
mod normals;
pub mod oral;
pub mod outline;
pub mod packed;
pub mod pattern;
pub mod perlin;
pub mod profile;
pub mod spline;
pub mod tentacles;
pub mod tissue;
pub mod umbrella;
pub mod variation;

#[cfg(test)]
mod tests;

pub use buffers::SurfaceBuffers;
pub use input::ShapeError;
pub use mesh::{JellyMesh, Resolution, build_at, build_into};
pub use outline::SliceOutline;
