//! The plugin's system sets, in the order they run, and the resources every part shares.
//!
//! Every system of the plugin is in one [`JellyfishSystems`] set; order your own systems
//! against them (steering before `StepSlices`, reading meshes after `RebuildMeshes`).

use super::settings::JellyfishSettings;
use super::timings::JellyfishTimings;
use bevy::asset::{AssetEventSystems, AssetTrackingSystems};
use bevy::camera::visibility::VisibilitySystems;
use bevy::prelude::*;
use bevy::transform::TransformSystems;

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
    /// PostUpdate: move each jellyfish along its axis, blended between fixed steps.
    WriteTransforms,
    /// PostUpdate: rebuild meshes in place, before bounds and render extraction.
    RebuildMeshes,
    /// PostUpdate, after Bevy's transform propagation: each jellyfish's parts (its
    /// tentacles and glow layer) placed and bounded where their bell is, before Bevy culls.
    PlaceParts,
    /// PostUpdate: materials made, updated after edits and put on new meshes.
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
                    JellyfishSystems::WriteTransforms,
                    JellyfishSystems::RebuildMeshes,
                )
                    .chain()
                    .before(TransformSystems::Propagate)
                    .before(AssetEventSystems),
            )
            .configure_sets(
                PostUpdate,
                JellyfishSystems::PlaceParts
                    .after(TransformSystems::Propagate)
                    .before(VisibilitySystems::CheckVisibility),
            )
            .configure_sets(
                PostUpdate,
                JellyfishSystems::Materials.after(JellyfishSystems::RebuildMeshes),
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
