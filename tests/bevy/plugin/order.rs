//! Order: no system of the plugin runs before or after another that touches the same data
//! as the executor's threads happen to finish.

use super::*;
use crate::common::app::ambiguities_of_ours;
use crate::scene::AquariumPlugin;
use crate::school::School;
use crate::screenshot::Offscreen;
use bevy::render::RenderApp;
use bevy_jellyfish::JellyfishEditorPlugin;
use bevy_jellyfish::plugin::JellyfishDebugPlugin;

/// Every pair of systems that share data with one of the plugin's is ordered, in every
/// schedule of the headless app (with a renderer, below). An unordered pair decides, by
/// the machine's load, the frame in which an edit reaches the materials or whether a
/// tentacle's material is chosen from this frame's transform or the last.
#[test]
fn the_plugins_systems_run_in_one_order() {
    let mut app = app();
    let h = add_species(&mut app, species());
    app.world_mut().spawn(Jellyfish::new(h));
    let found = ambiguities_of_ours(app.world_mut(), &[]);
    assert!(
        found.is_empty(),
        "{} pairs left to the executor:\n{}",
        found.len(),
        found.join("\n")
    );
    // The schedules built with the check run as before.
    run(&mut app, 3);
}

/// The same with Bevy's renderer (the aquarium's scene, both surface paths' systems, the
/// species editor and the debug overlay), in the main app and in the render app. (The shape buffers'
/// preparation and the surface materials' share no data Bevy sees, so this does not see
/// them unordered: `render.rs`'s `RenderOrder` checks that pair by name.) Needs an
/// adapter, as the render tests do.
#[test]
fn the_plugins_systems_run_in_one_order_with_a_renderer() {
    let mut offscreen = match Offscreen::new(64, 48, |app| {
        app.add_plugins(AquariumPlugin {
            school: School {
                per_species: 1,
                seed: 1,
            },
            surfaces: SurfaceMode::Auto,
            detail: default(),
        })
        .add_plugins((
            JellyfishEditorPlugin::default(),
            JellyfishDebugPlugin,
            RenderAppOrder,
        ));
    }) {
        Ok(offscreen) => offscreen,
        Err(e) if std::env::var("JELLYFISH_REQUIRE_RENDER").is_ok_and(|v| v == "1") => {
            panic!("JELLYFISH_REQUIRE_RENDER=1, but {e}")
        }
        Err(e) => {
            eprintln!("skipping the render app's order: {e}");
            return;
        }
    };
    let mut found = offscreen
        .world_mut()
        .remove_resource::<RenderAppAmbiguities>()
        .expect("the render app was checked when the app finished")
        .0;
    found.extend(ambiguities_of_ours(offscreen.world_mut(), &[]));
    assert!(
        found.is_empty(),
        "{} pairs left to the executor:\n{}",
        found.len(),
        found.join("\n")
    );
    for _ in 0..3 {
        offscreen.update();
    }
}

/// Checks the render app when the app finishes, before the render world moves to its own
/// thread, and leaves what it found in the main world. Not its `ExtractSchedule`, whose
/// systems need the main world handed to them to be built (and which runs on one thread).
struct RenderAppOrder;

#[derive(Resource)]
struct RenderAppAmbiguities(Vec<String>);

impl Plugin for RenderAppOrder {
    fn build(&self, _: &mut App) {}

    fn finish(&self, app: &mut App) {
        let found = app
            .get_sub_app_mut(RenderApp)
            .map(|render| ambiguities_of_ours(render.world_mut(), &["ExtractSchedule"]))
            .unwrap_or_default();
        app.insert_resource(RenderAppAmbiguities(found));
    }
}
