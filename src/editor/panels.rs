//! The editor's egui windows: the species editor and the stats panel.

use super::EditorConfig;
use super::params::species_controls;
use super::session::SpeciesEditor;
use crate::plugin::{JellyfishDiagnostics, JellyfishSettings};
use crate::species::Species;
use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore, FrameTimeDiagnosticsPlugin};
use bevy::prelude::*;
use bevy_egui::{EguiContexts, egui};

const ERROR: egui::Color32 = egui::Color32::from_rgb(255, 110, 100);

/// The loaded species, labelled by file (or name) and sorted, for the picker.
fn species_list(assets: &Assets<Species>, server: &AssetServer) -> Vec<(AssetId<Species>, String)> {
    let mut list: Vec<_> = assets
        .iter()
        .map(|(id, species)| {
            let label = match server.get_path(id) {
                Some(path) => format!("{} ({})", species.name, path.path().display()),
                None => species.name.clone(),
            };
            (id, label)
        })
        .collect();
    list.sort_by(|a, b| a.1.cmp(&b.1));
    list
}

pub(super) fn species_window(
    mut contexts: EguiContexts,
    mut editor: ResMut<SpeciesEditor>,
    mut assets: ResMut<Assets<Species>>,
    server: Res<AssetServer>,
    config: Res<EditorConfig>,
    mut settings: ResMut<JellyfishSettings>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    let list = species_list(&assets, &server);
    let selected = editor.selected().filter(|id| assets.contains(*id));
    if selected.is_none()
        && let Some((first, _)) = list.first()
    {
        editor.select(*first, &assets);
    }
    editor.follow(&assets);
    let file = editor
        .selected()
        .and_then(|id| server.get_path(id))
        .map(|p| config.assets_dir.join(p.path()));

    egui::Window::new("Species")
        .default_pos([10.0, 10.0])
        .default_width(360.0)
        .default_height(560.0)
        .vscroll(true)
        .show(ctx, |ui| {
            let current = editor.selected();
            let current_label = list
                .iter()
                .find(|(id, _)| Some(*id) == current)
                .map_or("(none loaded)", |(_, l)| l.as_str());
            egui::ComboBox::from_label("species")
                .selected_text(current_label)
                .show_ui(ui, |ui| {
                    for (id, label) in &list {
                        if ui.selectable_label(Some(*id) == current, label).clicked() {
                            editor.select(*id, &assets);
                        }
                    }
                });
            if editor.selected().is_none() {
                return;
            }
            let mut changed = ui
                .horizontal(|ui| {
                    ui.label("name");
                    ui.text_edit_singleline(&mut editor.draft_mut().name)
                        .changed()
                })
                .inner;
            ui.horizontal(|ui| {
                if ui.button("reset to preset").clicked() {
                    editor.reset(&mut assets);
                }
                let save = ui.add_enabled(file.is_some(), egui::Button::new("save to file"));
                if let Some(path) = &file
                    && save.on_hover_text(path.display().to_string()).clicked()
                {
                    // The outcome is shown as the status line.
                    let _ = editor.save(path);
                }
            });
            whole_animal(ui, &mut editor, &mut assets);
            if let Some(status) = editor.status() {
                ui.label(status);
            }
            // Above the sliders, so it is seen whichever section is open.
            if let Some(error) = editor.error() {
                let text = egui::RichText::new(format!("not applied: {error}")).color(ERROR);
                ui.add(egui::Label::new(text).wrap());
            }
            ui.separator();
            changed |= species_controls(ui, editor.draft_mut());
            if changed {
                // An invalid draft is kept and shown above; the asset is untouched.
                let _ = editor.apply(&mut assets);
            }
            ui.separator();
            level_of_detail(ui, &mut settings);
        });
    Ok(())
}

/// The whole animal's size: dragged, every length of its body grows with the bell and
/// its pulse rate follows (the `diameter` slider below moves the bell's width alone).
fn whole_animal(ui: &mut egui::Ui, editor: &mut SpeciesEditor, assets: &mut Assets<Species>) {
    let mut millimetres = 1000.0 * editor.draft().diameter;
    let limit = crate::species::limits::of("diameter").map_or(0.002..=1.0, |l| l.min..=l.max);
    let range = (1000.0 * *limit.start() as f32)..=(1000.0 * *limit.end() as f32);
    let dragged = ui
        .horizontal(|ui| {
            ui.label("whole animal");
            ui.add(
                egui::DragValue::new(&mut millimetres)
                    .range(range)
                    .speed(0.2)
                    .suffix(" mm"),
            )
            .on_hover_text(
                "every length of the body scaled, at the animal's pulse rate for the size",
            )
            .changed()
        })
        .inner;
    if dragged {
        // An invalid size is kept in the draft and shown above the sliders.
        let _ = editor.resize(millimetres / 1000.0, assets);
    }
}

/// The plugin settings shared by all jellyfish (drawing only: the physics belongs to each
/// species). Written back only when edited.
fn level_of_detail(ui: &mut egui::Ui, settings: &mut ResMut<JellyfishSettings>) {
    let mut edited = settings.as_ref().clone();
    egui::CollapsingHeader::new("All jellyfish").show(ui, |ui| {
        egui::Grid::new("level of detail")
            .num_columns(2)
            .show(ui, |ui| {
                ui.label("mesh detail");
                ui.add(egui::Slider::new(
                    &mut edited.mesh_resolution_scale,
                    0.25..=2.0,
                ));
                ui.end_row();
            });
    });
    if edited != **settings {
        **settings = edited;
    }
}

/// Frame rate, jellyfish count and the plugin's CPU time per frame.
pub(super) fn stats_window(mut contexts: EguiContexts, store: Res<DiagnosticsStore>) -> Result {
    let ctx = contexts.ctx_mut()?;
    let get = |p: &DiagnosticPath| store.get(p).and_then(|d| d.smoothed()).unwrap_or(0.0);
    let count = get(&JellyfishDiagnostics::COUNT);
    let per = |ms: f64| if count > 0.0 { ms / count } else { 0.0 };
    let (simulation, meshing) = (
        get(&JellyfishDiagnostics::SIMULATION),
        get(&JellyfishDiagnostics::MESHING),
    );
    egui::Window::new("Stats")
        .anchor(egui::Align2::RIGHT_TOP, [-10.0, 10.0])
        .resizable(false)
        .show(ctx, |ui| {
            // Wide enough for the longest numbers, so the window does not jitter.
            ui.set_min_width(280.0);
            egui::Grid::new("stats").num_columns(2).show(ui, |ui| {
                let mut row = |label: &str, value: String| {
                    ui.label(label);
                    ui.label(value);
                    ui.end_row();
                };
                row(
                    "frame",
                    format!(
                        "{:.0} fps, {:.1} ms",
                        get(&FrameTimeDiagnosticsPlugin::FPS),
                        get(&FrameTimeDiagnosticsPlugin::FRAME_TIME)
                    ),
                );
                row("jellyfish", format!("{count:.0}"));
                row(
                    "simulation",
                    format!("{simulation:.2} ms ({:.3} each)", per(simulation)),
                );
                row(
                    "meshing",
                    format!("{meshing:.2} ms ({:.3} each)", per(meshing)),
                );
            });
            ui.label("CPU time per frame, summed over jellyfish")
        });
    Ok(())
}
