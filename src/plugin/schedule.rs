//! The plugin's system sets, in the order they run, and the resources every part shares.
//!
//! Every system of the plugin is in one [`JellyfishSystems`] set; order your own systems
//! against them (steering before `StepSlices`, reading meshes after `RebuildMeshes`).

use super::settings::JellyfishSettings;
use super::timings::JellyfishTimings;
use bevy::asset::{AssetEventSystems, AssetTrackingSystems};
use bevy::camera::CameraUpdateSystems;
use bevy::camera::visibility::VisibilitySystems;
use bevy::prelude::*;
use bevy::transform::TransformSystems;
use bevy::transform::systems::sync_simple_transforms;

/// The plugin's systems, in the order they run within a frame.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JellyfishSystems {
    /// PreUpdate: species files loaded or refused, before anything reads them.
    LoadSpecies,
    /// PreUpdate: create slices for new jellyfish, apply species and settings edits.
    Prepare,
    /// PreUpdate: choose levels of detail and move jellyfish between them.
    ChooseDetail,
    /// PostUpdate: step the slices by the frame's virtual time, in parallel over jellyfish.
    StepSlices,
    /// PostUpdate: the water's disturbances felt (the tank's stirs sent, flashes and
    /// escapes started, echoes passed on) where each jellyfish is at its newest step.
    Touch,
    /// PostUpdate: move each jellyfish along its axis, blended between fixed steps.
    WriteTransforms,
    /// PostUpdate: rebuild meshes in place, before bounds and render extraction (and
    /// before the cameras' update: the frusta it culls by are the last frame's).
    RebuildMeshes,
    /// PostUpdate, the end of Bevy's transform propagation (in its set): each jellyfish's
    /// parts (its tentacles and glow layer) placed and bounded where their bell is, before
    /// anything reads their transforms and before Bevy culls.
    PlaceParts,
    /// PostUpdate, after Bevy's visibility propagation and before its culling: each part
    /// shown or hidden with its jellyfish (unless the part is itself made visible or
    /// hidden).
    ShowParts,
    /// PostUpdate, after Bevy's transform propagation and the assets' events: materials
    /// made, updated after edits and put on new meshes.
    Materials,
    /// FixedUpdate: schools set their members' headings (steer your own before
    /// `StepSlices` too, in any schedule before `PostUpdate`).
    SteerSchools,
    /// FixedUpdate: the tank's water steps, taking the jets gathered since the last tick.
    StepWater,
    /// FixedUpdate: the jellyfish's jets are gathered for the next tick of the water.
    StirWater,
    /// Last: the frame's figures handed to Bevy's diagnostics.
    Diagnostics,
    /// Last: the next steps of cycles recorded after an edit start, to run in the
    /// background while the frame is drawn and until the next frame's `ChooseDetail`.
    RecordCycles,
}

/// Orders the sets and inserts the shared resources: the settings (kept if the app already
/// has them) and the per-frame timings. Every other part of the plugin builds on it.
#[derive(Clone, Debug, Default)]
pub struct JellyfishSchedulePlugin {
    /// The settings inserted unless the app already has a `JellyfishSettings`.
    pub settings: JellyfishSettings,
}

impl Plugin for JellyfishSchedulePlugin {
    fn build(&self, app: &mut App) {
        if !app.world().contains_resource::<JellyfishSettings>() {
            app.insert_resource(self.settings.clone());
        }
        app.register_type::<JellyfishSettings>()
            .init_resource::<JellyfishTimings>()
            .configure_sets(
                PreUpdate,
                (
                    JellyfishSystems::LoadSpecies,
                    JellyfishSystems::Prepare,
                    JellyfishSystems::ChooseDetail,
                )
                    .chain()
                    .after(AssetTrackingSystems),
            )
            .configure_sets(
                PostUpdate,
                (
                    JellyfishSystems::StepSlices,
                    JellyfishSystems::Touch,
                    JellyfishSystems::WriteTransforms,
                    JellyfishSystems::RebuildMeshes,
                )
                    .chain()
                    .before(TransformSystems::Propagate)
                    .before(AssetEventSystems),
            )
            // The meshes are built with the cameras' frusta and state of the last frame,
            // both, whichever thread updates the cameras first.
            .configure_sets(
                PostUpdate,
                JellyfishSystems::RebuildMeshes.before(CameraUpdateSystems),
            )
            // Placing the parts finishes the propagation (they hold no `Transform`), so whatever reads transforms after it reads theirs placed.
            .configure_sets(
                PostUpdate,
                JellyfishSystems::PlaceParts
                    .in_set(TransformSystems::Propagate)
                    .after(sync_simple_transforms)
                    .before(VisibilitySystems::CheckVisibility),
            )
            // The parts are not children (`plugin::render::parts`): they take their
            // jellyfish's visibility once Bevy has worked it out.
            .configure_sets(
                PostUpdate,
                JellyfishSystems::ShowParts
                    .after(VisibilitySystems::VisibilityPropagate)
                    .before(VisibilitySystems::CheckVisibility),
            )
            .configure_sets(
                PostUpdate,
                // After the transforms (a tentacle's material follows its jellyfish's
                // scale) and the assets' events (an edit is read the frame it arrives; a
                // material made now is drawn from the next frame, when its own event is
                // sent). Before the events, the materials held up Bevy's culling: the
                // 10,002-jellyfish frame's p99 +3 ms.
                JellyfishSystems::Materials
                    .after(JellyfishSystems::RebuildMeshes)
                    .after(TransformSystems::Propagate)
                    .after(AssetEventSystems),
            )
            .configure_sets(
                FixedUpdate,
                (JellyfishSystems::StepWater, JellyfishSystems::StirWater).chain(),
            )
            .configure_sets(
                Last,
                JellyfishSystems::RecordCycles.after(JellyfishSystems::Diagnostics),
            );
    }
}
