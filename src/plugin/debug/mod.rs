//! A debug overlay of the simulation, drawn with gizmos (the `debug` feature), as physics
//! plugins ship theirs: every jellyfish's level of detail and reach, and for the ones
//! marked [`ShowSlice`] the slice itself in its plane through the bell — the water's
//! velocity, trace particles it carries (the paper's Fig. 6) and the body's springs
//! coloured by tension. What is drawn is chosen in the [`JellyfishGizmos`] gizmo group.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_jellyfish::plugin::{JellyfishDebugPlugin, JellyfishGizmos, ShowSlice};
//! use bevy_jellyfish::{Jellyfish, JellyfishPlugin};
//!
//! fn main() {
//!     App::new()
//!         .add_plugins((DefaultPlugins, JellyfishPlugin::default(), JellyfishDebugPlugin))
//!         .add_systems(Startup, |mut commands: Commands, assets: Res<AssetServer>| {
//!             let species = assets.load("species/aurelia.species.ron");
//!             commands.spawn((Jellyfish::new(species), ShowSlice));
//!         })
//!         // Springs only: no water.
//!         .add_systems(Startup, |mut store: ResMut<GizmoConfigStore>| {
//!             let (_, gizmos) = store.config_mut::<JellyfishGizmos>();
//!             gizmos.flow = false;
//!             gizmos.particles = false;
//!         })
//!         .run();
//! }
//! ```

mod slice;

use super::schedule::JellyfishSystems;
use super::slice::{JellyfishSlice, Tier};
use bevy::gizmos::GizmoPlugin;
use bevy::gizmos::config::GizmoConfigGroup;
use bevy::prelude::*;

pub use slice::TraceParticles;

/// Draws the overlay; adds Bevy's [`GizmoPlugin`] if the app has none (a headless app).
#[derive(Clone, Copy, Debug, Default)]
pub struct JellyfishDebugPlugin;

impl Plugin for JellyfishDebugPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<GizmoPlugin>() {
            app.add_plugins(GizmoPlugin);
        }
        app.init_gizmo_group::<JellyfishGizmos>()
            .register_type::<ShowSlice>()
            .add_systems(
                PostUpdate,
                (draw_reach, slice::draw_slices)
                    .after(JellyfishSystems::WriteTransforms)
                    .before(bevy::transform::TransformSystems::Propagate),
            );
    }
}

/// What the overlay draws; change it in the
/// [`GizmoConfigStore`](bevy::gizmos::config::GizmoConfigStore) (its line widths and
/// visibility are the group's [`GizmoConfig`](bevy::gizmos::config::GizmoConfig)).
#[derive(Clone, Debug, Reflect, GizmoConfigGroup)]
#[reflect(Default)]
pub struct JellyfishGizmos {
    /// A circle around every jellyfish, as far as its bell and fringe reach, coloured by
    /// its level of detail: near green, mid amber, far grey.
    pub reach: bool,
    /// On [`ShowSlice`] jellyfish: arrows of the slice's water velocity on a coarse
    /// lattice, the fastest one lattice step long.
    pub flow: bool,
    /// On [`ShowSlice`] jellyfish: particles carried by the slice's water.
    pub particles: bool,
    /// On [`ShowSlice`] jellyfish: every spring of the body, coloured by tension (red
    /// stretched, blue compressed).
    pub springs: bool,
}

impl Default for JellyfishGizmos {
    fn default() -> Self {
        Self {
            reach: true,
            flow: true,
            particles: true,
            springs: true,
        }
    }
}

/// Marks a jellyfish whose slice the overlay draws (drawing every slice of a school would
/// hide the school).
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component, Default)]
#[require(TraceParticles)]
pub struct ShowSlice;

/// The colour of a level of detail.
fn tier_color(tier: Tier) -> Color {
    match tier {
        Tier::Near => Color::srgb(0.3, 1.0, 0.4),
        Tier::Mid => Color::srgb(1.0, 0.75, 0.2),
        Tier::Far => Color::srgb(0.55, 0.55, 0.6),
    }
}

/// A circle facing the camera's usual view (in the jellyfish's own plane through its axis
/// and x) around each started jellyfish, its radius the bell's and the longest hanging
/// part's reach.
fn draw_reach(
    mut gizmos: Gizmos<JellyfishGizmos>,
    jellyfish: Query<(&JellyfishSlice, &GlobalTransform)>,
) {
    if !gizmos.config_ext.reach {
        return;
    }
    for (slice, global) in &jellyfish {
        let Some(species) = slice.species() else {
            continue;
        };
        let hanging = species.hanging_length();
        let local = 0.5 * species.diameter + hanging;
        let (scale, rotation, centre) = global.to_scale_rotation_translation();
        let isometry = Isometry3d::new(centre, rotation);
        gizmos.circle(
            isometry,
            local * scale.max_element(),
            tier_color(slice.tier()),
        );
    }
}
