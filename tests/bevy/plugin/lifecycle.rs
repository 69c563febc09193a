//! A jellyfish's life: it starts, swims, is meshed, is heard by observers, recovers,
//! leaves; a school starts over a few frames; parts of the plugin can be left out.

use super::*;
use bevy::camera::primitives::Aabb;

#[test]
fn a_spawned_jellyfish_swims_along_its_axis() {
    let mut app = app();
    let h = add_species(&mut app, species());
    // Lying on its side, apex towards −x, ten times life size.
    let start = Transform::from_xyz(1.0, 2.0, 3.0)
        .with_rotation(Quat::from_rotation_z(std::f32::consts::FRAC_PI_2))
        .with_scale(Vec3::splat(10.0));
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h).with_phase(0.0), start))
        .id();
    run(&mut app, 240); // 4 s: nearly three strokes
    let end = *app.world().get::<Transform>(e).unwrap();
    let moved = end.translation - start.translation;
    let swum = slice(&app, e).swim_distance();
    assert!(swum > 0.002, "the slice swam {swum} m");
    assert!(
        moved.normalize().dot(Vec3::NEG_X) > 0.9999,
        "moved along its axis: {moved}"
    );
    // Blended between the last two steps, so within a step of the slice's distance.
    assert!(
        (moved.length() / 10.0 - swum).abs() < 0.2 * swum,
        "moved {moved}, swum {swum}"
    );
    assert_eq!(end.rotation, start.rotation);
    assert_eq!(slice(&app, e).sim().unwrap().recoveries(), 0);
}

#[test]
fn its_mesh_changes_between_frames() {
    let mut app = app();
    let h = add_species(&mut app, species());
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h).with_phase(0.1), Transform::default()))
        .id();
    run(&mut app, 2);
    let before = umbrella_positions(&app, e);
    let handle = app.world().get::<Mesh3d>(e).unwrap().0.clone();
    run(&mut app, 3);
    let after = umbrella_positions(&app, e);
    assert_eq!(before.len(), after.len());
    assert!(!before.is_empty());
    assert_ne!(before, after, "the bell moved");
    assert_eq!(
        app.world().get::<Mesh3d>(e).unwrap().0,
        handle,
        "updated in place, same handle"
    );
    let tentacles = app.world().get::<JellyfishMeshes>(e).unwrap();
    let part = tentacles.tentacle_entity.expect("tentacle part");
    assert_eq!(
        app.world().get::<PartOf>(part).unwrap().jellyfish(),
        e,
        "tentacles are one part's mesh"
    );
}

#[test]
fn its_parts_sit_on_the_bell_wherever_it_is_carried() {
    let mut app = app();
    let h = add_species(&mut app, species());
    // A jellyfish carried by a turning, moving parent: its parts must follow both.
    let carrier = app
        .world_mut()
        .spawn(Transform::from_xyz(5.0, 0.0, 0.0))
        .id();
    let e = app
        .world_mut()
        .spawn((
            Jellyfish::new(h).with_phase(0.2),
            Transform::from_xyz(0.0, 1.0, 0.0).with_scale(Vec3::splat(3.0)),
            ChildOf(carrier),
        ))
        .id();
    let on_the_bell = |app: &App| {
        let meshes = app.world().get::<JellyfishMeshes>(e).unwrap();
        let bell = *app.world().get::<GlobalTransform>(e).unwrap();
        let bounds = *app.world().get::<Aabb>(e).unwrap();
        for part in [meshes.tentacle_entity, meshes.glow_entity] {
            let part = part.expect("tentacles and a glow layer");
            assert_eq!(app.world().get::<PartOf>(part).unwrap().jellyfish(), e);
            assert!(
                app.world().get::<ChildOf>(part).is_none(),
                "a part is no child for Bevy's propagation to visit"
            );
            assert!(
                app.world().get::<Transform>(part).is_none(),
                "a part holds no Transform for propagation to multiply"
            );
            assert_eq!(*app.world().get::<GlobalTransform>(part).unwrap(), bell);
            assert_eq!(*app.world().get::<Aabb>(part).unwrap(), bounds);
        }
        bell
    };
    run(&mut app, 3);
    let first = on_the_bell(&app);
    assert!(
        (first.translation() - Vec3::new(5.0, 1.0, 0.0)).length() < 0.05,
        "carried: {first:?}"
    );
    app.world_mut()
        .get_mut::<Transform>(carrier)
        .unwrap()
        .rotate_z(1.0);
    // A part given a Transform again (inserting `Mesh3d` brings one) loses it.
    let tentacles = app
        .world()
        .get::<JellyfishMeshes>(e)
        .unwrap()
        .tentacle_entity;
    app.world_mut()
        .entity_mut(tentacles.unwrap())
        .insert(Transform::from_xyz(9.0, 9.0, 9.0));
    run(&mut app, 2);
    let turned = on_the_bell(&app);
    assert!(
        turned.rotation().angle_between(first.rotation()) > 0.9,
        "the carrier's turn reached the bell and its parts"
    );
}

/// A part is shown and hidden with its jellyfish, as a child would be, wherever the
/// jellyfish's visibility comes from (here a carrier it is a child of), unless the part is
/// made visible or hidden itself.
#[test]
fn its_parts_are_shown_and_hidden_with_it() {
    let mut app = Headless {
        settings: settings(),
        frame: frame(60),
        ..default()
    }
    .build(|app| {
        app.add_plugins(VisibilityPlugin);
    });
    let h = add_species(&mut app, species());
    let carrier = app
        .world_mut()
        .spawn((Transform::default(), Visibility::default()))
        .id();
    let e = app
        .world_mut()
        .spawn((
            Jellyfish::new(h.clone()),
            Transform::default(),
            ChildOf(carrier),
        ))
        .id();
    run(&mut app, 3);
    let meshes = app.world().get::<JellyfishMeshes>(e).unwrap();
    let parts = [meshes.tentacle_entity, meshes.glow_entity].map(|p| p.expect("a part"));
    let shown = |app: &App| parts.map(|p| app.world().get::<InheritedVisibility>(p).unwrap().get());
    assert_eq!(shown(&app), [true, true]);
    let set = |app: &mut App, entity: Entity, to: Visibility| {
        *app.world_mut().get_mut::<Visibility>(entity).unwrap() = to;
        run(app, 1);
    };
    set(&mut app, carrier, Visibility::Hidden);
    assert!(!app.world().get::<InheritedVisibility>(e).unwrap().get());
    assert_eq!(shown(&app), [false, false], "hidden with the carrier");
    set(&mut app, parts[0], Visibility::Visible);
    assert_eq!(
        shown(&app),
        [true, false],
        "tentacles made visible themselves"
    );
    set(&mut app, parts[0], Visibility::Hidden);
    set(&mut app, carrier, Visibility::Inherited);
    assert_eq!(shown(&app), [false, true], "tentacles hidden themselves");
    set(&mut app, parts[0], Visibility::Inherited);
    assert_eq!(shown(&app), [true, true]);
    // The parts of one spawned while its carrier is hidden are hidden from their first
    // frame.
    set(&mut app, carrier, Visibility::Hidden);
    let later = app
        .world_mut()
        .spawn((Jellyfish::new(h), Transform::default(), ChildOf(carrier)))
        .id();
    let mut seen = 0;
    for _ in 0..4 {
        run(&mut app, 1);
        let meshes = app.world().get::<JellyfishMeshes>(later).unwrap();
        for part in [meshes.tentacle_entity, meshes.glow_entity]
            .into_iter()
            .flatten()
        {
            assert!(!app.world().get::<InheritedVisibility>(part).unwrap().get());
            seen += 1;
        }
    }
    assert!(seen > 0, "its parts were made");
}

#[test]
fn seeds_pick_the_individual() {
    let mut app = app();
    let h = add_species(&mut app, species());
    let spawn = |app: &mut App, seed| {
        app.world_mut()
            .spawn((
                Jellyfish::new(h.clone()).with_seed(seed).with_phase(0.0),
                Transform::default(),
            ))
            .id()
    };
    let (a, b, c) = (spawn(&mut app, 1), spawn(&mut app, 2), spawn(&mut app, 1));
    run(&mut app, 3);
    let (pa, pb, pc) = (
        umbrella_positions(&app, a),
        umbrella_positions(&app, b),
        umbrella_positions(&app, c),
    );
    assert_ne!(pa, pb, "two seeds, two surfaces");
    assert_eq!(pa, pc, "one seed, one surface");
}

#[test]
fn individuals_start_at_their_own_phase() {
    let mut app = app();
    let h = add_species(&mut app, species());
    let mut spawn = |j: Jellyfish| app.world_mut().spawn((j, Transform::default())).id();
    let a = spawn(Jellyfish::new(h.clone()));
    let b = spawn(Jellyfish::new(h.clone()));
    let quarter = spawn(Jellyfish::new(h.clone()).with_phase(0.25));
    app.update(); // slices are built; the clock has not moved yet
    let phase = |e| slice(&app, e).sim().unwrap().phase();
    assert_ne!(phase(a), phase(b), "a school does not beat in unison");
    assert_ne!(slice(&app, a).seed(), slice(&app, b).seed());
    // The phase is counted in whole fixed steps.
    let step = 1.0 / SliceSim::steps_per_cycle(&species()) as f32;
    assert!((phase(quarter) - 0.25).abs() <= step, "{}", phase(quarter));
}

#[test]
fn despawning_frees_its_mesh_assets() {
    let mut app = app();
    let h = add_species(&mut app, species());
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h), Transform::default()))
        .id();
    run(&mut app, 2);
    let meshes = app.world().get::<JellyfishMeshes>(e).unwrap();
    let ids = [
        meshes.umbrella.as_ref().unwrap().id(),
        meshes.tentacles.as_ref().unwrap().id(),
    ];
    let child = meshes.tentacle_entity.unwrap();
    for id in ids {
        assert!(app.world().resource::<Assets<Mesh>>().contains(id));
    }
    app.world_mut().despawn(e);
    run(&mut app, 2);
    assert!(
        app.world().get_entity(child).is_err(),
        "tentacle child gone"
    );
    for id in ids {
        assert!(
            !app.world().resource::<Assets<Mesh>>().contains(id),
            "mesh {id} freed"
        );
    }
}

#[test]
fn a_large_school_starts_over_a_few_frames() {
    let mut app = app();
    let h = add_species(&mut app, species());
    let count = 69;
    for i in 0..count {
        app.world_mut().spawn((
            Jellyfish::new(h.clone()),
            Transform::from_xyz(i as f32, 0.0, 0.0),
        ));
    }
    let started = |app: &mut App| {
        let mut q = app.world_mut().query::<&JellyfishSlice>();
        q.iter(app.world()).filter(|s| s.sim().is_some()).count()
    };
    // The same number each frame (a count, not a time budget), until all have started.
    app.update();
    let per_frame = started(&mut app);
    assert!(
        per_frame > 0 && 2 * per_frame < count,
        "one frame's worth: {per_frame}"
    );
    let frames = count.div_ceil(per_frame);
    for frame in 2..=frames {
        app.update();
        assert_eq!(
            started(&mut app),
            (frame * per_frame).min(count),
            "frame {frame}"
        );
    }
    assert!(
        frames <= 3,
        "all of them by the third frame ({per_frame} a frame)"
    );
}

#[derive(Resource, Default)]
struct SeenEvents {
    started: Vec<Entity>,
    strokes: Vec<(Entity, u64)>,
}

#[test]
fn observers_hear_a_jellyfish_start_and_each_stroke_begin() {
    use bevy_jellyfish::plugin::{JellyfishStarted, StrokeStarted};
    let (mut app, _, e) = one_jellyfish();
    app.init_resource::<SeenEvents>()
        .add_observer(|s: On<JellyfishStarted>, mut seen: ResMut<SeenEvents>| {
            seen.started.push(s.entity)
        })
        .add_observer(|s: On<StrokeStarted>, mut seen: ResMut<SeenEvents>| {
            seen.strokes.push((s.entity, s.cycle))
        });
    let period = species().period();
    run(&mut app, (3.5 * period * 60.0).round() as usize);
    let seen = app.world().resource::<SeenEvents>();
    assert_eq!(seen.started, [e]);
    assert!(
        (3..=4).contains(&seen.strokes.len()),
        "one stroke per period: {:?}",
        seen.strokes
    );
    for pair in seen.strokes.windows(2) {
        assert_eq!(
            pair[1].1,
            pair[0].1 + 1,
            "strokes count up: {:?}",
            seen.strokes
        );
        assert_eq!(pair[0].0, e);
    }
}

/// A blown-up slice is restarted at rest where it was, observers hear it once, and the
/// jellyfish swims on with finite meshes.
#[test]
fn a_blown_up_slice_recovers_and_observers_hear_it() {
    use bevy_jellyfish::plugin::SliceRecovered;
    #[derive(Resource, Default)]
    struct Heard(Vec<(Entity, u32)>);
    let (mut app, _, e) = one_jellyfish();
    app.init_resource::<Heard>()
        .add_observer(|r: On<SliceRecovered>, mut heard: ResMut<Heard>| {
            heard.0.push((r.entity, r.recoveries))
        });
    run(&mut app, 30);
    let before = app.world().get::<Transform>(e).unwrap().translation;
    app.world_mut()
        .get_mut::<JellyfishSlice>(e)
        .unwrap()
        .sim_mut_for_tests()
        .expect("a live slice")
        .poison_for_tests();
    run(&mut app, 60);
    assert_eq!(app.world().resource::<Heard>().0, [(e, 1)], "heard once");
    assert_eq!(slice(&app, e).sim().unwrap().recoveries(), 1);
    let after = app.world().get::<Transform>(e).unwrap().translation;
    assert!(after.is_finite(), "the transform stays finite: {after}");
    assert!(
        after.distance(before) < 0.05,
        "restarted where it was: {before} → {after}"
    );
    let positions = umbrella_positions(&app, e);
    assert!(
        positions.iter().flatten().all(|x| x.is_finite()),
        "finite meshes"
    );
}

#[test]
fn a_game_can_leave_parts_out() {
    use bevy::mesh::MeshPlugin;
    use bevy_jellyfish::plugin::{
        DetailPlugin, JellyfishDiagnosticsPlugin, JellyfishMaterialPlugin, JellyfishPlugins,
        TankWater, TankWaterPlugin,
    };
    let parts = JellyfishPlugins {
        settings: JellyfishSettings {
            // With levels of detail, no jellyfish would be near.
            detail: DetailLevels {
                near: 0,
                mid: 0,
                ..default()
            },
            ..settings()
        },
    }
    .build()
    .disable::<DetailPlugin>()
    .disable::<TankWaterPlugin>()
    .disable::<JellyfishMaterialPlugin>()
    .disable::<JellyfishDiagnosticsPlugin>();
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin::default(),
        MeshPlugin,
        TransformPlugin,
        parts,
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(frame(60)))
    .insert_resource(TankWater::new(Vec3::splat(-2.0), Vec3::splat(2.0), 0.5));
    app.finish();
    app.cleanup();
    let h = add_species(&mut app, species());
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h), Transform::default()))
        .id();
    run(&mut app, 90);
    let jelly = slice(&app, e);
    assert_eq!(
        jelly.tier(),
        Tier::Near,
        "no levels of detail: every one near"
    );
    assert!(jelly.swim_distance() > 0.0, "it swims");
    assert!(app.world().get_resource::<CycleCaches>().is_none());
    let meshes = app.world().get::<JellyfishMeshes>(e).unwrap();
    assert!(meshes.umbrella.is_some(), "it is meshed");
    assert!(
        app.world()
            .get::<MeshMaterial3d<StandardMaterial>>(e)
            .is_none(),
        "no material of ours"
    );
    let tank = app.world().resource::<TankWater>();
    assert_eq!(tank.speed_max(), 0.0, "nothing steps or stirs the tank");
}
