//! One table of limits: for every numeric field of [`Species`], the range it may take, in
//! its unit, and what breaks beyond it. Validation, the species loader (through
//! validation) and the editor's sliders all read this table; a value outside is an error
//! naming the field and the range.
//!
//! A few limits join fields: the bell's proportions, and two budgets a value inside every
//! range could still exceed — the slice's cost per simulated second and the mesh's vertex
//! count. Those are checked after the table, and the error names the field that tips it.

pub use super::cost::{MAX_COST_PER_SECOND, simulation_cost, simulation_cost_terms};
use super::{Bending, Species, SpeciesError};

/// The range one field may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    /// The field, as named in [`Species`], RON files and errors (array elements as
    /// `bell_color[3]`).
    pub field: &'static str,
    /// The least allowed value.
    pub min: f64,
    /// The greatest allowed value.
    pub max: f64,
    /// The field's unit as a suffix (empty for pure numbers).
    pub unit: &'static str,
    /// What breaks beyond the range.
    pub why: &'static str,
}

impl Limit {
    /// Whether `value` is finite and in the range. The fields are `f32`: the ends are
    /// rounded to `f32` too, so a field set to an end is inside.
    pub fn admits(&self, value: f64) -> bool {
        let (min, max) = (self.min as f32 as f64, self.max as f32 as f64);
        value.is_finite() && value >= min && value <= max
    }

    /// The range, readable: `[0.3, 1]`, `[2, 1000] mm`.
    pub fn range(&self) -> String {
        format!(
            "[{}, {}]{}",
            trim(self.min),
            trim(self.max),
            if self.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", self.unit)
            }
        )
    }

    fn check(&self, value: f64) -> Result<(), SpeciesError> {
        if self.admits(value) {
            return Ok(());
        }
        Err(SpeciesError::invalid(
            self.field,
            format!(
                "must be in {} ({}), got {}",
                self.range(),
                self.why,
                trim(value)
            ),
        ))
    }
}

/// A number without trailing zeros or float noise.
fn trim(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let s = format!("{:.6}", v);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "0" && v != 0.0 || v.abs() >= 1e6 || (v != 0.0 && v.abs() < 1e-4) {
        format!("{v:e}")
    } else {
        s.to_string()
    }
}

macro_rules! limit {
    ($field:literal, $min:expr, $max:expr, $unit:literal, $why:literal) => {
        Limit {
            field: $field,
            min: $min,
            max: $max,
            unit: $unit,
            why: $why,
        }
    };
}

/// The table, in the order of [`Species`]' fields.
#[rustfmt::skip]
pub const LIMITS: &[Limit] = &[
    limit!("grid_resolution", 24.0, 192.0, "cells", "fewer leave the default bell a few cells wide and it stops swimming; a step's cost grows with the square"),
    limit!("viscosity", 1e-4, 10.0, "Pa·s", "below a tenth of water's the grid's own viscosity dominates; above honey's the diffusion substeps are capped and nothing swims anyway"),
    limit!("density", 500.0, 2000.0, "kg/m³", "the density of liquids; far outside, the bell's implicit forces and the water's mass disagree"),
    limit!("domain_diameters", 3.0, 20.0, "diameters", "a smaller box has no room for the wake; a larger one spends its cells on far water"),
    limit!("boundary_width", 0.1, 1.0, "diameters", "narrower than the bell's wall the bell leaks; wider, it smears into a blob that stops swimming"),
    limit!("diameter", 0.002, 1.0, "m", "hydromedusae of a few millimetres to scyphozoans of a metre; beyond, the slice's geometry overflows"),
    limit!("height", 0.001, 2.0, "m", "with at most twice the diameter (below): taller bells fold"),
    limit!("thickness", 1e-4, 0.25, "m", "with at most half the diameter and the height (below): thicker walls fill the bell"),
    limit!("margin_thickness_ratio", 0.05, 1.0, "", "a thinner margin is a fringe of single points"),
    limit!("elastic_modulus", 10.0, 1e5, "Pa", "softer mesoglea cannot hold the bell against its water; stiffer, the hinges and hoops outrun the implicit step and the bell shivers"),
    limit!("angular_stiffness", 1e-7, 125.0, "N·m/rad", "without bending the bell folds; stiffer than 1, or than (D / 0.2 m)³ for a bell wider than 20 cm (below), the implicit step cannot keep up and the bell shivers (a 155 mm moon jelly's 19 mm apex needs 0.36, a metre-wide one's 97)"),
    limit!("mesoglea_resilience", 0.05, 1.0, "", "a bell that returns less of its energy barely re-expands; more than all of it is no material"),
    limit!("muscle_modulus", 1e3, 1e8, "Pa", "muscle fibres: soft gel to stiff collagen"),
    limit!("muscle_cross_section", 1e-5, 1.0, "", "a fraction of the wall"),
    limit!("hoop_cross_section", 1e-5, 1.0, "", "a fraction of the wall; beyond it the hoop outruns the implicit step"),
    limit!("contraction_frequency", 0.05, 5.0, "Hz", "slower strokes are rest; faster ones need more steps than a frame can pay for"),
    limit!("natural_frequency", 0.05, 5.0, "Hz", "the animal's own pulse rate: as the contraction frequency"),
    limit!("natural_diameter", 0.002, 1.0, "m", "the size that rate was measured at: as the diameter"),
    limit!("contraction_ratio", 0.3, 1.0, "", "deeper contractions fold the margin into the apex"),
    limit!("contraction_duty", 0.1, 0.9, "", "the contraction or the re-expansion needs a tenth of the cycle"),
    limit!("relaxation_span", 0.1, 1.0, "", "a fraction of the time between contractions; quicker, the muscle snaps back"),
    limit!("muscle_extent", 0.1, 1.0, "", "a fraction of the subumbrella's arc from the margin: at least the margin's ring, at most all of it"),
    limit!("expansion_stagger", 0.0, 1.0, "", "between unison and the paper's staggered expansion"),
    limit!("tentacle_count", 0.0, 256.0, "", "each tentacle is a tube of the mesh"),
    limit!("tentacle_length", 0.0, 2.0, "m", "with at most ten bell diameters (below): longer chains leave the box"),
    limit!("tentacle_cross_section", 1e-4, 1.0, "", "a fraction of the margin's wall"),
    limit!("tentacle_radius", 1e-5, 0.05, "m", "with at most a twentieth of the diameter (below)"),
    limit!("tentacle_length_spread", 0.0, 0.9, "", "a fraction of the length; a tentacle drawn shorter than a tenth of it is a stub"),
    limit!("tentacle_guides", 0.0, 16.0, "", "each guide adds 36 bytes to the packed shape (and, with any, each oral tube 36 more); a current and a turn are the first two harmonics around the margin"),
    limit!("manubrium_length", 0.0, 4.0, "m", "with at most four bell diameters (below): a prolate medusa's hangs up to two and a half times the bell's height, and it is carried one way, as the oral arms are"),
    limit!("manubrium_radius", 1e-5, 0.25, "m", "with at most a quarter of the diameter (below)"),
    limit!("oral_arm_count", 0.0, 32.0, "", "each arm is a blade of the mesh"),
    limit!("oral_arm_length", 0.0, 5.0, "m", "with at most five bell diameters (below): longer arms trail out of the slice's box"),
    limit!("oral_arm_width", 1e-5, 0.5, "m", "with at most half the diameter (below)"),
    limit!("oral_arm_frill", 0.0, 2.0, "× width", "deeper ruffles fold the blade through itself"),
    limit!("gonad_count", 0.0, 128.0, "", "more gonads than the pattern's texels blur into a ring"),
    limit!("gonad_size", 0.0, 1.0, "× span", "a fraction of the subumbrella from apex to margin"),
    limit!("gonad_color[0]", 0.0, 1.0, "", "linear red"),
    limit!("gonad_color[1]", 0.0, 1.0, "", "linear green"),
    limit!("gonad_color[2]", 0.0, 1.0, "", "linear blue"),
    limit!("gonad_color[3]", 0.0, 1.0, "", "opacity"),
    limit!("radial_canal_count", 0.0, 256.0, "", "more canals than the pattern's texels blur together"),
    limit!("canal_width", 0.0, 0.2, "× span", "wider canals cover the bell"),
    limit!("structural_scale", 0.0, 2.0, "× thickness", "larger lobes turn the bell inside out"),
    limit!("structural_frequency", 0.0, 64.0, "lobes", "more lobes than the mesh has segments alias"),
    limit!("compression_scale", 0.0, 1.0, "× thickness", "larger ripples cross the subumbrella"),
    limit!("compression_frequency", 0.0, 64.0, "ripples", "more ripples than the mesh has segments alias"),
    limit!("unstructured_scale", 0.0, 4.0, "× thickness", "larger noise turns the bell inside out"),
    limit!("noise_frequency_lat", 0.0, 64.0, "", "finer noise than the mesh's rings aliases (and overflows the noise field)"),
    limit!("noise_frequency_lon", 0.0, 256.0, "", "finer noise than the mesh's segments aliases (and overflows the noise field)"),
    limit!("noise_frequency_time", 0.0, 10.0, "/s", "faster noise flickers"),
    limit!("mesh_rings", 2.0, 128.0, "", "with the vertex budget (below)"),
    limit!("mesh_segments", 3.0, 256.0, "", "with the vertex budget (below)"),
    limit!("tentacle_sides", 3.0, 32.0, "", "with the vertex budget (below)"),
    limit!("bell_color[0]", 0.0, 1.0, "", "linear red"),
    limit!("bell_color[1]", 0.0, 1.0, "", "linear green"),
    limit!("bell_color[2]", 0.0, 1.0, "", "linear blue"),
    limit!("bell_color[3]", 0.0, 1.0, "", "opacity"),
    limit!("glow_color[0]", 0.0, 16.0, "", "linear red, HDR"),
    limit!("glow_color[1]", 0.0, 16.0, "", "linear green, HDR"),
    limit!("glow_color[2]", 0.0, 16.0, "", "linear blue, HDR"),
    limit!("glow", 0.0, 16.0, "", "brighter saturates bloom"),
    limit!("glow_band", 0.0, 16.0, "", "brighter saturates bloom"),
    limit!("flash", 0.0, 64.0, "", "brighter saturates bloom"),
    limit!("flash_decay", 0.05, 10.0, "s", "quicker is a flicker; slower, a lamp"),
    limit!("flash_refractory", 0.0, 60.0, "s", "longer, a touched animal hardly ever flashes"),
    limit!("touch_reach", 0.25, 10.0, "diameters", "nearer misses a touch on the bell's rim; farther, a touch across the tank"),
    limit!("echo_reach", 0.0, 20.0, "diameters", "farther, one touch lights a whole school"),
    limit!("echo_delay", 0.02, 5.0, "s", "sooner is one flash; later, not an answer to it"),
    limit!("escape_depth", 0.0, 1.0, "", "a fraction of the stroke's depth; with the contraction ratio (below)"),
    limit!("escape_rhythm", 1.0, 3.0, "", "times the pulse rate; quicker, the bell cannot refill"),
    limit!("escape_strokes", 0.0, 10.0, "", "longer is a new rhythm, not an escape"),
];

/// The limit of `field`, if it has one (numeric fields do).
pub fn of(field: &str) -> Option<&'static Limit> {
    LIMITS.iter().find(|l| l.field == field)
}

/// Most vertices one jellyfish's mesh may have: the plugin rebuilds and uploads it every
/// frame, at about 0.3 µs a vertex on one core (50,000 vertices: 0.9 s of each second at
/// 60 Hz). The default moon jelly has under 10,000.
pub const MAX_MESH_VERTICES: usize = 50_000;

/// The species' numeric fields with their table names.
fn values(s: &Species) -> Vec<(&'static str, f64)> {
    vec![
        ("grid_resolution", s.grid_resolution as f64),
        ("viscosity", s.viscosity as f64),
        ("density", s.density as f64),
        ("domain_diameters", s.domain_diameters as f64),
        ("boundary_width", s.boundary_width as f64),
        ("diameter", s.diameter as f64),
        ("height", s.height as f64),
        ("thickness", s.thickness as f64),
        ("margin_thickness_ratio", s.margin_thickness_ratio as f64),
        ("elastic_modulus", s.elastic_modulus as f64),
        ("angular_stiffness", s.angular_stiffness as f64),
        ("mesoglea_resilience", s.mesoglea_resilience as f64),
        ("muscle_modulus", s.muscle_modulus as f64),
        ("muscle_cross_section", s.muscle_cross_section as f64),
        ("hoop_cross_section", s.hoop_cross_section as f64),
        ("contraction_frequency", s.contraction_frequency as f64),
        ("natural_frequency", s.natural_frequency as f64),
        ("natural_diameter", s.natural_diameter as f64),
        ("contraction_ratio", s.contraction_ratio as f64),
        ("contraction_duty", s.contraction_duty as f64),
        ("relaxation_span", s.relaxation_span as f64),
        ("muscle_extent", s.muscle_extent as f64),
        ("expansion_stagger", s.expansion_stagger as f64),
        ("tentacle_count", s.tentacle_count as f64),
        ("tentacle_length", s.tentacle_length as f64),
        ("tentacle_cross_section", s.tentacle_cross_section as f64),
        ("tentacle_radius", s.tentacle_radius as f64),
        ("tentacle_length_spread", s.tentacle_length_spread as f64),
        ("tentacle_guides", s.tentacle_guides as f64),
        ("manubrium_length", s.manubrium_length as f64),
        ("manubrium_radius", s.manubrium_radius as f64),
        ("oral_arm_count", s.oral_arm_count as f64),
        ("oral_arm_length", s.oral_arm_length as f64),
        ("oral_arm_width", s.oral_arm_width as f64),
        ("oral_arm_frill", s.oral_arm_frill as f64),
        ("gonad_count", s.gonad_count as f64),
        ("gonad_size", s.gonad_size as f64),
        ("gonad_color[0]", s.gonad_color[0] as f64),
        ("gonad_color[1]", s.gonad_color[1] as f64),
        ("gonad_color[2]", s.gonad_color[2] as f64),
        ("gonad_color[3]", s.gonad_color[3] as f64),
        ("radial_canal_count", s.radial_canal_count as f64),
        ("canal_width", s.canal_width as f64),
        ("structural_scale", s.structural_scale as f64),
        ("structural_frequency", s.structural_frequency as f64),
        ("compression_scale", s.compression_scale as f64),
        ("compression_frequency", s.compression_frequency as f64),
        ("unstructured_scale", s.unstructured_scale as f64),
        ("noise_frequency_lat", s.noise_frequency_lat as f64),
        ("noise_frequency_lon", s.noise_frequency_lon as f64),
        ("noise_frequency_time", s.noise_frequency_time as f64),
        ("mesh_rings", s.mesh_rings as f64),
        ("mesh_segments", s.mesh_segments as f64),
        ("tentacle_sides", s.tentacle_sides as f64),
        ("bell_color[0]", s.bell_color[0] as f64),
        ("bell_color[1]", s.bell_color[1] as f64),
        ("bell_color[2]", s.bell_color[2] as f64),
        ("bell_color[3]", s.bell_color[3] as f64),
        ("glow_color[0]", s.glow_color[0] as f64),
        ("glow_color[1]", s.glow_color[1] as f64),
        ("glow_color[2]", s.glow_color[2] as f64),
        ("glow", s.glow as f64),
        ("glow_band", s.glow_band as f64),
        ("flash", s.flash as f64),
        ("flash_decay", s.flash_decay as f64),
        ("flash_refractory", s.flash_refractory as f64),
        ("touch_reach", s.touch_reach as f64),
        ("echo_reach", s.echo_reach as f64),
        ("echo_delay", s.echo_delay as f64),
        ("escape_depth", s.escape_depth as f64),
        ("escape_rhythm", s.escape_rhythm as f64),
        ("escape_strokes", s.escape_strokes as f64),
    ]
}

/// Vertices of the species' mesh: both umbrella surfaces (an apex vertex and `rings`
/// rings of `segments + 1`), the tentacles (two caps and [`tentacle_points`] rings of
/// `sides + 1` each) and the oral tubes (`rings + 1` rings of [`ORAL_SIDES`]` + 1`).
/// `shape::Resolution` builds exactly this (a test holds them equal).
pub fn mesh_vertices(s: &Species) -> usize {
    let (rings, segments) = (s.mesh_rings as usize, s.mesh_segments as usize);
    let umbrella = 2 * (1 + rings * (segments + 1));
    let tentacles = if s.tentacle_length > 0.0 {
        s.tentacle_count as usize
            * (2 + tentacle_points(s, rings) * (s.tentacle_sides as usize + 1))
    } else {
        0
    };
    umbrella + tentacles + oral_tubes(s) * (2 + (rings + 1) * (ORAL_SIDES + 1))
}

/// Rings along each tentacle for a bell of `rings` rings: half the bell's for a tentacle a
/// bell diameter long or longer (a thin tube bends smoothly with fewer), in proportion for
/// shorter ones, at least three. A moon jelly's short fringe is most of its vertices.
pub fn tentacle_points(s: &Species, rings: usize) -> usize {
    let most = rings / 2 + 1;
    let share = (s.tentacle_length / s.diameter).clamp(0.0, 1.0);
    let share = if share.is_finite() { share } else { 1.0 };
    (rounded(share * (rings / 2) as f32) + 1).clamp(3.min(most), most)
}

/// `x.round()` as a count, for `x` in [0, 2²³]: the same number without the call into
/// libm that `f32::round` is on the baseline x86-64 target (a mesh's resolution is asked
/// for every jellyfish every frame).
pub(crate) fn rounded(x: f32) -> usize {
    let whole = x as usize;
    whole + usize::from(x - whole as f32 >= 0.5)
}

/// Sides of the manubrium's and the oral arms' tubes: eight, so a blade has two edges.
pub const ORAL_SIDES: usize = 8;

/// The most oral tubes a mesh draws (an unvalidated species may ask for more).
pub const MAX_DRAWN_ORAL_TUBES: usize = 64;

/// Tubes hanging from the subumbrellar apex: the manubrium (if it has a length) and the
/// oral arms (if they have one).
pub fn oral_tubes(s: &Species) -> usize {
    let manubrium = (s.manubrium_length > 0.0) as usize;
    let arms = if s.oral_arm_length > 0.0 {
        s.oral_arm_count as usize
    } else {
        0
    };
    manubrium + arms
}

/// Checks every field against the table, then the limits that join fields.
/// The stiffest bending the implicit step keeps up with on a bell `diameter` wide, N·m/rad:
/// 1, and for a bell wider than 20 cm (D / 0.2 m)³. A bigger bell takes a longer step and
/// its points drag more water, which holds stiffer hinges: measured, an isometrically grown
/// moon jelly (its plate as the size cubed) swims whole to a metre, where the fixed cap of
/// 1 N·m/rad refused it above 22 cm; at 40 mm, 100 N·m/rad restarts it.
pub fn stiffest_bending(diameter: f32) -> f64 {
    (diameter as f64 / 0.2).powi(3).max(1.0)
}

pub(super) fn validate(s: &Species) -> Result<(), SpeciesError> {
    for (field, value) in values(s) {
        of(field)
            .expect("every numeric field has a limit")
            .check(value)?;
    }
    let joint = |field: &'static str, reason: String| Err(SpeciesError::invalid(field, reason));
    if s.height > 2.0 * s.diameter {
        return joint(
            "height",
            format!(
                "must be at most twice the diameter ({} m), got {} m",
                2.0 * s.diameter,
                s.height
            ),
        );
    }
    if s.thickness > 0.5 * s.diameter.min(2.0 * s.height) {
        return joint(
            "thickness",
            format!(
                "must be at most {} m (half the diameter and the height), got {} m",
                0.5 * s.diameter.min(2.0 * s.height),
                s.thickness
            ),
        );
    }
    // The mesoglea's own bending is held to the springs' limit: the implicit step meets
    // the same hinges either way.
    let springs = of("angular_stiffness").expect("a listed field");
    let stiffest = stiffest_bending(s.diameter);
    let plate = s.bending_stiffness() as f64;
    if s.bending == Bending::Mesoglea && !(springs.min..=stiffest).contains(&plate) {
        let remedy = if plate < springs.min {
            "thicker or stiffer"
        } else {
            "thinner or softer"
        };
        return joint(
            "bending",
            format!(
                "the mesoglea bends as a plate, E·ϑ³/12 per 2 mm of hinge: {} N·m/rad from \
                 elastic_modulus {} Pa and thickness {} m, outside [{}, {}] N·m/rad for a \
                 bell {} m wide ({}); make the wall {remedy}, or take bending: Springs",
                trim(plate),
                s.elastic_modulus,
                s.thickness,
                trim(springs.min),
                trim(stiffest),
                s.diameter,
                springs.why
            ),
        );
    }
    if s.bending == Bending::Springs && s.angular_stiffness as f64 > stiffest {
        return joint(
            "angular_stiffness",
            format!(
                "must be at most {} N·m/rad for a bell {} m wide ({}), got {}",
                trim(stiffest),
                s.diameter,
                springs.why,
                s.angular_stiffness
            ),
        );
    }
    let deepest = 1.0 - (1.0 - s.contraction_ratio) * (1.0 + s.escape_depth);
    if deepest < 0.1 {
        return joint(
            "escape_depth",
            format!(
                "an escape would contract the muscle to {deepest} of its length (contraction \
                 ratio {}, depth {}): at least 0.1 keeps the bell from folding",
                s.contraction_ratio, s.escape_depth
            ),
        );
    }
    if s.tentacle_length > 10.0 * s.diameter {
        return joint(
            "tentacle_length",
            format!(
                "must be at most ten diameters ({} m), got {} m",
                10.0 * s.diameter,
                s.tentacle_length
            ),
        );
    }
    if s.tentacle_radius > 0.05 * s.diameter {
        return joint(
            "tentacle_radius",
            format!(
                "must be at most a twentieth of the diameter ({} m), got {} m",
                0.05 * s.diameter,
                s.tentacle_radius
            ),
        );
    }
    for (field, value, most, of_what) in [
        (
            "manubrium_length",
            s.manubrium_length,
            4.0 * s.diameter,
            "four diameters",
        ),
        (
            "manubrium_radius",
            s.manubrium_radius,
            0.25 * s.diameter,
            "a quarter of the diameter",
        ),
        (
            "oral_arm_length",
            s.oral_arm_length,
            5.0 * s.diameter,
            "five diameters",
        ),
        (
            "oral_arm_width",
            s.oral_arm_width,
            0.5 * s.diameter,
            "half the diameter",
        ),
    ] {
        if value > most {
            return joint(
                field,
                format!("must be at most {of_what} ({most} m), got {value} m"),
            );
        }
    }
    let vertices = mesh_vertices(s);
    if vertices > MAX_MESH_VERTICES {
        // Name the field that contributes most: the tentacles or the umbrella.
        let tentacles = vertices - 2 * (1 + s.mesh_rings as usize * (s.mesh_segments as usize + 1));
        let field = if tentacles * 2 > vertices {
            "tentacle_count"
        } else {
            "mesh_segments"
        };
        return joint(
            field,
            format!(
                "the mesh would have {vertices} vertices, more than {MAX_MESH_VERTICES} \
                 (mesh_rings {}, mesh_segments {}, tentacle_count {}, tentacle_sides {})",
                s.mesh_rings, s.mesh_segments, s.tentacle_count, s.tentacle_sides
            ),
        );
    }
    let cost = simulation_cost(s);
    if cost > MAX_COST_PER_SECOND {
        return joint(
            "grid_resolution",
            format!(
                "a simulated second would cost about {cost:.2} s of one core, more than \
                 {MAX_COST_PER_SECOND} s: {} cells per side, {} steps per cycle at {} Hz \
                 (a coarser grid, a slower stroke or a larger box costs less)",
                s.grid_resolution,
                s.steps_per_cycle(),
                s.contraction_frequency
            ),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_limit_is_a_range_with_a_reason() {
        for l in LIMITS {
            assert!(
                l.min < l.max && l.min.is_finite() && l.max.is_finite(),
                "{}",
                l.field
            );
            assert!(!l.why.is_empty(), "{}", l.field);
        }
        let names: Vec<_> = values(&Species::aurelia())
            .into_iter()
            .map(|(f, _)| f)
            .collect();
        let table: Vec<_> = LIMITS.iter().map(|l| l.field).collect();
        assert_eq!(names, table, "the table and the fields agree, in order");
    }

    #[test]
    fn a_value_outside_names_the_field_and_the_range() {
        let s = Species {
            contraction_ratio: 0.2,
            ..Species::aurelia()
        };
        let e = s.validate().unwrap_err();
        assert_eq!(e.field(), Some("contraction_ratio"));
        assert!(e.to_string().contains("[0.3, 1]"), "{e}");
    }

    #[test]
    fn ranges_read_well() {
        assert_eq!(of("diameter").unwrap().range(), "[0.002, 1] m");
        assert_eq!(of("viscosity").unwrap().range(), "[0.0001, 10] Pa·s");
        assert_eq!(
            of("angular_stiffness").unwrap().range(),
            "[1e-7, 125] N·m/rad"
        );
    }
}
