//! Time: the motion is the same at any frame rate, every frame at 144 Hz draws a new
//! state, pausing pauses, and the diagnostics measure each frame.

use super::*;

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
