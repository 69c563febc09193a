//! The species editor without a window: its parameter table covers every field of
//! `Species` with sliders that hold the shipped species, and its session applies valid
//! drafts to living jellyfish, refuses invalid ones, grows the whole animal, resets to
//! presets and saves files.

use crate::common::app::Headless;
use crate::common::shipped_species;
use bevy::prelude::*;
use bevy::reflect::structs::Struct;
use bevy_egui::egui;
use bevy_jellyfish::editor::params::{OTHER_FIELDS, SECTIONS, Value, species_controls};
use bevy_jellyfish::editor::{SaveError, SpeciesEditor, remember_presets};
use bevy_jellyfish::plugin::JellyfishSlice;
use bevy_jellyfish::{Jellyfish, JellyfishSettings, Species};
use std::collections::HashSet;
use std::path::PathBuf;
use std::time::Duration;

fn field_names() -> Vec<String> {
    let species = Species::aurelia();
    (0..species.field_len())
        .map(|i| species.name_at(i).unwrap().to_string())
        .collect()
}

fn shipped() -> Vec<Species> {
    let mut all = vec![Species::aurelia()];
    all.extend(shipped_species());
    assert!(all.len() >= 4);
    all
}

#[test]
fn every_species_field_has_exactly_one_control() {
    let mut controlled: Vec<&str> = SECTIONS
        .iter()
        .flat_map(|s| s.params.iter().map(|p| p.field))
        .chain(OTHER_FIELDS.iter().copied())
        .collect();
    let unique: HashSet<&str> = controlled.iter().copied().collect();
    assert_eq!(unique.len(), controlled.len(), "a field has two controls");
    controlled.sort();
    let mut fields = field_names();
    fields.sort();
    assert_eq!(controlled, fields);
}

#[test]
fn each_slider_edits_the_field_it_names() {
    for param in SECTIONS.iter().flat_map(|s| s.params) {
        let mut species = Species::aurelia();
        match (param.value)(&mut species) {
            Value::Real(v) => *v = 12345.5,
            Value::Count(v) => *v = 12345,
        }
        let field = species.field(param.field).unwrap();
        let written = field
            .try_downcast_ref::<f32>()
            .map(|v| *v == 12345.5)
            .or_else(|| field.try_downcast_ref::<u32>().map(|v| *v == 12345))
            .unwrap();
        assert!(written, "slider {:?} writes another field", param.label);
    }
}

#[test]
fn slider_ranges_hold_every_shipped_species() {
    let species = shipped();
    for param in SECTIONS.iter().flat_map(|s| s.params) {
        let (lo, hi) = (*param.range().start(), *param.range().end());
        assert!(lo < hi, "{}", param.field);
        assert!(
            !param.logarithmic || lo > 0.0,
            "{}: log range from 0",
            param.field
        );
        for s in &species {
            let mut s = s.clone();
            let shown = match (param.value)(&mut s) {
                Value::Real(v) => *v as f64 * param.scale,
                Value::Count(v) => *v as f64,
            };
            assert!(
                (lo..=hi).contains(&shown),
                "{} of {} is {shown}, outside the slider's {lo}..={hi}",
                param.field,
                s.name
            );
        }
    }
}

#[test]
fn sliders_span_the_limits_table_and_show_it() {
    use bevy_jellyfish::species::limits;
    for param in SECTIONS.iter().flat_map(|s| s.params) {
        let limit = limits::of(param.field).expect("a slider's field has a limit");
        assert_eq!(
            param.range(),
            limit.min * param.scale..=limit.max * param.scale,
            "{}",
            param.field
        );
        assert!(param.range_text().contains('–'), "{}", param.range_text());
    }
    // Every numeric field of the table has its slider or its own widget.
    for limit in limits::LIMITS {
        let field = limit.field.split('[').next().unwrap();
        let slider = SECTIONS
            .iter()
            .flat_map(|s| s.params)
            .any(|p| p.field == field);
        assert!(slider || OTHER_FIELDS.contains(&field), "{field}");
    }
}

#[test]
fn drawing_the_panel_without_input_changes_nothing() {
    let ctx = egui::Context::default();
    let mut species = Species::aurelia();
    for _ in 0..3 {
        let mut output = ctx.run_ui(egui::RawInput::default(), |ui| {
            egui::CentralPanel::default().show(ui, |ui| {
                assert!(!species_controls(ui, &mut species));
            });
        });
        output.textures_delta.clear();
    }
    assert_eq!(species, Species::aurelia());
}

/// A headless app with the plugin, one species and one jellyfish of it.
fn app() -> (App, Handle<Species>, Entity) {
    let mut app = Headless {
        settings: JellyfishSettings {
            mesh_resolution_scale: 0.3,
            ..default()
        },
        frame: Duration::from_millis(16),
        ..default()
    }
    .build(|app| {
        app.init_resource::<SpeciesEditor>()
            .add_systems(Update, remember_presets);
    });
    let preset = Species {
        tentacle_count: 4,
        ..Species::aurelia()
    };
    let h = app
        .world_mut()
        .resource_mut::<Assets<Species>>()
        .add(preset);
    let e = app.world_mut().spawn(Jellyfish::new(h.clone())).id();
    frames(&mut app, 3);
    let world = app.world_mut();
    world.resource_scope(|world, mut editor: Mut<SpeciesEditor>| {
        editor.select(h.id(), world.resource::<Assets<Species>>());
    });
    (app, h, e)
}

/// An asset edit reaches jellyfish the frame after it is made: its event is sent at the
/// end of a frame and read at the start of the next.
fn frames(app: &mut App, n: usize) {
    for _ in 0..n {
        app.update();
    }
}

/// Runs `f` with the editor and the species assets.
fn edit<R>(app: &mut App, f: impl FnOnce(&mut SpeciesEditor, &mut Assets<Species>) -> R) -> R {
    app.world_mut()
        .resource_scope(|world, mut editor: Mut<SpeciesEditor>| {
            f(&mut editor, &mut world.resource_mut::<Assets<Species>>())
        })
}

fn simulated(app: &App, e: Entity) -> Species {
    let slice = app.world().get::<JellyfishSlice>(e).unwrap();
    slice.species().unwrap().clone()
}

#[test]
fn a_valid_draft_reaches_living_jellyfish() {
    let (mut app, h, e) = app();
    edit(&mut app, |editor, assets| {
        editor.draft_mut().contraction_frequency = 1.3;
        editor.draft_mut().tentacle_count = 6;
        editor.apply(assets).unwrap();
        assert_eq!(assets.get(&h).unwrap().contraction_frequency, 1.3);
    });
    frames(&mut app, 2);
    let s = simulated(&app, e);
    assert_eq!((s.contraction_frequency, s.tentacle_count), (1.3, 6));
}

#[test]
fn an_invalid_draft_is_shown_and_not_applied() {
    let (mut app, h, e) = app();
    let before = app
        .world()
        .resource::<Assets<Species>>()
        .get(&h)
        .unwrap()
        .clone();
    edit(&mut app, |editor, assets| {
        editor.draft_mut().thickness = 0.05; // thicker than the bell is wide
        let error = editor.apply(assets).unwrap_err();
        assert_eq!(error.field(), Some("thickness"));
        assert_eq!(editor.error().unwrap().field(), Some("thickness"));
        assert_eq!(*assets.get(&h).unwrap(), before);
        // The invalid draft stays for the user to fix, even if the asset changes.
        assets.get_mut(&h).unwrap().glow = 2.0;
        editor.follow(assets);
        assert_eq!(editor.draft().thickness, 0.05);
        // Fixed, it applies and the error clears.
        editor.draft_mut().thickness = 0.005;
        editor.apply(assets).unwrap();
        assert!(editor.error().is_none());
    });
    frames(&mut app, 2);
    assert_eq!(simulated(&app, e).thickness, 0.005);
}

#[test]
fn a_valid_draft_follows_edits_made_elsewhere() {
    let (mut app, h, _) = app();
    edit(&mut app, |editor, assets| {
        assets.get_mut(&h).unwrap().glow = 2.5;
        editor.follow(assets);
        assert_eq!(editor.draft().glow, 2.5);
    });
}

#[test]
fn reset_restores_the_preset() {
    let (mut app, h, e) = app();
    edit(&mut app, |editor, assets| {
        editor.draft_mut().expansion_stagger = 0.0;
        editor.draft_mut().diameter = 0.05;
        editor.apply(assets).unwrap();
    });
    frames(&mut app, 2);
    assert_eq!(simulated(&app, e).expansion_stagger, 0.0);
    edit(&mut app, |editor, assets| {
        editor.reset(assets);
        assert_eq!(
            assets.get(&h).unwrap().tentacle_count,
            4,
            "preset, not aurelia"
        );
        assert_eq!(
            assets.get(&h).unwrap().diameter,
            Species::aurelia().diameter
        );
        assert_eq!(editor.draft(), assets.get(&h).unwrap());
    });
    frames(&mut app, 2);
    assert_eq!(
        simulated(&app, e).expansion_stagger,
        Species::aurelia().expansion_stagger
    );
}

fn scratch_file(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("jellyfish-editor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn save_writes_a_file_that_loads_back_and_keeps_its_comments() {
    let (mut app, _, _) = app();
    let path = scratch_file("saved.species.ron");
    let shipped =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/species/aequorea.species.ron");
    std::fs::copy(&shipped, &path).unwrap();
    let draft = edit(&mut app, |editor, assets| {
        editor.draft_mut().name = "Edited".into();
        editor.draft_mut().bell_color = [0.1, 0.2, 0.3, 0.4];
        editor.apply(assets).unwrap();
        editor.save(&path).unwrap();
        assert!(editor.status().unwrap().starts_with("saved"));
        editor.draft().clone()
    });
    let text = std::fs::read_to_string(&path).unwrap();
    let original = std::fs::read_to_string(&shipped).unwrap();
    let comments = |t: &str| -> Vec<String> {
        t.lines()
            .take_while(|l| l.starts_with("//"))
            .map(String::from)
            .collect()
    };
    assert!(!comments(&original).is_empty());
    assert_eq!(comments(&text), comments(&original));
    assert_eq!(Species::from_ron(&text).unwrap(), draft);
    // Like the shipped files, it spells out only what differs from the moon jelly.
    assert!(text.contains("bell_color") && text.contains("tentacle_count"));
    assert!(
        !text.contains("viscosity") && !text.contains("diameter"),
        "{text}"
    );
}

#[test]
fn an_invalid_draft_is_not_saved() {
    let (mut app, _, _) = app();
    let path = scratch_file("invalid.species.ron");
    std::fs::write(&path, "(name: \"Kept\")").unwrap();
    edit(&mut app, |editor, assets| {
        editor.draft_mut().contraction_ratio = 3.0;
        let _ = editor.apply(assets);
        let error = editor.save(&path).unwrap_err();
        assert!(matches!(&error, SaveError::Invalid(e) if e.field() == Some("contraction_ratio")));
        assert!(editor.status().unwrap().contains("contraction_ratio"));
    });
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "(name: \"Kept\")");
}

#[test]
fn the_whole_animal_grows_and_beats_at_its_rate_for_the_size() {
    let (mut app, h, e) = app();
    let small = app
        .world()
        .resource::<Assets<Species>>()
        .get(&h)
        .unwrap()
        .clone();
    let grown = small.resized(2.0 * small.diameter);
    edit(&mut app, |editor, assets| {
        editor.resize(2.0 * small.diameter, assets).unwrap();
        assert_eq!(assets.get(&h).unwrap(), &grown);
        assert!((grown.height - 2.0 * small.height).abs() < 1e-7);
        assert!(grown.contraction_frequency < small.contraction_frequency);
        let status = editor.status().unwrap();
        assert!(
            status.starts_with("the whole animal at 80.0 mm"),
            "{status}"
        );
        // Beyond the limits: refused by name, the asset as it was.
        let error = editor.resize(5.0, assets).unwrap_err();
        assert_eq!(error.field(), Some("diameter"));
        assert_eq!(assets.get(&h).unwrap(), &grown);
    });
    frames(&mut app, 2);
    let s = simulated(&app, e);
    assert_eq!(
        (s.diameter, s.contraction_frequency),
        (grown.diameter, grown.contraction_frequency)
    );
}
