//! Water and steering through the real plugin, headless: currents carry jellyfish, a stir
//! moves those near it, a swimmer held in a current stays put, commanded turns happen
//! during strokes only, and all of it replays bit for bit, whatever order the jellyfish
//! are met in.

use crate::common::app::{Headless, SCALE, spawn};
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::Species;
use bevy_jellyfish::plugin::{
    AmbientWater, DetailLevels, JellyfishSettings, JellyfishSlice, Resting, Steering, SwimMotion,
    TankWater, Tier,
};
use bevy_jellyfish::sim::tank::TankFluid;
use std::time::Duration;

fn app() -> App {
    Headless::default().build(|_| {})
}

/// Aurelia with a light mesh (8 tentacles) for the debug build.
fn species() -> Species {
    Species {
        tentacle_count: 8,
        ..Species::aurelia()
    }
}

fn run_for(app: &mut App, seconds: f32) {
    for _ in 0..(seconds * 60.0).round() as usize {
        app.update();
    }
}

fn at(app: &App, e: Entity) -> Vec3 {
    app.world().get::<Transform>(e).unwrap().translation
}

fn axis(app: &App, e: Entity) -> Vec3 {
    app.world().get::<SwimMotion>(e).unwrap().pose.rotation * Vec3::Y
}

#[test]
fn a_resting_jellyfish_drifts_with_a_uniform_current() {
    let mut app = app();
    let current = Vec3::new(0.4, 0.0, -0.3);
    app.insert_resource(AmbientWater::uniform(current));
    let e = spawn(&mut app, &species(), Vec3::ZERO, Resting);
    run_for(&mut app, 1.0);
    let start = at(&app, e);
    run_for(&mut app, 4.0);
    let drift = (at(&app, e) - start) / 4.0;
    assert!(
        (drift - current).length() <= 0.05 * current.length(),
        "drifted at {drift}, the current is {current}"
    );
    let sim = app.world().get::<JellyfishSlice>(e).unwrap().sim().unwrap();
    assert!(sim.resting() && sim.phase() == 0.0, "the stroke is held");
}

/// Where a jellyfish resting in a shear current is after `seconds`, at `fps` frames a
/// second, near (its own slice) or far (its species' replayed cycle).
fn drift_in_a_shear(fps: u32, near: bool, seconds: u32) -> Transform {
    let mut app = Headless {
        settings: JellyfishSettings {
            mesh_resolution_scale: 0.25,
            detail: DetailLevels {
                near: near as usize,
                mid: 0,
                ..default()
            },
            ..default()
        },
        frame: Duration::from_secs(1) / fps,
        ..default()
    }
    .build(|_| {});
    app.insert_resource(AmbientWater::from_fn(|p, _| {
        Vec3::new(0.3 + 0.2 * p.y, 0.0, 0.1 * p.x)
    }));
    let e = spawn(&mut app, &species(), Vec3::new(0.0, 0.5, 0.0), Resting);
    // The clock's first update has no delta.
    for _ in 0..=fps * seconds {
        app.update();
    }
    let tier = app.world().get::<JellyfishSlice>(e).unwrap().tier();
    assert_eq!(tier, if near { Tier::Near } else { Tier::Far });
    *app.world().get::<Transform>(e).unwrap()
}

#[test]
fn a_far_jellyfish_drifts_as_a_near_one_and_alike_at_any_frame_rate() {
    // A far jellyfish reads the water four times a second of its steps and holds it
    // between: a whole number of its own steps, so its path is the same at any frame rate,
    // and close to a near one's, which reads it every step.
    let (slow, quick) = (
        drift_in_a_shear(30, false, 3),
        drift_in_a_shear(90, false, 3),
    );
    assert_eq!(
        slow.translation.to_array().map(f32::to_bits),
        quick.translation.to_array().map(f32::to_bits),
        "{slow:?} against {quick:?}"
    );
    assert_eq!(slow.rotation, quick.rotation);
    let near = drift_in_a_shear(30, true, 3);
    let start = Vec3::new(0.0, 0.5, 0.0);
    let (far_drift, near_drift) = (
        slow.translation.distance(start),
        near.translation.distance(start),
    );
    let apart = slow.translation.distance(near.translation);
    assert!(near_drift > 0.5, "the near one drifted {near_drift}");
    assert!(
        apart < 0.02 * near_drift,
        "far drifted {far_drift} to {}, near {near_drift} to {}: {apart} apart",
        slow.translation,
        near.translation
    );
}

#[test]
fn a_resting_jellyfish_resumes_its_stroke_in_phase() {
    let mut app = app();
    let e = spawn(&mut app, &species(), Vec3::ZERO, ());
    run_for(&mut app, 0.5);
    app.world_mut().entity_mut(e).insert(Resting);
    run_for(&mut app, 0.2);
    let phase = |app: &App| {
        app.world()
            .get::<JellyfishSlice>(e)
            .unwrap()
            .sim()
            .unwrap()
            .phase()
    };
    let held = phase(&app);
    run_for(&mut app, 1.0);
    assert_eq!(phase(&app), held, "held while resting");
    app.world_mut().entity_mut(e).remove::<Resting>();
    run_for(&mut app, 0.1);
    let resumed = phase(&app);
    assert!(
        resumed > held && resumed < held + 0.1,
        "{held} then {resumed}"
    );
}

/// Mean swimming speed (world units per second) over strokes 10–20 of a free swimmer.
fn free_speed(species: &Species) -> f32 {
    let mut app = app();
    let e = spawn(&mut app, species, Vec3::ZERO, ());
    let period = species.period();
    run_for(&mut app, 10.0 * period);
    let start = at(&app, e);
    run_for(&mut app, 10.0 * period);
    (at(&app, e) - start).length() / (10.0 * period)
}

#[test]
fn a_swimmer_held_by_a_current_as_fast_as_it_swims_stays_put() {
    let s = species();
    let speed = free_speed(&s);
    assert!(speed > 0.0);
    let mut app = app();
    app.insert_resource(AmbientWater::uniform(-Vec3::Y * speed));
    let e = spawn(&mut app, &s, Vec3::ZERO, ());
    run_for(&mut app, 10.0 * s.period());
    let start = at(&app, e);
    let diameter = s.diameter * SCALE;
    let mut farthest = 0.0f32;
    for _ in 0..10 {
        run_for(&mut app, s.period());
        farthest = farthest.max(at(&app, e).distance(start));
    }
    assert!(
        farthest <= 0.5 * diameter,
        "moved {farthest} from its start, half a diameter is {}",
        0.5 * diameter
    );
}

#[test]
fn a_stir_moves_jellyfish_near_it_and_not_those_far_away() {
    let mut app = app();
    let mut tank = TankWater::new(
        Vec3::new(-10.0, 0.0, -10.0),
        Vec3::new(10.0, 10.0, 10.0),
        0.5,
    );
    tank.jet_strength = 0.0;
    app.insert_resource(tank);
    // The stir's radius; a jellyfish within two of them, one beyond five.
    let radius = 1.0;
    let centre = Vec3::new(0.0, 5.0, 0.0);
    let near = spawn(
        &mut app,
        &species(),
        centre + Vec3::Z * 1.5 * radius,
        Resting,
    );
    let far = spawn(
        &mut app,
        &species(),
        centre + Vec3::X * 5.5 * radius,
        Resting,
    );
    run_for(&mut app, 0.5);
    let (near0, far0) = (at(&app, near), at(&app, far));
    app.world_mut()
        .resource_mut::<TankWater>()
        .stir(centre, radius, Vec3::new(0.0, 0.0, 5.0));
    run_for(&mut app, 2.0);
    let (moved_near, moved_far) = (at(&app, near).distance(near0), at(&app, far).distance(far0));
    println!(
        "a stir moved the jellyfish 1.5 radii away {moved_near:.3}, 5.5 radii away {moved_far:.4}"
    );
    assert!(moved_near > 0.3, "the near one moved {moved_near}");
    let diameter = species().diameter * SCALE;
    assert!(
        moved_far < 0.05 * moved_near && moved_far < 0.05 * diameter,
        "the far one moved {moved_far} (near {moved_near})"
    );
}

/// The tank's water steps on every `ticks_per_step`th fixed tick by the ticks' time
/// together: after any number of ticks it is, bit for bit, the water stepped by hand that
/// many times over, with every other tick (the default) and with every tick. Above one
/// tick a step, a step begun on its tick is finished, and seen, on the next.
#[test]
fn the_tank_steps_once_every_ticks_per_step_fixed_ticks() {
    for ticks_per_step in [2, 1] {
        let (min, max, cell) = (Vec3::new(-4.0, 0.0, -4.0), Vec3::new(4.0, 6.0, 4.0), 0.5);
        let (at, radius, push) = (Vec3::new(0.5, 3.0, 0.0), 1.2, Vec3::new(1.0, 0.4, 0.0));
        let mut app = app();
        let mut tank = TankWater::new(min, max, cell);
        (tank.jet_strength, tank.ticks_per_step) = (0.0, ticks_per_step);
        tank.stir(at, radius, push);
        app.insert_resource(tank);
        app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            1.0 / 64.0,
        )));
        let mut checked = 0;
        for _ in 0..24 {
            app.update();
            let fixed = app.world().resource::<Time<Fixed>>();
            let ticks = (fixed.elapsed().as_nanos() / fixed.timestep().as_nanos()) as u32;
            let mut by_hand = TankFluid::new(min, max, cell);
            by_hand.stir(at, radius, push);
            let dt = fixed.timestep().as_secs_f32() * ticks_per_step as f32;
            let finished = if ticks_per_step > 1 {
                ticks.saturating_sub(1) / ticks_per_step
            } else {
                ticks
            };
            for _ in 0..finished {
                by_hand.step(dt);
            }
            let bits = |v: &[Vec3]| {
                v.iter()
                    .map(|v| v.to_array().map(f32::to_bits))
                    .collect::<Vec<_>>()
            };
            let water = app.world().resource::<TankWater>();
            assert!(
                bits(water.velocities()) == bits(by_hand.velocities()),
                "after {ticks} ticks, stepping every {ticks_per_step}"
            );
            checked += usize::from(ticks >= 2 * ticks_per_step);
        }
        assert!(
            checked > 10,
            "{checked} updates checked after the water moved"
        );
    }
}

#[test]
fn a_commanded_right_angle_turn_takes_a_few_strokes_and_none_while_coasting() {
    let s = species();
    let mut app = app();
    // One fixed tick per update.
    app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / 64.0,
    )));
    let e = spawn(&mut app, &s, Vec3::ZERO, Steering::heading(Vec3::X));
    app.update();
    // Count strokes until the axis is within 5° of +x, and watch the coasting halves.
    let ticks_per_stroke = (s.period() * 64.0) as usize;
    let mut strokes = None;
    let mut turned_while_coasting = Vec::new();
    for tick in 0..12 * ticks_per_stroke {
        let before = (axis(&app, e), phase_of(&app, e));
        app.update();
        let after = (axis(&app, e), phase_of(&app, e));
        // Both ends of the tick in the coasting part of the cycle, no new stroke begun.
        let duty = s.contraction_duty;
        let step = 1.0 / s.steps_per_cycle() as f32;
        if before.1 > duty + step && after.1 > before.1 && before.0 != after.0 {
            turned_while_coasting.push(tick);
        }
        if strokes.is_none() && after.0.angle_between(Vec3::X) < 5f32.to_radians() {
            strokes = Some(tick as f32 / ticks_per_stroke as f32);
        }
    }
    let strokes = strokes.expect("the turn completes");
    println!("a right angle in {strokes:.1} strokes from rest");
    assert!(strokes <= 6.0, "{strokes} strokes");
    assert!(strokes >= 1.0, "{strokes}: no snapping round");
    assert!(
        turned_while_coasting.is_empty(),
        "turned while coasting at ticks {turned_while_coasting:?}"
    );
}

fn phase_of(app: &App, e: Entity) -> f32 {
    app.world()
        .get::<JellyfishSlice>(e)
        .and_then(|s| s.sim())
        .map_or(0.0, |s| s.phase())
}

/// Angle turned towards +x in two strokes.
fn turn_in_two_strokes(species: &Species) -> f32 {
    let mut app = app();
    let e = spawn(&mut app, species, Vec3::ZERO, Steering::heading(Vec3::X));
    app.update();
    let start = axis(&app, e);
    run_for(&mut app, 2.0 * species.period());
    axis(&app, e).angle_between(start)
}

#[test]
fn a_stronger_stroke_turns_faster() {
    let strong = species();
    let weak = Species {
        contraction_ratio: 0.8,
        ..species()
    };
    let (a, b) = (turn_in_two_strokes(&strong), turn_in_two_strokes(&weak));
    println!(
        "two strokes turn {:.1}° (ratio 0.56) and {:.1}° (ratio 0.8)",
        a.to_degrees(),
        b.to_degrees()
    );
    assert!(a > 1.3 * b, "strong {a} rad, weak {b} rad");
}

/// Transforms, and the tank's water as bits, after a scripted run with a swirling
/// current, a stirred tank whose jets overlap, and steering. `shuffle` puts a marker on
/// every other jellyfish after the first frame: another table, so every query (the
/// jets' gathering among them) meets them in another order.
fn scripted_run(shuffle: bool) -> (Vec<Transform>, Vec<[u32; 3]>) {
    #[derive(Component)]
    struct Shuffled;
    let mut app = app();
    let mut tank = TankWater::new(Vec3::new(-6.0, 0.0, -6.0), Vec3::new(6.0, 8.0, 6.0), 0.75);
    tank.jet_strength = 0.5;
    app.insert_resource(tank);
    let mut entities = Vec::new();
    for k in 0..4 {
        let p = Vec3::new(-2.0 + 1.5 * k as f32, 3.0, 0.5 * k as f32);
        let steering = Steering::towards(Vec3::new(0.0, 6.0, 0.0));
        entities.push(spawn(&mut app, &species(), p, steering));
    }
    for frame in 0..180 {
        if frame % 40 == 10 {
            app.world_mut().resource_mut::<TankWater>().stir(
                Vec3::new(0.0, 3.0, 0.0),
                1.5,
                Vec3::new(1.0, 0.5, 0.0),
            );
        }
        app.update();
        if shuffle && frame == 0 {
            for e in entities.iter().step_by(2) {
                app.world_mut().entity_mut(*e).insert(Shuffled);
            }
        }
    }
    let water = app.world().resource::<TankWater>();
    let bits = water
        .velocities()
        .iter()
        .map(|v| v.to_array().map(f32::to_bits))
        .collect();
    let transforms = entities
        .iter()
        .map(|e| *app.world().get::<Transform>(*e).unwrap())
        .collect();
    (transforms, bits)
}

#[test]
fn currents_stirs_and_steering_replay_identically() {
    let (a, b) = (scripted_run(false), scripted_run(false));
    assert_eq!(a, b);
    assert!(
        a.0.iter().any(|t| t.rotation != Quat::IDENTITY),
        "steering turned someone"
    );
    assert!(
        a.1.iter().any(|v| *v != [0; 3]),
        "the jets stirred the tank"
    );
    // The jets are summed in entity order, whatever order the queries meet them in.
    assert!(
        scripted_run(true) == a,
        "the order jellyfish are met in changed the water"
    );
}
