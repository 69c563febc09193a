//! For measuring the core: what the tests, benches and examples read of a slice beyond
//! the headless API ([`SliceSim`](super::SliceSim), [`SliceView`](super::SliceView)).
//!
//! Reached through [`SliceSim::fluid`](super::SliceSim::fluid),
//! [`SliceSim::body`](super::SliceSim::body) and
//! [`SliceSim::outline`](super::SliceSim::outline). Not semver-stable: these follow the
//! numerics and may change in any release.

pub use super::body::{Body, Outline, cavity, contains};
pub use super::fluid::Fluid;
