//! Levels of detail: tiers by size on screen within the budgets, replays of the recorded
//! cycle, changes of tier without a jump, and edits while far.

use super::*;

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
    replay_and_change_tier(species());
}

#[test]
fn an_axisymmetric_species_is_stepped_recorded_and_replayed_alike() {
    replay_and_change_tier(Species {
        slice_geometry: SliceGeometry::Axisymmetric,
        ..species()
    });
}

/// Two jellyfish of `species` with room for one near: the other replays the species'
/// recorded cycle, swims its distance, and changes tier both ways without a jump.
fn replay_and_change_tier(species: Species) {
    let mut app = app();
    set_detail(&mut app, 1, 0);
    let h = add_species(&mut app, species.clone());
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
    let period = species.period();
    let cycle = app
        .world_mut()
        .resource_mut::<CycleCaches>()
        .get(&species)
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
        // Each tier's stepping and meshing is timed, and is a part of the totals.
        let sum = |p: &DiagnosticPath| store.get(p).map_or(0.0, |d| d.values().sum::<f64>());
        let tiers = [
            JellyfishDiagnostics::NEAR_MS,
            JellyfishDiagnostics::MID_MS,
            JellyfishDiagnostics::FAR_MS,
        ]
        .map(|p| sum(&p));
        assert!(
            tiers.iter().all(|ms| *ms > 0.0),
            "every tier timed: {tiers:?}"
        );
        let total = sum(&JellyfishDiagnostics::SIMULATION) + sum(&JellyfishDiagnostics::MESHING);
        assert!(
            tiers.iter().sum::<f64>() <= total * (1.0 + 1e-9),
            "the tiers are parts of the totals: {tiers:?} of {total}"
        );
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

/// An edit records the far cycle a few steps a frame while the old one plays, then the
/// far jellyfish plays the new one. How many frames that takes is a count of steps, so
/// the same in every run, and fewer steps a frame spread it over more frames.
#[test]
fn an_edit_records_the_far_cycle_a_few_steps_a_frame() {
    let frames_to_record = |steps: u32| {
        let mut app = app();
        app.world_mut().resource_mut::<JellyfishSettings>().detail = DetailLevels {
            near: 1,
            mid: 0,
            recording_steps_per_frame: steps,
            ..default()
        };
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
            || app.world().resource::<CycleCaches>().recording()
        {
            assert!(frames < 4000, "the edited cycle was never recorded");
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
        // The mid tier's compact variant too, for the first move there.
        let caches = app.world().resource::<CycleCaches>();
        assert!(caches.find(&edited.compact_box()).is_some());
        frames
    };
    let (a, again, quicker) = (
        frames_to_record(24),
        frames_to_record(24),
        frames_to_record(96),
    );
    println!("recorded in {a} frames at 24 steps a frame, {quicker} at 96");
    assert_eq!(a, again, "the same frame in every run");
    // The warm-up alone is eight cycles of about a hundred steps.
    assert!(a > 30, "{a} frames: spread out");
    assert!(quicker < a / 2, "{quicker} frames at 96 steps, {a} at 24");
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
    // frames are the same: the same place, and the same shape but for the far one showing
    // the nearer recorded step where the near one blends the two around the frame's time
    // (half a step at most, less than a frame's own change).
    let largest = |a: &[[f32; 3]], b: &[[f32; 3]]| {
        a.iter()
            .zip(b)
            .map(|(p, q)| Vec3::from(*p).distance(Vec3::from(*q)))
            .fold(0.0f32, f32::max)
    };
    let mut before: Vec<_> = ef.iter().map(|e| umbrella_positions(&far, *e)).collect();
    let (mut shape, mut frame) = (0.0f32, 0.0f32);
    for _ in 0..4 {
        far.update();
        promoted.update();
        for (k, (a, b)) in ef.iter().zip(&ep).enumerate() {
            assert_eq!(slice(&promoted, *b).tier(), Tier::Near);
            let now = umbrella_positions(&far, *a);
            shape = shape.max(largest(&now, &umbrella_positions(&promoted, *b)));
            frame = frame.max(largest(&now, &before[k]));
            let at = |app: &App, e: Entity| app.world().get::<Transform>(e).unwrap().translation;
            assert!(at(&far, *a).distance(at(&promoted, *b)) < 1e-6);
            before[k] = now;
        }
    }
    println!("promoted against far: shapes differ by {shape}, a frame changes one by {frame}");
    assert!(
        shape <= 0.75 * frame,
        "shape differs by {shape}, a frame changes it by {frame}"
    );
}

/// Physics never depends on the order jellyfish are stepped: the same scene, once with
/// a marker on every other jellyfish (which moves them to another table, so every query
/// meets them in another order and the parallel batches hold other jellyfish), swims,
/// trails and draws the same, bit for bit, near, mid and far, alone and in a school.
#[test]
fn the_order_jellyfish_are_stepped_in_changes_nothing() {
    #[derive(Component)]
    struct Shuffled;
    type State = (Vec<u32>, Vec<u32>, Vec<u32>, Tier);
    let scene = |shuffle: bool| {
        let mut app = app();
        set_detail(&mut app, 2, 2);
        spawn_camera(&mut app);
        let h = add_species(&mut app, species());
        let sarsia = add_species(
            &mut app,
            Species {
                tentacle_count: 4,
                ..Species::sarsia()
            },
        );
        for (k, z) in [-3.0f32, -24.0, -5.0, -12.0, -2.0, -40.0, -8.0]
            .iter()
            .enumerate()
        {
            let species = if k % 2 == 0 {
                h.clone()
            } else {
                sarsia.clone()
            };
            app.world_mut().spawn((
                Jellyfish::new(species).with_seed(k as u32 + 1),
                Transform::from_xyz(k as f32 - 3.0, 0.0, *z).with_scale(Vec3::splat(10.0)),
            ));
        }
        app.world_mut().spawn((
            bevy_jellyfish::plugin::JellyfishSchool::new(h, 6, Vec3::new(3.0, 2.0, 3.0))
                .with_seed(3),
            Transform::from_xyz(0.0, 0.0, -15.0),
        ));
        run(&mut app, 2);
        if shuffle {
            let world = app.world_mut();
            let all: Vec<Entity> = world
                .query_filtered::<Entity, With<Jellyfish>>()
                .iter(world)
                .collect();
            for e in all.into_iter().step_by(2) {
                world.entity_mut(e).insert(Shuffled);
            }
        }
        run(&mut app, 150);
        let world = app.world_mut();
        let mut states: Vec<(Entity, State)> = world
            .query::<(
                Entity,
                &Transform,
                &JellyfishSlice,
                Option<&bevy_jellyfish::plugin::TentacleGuides>,
            )>()
            .iter(world)
            .map(|(e, t, s, guides)| {
                let pose = t
                    .translation
                    .to_array()
                    .into_iter()
                    .chain(t.rotation.to_array())
                    .chain([s.phase().unwrap_or(-1.0), s.swim_distance()])
                    .map(f32::to_bits)
                    .collect();
                let trail = guides
                    .map(|g| {
                        g.reference()
                            .iter()
                            .chain(g.offsets())
                            .flat_map(|v| v.to_array())
                    })
                    .into_iter()
                    .flatten()
                    .map(f32::to_bits)
                    .collect();
                (e, (pose, trail, Vec::new(), s.tier()))
            })
            .collect();
        for (e, state) in &mut states {
            let meshes = app.world().get::<JellyfishMeshes>(*e).unwrap();
            if meshes.umbrella.is_some() {
                state.2 = umbrella_positions(&app, *e)
                    .iter()
                    .flatten()
                    .map(|v| v.to_bits())
                    .collect();
            }
        }
        let met: Vec<Entity> = states.iter().map(|(e, _)| *e).collect();
        states.sort_by_key(|(e, _)| *e);
        (states, met)
    };
    let ((calm, calm_order), (shuffled, shuffled_order)) = (scene(false), scene(true));
    assert_ne!(calm_order, shuffled_order, "the marker changes the order");
    let tiers: Vec<Tier> = calm.iter().map(|(_, s)| s.3).collect();
    for tier in [Tier::Near, Tier::Mid, Tier::Far] {
        assert!(
            tiers.contains(&tier),
            "the scene has {tier:?} jellyfish: {tiers:?}"
        );
    }
    assert_eq!(calm.len(), 13);
    let mut drawn = 0;
    for ((e, a), (_, b)) in calm.iter().zip(&shuffled) {
        assert_eq!(a.3, b.3, "{e}: tier");
        assert!(
            a.0 == b.0,
            "{e} ({:?}): pose, phase or distance differ",
            a.3
        );
        assert!(a.1 == b.1, "{e} ({:?}): trails differ", a.3);
        assert!(a.2 == b.2, "{e} ({:?}): umbrellas differ", a.3);
        drawn += usize::from(!a.2.is_empty());
    }
    println!(
        "{} jellyfish ({tiers:?}), {drawn} of them meshed",
        calm.len()
    );
    assert!(drawn >= 4, "{drawn} umbrellas meshed");
}
