//! The packed block's layout, in one table: the packer and its CPU mirror use these
//! constants, and the vertex shader imports them from the WGSL module that [`wgsl`] writes
//! from the same table (`#import bevy_jellyfish::packed`), so the shader holds no copy.
//!
//! The table also names the constants of other modules that the shader's arithmetic
//! shares with the CPU mesh (`ORAL_SIDES`, `SIDEWAYS`, `APEX_FADE`, `TENTACLE_TIP`,
//! `ARM_CURL`) and `TAU`.

// The WGSL writer's one caller is the plugin.
#![cfg_attr(not(feature = "bevy"), allow(dead_code))]

use crate::shape::oral::ARM_CURL;
use crate::shape::tentacles::SIDEWAYS;
use crate::shape::tissue::TENTACLE_TIP;
use crate::shape::variation::APEX_FADE;
use crate::sim::guides::{GUIDE_NODES, THIN_NODES};

// A guide's halves fill whole values, thinned or not.
const _: () = assert!((3 * (GUIDE_NODES - 1)).is_multiple_of(2));
const _: () = assert!((3 * (THIN_NODES - 1)).is_multiple_of(2));

/// Values per guide of a trail of `nodes` nodes, the root (not stored) included: three
/// halves a node, two to a value. The shader's `trail_values`.
pub(crate) const fn trail_values(nodes: usize) -> usize {
    3 * (nodes - 1) / 2
}
use crate::species::limits::ORAL_SIDES;
use std::f32::consts::TAU;

/// The WGSL import path of the module [`wgsl`] writes.
pub(crate) const IMPORT_PATH: &str = "bevy_jellyfish::packed";

/// One constant of the table as the shader sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Value {
    /// An offset, a size or a count: WGSL `u32`.
    Count(usize),
    /// WGSL `f32`.
    Real(f32),
}

impl Value {
    /// The WGSL type and literal.
    pub(crate) fn wgsl(self) -> (&'static str, String) {
        match self {
            Value::Count(v) => {
                let v = u32::try_from(v).expect("a layout constant fits a u32");
                ("u32", format!("{v}u"))
            }
            // `{:?}` is the shortest literal that reads back as the same f32, always with
            // a `.` or an exponent, so WGSL reads it as a float.
            Value::Real(v) => ("f32", format!("{v:?}")),
        }
    }
}

/// One row of the table: a constant's name (the same in Rust and WGSL), its value and
/// its doc comment's lines.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Constant {
    pub name: &'static str,
    pub value: Value,
    pub doc: &'static [&'static str],
}

/// Defines the layout's own constants (`usize`) and, in `shared`, names constants
/// defined elsewhere with their kind; [`TABLE`] lists both, in order.
macro_rules! layout {
    (
        own { $( $(#[doc = $doc:literal])* $name:ident = $value:expr; )* }
        shared { $( $(#[doc = $sdoc:literal])* $shared:ident: $kind:ident; )* }
    ) => {
        $( $(#[doc = $doc])* pub(crate) const $name: usize = $value; )*

        /// Every constant the shader imports: the layout's, then the shared ones.
        pub(crate) const TABLE: &[Constant] = &[
            $( Constant { name: stringify!($name), value: Value::Count($name), doc: &[$($doc),*] }, )*
            $( Constant { name: stringify!($shared), value: Value::$kind($shared), doc: &[$($sdoc),*] }, )*
        ];
    };
}

layout! {
    own {
        /// Header offsets of the packed block. First the individual's own words, which a
        /// far jellyfish sends alone (`INSTANCE`): its seed (as `f32` bits).
        H_SEED = 0;
        /// The noise's time coordinate `f_t·t`.
        H_TAU = 1;
        /// Unstructured (noise) amplitude, m.
        H_UNSTRUCTURED = 2;
        /// Where the frame starts: the header's other words, then the rings and discs. As
        /// packed, 0 (the block is its own frame). In the shape buffer, from the buffer's
        /// start: the upload writes the block's own start, or for a far jellyfish
        /// `RECORDED_FRAME` plus where its recorded step starts in the recorded buffer.
        H_FRAME = 3;
        /// Values of the individual's own words.
        INSTANCE = 4;
        /// Rings (opposite pairs) from apex to margin; from here on the frame's words.
        H_RINGS = 4;
        /// Segments around the axis.
        H_SEGMENTS = 5;
        /// Tentacles around the margin.
        H_TENTACLES = 6;
        /// Sides of each tentacle's tube.
        H_SIDES = 7;
        /// Points along each tentacle chain.
        H_POINTS = 8;
        /// Structural variation's amplitude, m.
        H_STRUCTURAL = 9;
        /// Structural lobes around the bell.
        H_STRUCTURAL_FREQUENCY = 10;
        /// 1 for `|sin|` lobes, 0 for `sin`.
        H_STRUCTURAL_ABS = 11;
        /// Compression ripples' amplitude, m.
        H_COMPRESSION = 12;
        /// Compression ripples around the bell.
        H_COMPRESSION_FREQUENCY = 13;
        /// The noise's frequency along the latitude.
        H_LAT_FREQUENCY = 14;
        /// The radius of the noise's circle around the bell.
        H_LON_RADIUS = 15;
        /// Tentacle tube radius, m.
        H_TENTACLE_RADIUS = 16;
        /// The aperture's disc (`DISC` values).
        H_APERTURE = 17;
        /// The margin's two mesoglea normals (`NORMALS` values).
        H_MARGIN_NORMALS = H_APERTURE + DISC;
        /// Tubes of the manubrium and the oral arms.
        H_ORAL = H_MARGIN_NORMALS + NORMALS;
        /// 1 if oral tube 0 is a manubrium.
        H_MANUBRIUM = 27;
        /// The manubrium's radius, m.
        H_MANUBRIUM_RADIUS = 28;
        /// An oral arm's blade width, m.
        H_ARM_WIDTH = 29;
        /// The arms' ruffle depth, a fraction of the width.
        H_ARM_FRILL = 30;
        /// Ruffle waves along an arm.
        H_ARM_WAVES = 31;
        /// Rings along each oral tube.
        H_ORAL_POINTS = 32;
        /// The species' `tentacle_length_spread`.
        H_TENTACLE_SPREAD = 33;
        /// Guide chains of the fringe's trail.
        H_GUIDES = 34;
        /// Guide chains of the oral tubes (one per tube, or none), stored after the
        /// fringe's.
        H_ORAL_GUIDES = 35;
        /// Where the trails start, from the individual's words: after the oral discs in a
        /// block as packed, right after `INSTANCE` for a far jellyfish's.
        H_TRAILS = 36;
        /// Nodes of each guide of the trails, the root included (which is not stored):
        /// `GUIDE_NODES`, or a far jellyfish's thinned `THIN_NODES` (`sim::guides`).
        H_TRAIL_NODES = 37;
        /// Header length.
        HEADER = 38;
        /// Set in `H_FRAME` where the frame is in the recorded buffer (a far jellyfish's
        /// recorded step), not in the shape buffer.
        RECORDED_FRAME = 1 << 31;
        /// The `MeshTag` of a CPU mesh wearing the template material: the vertex shader
        /// draws its vertices as they are (no slot is this large).
        CPU_MESH_TAG = u32::MAX as usize;
        /// Values per guide of a trail of `GUIDE_NODES` nodes (`trail_values`): the
        /// offsets (x, y, z) of its nodes after the root (which never moves), as halves
        /// (IEEE binary16: 24 µm at 5 cm), two to a value, the first in its low bits.
        TRAIL = trail_values(GUIDE_NODES);
        /// Values per disc: centre (x, y), radius, radial (x, y).
        DISC = 5;
        /// Values per pair of mesoglea normals: left (x, y), then right (x, y).
        NORMALS = 4;
        /// Offsets in a ring: the subumbrella disc.
        RING_SUBUMBRELLA = 0;
        /// The exumbrella disc.
        RING_EXUMBRELLA = RING_SUBUMBRELLA + DISC;
        /// The two mesoglea normals.
        RING_NORMALS = RING_EXUMBRELLA + DISC;
        /// The ring's latitude.
        RING_LATITUDE = RING_NORMALS + NORMALS;
        /// The ring's contraction.
        RING_CONTRACTION = RING_LATITUDE + 1;
        /// Values per ring.
        RING = RING_CONTRACTION + 1;
    }
    shared {
        /// Sides of the manubrium's and the oral arms' tubes (`species::limits`).
        ORAL_SIDES: Count;
        /// Nodes per guide chain, the root included (`sim::guides`).
        GUIDE_NODES: Count;
        /// Latitude offset of the tentacles' sideways noise channel (`shape::tentacles`).
        SIDEWAYS: Real;
        /// Latitude below which structural and compression variation fade in
        /// (`shape::variation`).
        APEX_FADE: Real;
        /// A tentacle's tip radius over its root's (`shape::tissue`).
        TENTACLE_TIP: Real;
        /// How far an oral arm's blade curls, per unit of frill (`shape::oral`).
        ARM_CURL: Real;
        /// A turn, rad.
        TAU: Real;
    }
}

/// The WGSL module `bevy_jellyfish::packed`: every constant of [`TABLE`], typed.
pub(crate) fn wgsl() -> String {
    let mut out = format!(
        "// Written by bevy_jellyfish from shape::packed::layout's table: the packed block's\n\
         // layout and what the vertex shader shares with the CPU mesh. Change the table, not\n\
         // this.\n\
         #define_import_path {IMPORT_PATH}\n"
    );
    for c in TABLE {
        let (ty, literal) = c.value.wgsl();
        out.push('\n');
        for line in c.doc {
            out.push_str("//");
            out.push_str(line);
            out.push('\n');
        }
        out.push_str(&format!("const {}: {ty} = {literal};\n", c.name));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The header's fields cover it once each, in order: none overlaps another and none
    /// is left out, the individual's first; and a ring's fields cover the ring.
    #[test]
    fn the_fields_tile_the_header_and_the_ring() {
        let width = |name: &str| match name {
            "H_APERTURE" => DISC,
            "H_MARGIN_NORMALS" => NORMALS,
            _ => 1,
        };
        let mut next = 0;
        for c in TABLE.iter().filter(|c| c.name.starts_with("H_")) {
            assert_eq!(c.value, Value::Count(next), "{}", c.name);
            next += width(c.name);
        }
        assert_eq!(next, HEADER);
        // The individual's words come first; the frame's follow.
        assert_eq!(
            [H_SEED, H_TAU, H_UNSTRUCTURED, H_FRAME, INSTANCE],
            [0, 1, 2, 3, H_RINGS]
        );
        assert_eq!(
            [
                RING_SUBUMBRELLA,
                RING_EXUMBRELLA,
                RING_NORMALS,
                RING_LATITUDE
            ],
            [0, DISC, 2 * DISC, 2 * DISC + NORMALS]
        );
        assert_eq!(RING, 2 * DISC + NORMALS + 2);
    }

    /// Each name once, each a WGSL identifier, and the module declares them all with the
    /// table's values, reading back to the same numbers.
    #[test]
    fn the_module_declares_the_table() {
        let module = wgsl();
        assert!(module.contains(&format!("#define_import_path {IMPORT_PATH}\n")));
        let declared: Vec<(&str, &str, &str)> = module
            .lines()
            .filter_map(|l| l.strip_prefix("const "))
            .map(|l| {
                let (name, rest) = l.split_once(": ").unwrap();
                let (ty, rest) = rest.split_once(" = ").unwrap();
                (name, ty, rest.strip_suffix(';').unwrap())
            })
            .collect();
        assert_eq!(declared.len(), TABLE.len());
        for (c, (name, ty, literal)) in TABLE.iter().zip(declared) {
            assert_eq!(c.name, name);
            assert!(!c.doc.is_empty(), "{name} is documented");
            let read = match ty {
                "u32" => Value::Count(literal.strip_suffix('u').unwrap().parse().unwrap()),
                "f32" => Value::Real(literal.parse().unwrap()),
                other => panic!("{name}: type {other}"),
            };
            assert_eq!(read, c.value, "{name}");
        }
        let mut names: Vec<_> = TABLE.iter().map(|c| c.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), TABLE.len(), "a name twice");
    }
}
