//! The ECS plugin, headless: `MinimalPlugins` + assets + meshes + transforms, with the
//! clock driven by hand. Slices run at the species' own grid and meshes at a reduced
//! resolution, so the debug build stays quick.

use crate::common::app::Headless;
use crate::common::species_files;
use bevy::asset::{AssetLoadFailedEvent, AssetPlugin};
use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore};
use bevy::ecs::system::RunSystemOnce;
use bevy::mesh::MeshTag;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy::render::storage::ShaderBuffer;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::plugin::{
    CycleCaches, DetailLevels, JellyfishGeometry, JellyfishGlow, JellyfishMeshes, JellyfishSlice,
    ShapeBuffers, SurfaceMode, SurfacePath, Tier,
};
use bevy_jellyfish::{
    Jellyfish, JellyfishDiagnostics, JellyfishSettings, SliceSim, Species, SpeciesRejected,
};
use std::path::PathBuf;
use std::time::Duration;

fn settings() -> JellyfishSettings {
    JellyfishSettings {
        mesh_resolution_scale: 0.5,
        ..default()
    }
}

fn app_with(assets: AssetPlugin) -> App {
    Headless {
        assets,
        settings: settings(),
        frame: frame(60),
    }
    .build(|_| {})
}

fn app() -> App {
    app_with(AssetPlugin::default())
}

fn frame(fps: u32) -> Duration {
    Duration::from_secs_f64(1.0 / fps as f64)
}

fn set_frame(app: &mut App, d: Duration) {
    app.insert_resource(TimeUpdateStrategy::ManualDuration(d));
}

fn run(app: &mut App, frames: usize) {
    for _ in 0..frames {
        app.update();
    }
}

/// Aurelia with a lighter mesh (8 tentacles) for the debug build.
fn species() -> Species {
    Species {
        tentacle_count: 8,
        ..Species::aurelia()
    }
}

fn add_species(app: &mut App, s: Species) -> Handle<Species> {
    app.world_mut().resource_mut::<Assets<Species>>().add(s)
}

/// An app with one jellyfish of the test species at the origin.
fn one_jellyfish() -> (App, Handle<Species>, Entity) {
    let mut app = app();
    let h = add_species(&mut app, species());
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h.clone()), Transform::default()))
        .id();
    (app, h, e)
}

fn slice(app: &App, e: Entity) -> &JellyfishSlice {
    app.world().get::<JellyfishSlice>(e).unwrap()
}

fn umbrella_positions(app: &App, e: Entity) -> Vec<[f32; 3]> {
    let meshes = app.world().get::<JellyfishMeshes>(e).unwrap();
    let handle = meshes.umbrella.as_ref().expect("umbrella mesh built");
    let mesh = app.world().resource::<Assets<Mesh>>().get(handle).unwrap();
    match mesh.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(p)) => p.clone(),
        other => panic!("positions: {other:?}"),
    }
}

fn rejections(app: &mut App) -> Vec<SpeciesRejected> {
    app.world_mut()
        .resource_mut::<Messages<SpeciesRejected>>()
        .drain()
        .collect()
}

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
    let child = tentacles.tentacle_entity.expect("tentacle child");
    assert_eq!(
        app.world().get::<ChildOf>(child).unwrap().parent(),
        e,
        "tentacles are one child mesh"
    );
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
fn a_species_edited_at_run_time_reaches_living_jellyfish() {
    let (mut app, h, e) = one_jellyfish();
    run(&mut app, 60);
    let cycles = |app: &App| {
        let sim = slice(app, e).sim().unwrap();
        sim.cycle() as f32 + sim.phase()
    };
    let before = cycles(&app);
    {
        let mut assets = app.world_mut().resource_mut::<Assets<Species>>();
        let mut s = assets.get_mut(&h).unwrap();
        s.contraction_frequency = 1.1;
        s.diameter = 0.05; // geometry: the slice rebuilds in place
    }
    run(&mut app, 3);
    let sl = slice(&app, e);
    let sim = sl.sim().unwrap();
    assert_eq!(sim.species().contraction_frequency, 1.1);
    assert_eq!(sim.species().diameter, 0.05);
    assert_eq!(sl.species().unwrap().diameter, 0.05);
    // The stroke carries on from where it was, at the new frequency.
    let after = cycles(&app);
    assert!(
        after >= before && after < before + 0.2,
        "{before} then {after} cycles"
    );
    run(&mut app, 3);
    assert!(!umbrella_positions(&app, e).is_empty());
}

#[test]
fn settings_change_only_the_drawing() {
    let (mut app, _, e) = one_jellyfish();
    run(&mut app, 30);
    let before = slice(&app, e).sim().unwrap().species().clone();
    let vertices = umbrella_positions(&app, e).len();
    app.insert_resource(JellyfishSettings {
        mesh_resolution_scale: 1.0,
        ..default()
    });
    run(&mut app, 2);
    assert_eq!(slice(&app, e).sim().unwrap().species(), &before);
    assert!(umbrella_positions(&app, e).len() > vertices, "a finer mesh");
}

#[test]
fn a_new_species_handle_reaches_the_jellyfish() {
    let mut app = app();
    let h = add_species(&mut app, species());
    let other = add_species(
        &mut app,
        Species {
            name: "Other".into(),
            contraction_frequency: 0.5,
            ..species()
        },
    );
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h), Transform::default()))
        .id();
    run(&mut app, 5);
    app.world_mut().get_mut::<Jellyfish>(e).unwrap().species = other;
    run(&mut app, 2);
    assert_eq!(slice(&app, e).sim().unwrap().species().name, "Other");
}

#[test]
fn an_invalid_edit_is_refused_and_jellyfish_keep_the_last_valid_species() {
    let (mut app, h, e) = one_jellyfish();
    run(&mut app, 10);
    rejections(&mut app);
    app.world_mut()
        .resource_mut::<Assets<Species>>()
        .get_mut(&h)
        .unwrap()
        .contraction_ratio = 3.0;
    run(&mut app, 3);
    let refused = rejections(&mut app);
    assert_eq!(refused.len(), 1, "{refused:?}");
    assert_eq!(refused[0].species, h.id());
    assert_eq!(refused[0].error.field(), Some("contraction_ratio"));
    let time = slice(&app, e).sim().unwrap().time();
    run(&mut app, 10);
    let sim = slice(&app, e).sim().unwrap();
    assert_eq!(sim.species().contraction_ratio, species().contraction_ratio);
    assert!(sim.time() > time, "still swimming");
}

/// A folder of its own for files the test rewrites.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("jellyfish-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Updates (with real pauses: loading is asynchronous) until `done`.
fn wait(app: &mut App, what: &str, mut done: impl FnMut(&mut App) -> bool) {
    for _ in 0..500 {
        app.update();
        if done(app) {
            return;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    panic!("timed out waiting for {what}");
}

/// Species files that failed to load or reload, as Bevy reported them.
#[derive(Resource, Default)]
struct FailedLoads(usize);

fn count_failed_loads(
    mut failed: MessageReader<AssetLoadFailedEvent<Species>>,
    mut count: ResMut<FailedLoads>,
) {
    count.0 += failed.read().count();
}

#[test]
fn an_invalid_species_file_is_refused_naming_the_field() {
    let dir = scratch_dir("reload");
    let file = dir.join("test.species.ron");
    std::fs::write(&file, "(name: \"Test\", tentacle_count: 8)").unwrap();
    let mut app = app_with(AssetPlugin {
        file_path: dir.to_string_lossy().into_owned(),
        ..default()
    });
    app.init_resource::<FailedLoads>()
        .add_systems(Update, count_failed_loads);
    let h: Handle<Species> = app
        .world()
        .resource::<AssetServer>()
        .load("test.species.ron");
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h.clone()), Transform::default()))
        .id();
    wait(&mut app, "the slice", |app| slice(app, e).sim().is_some());

    // A bad file: Bevy logs the loader's error (naming the field), we say what happens.
    std::fs::write(&file, "(name: \"Bad\", diameter: -0.04)").unwrap();
    app.world()
        .resource::<AssetServer>()
        .reload("test.species.ron");
    let mut refused = Vec::new();
    wait(&mut app, "the refusal", |app| {
        refused.extend(rejections(app));
        !refused.is_empty()
    });
    assert_eq!(refused[0].species, h.id());
    assert_eq!(refused[0].error.field(), Some("diameter"));
    assert!(refused[0].error.to_string().contains("diameter"));
    // The same bad file again (a watcher often reloads twice on one save): said once.
    // The reload must have failed again before the count means anything; every frame's
    // refusals are gathered (messages last two frames).
    let settle = |app: &mut App, refused: &mut Vec<SpeciesRejected>| {
        for _ in 0..3 {
            app.update();
            refused.extend(rejections(app));
        }
    };
    settle(&mut app, &mut refused);
    let failed = app.world().resource::<FailedLoads>().0;
    app.world()
        .resource::<AssetServer>()
        .reload("test.species.ron");
    wait(&mut app, "the second failed load", |app| {
        refused.extend(rejections(app));
        app.world().resource::<FailedLoads>().0 > failed
    });
    settle(&mut app, &mut refused);
    refused.extend(rejections(&mut app));
    assert_eq!(refused.len(), 1, "one refusal per bad file: {refused:?}");
    let sim = slice(&app, e).sim().unwrap();
    assert_eq!(sim.species().name, "Test");
    assert_eq!(sim.species().diameter, Species::aurelia().diameter);
    assert_eq!(
        app.world()
            .resource::<Assets<Species>>()
            .get(&h)
            .unwrap()
            .name,
        "Test"
    );

    // A good edit of the file reaches the living jellyfish (hot reload does this on save).
    std::fs::write(&file, "(name: \"Edited\", tentacle_count: 8, glow: 2.0)").unwrap();
    app.world()
        .resource::<AssetServer>()
        .reload("test.species.ron");
    wait(&mut app, "the edit", |app| {
        slice(app, e).species().unwrap().name == "Edited"
    });
    assert_eq!(slice(&app, e).sim().unwrap().species().glow, 2.0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn shipped_species_validate_differ_and_swim() {
    let files = species_files();
    let names: Vec<_> = files
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "aequorea.species.ron",
            "aurelia.species.ron",
            "sarsia.species.ron"
        ]
    );
    let mut all = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let s = Species::from_ron(&text).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        // At its own grid: a small bell needs the finer cells to swim.
        let mut sim = SliceSim::new(&s).unwrap();
        while sim.time() < 3.0 * s.period() {
            sim.advance(1.0 / 32.0);
        }
        assert_eq!(sim.recoveries(), 0, "{}", s.name);
        assert!(
            sim.bell_points().iter().all(|p| p.is_finite()),
            "{}",
            s.name
        );
        assert!(
            sim.swim_distance() > 0.1 * s.diameter,
            "{} swam {} m in three strokes",
            s.name,
            sim.swim_distance()
        );
        all.push(s);
    }
    let [aequorea, aurelia, sarsia] = &all[..] else {
        unreachable!()
    };
    assert_eq!(
        aurelia,
        &Species::aurelia(),
        "aurelia.species.ron is the defaults"
    );
    let flatness = |s: &Species| s.height / s.diameter;
    assert!(
        flatness(aequorea) < 0.6 * flatness(aurelia),
        "Aequorea is flat"
    );
    assert!(
        aurelia.tentacle_count >= 100 && aurelia.tentacle_length < 0.5 * aurelia.diameter,
        "a moon jelly's fringe: hundreds of short tentacles"
    );
    assert!(
        aequorea.tentacle_count >= 50 && aequorea.tentacle_length > 0.5 * aequorea.diameter,
        "a crystal jelly's fringe of long tentacles"
    );
    assert!(flatness(sarsia) > 1.2, "Sarsia is tall");
    assert!(sarsia.tentacle_count <= 4);
    assert!(
        sarsia.tentacle_length > sarsia.height,
        "tentacles longer than the bell"
    );
}

#[test]
fn shipped_species_load_through_the_asset_server() {
    let mut app = app();
    let handles: Vec<Handle<Species>> = ["aurelia", "aequorea", "sarsia"]
        .iter()
        .map(|n| {
            app.world()
                .resource::<AssetServer>()
                .load(format!("species/{n}.species.ron"))
        })
        .collect();
    wait(&mut app, "three species", |app| {
        let assets = app.world().resource::<Assets<Species>>();
        handles.iter().all(|h| assets.contains(h))
    });
    let assets = app.world().resource::<Assets<Species>>();
    let names: Vec<_> = handles
        .iter()
        .map(|h| assets.get(h).unwrap().name.clone())
        .collect();
    assert_eq!(names, ["Aurelia", "Aequorea", "Sarsia"]);
}

/// Runs `frames` frames at `fps`, then one short frame so the clock reads exactly `total`.
fn run_at(fps: u32, total: Duration) -> (Transform, f32, u64) {
    run_at_with(fps, total, |_| {})
}

/// [`run_at`], calling `each_frame` with the app after every frame.
fn run_at_with(
    fps: u32,
    total: Duration,
    mut each_frame: impl FnMut(&App),
) -> (Transform, f32, u64) {
    let mut app = app();
    let h = add_species(&mut app, species());
    let e = app
        .world_mut()
        .spawn((
            Jellyfish::new(h).with_seed(7).with_phase(0.3),
            Transform::from_xyz(0.5, 0.0, 0.0)
                .with_rotation(Quat::from_rotation_x(0.4))
                .with_scale(Vec3::splat(5.0)),
        ))
        .id();
    let step = frame(fps);
    let mut elapsed = Duration::ZERO;
    set_frame(&mut app, step);
    app.update(); // the clock's first update has no delta
    while elapsed + step <= total {
        app.update();
        each_frame(&app);
        elapsed += step;
    }
    set_frame(&mut app, total - elapsed);
    app.update();
    let transform = *app.world().get::<Transform>(e).unwrap();
    let sl = slice(&app, e);
    (transform, sl.swim_distance(), sl.sim().unwrap().steps())
}

#[test]
fn frame_rate_does_not_change_the_motion() {
    let total = Duration::from_millis(2000);
    let (a, da, sa) = run_at(30, total);
    let (b, db, sb) = run_at(144, total);
    assert!(sa > 20, "{sa} steps");
    assert_eq!(sa, sb, "same number of steps");
    assert_eq!(da.to_bits(), db.to_bits(), "same slice");
    assert!(da > 0.0);
    for (x, y) in a
        .translation
        .to_array()
        .iter()
        .zip(b.translation.to_array())
    {
        assert_eq!(x.to_bits(), y.to_bits(), "{a:?} vs {b:?}");
    }
    assert_eq!(a.rotation, b.rotation);
}

#[test]
fn at_144_hz_every_frame_draws_a_new_state() {
    // Slices step every 28 ms, frames come every 7 ms: the drawing must move anyway.
    let mut last: Option<(Vec3, Vec<[f32; 3]>)> = None;
    let mut frames = 0;
    let mut still = Vec::new();
    run_at_with(144, Duration::from_millis(1500), |app| {
        let mut q = app
            .world()
            .try_query::<(Entity, &Transform, &Jellyfish)>()
            .unwrap();
        let (e, t, _) = q.iter(app.world()).next().unwrap();
        let now = (t.translation, umbrella_positions(app, e));
        frames += 1;
        if let Some(before) = &last
            && frames > 20
            && (before.0 == now.0 || before.1 == now.1)
        {
            still.push(frames);
        }
        last = Some(now);
    });
    assert!(frames > 200);
    assert!(still.is_empty(), "frames that showed no motion: {still:?}");
}

#[test]
fn diagnostics_report_simulation_and_meshing_time() {
    let mut app = app();
    let h = add_species(&mut app, species());
    for i in 0..3 {
        app.world_mut().spawn((
            Jellyfish::new(h.clone()),
            Transform::from_xyz(i as f32, 0.0, 0.0),
        ));
    }
    run(&mut app, 10);
    let store = app.world().resource::<DiagnosticsStore>();
    let value = |p: &DiagnosticPath| store.get(p).and_then(|d| d.value()).unwrap();
    assert_eq!(value(&JellyfishDiagnostics::COUNT), 3.0);
    let sim: f64 = store
        .get(&JellyfishDiagnostics::SIMULATION)
        .unwrap()
        .values()
        .sum();
    assert!(sim > 0.0);
    assert!(value(&JellyfishDiagnostics::MESHING) > 0.0);
}

/// `cargo test --test plugin -- --ignored --nocapture`: cost per jellyfish per frame at
/// the default species' grid and full mesh resolution, 60 frames per second.
#[test]
#[ignore]
fn cost_per_jellyfish() {
    let count = 20;
    let mut app = app();
    app.insert_resource(JellyfishSettings::default());
    let h = add_species(&mut app, Species::aurelia());
    for i in 0..count {
        app.world_mut().spawn((
            Jellyfish::new(h.clone()),
            Transform::from_xyz(i as f32, 0.0, 0.0),
        ));
    }
    run(&mut app, 30);
    let frames = 240;
    let (mut sim, mut mesh) = (0.0, 0.0);
    let start = std::time::Instant::now();
    for _ in 0..frames {
        app.update();
        let store = app.world().resource::<DiagnosticsStore>();
        let value = |p: &DiagnosticPath| store.get(p).and_then(|d| d.value()).unwrap();
        sim += value(&JellyfishDiagnostics::SIMULATION);
        mesh += value(&JellyfishDiagnostics::MESHING);
    }
    let wall = start.elapsed().as_secs_f64() * 1e3 / frames as f64;
    let per = |v: f64| v / (frames * count) as f64;
    println!(
        "{count} jellyfish, default grid, 60 fps, {} profile: per jellyfish per frame \
         simulation {:.3} ms, meshing {:.3} ms (CPU); whole frame {wall:.2} ms wall",
        if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        },
        per(sim),
        per(mesh)
    );
}

/// A camera at the origin looking down −z, with the frustum the renderer would compute.
fn spawn_camera(app: &mut App) {
    use bevy::camera::primitives::Frustum;
    let transform = Transform::default();
    let projection = Projection::Perspective(PerspectiveProjection::default());
    let frustum: Frustum = projection.compute_frustum(&GlobalTransform::from(transform));
    app.world_mut()
        .spawn((Camera3d::default(), projection, transform, frustum));
}

#[test]
fn jellyfish_out_of_view_are_not_meshed_but_keep_swimming() {
    use bevy::camera::primitives::Aabb;
    use bevy::camera::visibility::NoAutoAabb;
    let mut app = app();
    spawn_camera(&mut app);
    let h = add_species(&mut app, species());
    let mut spawn = |at: Vec3| {
        app.world_mut()
            .spawn((
                Jellyfish::new(h.clone()).with_phase(0.2),
                Transform::from_translation(at).with_scale(Vec3::splat(10.0)),
            ))
            .id()
    };
    let (ahead, behind) = (
        spawn(Vec3::new(0.0, 0.0, -3.0)),
        spawn(Vec3::new(0.0, 0.0, 3.0)),
    );
    run(&mut app, 10);
    let meshes = |app: &App, e| app.world().get::<JellyfishMeshes>(e).unwrap().seen();
    assert!(meshes(&app, ahead), "in view: meshed");
    assert!(!meshes(&app, behind), "behind the camera: not meshed");
    assert!(
        app.world()
            .get::<JellyfishMeshes>(behind)
            .unwrap()
            .umbrella
            .is_none(),
        "never meshed while out of view"
    );
    let time = slice(&app, behind).sim().unwrap().time();
    run(&mut app, 10);
    assert!(
        slice(&app, behind).sim().unwrap().time() > time,
        "its slice runs on"
    );
    // Bounds come from the slice, not from a scan of the vertices.
    assert!(app.world().get::<NoAutoAabb>(ahead).is_some());
    let before = *app.world().get::<Aabb>(ahead).unwrap();
    run(&mut app, 20);
    let after = *app.world().get::<Aabb>(ahead).unwrap();
    assert_ne!(before, after, "the bounds follow the stroke");
    let positions = umbrella_positions(&app, ahead);
    let (lo, hi) = (after.min(), after.max());
    for p in positions {
        let p = Vec3::from_array(p);
        assert!(
            p.cmpge(Vec3::from(lo) - 1e-5).all() && p.cmple(Vec3::from(hi) + 1e-5).all(),
            "{p} outside {after:?}"
        );
    }
    // Turned to face the camera, it is meshed the next frame.
    app.world_mut()
        .get_mut::<Transform>(behind)
        .unwrap()
        .translation
        .z = -3.0;
    run(&mut app, 2);
    assert!(meshes(&app, behind));
    assert!(
        app.world()
            .get::<JellyfishMeshes>(behind)
            .unwrap()
            .umbrella
            .is_some()
    );
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

/// An app drawing with templates: headless, so it brings its own storage-buffer assets
/// (what a renderer would upload).
fn template_app() -> App {
    Headless {
        settings: JellyfishSettings {
            surfaces: SurfaceMode::Templates,
            ..settings()
        },
        frame: frame(60),
        ..default()
    }
    .build(|app| {
        app.init_asset::<ShaderBuffer>();
    })
}

fn mesh_data_bytes(app: &App) -> f64 {
    let store = app.world().resource::<DiagnosticsStore>();
    store
        .get(&JellyfishDiagnostics::MESH_DATA)
        .and_then(|d| d.value())
        .unwrap_or(f64::NAN)
        * 1e6
}

fn tags(app: &mut App) -> Vec<(Entity, Option<u32>, Option<AssetId<Mesh>>)> {
    let mut q = app
        .world_mut()
        .query_filtered::<(Entity, Option<&MeshTag>, Option<&Mesh3d>), With<Jellyfish>>();
    let mut v: Vec<_> = q
        .iter(app.world())
        .map(|(e, t, m)| (e, t.map(|t| t.0), m.map(|m| m.0.id())))
        .collect();
    v.sort_by_key(|(e, ..)| *e);
    v
}

#[test]
fn templates_share_one_mesh_and_send_kilobytes_not_meshes() {
    let mut app = template_app();
    let h = add_species(&mut app, species());
    let school: Vec<Entity> = (0..4)
        .map(|i| {
            let at = Transform::from_xyz(i as f32, 0.0, 0.0);
            app.world_mut().spawn((Jellyfish::new(h.clone()), at)).id()
        })
        .collect();
    run(&mut app, 6);
    assert_eq!(
        *app.world().resource::<SurfacePath>(),
        SurfacePath::Templates
    );
    let tagged = tags(&mut app);
    let mesh = tagged[0].2.expect("a template mesh");
    assert!(
        tagged.iter().all(|(_, _, m)| *m == Some(mesh)),
        "{tagged:?}"
    );
    let mut slots: Vec<u32> = tagged.iter().map(|(_, t, _)| t.unwrap()).collect();
    slots.sort();
    slots.dedup();
    assert_eq!(slots.len(), 4, "one slot each: {tagged:?}");
    assert!(slots.iter().all(|t| t & 1 == 0), "umbrellas are part 0");
    // Each tentacle child carries its parent's slot, part 1.
    for &e in &school {
        let meshes = app.world().get::<JellyfishMeshes>(e).unwrap();
        let child = meshes.tentacle_entity.expect("tentacles");
        let parent_tag = app.world().get::<MeshTag>(e).unwrap().0;
        assert_eq!(app.world().get::<MeshTag>(child).unwrap().0, parent_tag | 1);
        assert_eq!(meshes.path(), Some(SurfacePath::Templates));
    }
    // A few kilobytes per jellyfish reach the renderer, against the whole mesh.
    let per_jellyfish = mesh_data_bytes(&app) / 4.0;
    let res = JellyfishSettings {
        surfaces: SurfaceMode::Templates,
        ..settings()
    }
    .resolution(&species());
    let mesh_bytes = 32.0 * (res.umbrella_vertices() + res.tentacle_vertices()) as f64;
    println!("{per_jellyfish:.0} bytes per jellyfish per frame, against {mesh_bytes:.0}");
    assert!(
        per_jellyfish > 100.0 && per_jellyfish < 4096.0,
        "{per_jellyfish} bytes"
    );
    assert!(per_jellyfish * 10.0 < mesh_bytes);
    // The shapes change as they swim: the buffer is rewritten, not frozen.
    let buffers = app.world().resource::<ShapeBuffers>().clone();
    let read = |app: &App| {
        let assets = app.world().resource::<Assets<ShaderBuffer>>();
        assets.get(&buffers.shapes).and_then(|b| b.data.clone())
    };
    run(&mut app, 1);
    let first = read(&app);
    run(&mut app, 10);
    assert!(first.is_some() && first != read(&app));
    // Despawning gives the slot back for the next jellyfish.
    let freed = app.world().get::<MeshTag>(school[1]).unwrap().0;
    app.world_mut().entity_mut(school[1]).despawn();
    run(&mut app, 1);
    let e = app.world_mut().spawn(Jellyfish::new(h.clone())).id();
    run(&mut app, 4);
    assert_eq!(app.world().get::<MeshTag>(e).unwrap().0, freed);
}

#[test]
fn switching_surfaces_moves_living_jellyfish_between_paths() {
    let mut app = template_app();
    let h = add_species(&mut app, species());
    let a = app.world_mut().spawn(Jellyfish::new(h.clone())).id();
    let b = app.world_mut().spawn(Jellyfish::new(h.clone())).id();
    run(&mut app, 6);
    let shared = |app: &mut App| {
        let t = tags(app);
        t[0].2.is_some() && t[0].2 == t[1].2 && t.iter().all(|(_, tag, _)| tag.is_some())
    };
    assert!(shared(&mut app));
    let mut cpu = settings();
    cpu.surfaces = SurfaceMode::CpuMeshes;
    app.insert_resource(cpu);
    run(&mut app, 3);
    let t = tags(&mut app);
    assert!(
        t.iter().all(|(_, tag, m)| tag.is_none() && m.is_some()),
        "{t:?}"
    );
    assert_ne!(t[0].2, t[1].2, "CPU meshes are each jellyfish's own");
    assert_eq!(
        umbrella_positions(&app, a).len(),
        umbrella_positions(&app, b).len()
    );
    glow_layers_match_umbrellas(&mut app);
    app.insert_resource(template_settings());
    run(&mut app, 3);
    assert!(shared(&mut app));
    glow_layers_match_umbrellas(&mut app);
}

/// One glow layer per jellyfish (none left over from a path it left), drawing the
/// umbrella's mesh with the umbrella's tag.
fn glow_layers_match_umbrellas(app: &mut App) {
    let mut glows = app
        .world_mut()
        .query_filtered::<(Entity, &Mesh3d, Option<&MeshTag>, &ChildOf), With<JellyfishGlow>>();
    let glows: Vec<_> = glows
        .iter(app.world())
        .map(|(e, m, t, c)| (e, m.0.id(), t.map(|t| t.0), c.parent()))
        .collect();
    let umbrellas = tags(app);
    assert_eq!(glows.len(), umbrellas.len(), "{glows:?}");
    for (jellyfish, tag, mesh) in umbrellas {
        let own = app
            .world()
            .get::<JellyfishMeshes>(jellyfish)
            .unwrap()
            .glow_entity;
        let glow = glows
            .iter()
            .find(|g| g.3 == jellyfish)
            .expect("a glow layer");
        assert_eq!(Some(glow.0), own);
        assert_eq!((glow.1, glow.2), (mesh.unwrap(), tag), "{glows:?}");
    }
}

fn template_settings() -> JellyfishSettings {
    JellyfishSettings {
        surfaces: SurfaceMode::Templates,
        ..settings()
    }
}

#[test]
fn a_game_material_keeps_cpu_meshes_and_templates_fall_back_without_buffers() {
    let mut app = template_app();
    let h = add_species(&mut app, species());
    let own = app
        .world_mut()
        .spawn((
            Jellyfish::new(h.clone()),
            MeshMaterial3d::<StandardMaterial>(Handle::default()),
        ))
        .id();
    let plain = app.world_mut().spawn(Jellyfish::new(h.clone())).id();
    run(&mut app, 6);
    let path = |app: &App, e| app.world().get::<JellyfishMeshes>(e).unwrap().path();
    assert_eq!(path(&app, own), Some(SurfacePath::CpuMeshes));
    assert_eq!(path(&app, plain), Some(SurfacePath::Templates));
    assert!(!umbrella_positions(&app, own).is_empty());

    // Templates asked for where nothing can hold the shapes: CPU meshes, not nothing.
    let mut app = app_with(AssetPlugin::default());
    app.insert_resource(template_settings());
    let h = add_species(&mut app, species());
    let e = app.world_mut().spawn(Jellyfish::new(h)).id();
    run(&mut app, 6);
    assert_eq!(
        *app.world().resource::<SurfacePath>(),
        SurfacePath::CpuMeshes
    );
    assert!(!umbrella_positions(&app, e).is_empty());
}

/// What `JellyfishGeometry` gives is the drawn mesh, in world space, inside the bounds.
#[test]
fn geometry_is_the_drawn_surface_in_world_space() {
    let (mut app, _, e) = one_jellyfish();
    let placed = Transform::from_xyz(1.0, 2.0, -3.0)
        .with_rotation(Quat::from_rotation_z(0.7) * Quat::from_rotation_x(0.3))
        .with_scale(Vec3::splat(25.0));
    app.world_mut().entity_mut(e).insert(placed);
    run(&mut app, 8);
    let drawn = umbrella_positions(&app, e);
    let world = *app.world().get::<GlobalTransform>(e).unwrap();
    let (surfaces, sphere) = app
        .world_mut()
        .run_system_once(move |geometry: JellyfishGeometry| {
            (geometry.surfaces(e), geometry.bounding_sphere(e))
        })
        .unwrap();
    let surfaces = surfaces.expect("a drawn jellyfish has geometry");
    let (centre, radius) = sphere.unwrap();
    assert_eq!(surfaces.umbrella.positions.len(), drawn.len());
    for (p, local) in surfaces.umbrella.positions.iter().zip(&drawn) {
        let expect = world.transform_point(Vec3::from_array(*local));
        assert!(
            Vec3::from_array(*p).distance(expect) < 1e-4,
            "{p:?} vs {expect}"
        );
    }
    for p in surfaces
        .umbrella
        .positions
        .iter()
        .chain(&surfaces.tentacles.positions)
    {
        assert!(Vec3::from_array(*p).distance(centre) <= radius * 1.0001);
    }
    // Normals are unit and point out of the bell at the exumbrellar apex.
    let n = Vec3::from_array(surfaces.umbrella.normals[0]);
    assert!((n.length() - 1.0).abs() < 1e-4);
    assert!(n.dot(world.rotation() * Vec3::Y) > 0.9);
    let not_a_jellyfish = app.world_mut().spawn_empty().id();
    let none = app
        .world_mut()
        .run_system_once(move |g: JellyfishGeometry| g.surfaces(not_a_jellyfish).is_none())
        .unwrap();
    assert!(none);
}

// --- Levels of detail ---

fn set_detail(app: &mut App, near: usize, mid: usize) {
    app.world_mut().resource_mut::<JellyfishSettings>().detail = DetailLevels {
        near,
        mid,
        ..default()
    };
}

/// The largest change of any umbrella vertex (mesh frame) and of the position from one
/// frame to the next, over `frames` frames.
fn largest_frame_changes(app: &mut App, e: Entity, frames: usize) -> (f32, f32) {
    let (mut shape, mut travel) = (0.0f32, 0.0f32);
    let mut last = (
        umbrella_positions(app, e),
        app.world().get::<Transform>(e).unwrap().translation,
    );
    for _ in 0..frames {
        app.update();
        let now = (
            umbrella_positions(app, e),
            app.world().get::<Transform>(e).unwrap().translation,
        );
        for (a, b) in now.0.iter().zip(&last.0) {
            shape = shape.max(Vec3::from(*a).distance(Vec3::from(*b)));
        }
        travel = travel.max(now.1.distance(last.1));
        last = now;
    }
    (shape, travel)
}

#[test]
fn beyond_the_budget_jellyfish_replay_their_cycle_and_change_tier_without_a_jump() {
    let mut app = app();
    set_detail(&mut app, 1, 0);
    let h = add_species(&mut app, species());
    let spawn = |app: &mut App, x: f32| {
        app.world_mut()
            .spawn((
                Jellyfish::new(h.clone()).with_phase(0.3),
                Transform::from_xyz(x, 0.0, 0.0).with_scale(Vec3::splat(10.0)),
            ))
            .id()
    };
    let (a, b) = (spawn(&mut app, 0.0), spawn(&mut app, 5.0));
    let (first, second) = (a.min(b), a.max(b));
    run(&mut app, 30);
    // No camera: the lowest entity is near, the other replays its species' cycle.
    assert_eq!(slice(&app, first).tier(), Tier::Near);
    assert_eq!(slice(&app, second).tier(), Tier::Far);
    assert!(slice(&app, second).sim().is_none() && slice(&app, second).started());
    // The replay swims the recorded cycle's distance.
    let period = species().period();
    let cycle = app
        .world_mut()
        .resource_mut::<CycleCaches>()
        .get(&species())
        .unwrap()
        .swim_per_cycle();
    let y = |app: &App| app.world().get::<Transform>(second).unwrap().translation.y;
    let y0 = y(&app);
    run(&mut app, (3.0 * period * 60.0).round() as usize);
    let swum = (y(&app) - y0) / 10.0;
    assert!(
        (swum - 3.0 * cycle).abs() < 0.05 * 3.0 * cycle,
        "far: {swum} m in 3 cycles, recorded {cycle} m per cycle"
    );
    // Frame to frame changes while far, then across a promotion and a demotion: no
    // larger than the stroke's own.
    let (shape, travel) = largest_frame_changes(&mut app, second, 60);
    set_detail(&mut app, 2, 0);
    let (promoted_shape, promoted_travel) = largest_frame_changes(&mut app, second, 60);
    assert_eq!(slice(&app, second).tier(), Tier::Near);
    assert!(slice(&app, second).sim().is_some());
    set_detail(&mut app, 1, 0);
    let (demoted_shape, demoted_travel) = largest_frame_changes(&mut app, second, 60);
    assert_eq!(slice(&app, second).tier(), Tier::Far);
    for (what, change, stroke) in [
        ("shape, promoted", promoted_shape, shape),
        ("shape, demoted", demoted_shape, shape),
        ("travel, promoted", promoted_travel, travel),
        ("travel, demoted", demoted_travel, travel),
    ] {
        assert!(
            change <= 1.2 * stroke,
            "{what}: {change} per frame against {stroke} in the stroke"
        );
    }
}

#[test]
fn tiers_follow_size_on_screen_and_replay_identically() {
    let positions = || {
        let mut app = app();
        set_detail(&mut app, 1, 1);
        spawn_camera(&mut app);
        let h = add_species(&mut app, species());
        // Spawned farthest first, so entity order would pick the wrong ones.
        let e: Vec<Entity> = [-16.0, -8.0, -4.0, -2.0]
            .into_iter()
            .map(|z| {
                app.world_mut()
                    .spawn((
                        Jellyfish::new(h.clone()),
                        Transform::from_xyz(0.0, 0.0, z).with_scale(Vec3::splat(10.0)),
                    ))
                    .id()
            })
            .collect();
        run(&mut app, 90);
        let tiers: Vec<Tier> = e.iter().map(|e| slice(&app, *e).tier()).collect();
        assert_eq!(tiers, [Tier::Far, Tier::Far, Tier::Mid, Tier::Near]);
        let store = app.world().resource::<DiagnosticsStore>();
        let far = store
            .get(&JellyfishDiagnostics::FAR)
            .and_then(|d| d.value());
        assert_eq!(far, Some(2.0));
        e.iter()
            .map(|e| app.world().get::<Transform>(*e).unwrap().translation)
            .collect::<Vec<_>>()
    };
    assert_eq!(
        positions(),
        positions(),
        "a replay is the same, bit for bit"
    );
}

#[test]
fn pausing_virtual_time_pauses_the_jellyfish() {
    let (mut app, _, e) = one_jellyfish();
    run(&mut app, 60);
    let at = |app: &App| *app.world().get::<Transform>(e).unwrap();
    app.world_mut().resource_mut::<Time<Virtual>>().pause();
    let paused = at(&app);
    run(&mut app, 30);
    assert_eq!(at(&app), paused, "paused");
    app.world_mut().resource_mut::<Time<Virtual>>().unpause();
    run(&mut app, 30);
    assert_ne!(at(&app), paused, "moving again");
}

#[test]
fn an_edit_records_the_far_cycle_in_the_background() {
    let mut app = app();
    set_detail(&mut app, 1, 0);
    let h = add_species(&mut app, species());
    for x in [0.0, 5.0] {
        app.world_mut()
            .spawn((Jellyfish::new(h.clone()), Transform::from_xyz(x, 0.0, 0.0)));
    }
    run(&mut app, 10);
    let edited = Species {
        contraction_frequency: 1.0,
        ..species()
    };
    {
        let mut assets = app.world_mut().resource_mut::<Assets<Species>>();
        *assets.get_mut(&h).unwrap() = edited.clone();
    }
    // Frames go on while it records; the far jellyfish then plays the new cycle.
    let mut frames = 0;
    while app
        .world()
        .resource::<CycleCaches>()
        .find(&edited)
        .is_none()
    {
        assert!(frames < 2000, "the edited cycle was never recorded");
        app.update();
        frames += 1;
    }
    run(&mut app, 2);
    let mut q = app.world_mut().query::<&JellyfishSlice>();
    let far: Vec<_> = q
        .iter(app.world())
        .filter(|s| s.tier() == Tier::Far)
        .collect();
    assert_eq!(far.len(), 1);
    assert_eq!(far[0].species(), Some(&edited));
    assert!(!app.world().resource::<CycleCaches>().recording());
}

#[test]
fn a_promoted_jellyfish_draws_what_it_would_have_drawn_far() {
    // Two identical apps of far jellyfish; in one, all become near at once.
    let make = || {
        let mut app = app();
        set_detail(&mut app, 0, 0);
        let h = add_species(&mut app, species());
        let e: Vec<Entity> = (0..4)
            .map(|i| {
                app.world_mut()
                    .spawn((
                        Jellyfish::new(h.clone()).with_phase(i as f32 * 0.23),
                        Transform::from_xyz(i as f32, 0.0, 0.0).with_scale(Vec3::splat(10.0)),
                    ))
                    .id()
            })
            .collect();
        run(&mut app, 100);
        (app, e)
    };
    let (mut far, ef) = make();
    let (mut promoted, ep) = make();
    set_detail(&mut promoted, 100, 0);
    // The live slice resumes the recorded state, so until the recorded cycle ends the
    // frames are the same.
    for _ in 0..4 {
        far.update();
        promoted.update();
        for (a, b) in ef.iter().zip(&ep) {
            assert_eq!(slice(&promoted, *b).tier(), Tier::Near);
            let shape = umbrella_positions(&far, *a)
                .iter()
                .zip(&umbrella_positions(&promoted, *b))
                .map(|(p, q)| Vec3::from(*p).distance(Vec3::from(*q)))
                .fold(0.0f32, f32::max);
            let at = |app: &App, e: Entity| app.world().get::<Transform>(e).unwrap().translation;
            assert!(shape < 1e-6, "shape differs by {shape}");
            assert!(at(&far, *a).distance(at(&promoted, *b)) < 1e-6);
        }
    }
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
