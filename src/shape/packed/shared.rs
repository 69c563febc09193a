//! Far jellyfish share their recorded steps' frames.
//!
//! A block's frame (most of its header, its rings and discs) depends on the slice's shape
//! and the species alone; its first words on the individual (seed, noise time) and its
//! trails on its guides. A far jellyfish shows a step of its species' recorded cycle, so
//! every far jellyfish showing that step reads the same frame ([`pack_frame`], packed
//! once), and sends only its own words and trails ([`pack_instance`]): the upload points
//! its `H_FRAME` at the frame, which the vertex shader reads as
//! [`Block::far`](super::Block::far) does.

use super::layout::*;
use super::{ShapePacker, write_halves};
use crate::shape::input::ShapeError;
use crate::shape::mesh::Resolution;
use crate::shape::variation::Variation;
use crate::sim::SliceView;
use crate::sim::guides::{THIN_NODES, Trail};
use crate::species::Species;

/// Guides of a far jellyfish's thinned trail (`Trail::thin_into`), at most: the
/// fringe's sweep at four points around the margin, its root, middle and tip each, is
/// what a jellyfish a few pixels wide shows of it, and keeps its instance at 16 values.
pub const FAR_GUIDES: usize = 4;

/// Guides of a far jellyfish's trail at `res`.
pub fn far_guides(res: &Resolution) -> usize {
    res.guides.min(FAR_GUIDES)
}

/// Guides of a far jellyfish's trail of `species`, at any resolution: [`far_guides`].
pub fn far_guides_of(species: &Species) -> usize {
    Resolution::guides_of(species).min(FAR_GUIDES)
}

/// Appends the frame of a recorded step for far jellyfish: the block of `view` without
/// trails, saying that each instance carries its thinned fringe ([`far_guides`] of
/// [`THIN_NODES`]) right after its own words. On error nothing is appended.
pub fn pack_frame(
    packer: &mut ShapePacker,
    view: &SliceView,
    species: &Species,
    res: Resolution,
    out: &mut Vec<f32>,
) -> Result<(), ShapeError> {
    let still = SliceView {
        trail: Trail::NONE,
        oral_trail: Trail::NONE,
        ..*view
    };
    let start = out.len();
    packer.pack(&still, species, res, 0, 0.0, out)?;
    let header = &mut out[start..];
    let bits = |v: usize| f32::from_bits(v as u32);
    header[H_GUIDES] = bits(far_guides(&res));
    header[H_ORAL_GUIDES] = bits(0);
    header[H_TRAILS] = bits(INSTANCE);
    header[H_TRAIL_NODES] = bits(THIN_NODES);
    Ok(())
}

/// Appends a far jellyfish's own words (`INSTANCE` values: [`write_instance_words`]) and
/// its thinned fringe `trail` (`Trail::thin_into` with [`far_guides`]); zeros where it has
/// no such trail (its guides not followed). A far jellyfish does not follow its oral arms.
pub fn pack_instance(
    species: &Species,
    res: &Resolution,
    seed: u32,
    time: f32,
    trail: Trail,
    out: &mut Vec<f32>,
) {
    let start = out.len();
    out.resize(start + INSTANCE, 0.0);
    write_instance_words(species, seed, time, &mut out[start..]);
    if trail.nodes == THIN_NODES && trail.guides() == far_guides(res) {
        for nodes in trail.offsets.chunks_exact(THIN_NODES) {
            write_halves(&nodes[1..], out);
        }
    } else {
        out.resize(start + instance_len(res), 0.0);
    }
}

/// Writes a far jellyfish's own words over the first `INSTANCE` values of `own`: its
/// `seed`, its noise at `time` (s), `H_FRAME` left for the upload. These change every
/// frame; its trail, packed after them, a few times a second, so an instance whose trail
/// has not changed needs only these written again.
pub fn write_instance_words(species: &Species, seed: u32, time: f32, own: &mut [f32]) {
    let variation = Variation::new(species, seed, time);
    own[H_SEED] = f32::from_bits(seed);
    own[H_TAU] = variation.time_coordinate() as f32;
    own[H_UNSTRUCTURED] = variation.unstructured_amplitude();
    own[H_FRAME] = f32::from_bits(0);
}

/// Values of a far jellyfish's instance at `res`: [`MAX_INSTANCE`] at most (64 bytes).
pub fn instance_len(res: &Resolution) -> usize {
    INSTANCE + far_guides(res) * trail_values(THIN_NODES)
}

/// The most values a far jellyfish's instance takes ([`instance_len`]), 64 bytes: room
/// enough to hold one in place of a heap block.
pub const MAX_INSTANCE: usize = 16;

const _: () = assert!(INSTANCE + FAR_GUIDES * trail_values(THIN_NODES) <= MAX_INSTANCE);
