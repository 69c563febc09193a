//! Far jellyfish share their recorded frames' rings and discs.
//!
//! A block's rings and discs depend on the slice's shape alone; its header on the
//! individual (seed, noise time) and its trails on its guides. A far jellyfish shows a
//! frame of its species' recorded cycle, so every far jellyfish showing that frame can read
//! the same rings and discs ([`body`]): its own block is the header and its trails
//! ([`pack_instance`]), and the upload points its `H_BODY` at the frame's body.

use super::layout::*;
use super::{Block, carried_trails, write_trails};
use crate::shape::mesh::Resolution;
use crate::shape::variation::Variation;
use crate::sim::guides::Trail;
use crate::species::Species;

/// The rings and the tentacle and oral discs of a block as packed: what every far
/// jellyfish showing the same recorded frame shares.
pub fn body(block: &[f32]) -> &[f32] {
    let b = Block(block);
    &block[b.count(H_BODY)..b.count(H_TRAILS)]
}

/// Appends the block of a far jellyfish showing the recorded frame that `frame` packs
/// (`ShapePacker::pack`, any seed and time): the frame's header, with the individual's
/// `seed` and noise at `time` (s), and its own trails right after it. Its rings and discs
/// stay in `frame`: `H_BODY` is left for the upload to point at them, and [`joined`] puts
/// them back on the CPU.
#[allow(clippy::too_many_arguments)]
pub fn pack_instance(
    frame: &[f32],
    species: &Species,
    res: &Resolution,
    seed: u32,
    time: f32,
    trail: Trail,
    oral_trail: Trail,
    out: &mut Vec<f32>,
) {
    let variation = Variation::new(species, seed, time);
    let trails = carried_trails(trail, oral_trail, res);
    let bits = |v: usize| f32::from_bits(v as u32);
    let start = out.len();
    out.extend_from_slice(&frame[..HEADER]);
    let header = &mut out[start..];
    header[H_SEED] = f32::from_bits(seed);
    header[H_TAU] = variation.time_coordinate() as f32;
    header[H_UNSTRUCTURED] = variation.unstructured_amplitude();
    header[H_GUIDES] = bits(trails[0].1);
    header[H_ORAL_GUIDES] = bits(trails[1].1);
    header[H_BODY] = bits(0);
    header[H_TRAILS] = bits(HEADER);
    write_trails(trails, out);
}

/// A far jellyfish's `instance` ([`pack_instance`]) with the rings and discs of its
/// `frame` put back in: the block `ShapePacker::pack` writes for the same slice,
/// individual and trails.
pub fn joined(instance: &[f32], frame: &[f32]) -> Vec<f32> {
    let shared = body(frame);
    let mut block = Vec::with_capacity(instance.len() + shared.len());
    block.extend_from_slice(&instance[..HEADER]);
    block[H_BODY] = f32::from_bits(HEADER as u32);
    block[H_TRAILS] = f32::from_bits((HEADER + shared.len()) as u32);
    block.extend_from_slice(shared);
    block.extend_from_slice(&instance[HEADER..]);
    block
}
