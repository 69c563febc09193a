//! The bodies built last, by what they were built from: the species, where the aperture
//! sits and the cell size. A species edit rebuilds the body of each of its live slices
//! (a hundred in an aquarium), and every jellyfish moving to a live tier builds one, for
//! the same three mostly; a kept body is copied instead of built again, the same bits.

use super::Body;
use crate::species::Species;
use glam::Vec2;
use std::sync::{Arc, Mutex};

/// A body, by the species and the bits of its origin and cell size.
type Kept = (Species, [u32; 3], Arc<Body>);

/// A few species, a tier or two each.
const BODIES_KEPT: usize = 8;

/// The bodies built last, newest first.
static BODIES: Mutex<Vec<Kept>> = Mutex::new(Vec::new());

/// [`Body::build`], or a copy of the body built last from the same three.
pub(super) fn body(species: &Species, origin: Vec2, h: f32) -> Body {
    let key = [origin.x, origin.y, h].map(f32::to_bits);
    let known = BODIES.lock().ok().and_then(|kept| {
        kept.iter()
            .find(|(s, k, _)| *k == key && s == species)
            .map(|(.., body)| body.clone())
    });
    if let Some(known) = known {
        return Body::clone(&known);
    }
    let built = Body::build(species, origin, h);
    if let Ok(mut kept) = BODIES.lock() {
        kept.retain(|(s, k, _)| !(*k == key && s == species));
        kept.insert(0, (species.clone(), key, Arc::new(built.clone())));
        kept.truncate(BODIES_KEPT);
    }
    built
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::species::SliceGeometry;

    /// What a body was built with, to the bit (`{:?}` of a float is its shortest exact
    /// reading).
    fn reading(b: &Body) -> String {
        format!(
            "{:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
            b.points,
            b.bell,
            b.tentacles,
            b.springs,
            b.hinges,
            b.hoop_bends,
            b.muscles,
            b.damping_time.to_bits(),
            b.tentacle_drag,
            b.depth,
            b.mirror_partners,
        )
    }

    /// A kept body is the one built afresh, for every species, geometry and cell size
    /// asked for (more than are kept, so some are built again), and an edited species is
    /// never given the body of the one before.
    #[test]
    fn a_kept_body_is_the_one_built() {
        let mut species = vec![Species::aurelia(), Species::aequorea(), Species::sarsia()];
        let mut stiffer = Species::aequorea();
        stiffer.muscle_modulus *= 1.05;
        species.push(stiffer);
        for round in 0..2 {
            for s in &species {
                for geometry in [SliceGeometry::Planar, SliceGeometry::Axisymmetric] {
                    let s = Species {
                        slice_geometry: geometry,
                        ..s.clone()
                    };
                    for k in 0..3 {
                        let h = 0.0005 * (1.0 + k as f32);
                        let origin = Vec2::new(0.01 * k as f32, 0.02);
                        let built = Body::build(&s, origin, h);
                        let kept = Body::new(&s, origin, h);
                        assert_eq!(reading(&kept), reading(&built), "round {round}, h {h}");
                    }
                }
            }
        }
    }
}
