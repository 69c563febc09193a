//! The debug overlay (`JellyfishDebugPlugin`): it adds to a headless app, draws every
//! jellyfish's reach and a marked one's slice, and draws nothing once its group is off.

use super::*;
use bevy::gizmos::GizmoAsset;
use bevy::gizmos::config::GizmoConfigStore;
use bevy_jellyfish::plugin::{JellyfishDebugPlugin, JellyfishGizmos, ShowSlice};
use std::any::TypeId;

/// Vertices of the overlay's lines the last frame handed over.
fn drawn(app: &App) -> usize {
    let handles = app.world().resource::<bevy::gizmos::GizmoHandles>();
    let Some(Some(handle)) = handles.handles().get(&TypeId::of::<JellyfishGizmos>()) else {
        return 0;
    };
    let asset = app.world().resource::<Assets<GizmoAsset>>().get(handle);
    asset.map_or(0, |a| {
        let b = a.buffer().buffer();
        b.list_positions.len() + b.strip_positions.len()
    })
}

fn with_overlay() -> (App, Entity, Entity) {
    let mut app = Headless {
        settings: settings(),
        ..default()
    }
    .build(|app| {
        app.add_plugins(JellyfishDebugPlugin);
    });
    let h = add_species(&mut app, species());
    let shown = app
        .world_mut()
        .spawn((Jellyfish::new(h.clone()), Transform::default(), ShowSlice))
        .id();
    let plain = app
        .world_mut()
        .spawn((Jellyfish::new(h), Transform::from_xyz(1.0, 0.0, 0.0)))
        .id();
    (app, shown, plain)
}

#[test]
fn the_overlay_draws_reach_and_a_marked_slice_and_stops_when_off() {
    let (mut app, shown, plain) = with_overlay();
    run(&mut app, 30);
    assert!(slice(&app, shown).started() && slice(&app, plain).started());
    let everything = drawn(&app);

    // Reach only: one circle per jellyfish, far fewer lines than the slice's.
    {
        let mut store = app.world_mut().resource_mut::<GizmoConfigStore>();
        let (_, g) = store.config_mut::<JellyfishGizmos>();
        (g.flow, g.particles, g.springs) = (false, false, false);
    }
    run(&mut app, 1);
    let reach = drawn(&app);
    assert!(reach > 0, "the reach circles are drawn");
    assert!(
        everything > 4 * reach,
        "the marked slice adds its water and springs: {everything} against {reach}"
    );

    // The whole group off: nothing.
    app.world_mut()
        .resource_mut::<GizmoConfigStore>()
        .config_mut::<JellyfishGizmos>()
        .0
        .enabled = false;
    run(&mut app, 1);
    assert_eq!(drawn(&app), 0, "nothing is drawn with the group off");
}

#[test]
fn the_overlay_survives_a_blown_up_slice() {
    let (mut app, shown, _) = with_overlay();
    run(&mut app, 10);
    app.world_mut()
        .get_mut::<JellyfishSlice>(shown)
        .unwrap()
        .sim_mut_for_tests()
        .unwrap()
        .poison_for_tests();
    run(&mut app, 5);
    assert!(drawn(&app) > 0);
}
