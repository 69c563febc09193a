//! The drawn resolution of each species, worked out once for a run of jellyfish instead
//! of once for each: asked for every jellyfish twice a frame (is its template still the
//! one it needs, and what to build), it was 2% of the 10,002 frame's instructions.

use crate::plugin::settings::JellyfishSettings;
use crate::shape::mesh::Resolution;
use crate::species::Species;
use std::sync::Arc;

/// The drawn resolutions of the last few species asked about, known by their `Arc` (a
/// school's members share their species'). Held for one pass over the jellyfish only: a
/// species may be edited between frames. A handle to the heap, since Bevy's parallel
/// passes move their per-batch state in and out for every jellyfish (the resolutions
/// held in place were hundreds of bytes copied twice a jellyfish).
#[derive(Default)]
pub(crate) struct Resolutions {
    held: Vec<(Arc<Species>, Resolution)>,
    next: usize,
}

/// The most species held at once.
const HELD: usize = 4;

impl Resolutions {
    /// [`JellyfishSettings::resolution`] of `species`.
    pub(crate) fn of(
        &mut self,
        species: &Arc<Species>,
        settings: &JellyfishSettings,
    ) -> &Resolution {
        let at = match self.held.iter().position(|(s, _)| Arc::ptr_eq(s, species)) {
            Some(at) => at,
            None => {
                let held = (species.clone(), settings.resolution(species));
                if self.held.len() < HELD {
                    self.held.push(held);
                    self.held.len() - 1
                } else {
                    let at = self.next;
                    self.held[at] = held;
                    self.next = (at + 1) % HELD;
                    at
                }
            }
        };
        &self.held[at].1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each species' own resolution, whichever was asked about before it and however
    /// many: more species than it holds, asked about in turn, and two equal species that
    /// are different `Arc`s.
    #[test]
    fn each_species_gets_its_own_resolution() {
        let settings = JellyfishSettings {
            mesh_resolution_scale: 0.5,
            ..Default::default()
        };
        let species: Vec<Arc<Species>> = (0..7)
            .map(|i| {
                Arc::new(Species {
                    mesh_rings: 8 + 4 * (i % 6),
                    mesh_segments: 12 + 2 * i,
                    ..Species::aurelia()
                })
            })
            .collect();
        let mut memo = Resolutions::default();
        for round in 0..3 {
            for (i, s) in species.iter().enumerate() {
                let asked = if round == 1 { &species[6 - i] } else { s };
                assert_eq!(*memo.of(asked, &settings), settings.resolution(asked));
            }
        }
    }
}
