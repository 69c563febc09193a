//! The in-game species editor (feature `editor`): pick a loaded species, drag a slider,
//! and every jellyfish of that species changes on the next frame. Invalid values are
//! shown in the panel and not applied; a species resets to its preset (as first loaded)
//! or saves back to its RON file. A stats panel shows the frame rate, the jellyfish count
//! and the plugin's CPU time.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_jellyfish::{JellyfishEditorPlugin, JellyfishPlugin};
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, JellyfishPlugin::default(), JellyfishEditorPlugin::default()))
//!     .run();
//! ```
//!
//! Camera controllers should ignore the mouse while egui wants it: run them with
//! `run_if(not(bevy_egui::input::egui_wants_any_pointer_input))`.

mod panels;
pub mod params;
mod session;

pub use session::{SaveError, SpeciesEditor, write_species_file};

use crate::plugin::JellyfishSystems;
use crate::species::Species;
use bevy::diagnostic::FrameTimeDiagnosticsPlugin;
use bevy::prelude::*;
use bevy_egui::{EguiPlugin, EguiPostUpdateSet, EguiPreUpdateSet, EguiPrimaryContextPass};
use std::path::PathBuf;

/// Adds the species editor and stats windows (and [`EguiPlugin`] if the app has none).
/// Needs [`JellyfishPlugin`](crate::JellyfishPlugin).
#[derive(Clone, Debug)]
pub struct JellyfishEditorPlugin {
    /// The folder species files are saved into: the asset folder, as the asset server
    /// reads it (`assets/` beside the crate when run by cargo).
    pub assets_dir: PathBuf,
    /// Show the stats window.
    pub stats: bool,
}

impl Default for JellyfishEditorPlugin {
    fn default() -> Self {
        Self {
            assets_dir: bevy::asset::io::file::FileAssetReader::get_base_path().join("assets"),
            stats: true,
        }
    }
}

/// Where species are saved; set from [`JellyfishEditorPlugin::assets_dir`].
#[derive(Resource, Clone, Debug, Reflect)]
#[reflect(Resource)]
pub struct EditorConfig {
    /// The asset folder; species are saved as `species/<name>.species.ron` under it.
    pub assets_dir: PathBuf,
}

impl Plugin for JellyfishEditorPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<EguiPlugin>() {
            app.add_plugins(EguiPlugin::default());
        }
        if !app.is_plugin_added::<FrameTimeDiagnosticsPlugin>() {
            app.add_plugins(FrameTimeDiagnosticsPlugin::default());
        }
        app.insert_resource(EditorConfig {
            assets_dir: self.assets_dir.clone(),
        })
        .init_resource::<SpeciesEditor>()
        .register_type::<EditorConfig>()
        .register_type::<SpeciesEditor>()
        .add_systems(Update, remember_presets)
        // The editor's pass runs before the slices step, and egui's contexts are set up
        // before the jellyfish change tiers: both were the threads' choice.
        .configure_sets(
            PostUpdate,
            EguiPostUpdateSet::EndPass.before(JellyfishSystems::StepSlices),
        )
        .configure_sets(
            PreUpdate,
            EguiPreUpdateSet::InitContexts.before(JellyfishSystems::ChooseDetail),
        );
        if self.stats {
            // Drawn in one order, so the windows stack the same way every frame.
            app.add_systems(
                EguiPrimaryContextPass,
                (panels::species_window, panels::stats_window).chain(),
            );
        } else {
            app.add_systems(EguiPrimaryContextPass, panels::species_window);
        }
    }
}

/// A species' preset is its value when it first loaded.
pub fn remember_presets(
    mut events: MessageReader<AssetEvent<Species>>,
    assets: Res<Assets<Species>>,
    mut editor: ResMut<SpeciesEditor>,
) {
    for event in events.read() {
        if let AssetEvent::Added { id } | AssetEvent::LoadedWithDependencies { id } = event
            && let Some(species) = assets.get(*id)
        {
            editor.remember_preset(*id, species);
        }
    }
}
