//! Touch, through the real plugin: a [`Disturbance`] makes the crystal jelly it reaches
//! flash and escape (it swims further than its untouched twin), leaves one out of reach
//! alone, is echoed by a neighbour at most half as bright, is felt as strongly and replays
//! bit for bit however time is split into frames; a disturbance that is not finite is
//! refused.

use crate::common::app::{Headless, SCALE};
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::plugin::{
    DetailLevels, Disturbance, ECHO_SHARE, Flash, JellyfishSlice, SwimMotion, Tier,
};
use bevy_jellyfish::{JellyfishSettings, Species};
use std::time::Duration;

/// The crystal jelly with a light fringe for the debug build.
fn species() -> Species {
    Species {
        tentacle_count: 16,
        ..Species::aequorea()
    }
}

/// One bell diameter in the world.
fn diameter() -> f32 {
    species().diameter * SCALE
}

fn app(frame: f64) -> App {
    Headless {
        frame: Duration::from_secs_f64(frame),
        ..default()
    }
    .build(|_| {})
}

/// The crystal jelly at `at`, as the plugin tests place one.
fn spawn(app: &mut App, at: Vec3) -> Entity {
    crate::common::app::spawn(app, &species(), at, ())
}

fn slice(app: &App, e: Entity) -> &JellyfishSlice {
    app.world().get::<JellyfishSlice>(e).unwrap()
}

fn flash(app: &App, e: Entity) -> Flash {
    app.world().get::<Flash>(e).unwrap().clone()
}

fn centre(app: &App, e: Entity) -> Vec3 {
    app.world().get::<GlobalTransform>(e).unwrap().translation()
}

/// Where the jellyfish is at its newest step, world (no parent here).
fn stepped(app: &App, e: Entity) -> Vec3 {
    app.world().get::<SwimMotion>(e).unwrap().pose.position
}

/// One frame that takes no time, so it takes no step; frames of `frame` seconds after it.
fn still_update(app: &mut App, frame: f64) {
    app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
    app.update();
    let frame = Duration::from_secs_f64(frame);
    app.insert_resource(TimeUpdateStrategy::ManualDuration(frame));
}

fn touch(app: &mut App, d: Disturbance) {
    app.world_mut().write_message(d);
}

/// Runs until `seconds` of virtual time have passed since the app started.
fn run_until(app: &mut App, seconds: f64) {
    while app.world().resource::<Time<Virtual>>().elapsed_secs_f64() < seconds - 1e-9 {
        app.update();
    }
}

/// Touched, the crystal jelly flashes in its colour and escapes: over its next strokes it
/// swims further than its twin far away, which does nothing. Its flash fades.
#[test]
fn a_touched_jellyfish_flashes_and_swims_further_than_its_twin() {
    let mut app = app(1.0 / 60.0);
    let touched = spawn(&mut app, Vec3::ZERO);
    let twin = spawn(&mut app, Vec3::X * 100.0 * diameter());
    run_until(&mut app, 2.0);
    let before = [touched, twin].map(|e| slice(&app, e).swim_distance());
    // Felt where it is at its newest step, which the next frame's first steps move on:
    // the touch is sent with the frame that steps nothing new (an update of no time).
    let at = stepped(&app, touched) + Vec3::X * 0.2 * diameter();
    touch(&mut app, Disturbance::touch(at, 1.0));
    still_update(&mut app, 1.0 / 60.0);
    run_until(&mut app, 2.2);
    let lit = flash(&app, touched);
    let s = species();
    // Felt at four fifths of its strength a fifth of its reach away.
    assert!((lit.peak - 0.8 * s.flash).abs() < 1e-4, "{lit:?}");
    assert!(
        lit.brightness > 0.5 * lit.peak && lit.brightness <= lit.peak,
        "{lit:?}"
    );
    assert!(lit.origin.x > 0.9, "from the side it was touched: {lit:?}");
    assert!(slice(&app, touched).escaping());
    assert_eq!(flash(&app, twin), Flash::default(), "the twin is dark");
    assert!(!slice(&app, twin).escaping());

    // The escape's three strokes at its quicker rhythm, and one more.
    run_until(&mut app, 2.0 + 4.0 / s.contraction_frequency as f64);
    let swum = [touched, twin].map(|e| slice(&app, e).swim_distance());
    let (escaped, calm) = (swum[0] - before[0], swum[1] - before[1]);
    println!(
        "over four strokes after the touch: touched {:.3} D, its twin {:.3} D",
        escaped / s.diameter,
        calm / s.diameter
    );
    assert!(escaped > 1.1 * calm, "touched {escaped} m, twin {calm} m");
    assert!(!slice(&app, touched).escaping(), "it eased back");
    assert_eq!(flash(&app, touched).brightness, 0.0, "the flash faded");
}

/// A neighbour within the flasher's echo reach answers later and at most half as bright,
/// without escaping; one out of every reach stays dark.
#[test]
fn a_neighbour_echoes_the_flash_later_and_dimmer() {
    let mut app = app(1.0 / 60.0);
    let s = species();
    let touched = spawn(&mut app, Vec3::ZERO);
    let neighbour = spawn(&mut app, Vec3::X * 2.0 * diameter());
    let far = spawn(&mut app, Vec3::X * (s.echo_reach + 2.0) * diameter());
    run_until(&mut app, 1.0);
    let at = centre(&app, touched) - Vec3::X * 0.3 * diameter();
    touch(&mut app, Disturbance::touch(at, 1.0));
    app.update();
    assert!(flash(&app, touched).peak > 0.0);
    assert_eq!(flash(&app, neighbour).peak, 0.0, "not touched itself");
    let mut brightest = [0.0f32; 3];
    let mut first_echo = None;
    for _ in 0..(3.0 * 60.0) as usize {
        app.update();
        for (k, e) in [touched, neighbour, far].into_iter().enumerate() {
            brightest[k] = brightest[k].max(flash(&app, e).brightness);
        }
        if first_echo.is_none() && flash(&app, neighbour).started.is_some() {
            first_echo = Some(app.world().resource::<Time<Virtual>>().elapsed_secs_f64());
        }
    }
    let started = flash(&app, touched).started.unwrap();
    let echoed = first_echo.expect("the neighbour echoed");
    println!(
        "flash {:.2}, echo {:.2} after {:.2} s",
        brightest[0],
        brightest[1],
        echoed - started
    );
    assert!(echoed - started >= s.echo_delay as f64 - 1e-9);
    assert!(brightest[1] > 0.0 && brightest[1] <= ECHO_SHARE * brightest[0] + 1e-6);
    assert_eq!(brightest[2], 0.0, "out of reach");
    assert!(
        !slice(&app, neighbour).escaping(),
        "an echo is light, not a fright"
    );
}

/// The same touches at the same times give the same jellyfish, to the bit, with frames
/// of 1/64 s or 1/32 s; a second touch within the refractory time escapes but does not
/// flash again.
#[test]
fn a_scripted_sequence_of_touches_replays_identically() {
    let run = |frame: f64| {
        let mut app = app(frame);
        let a = spawn(&mut app, Vec3::ZERO);
        let b = spawn(&mut app, Vec3::X * 1.5 * diameter());
        app.update();
        let script = [(1.0, 0.4, a), (1.5, 1.0, a), (2.5, 0.7, b)];
        let mut flashes = Vec::new();
        for (at, strength, who) in script {
            run_until(&mut app, at - frame);
            // A touch as wide as its offset from the centre: felt at full strength
            // (`a_touch_at_a_fixed_point_is_felt_alike_at_any_frame_length` checks a
            // partial one).
            let point = centre(&app, who) + Vec3::Y * 0.2 * diameter();
            let d = Disturbance {
                radius: 0.25 * diameter(),
                ..Disturbance::touch(point, strength)
            };
            touch(&mut app, d);
            app.update();
            flashes.push(flash(&app, a).started);
        }
        run_until(&mut app, 4.0);
        let state = [a, b].map(|e| {
            let s = slice(&app, e);
            let f = flash(&app, e);
            (
                s.swim_distance().to_bits(),
                s.phase().unwrap().to_bits(),
                f.peak.to_bits(),
                f.brightness.to_bits(),
                f.started.map(f64::to_bits),
            )
        });
        (state, flashes)
    };
    let (a, flashes) = run(1.0 / 64.0);
    let (b, _) = run(1.0 / 32.0);
    assert_eq!(a, b, "1/64 s against 1/32 s frames");
    assert_eq!(
        flashes[0], flashes[1],
        "refractory: no second flash 0.5 s later"
    );
}

/// A touch at a fixed world point is felt exactly as strongly with frames of 1/25 s as of
/// 1/125 s: where the jellyfish is at its newest step, not where the last frame drew it
/// (a frame's swimming earlier, which the frame's length decides).
#[test]
fn a_touch_at_a_fixed_point_is_felt_alike_at_any_frame_length() {
    let felt = |frame: f64| {
        let mut app = app(frame);
        let e = spawn(&mut app, Vec3::ZERO);
        run_until(&mut app, 2.0 - frame);
        // Half its reach ahead of and beside where it started: partly felt.
        let reach = species().touch_reach * diameter();
        let point = Vec3::new(0.3, 0.4, 0.0) * reach;
        touch(&mut app, Disturbance::touch(point, 1.0));
        app.update();
        let swum = slice(&app, e).swim_distance();
        (flash(&app, e).peak, swum)
    };
    let (slow, quick) = (felt(1.0 / 25.0), felt(1.0 / 125.0));
    println!(
        "felt {} and {} (swum {} and {} m)",
        slow.0, quick.0, slow.1, quick.1
    );
    assert!(
        slow.0 > 0.0 && slow.0 < species().flash,
        "partly felt: {slow:?}"
    );
    assert_eq!(slow.1.to_bits(), quick.1.to_bits(), "the same steps");
    assert_eq!(
        slow.0.to_bits(),
        quick.0.to_bits(),
        "{slow:?} against {quick:?}"
    );
}

/// A disturbance that is not finite is refused: nothing flashes, nothing escapes, and
/// nothing turns into NaN.
#[test]
fn a_disturbance_that_is_not_finite_is_refused() {
    let mut app = app(1.0 / 60.0);
    let e = spawn(&mut app, Vec3::ZERO);
    run_until(&mut app, 1.0);
    let at = centre(&app, e);
    for d in [
        Disturbance::touch(Vec3::NAN, 1.0),
        Disturbance::touch(at, f32::NAN),
        Disturbance::touch(at, f32::INFINITY),
        Disturbance {
            radius: f32::NAN,
            ..Disturbance::touch(at, 1.0)
        },
    ] {
        touch(&mut app, d);
    }
    run_until(&mut app, 1.5);
    assert_eq!(flash(&app, e), Flash::default());
    assert!(!slice(&app, e).escaping());
    assert!(slice(&app, e).swim_distance().is_finite());
}

/// Far from the camera a touched jellyfish replays its recorded stroke at the escape's
/// quicker rhythm: it flashes, and swims further than its far twin until it eases back.
#[test]
fn a_far_jellyfish_escapes_at_the_quicker_rhythm() {
    let mut app = app(1.0 / 60.0);
    app.world_mut().resource_mut::<JellyfishSettings>().detail = DetailLevels {
        near: 0,
        mid: 0,
        ..default()
    };
    let touched = spawn(&mut app, Vec3::ZERO);
    let twin = spawn(&mut app, Vec3::X * 100.0 * diameter());
    run_until(&mut app, 2.0);
    assert!(
        [touched, twin]
            .iter()
            .all(|&e| slice(&app, e).tier() == Tier::Far)
    );
    let before = [touched, twin].map(|e| slice(&app, e).swim_distance());
    let at = centre(&app, touched);
    touch(&mut app, Disturbance::touch(at, 1.0));
    app.update();
    assert!(slice(&app, touched).escaping());
    assert!(flash(&app, touched).peak > 0.0);
    let s = species();
    run_until(&mut app, 2.0 + 4.0 / s.contraction_frequency as f64);
    let swum = [touched, twin].map(|e| slice(&app, e).swim_distance());
    let (escaped, calm) = (swum[0] - before[0], swum[1] - before[1]);
    println!(
        "far, over four strokes after the touch: touched {:.3} D, its twin {:.3} D",
        escaped / s.diameter,
        calm / s.diameter
    );
    assert!(escaped > 1.05 * calm, "touched {escaped} m, twin {calm} m");
    assert!(!slice(&app, touched).escaping(), "it eased back");

    // Touched again and brought near mid-escape, its live slice carries the escape on.
    let at = centre(&app, touched);
    touch(&mut app, Disturbance::touch(at, 1.0));
    app.update();
    app.world_mut().resource_mut::<JellyfishSettings>().detail = DetailLevels::default();
    for _ in 0..30 {
        app.update();
        if slice(&app, touched).tier() == Tier::Near {
            break;
        }
    }
    assert_eq!(slice(&app, touched).tier(), Tier::Near);
    assert!(slice(&app, touched).escaping(), "the escape came along");
}
