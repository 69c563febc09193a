//! The bell and tentacles as a spring-mass system (paper section 3.2).

use crate::species::Species;

/// Mesoglea thickness at arc fraction `s` of the bell (0 at the apex, 1 at the margin), m.
///
/// Thickest at the apex (the paper's ϑ), thinning quadratically towards the margin, as in
/// the paper's Fig. 2 cross-sections.
pub fn mesoglea_thickness(species: &Species, s: f32) -> f32 {
    let s = s.clamp(0.0, 1.0);
    species.thickness * (1.0 - (1.0 - species.margin_thickness_ratio) * s * s)
}
