//! One jellyfish's surfaces, regenerated in place from its slice each frame.

use super::buffers::SurfaceBuffers;
use super::discs::angles;
use super::input::{ShapeError, check};
use super::noise_field::{NoiseField, NoiseKey};
use super::oral::{self, ORAL_SIDES, OralScratch, OralStyle};
use super::profile::Profile;
use super::tentacles::{self, TentacleLayout, TentacleScratch};
use super::umbrella::{self, Column};
use super::variation::Variation;
use crate::sim::SliceView;
use crate::species::Species;
use std::f32::consts::TAU;

/// Mesh resolution, from the species. Clamped to the ranges `Species::validate` allows, so
/// an unvalidated species still gives a well-formed mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Resolution {
    /// Rings per umbrella surface from the apex to the margin.
    pub rings: usize,
    /// Segments around the axis.
    pub segments: usize,
    /// How many tentacles and how finely each is drawn.
    pub tentacles: TentacleLayout,
    /// The manubrium and oral arms ([`oral`]), drawn after the tentacles.
    pub oral: TentacleLayout,
    /// Guide chains the tentacles bend between (`Species::guide_count`).
    pub guides: usize,
    /// Guide chains of the oral tubes, one per tube or none (`Species::oral_guide_count`).
    pub oral_guides: usize,
}

impl Resolution {
    /// The resolution a species asks for.
    pub fn of(species: &Species) -> Self {
        Self::scaled(species, 1.0)
    }

    /// The fringe's guides drawn for `species`, at any scale: its simulated guides, at
    /// most 16.
    pub fn guides_of(species: &Species) -> usize {
        species.guide_count().min(16)
    }

    /// The species' resolution with its rings and segments multiplied by `scale` (a
    /// drawing setting), clamped to what validation allows.
    pub fn scaled(species: &Species, scale: f32) -> Self {
        let scale = if scale.is_finite() {
            scale.max(0.0)
        } else {
            1.0
        };
        // At the default scale a count is itself: no rounding (a call into libm on the
        // baseline target, and this runs for every jellyfish every frame).
        let scaled = |n: u32, lo: u32, hi: u32| {
            let n = if scale == 1.0 {
                n as usize
            } else {
                (n as f32 * scale).round() as usize
            };
            n.clamp(lo as usize, hi as usize)
        };
        let rings = scaled(species.mesh_rings, 2, 256);
        use crate::species::limits::{MAX_DRAWN_ORAL_TUBES, oral_tubes};
        let oral = oral_tubes(species).min(MAX_DRAWN_ORAL_TUBES);
        Self {
            rings,
            segments: scaled(species.mesh_segments, 3, 512),
            tentacles: TentacleLayout {
                // No length, no tubes (rather than a ring of zero-length ones).
                count: if species.tentacle_length > 0.0 {
                    species.tentacle_count.min(256) as usize
                } else {
                    0
                },
                sides: species.tentacle_sides.clamp(3, 32) as usize,
                points: crate::species::limits::tentacle_points(species, rings),
            },
            oral: TentacleLayout {
                count: oral,
                sides: ORAL_SIDES,
                points: rings + 1,
            },
            guides: Self::guides_of(species),
            oral_guides: species.oral_guide_count(),
        }
    }

    /// Vertices of the umbrella at this resolution.
    pub fn umbrella_vertices(&self) -> usize {
        umbrella::vertex_count(self.rings, self.segments)
    }

    /// Vertices of the hanging parts at this resolution: all tentacles, the manubrium and
    /// the oral arms.
    pub fn tentacle_vertices(&self) -> usize {
        self.tentacles.vertex_count() + self.oral.vertex_count()
    }
}

/// The umbrella and the hanging parts (tentacles, manubrium, oral arms) of one jellyfish:
/// two meshes for the plugin.
///
/// Topology (indices, UVs, buffer lengths) is fixed by the [`Resolution`]; a frame at the
/// same resolution only overwrites positions and normals, so no buffer reallocates.
/// With no tentacles the tentacle buffers are empty: don't hand them to Bevy then.
#[derive(Clone, Debug, Default)]
pub struct JellyMesh {
    /// The bell: exumbrella, subumbrella and the margin between them.
    pub umbrella: SurfaceBuffers,
    /// Every tentacle as a tube, then the manubrium and the oral arms.
    pub tentacles: SurfaceBuffers,
    resolution: Option<Resolution>,
    scratch: Scratch,
}

#[derive(Clone, Debug, Default)]
struct Scratch {
    profile: Profile,
    angles: Vec<(f32, f32)>,
    columns: Vec<Column>,
    tentacles: TentacleScratch,
    oral: OralScratch,
    noise: NoiseField,
}

impl JellyMesh {
    /// Empty buffers; the first [`build_into`] sizes them.
    pub fn new() -> Self {
        Self::default()
    }

    /// Builds the surfaces of one slice. `seed` picks the individual, `time` (s) moves
    /// its noise.
    pub fn from_slice(
        view: &SliceView,
        species: &Species,
        seed: u32,
        time: f32,
    ) -> Result<Self, ShapeError> {
        let mut mesh = Self::new();
        build_into(&mut mesh, view, species, seed, time)?;
        Ok(mesh)
    }

    /// The resolution of the current buffers, once built.
    pub fn resolution(&self) -> Option<Resolution> {
        self.resolution
    }
}

/// Regenerates `mesh` from a slice, in place, at the species' resolution.
///
/// On error the buffers keep the last good frame. Changing the species' resolution
/// rebuilds the topology (and may reallocate) once.
pub fn build_into(
    mesh: &mut JellyMesh,
    view: &SliceView,
    species: &Species,
    seed: u32,
    time: f32,
) -> Result<(), ShapeError> {
    build_at(mesh, view, species, Resolution::of(species), seed, time)
}

/// [`build_into`] at a given resolution.
pub fn build_at(
    mesh: &mut JellyMesh,
    view: &SliceView,
    species: &Species,
    res: Resolution,
    seed: u32,
    time: f32,
) -> Result<(), ShapeError> {
    check(view, species, time)?;
    let s = &mut mesh.scratch;
    if mesh.resolution != Some(res) {
        umbrella::write_topology(res.rings, res.segments, &mut mesh.umbrella);
        mesh.tentacles.reset(res.tentacle_vertices());
        tentacles::write_topology(&res.tentacles, 0, &mut mesh.tentacles);
        let first = res.tentacles.vertex_count();
        tentacles::write_topology(&res.oral, first, &mut mesh.tentacles);
        angles(res.segments, &mut s.angles);
        s.noise.set_samples(
            umbrella::noise_samples(&s.angles, res.rings)
                .chain(tentacles::noise_samples(&res.tentacles)),
        );
        mesh.resolution = Some(res);
    }
    let variation = Variation::new(species, seed, time);
    s.noise.update(
        &variation,
        NoiseKey {
            seed,
            lat_frequency_bits: species.noise_frequency_lat.to_bits(),
            lon_frequency_bits: species.noise_frequency_lon.to_bits(),
        },
    );
    let (umbrella_noise, tentacle_noise) = s.noise.values.split_at(res.rings * res.segments);
    s.columns.clear();
    s.columns.extend((0..res.segments).map(|j| {
        let sigma = TAU * j as f32 / res.segments as f32;
        Column {
            lobe: variation.structural(sigma, 1.0),
            ripple: variation.compression(sigma, 1.0, 1.0),
        }
    }));
    s.profile
        .build(view.bell, view.rest_bell, species, res.rings);
    umbrella::write_surface(
        &s.profile,
        &s.angles,
        &s.columns,
        umbrella_noise,
        &variation,
        &mut mesh.umbrella,
    );
    let n = view.bell.len();
    tentacles::write_surface(
        &res.tentacles,
        view.tentacles,
        &view.trail,
        [view.bell[0], view.bell[n - 1]],
        s.profile.margin(),
        species.tentacle_radius,
        tentacle_noise,
        &variation,
        &mut mesh.tentacles,
        &mut s.tentacles,
    );
    oral::write_surface(
        &res.oral,
        res.tentacles.vertex_count(),
        &OralStyle::of(species),
        view.oral_arms,
        &view.oral_trail,
        view.bell[n / 2],
        &aperture_disc(s.profile.margin()),
        &mut mesh.tentacles,
        &mut s.oral,
    );
    Ok(())
}

/// The aperture's disc, whose radial directions orient the tentacles and the oral arms.
pub(crate) fn aperture_disc(margin: &super::profile::RingPair) -> super::discs::Disc {
    super::discs::Disc::through(margin.subumbrella[0], margin.subumbrella[1], glam::Vec2::X)
}
