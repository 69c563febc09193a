//! The aquarium's own panel, beside the plugin's species editor and stats: how many
//! jellyfish of each species, and which seed places them.

use crate::school::School;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_jellyfish::JellyfishEditorPlugin;

pub fn plugin(app: &mut App) {
    app.add_plugins(JellyfishEditorPlugin::default())
        .add_systems(EguiPrimaryContextPass, school_window);
}

/// Edits a copy and writes the resource back only when it changed: a change respawns
/// every school.
fn school_window(mut contexts: EguiContexts, mut school: ResMut<School>) -> Result {
    let ctx = contexts.ctx_mut()?;
    let mut edited = *school;
    egui::Window::new("School")
        .anchor(egui::Align2::RIGHT_BOTTOM, [-10.0, -10.0])
        .resizable(false)
        .show(ctx, |ui| {
            egui::Grid::new("school").num_columns(2).show(ui, |ui| {
                ui.label("per species");
                ui.add(egui::Slider::new(&mut edited.per_species, 0..=334));
                ui.end_row();
                ui.label("seed");
                ui.add(egui::DragValue::new(&mut edited.seed));
                ui.end_row();
            });
            ui.label("left drag orbits, right drag pans, scroll zooms");
        });
    if edited.per_species != school.per_species || edited.seed != school.seed {
        *school = edited;
    }
    Ok(())
}
