//! Schools (`JellyfishSchool`): members spawned apart in the box, kept inside by steering,
//! despawned with the school, spawned again when it changes.

use super::*;
use bevy::ecs::hierarchy::ChildOf;
use bevy_jellyfish::plugin::{JellyfishSchool, MemberOf, SchoolMembers, SwimMotion};

fn school_app(count: usize, half: Vec3) -> (App, Entity) {
    let mut app = app();
    let h = add_species(&mut app, species());
    let school = app
        .world_mut()
        .spawn((
            JellyfishSchool::new(h, count, half).with_seed(7),
            Transform::from_xyz(0.0, 5.0, 0.0),
        ))
        .id();
    (app, school)
}

fn members(app: &App, school: Entity) -> Vec<Entity> {
    app.world()
        .get::<SchoolMembers>(school)
        .map_or(Vec::new(), |m| m.entities().to_vec())
}

/// Whether `p` is in the box of half `half` around (0, 5, 0), grown by `margin`.
fn inside(p: Vec3, half: Vec3, margin: f32) -> bool {
    ((p - Vec3::new(0.0, 5.0, 0.0)).abs() - half - Vec3::splat(margin)).max_element() <= 0.0
}

#[test]
fn a_school_spawns_its_members_apart_in_its_box_and_not_as_children() {
    let half = Vec3::new(4.0, 3.0, 4.0);
    let (mut app, school) = school_app(12, half);
    run(&mut app, 3);
    let members = members(&app, school);
    assert_eq!(members.len(), 12);
    let diameter = species().diameter * 20.0;
    let mut seeds = Vec::new();
    let mut places = Vec::new();
    for &m in &members {
        assert!(
            app.world().get::<ChildOf>(m).is_none(),
            "a member is not a child"
        );
        let j = app.world().get::<Jellyfish>(m).unwrap();
        seeds.push(j.seed.expect("each member has its own seed"));
        let t = app.world().get::<Transform>(m).unwrap();
        assert!(
            inside(t.translation, half, 0.0),
            "{:?} outside",
            t.translation
        );
        places.push(t.translation);
    }
    seeds.sort_unstable();
    seeds.dedup();
    assert_eq!(seeds.len(), 12, "seeds differ");
    for (i, a) in places.iter().enumerate() {
        for b in &places[i + 1..] {
            // Bells at most 15% larger than the species' at scale 20 do not overlap.
            assert!(a.distance(*b) >= 1.15 * diameter, "{a} and {b} overlap");
        }
    }
}

#[test]
fn members_stay_in_the_box_by_steering_never_by_jumping() {
    // A box a few bells wide: without steering they would swim out in seconds.
    let half = Vec3::splat(2.5);
    let (mut app, school) = school_app(6, half);
    run(&mut app, 3);
    let members = members(&app, school);
    let reach = |app: &App, m: Entity| app.world().get::<SwimMotion>(m).unwrap().pose.position;
    let mut last: Vec<Vec3> = members.iter().map(|&m| reach(&app, m)).collect();
    let (mut fastest, mut farthest) = (0.0f32, f32::MIN);
    for _ in 0..30 * 60 {
        app.update();
        for (k, &m) in members.iter().enumerate() {
            let p = reach(&app, m);
            fastest = fastest.max(p.distance(last[k]));
            let out = ((p - Vec3::new(0.0, 5.0, 0.0)).abs() - half).max_element();
            farthest = farthest.max(out);
            last[k] = p;
        }
    }
    // A moon jelly surges at most a few centimetres a second: ~0.02 units a frame.
    assert!(fastest < 0.05, "a member jumped {fastest} units in a frame");
    assert!(
        farthest < 0.8,
        "members left the box by {farthest} units (a bell and fringe is ~0.7)"
    );
}

#[test]
fn despawning_the_school_despawns_its_members() {
    let (mut app, school) = school_app(5, Vec3::splat(3.0));
    run(&mut app, 3);
    let members = members(&app, school);
    assert_eq!(members.len(), 5);
    app.world_mut().despawn(school);
    run(&mut app, 1);
    for m in members {
        assert!(
            app.world().get_entity(m).is_err(),
            "member {m} outlived its school"
        );
    }
}

#[test]
fn a_changed_school_is_spawned_again() {
    let (mut app, school) = school_app(5, Vec3::splat(3.0));
    run(&mut app, 3);
    let before = members(&app, school);
    app.world_mut()
        .get_mut::<JellyfishSchool>(school)
        .unwrap()
        .count = 3;
    run(&mut app, 2);
    let after = members(&app, school);
    assert_eq!(after.len(), 3);
    for m in before {
        assert!(
            app.world().get_entity(m).is_err(),
            "the old member {m} is gone"
        );
    }
}

/// A school larger than a frame's share fills a few dozen members a frame, so no frame
/// places and spawns thousands; every member is still apart from all the others and in
/// its box, and it is the same school in every run.
/// Where each member of a school was spawned, in spawn order.
#[derive(Resource, Default)]
struct SpawnedAt(Vec<Vec3>);

#[test]
fn a_large_school_fills_over_a_few_frames_apart_and_the_same_every_run() {
    let half = Vec3::new(10.0, 5.0, 10.0);
    // `scatter`: after each frame every member so far is moved far out of the box, as
    // if it had swum there; a fill places against where members were placed, so the
    // places must not change (with the frame rate deciding how far they swim between
    // frames, they would otherwise depend on it).
    let fill = |scatter: bool| {
        let (mut app, school) = school_app(150, half);
        // All far: no slices to build, only the species' recorded cycle.
        app.world_mut().resource_mut::<JellyfishSettings>().detail = DetailLevels {
            near: 0,
            mid: 0,
            ..default()
        };
        app.init_resource::<SpawnedAt>().add_observer(
            |add: On<Add, MemberOf>, places: Query<&Transform>, mut at: ResMut<SpawnedAt>| {
                at.0.push(places.get(add.entity).unwrap().translation);
            },
        );
        let mut counts: Vec<usize> = Vec::new();
        while counts.last() != Some(&150) {
            assert!(counts.len() < 20, "members after each frame: {counts:?}");
            app.update();
            counts.push(members(&app, school).len());
            if scatter {
                for m in members(&app, school) {
                    app.world_mut()
                        .get_mut::<Transform>(m)
                        .unwrap()
                        .translation
                        .x += 1000.0;
                }
            }
        }
        (
            counts,
            std::mem::take(&mut app.world_mut().resource_mut::<SpawnedAt>().0),
        )
    };
    let (counts, places) = fill(false);
    println!("members after each frame: {counts:?}");
    let most = std::iter::once(counts[0])
        .chain(counts.windows(2).map(|w| w[1] - w[0]))
        .max()
        .unwrap_or(0);
    assert_eq!(
        most, 64,
        "at most 64 a frame, and that many while some wait"
    );
    assert!(
        counts.iter().filter(|&&n| n > 0).count() >= 3,
        "150 members in at least three frames: {counts:?}"
    );
    assert_eq!(places.len(), 150);
    let diameter = species().diameter * 20.0;
    for (i, a) in places.iter().enumerate() {
        assert!(inside(*a, half, 0.0), "{a} outside");
        for b in &places[i + 1..] {
            assert!(a.distance(*b) >= 1.15 * diameter, "{a} and {b} overlap");
        }
    }
    assert_eq!(fill(false).1, places, "the same school every run");
    assert_eq!(
        fill(true).1,
        places,
        "placed against where the first members were placed, not where they went"
    );
}

/// Schools begun together are laid out the same whichever species' file loads first: a
/// school is placed around the members placed before it, and the order files load in is
/// the machine's (under CI's load the render test once compared two aquariums laid out
/// differently). One school's species is held back at its file (a gated asset source);
/// the other's is there from the start. Neither fills until both are there, and their
/// places are those of both species there at once.
#[test]
fn schools_begun_together_are_placed_alike_whichever_species_loads_first() {
    use bevy::asset::AssetApp;
    use bevy::asset::io::AssetSourceBuilder;
    use bevy::asset::io::memory::{Dir, MemoryAssetReader};
    use std::path::Path;
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};
    // A box they crowd, so that each school's places depend on the other's.
    let half = Vec3::new(1.0, 0.8, 1.0);
    let layout = |held: bool| {
        let dir = Dir::default();
        let file = Path::new("late.species.ron");
        dir.insert_asset_text(file, &Species::aurelia().to_ron().unwrap());
        let gate = Arc::new(AtomicBool::new(false));
        let reader = Held {
            files: MemoryAssetReader { root: dir },
            open: gate.clone(),
        };
        let mut app = App::new();
        app.register_asset_source(
            "gated",
            AssetSourceBuilder::new(move || Box::new(reader.clone())),
        );
        let mut app = crate::common::app::Headless {
            settings: settings(),
            frame: frame(60),
            ..default()
        }
        .build_on(app, |_| {});
        let first = if held {
            app.world()
                .resource::<AssetServer>()
                .load("gated://late.species.ron")
        } else {
            add_species(&mut app, Species::aurelia())
        };
        let second = add_species(&mut app, Species::aurelia());
        app.init_resource::<SpawnedAt>().add_observer(
            |add: On<Add, MemberOf>, places: Query<&Transform>, mut at: ResMut<SpawnedAt>| {
                at.0.push(places.get(add.entity).unwrap().translation);
            },
        );
        for (seed, h) in [(7, first), (8, second)] {
            app.world_mut().spawn((
                JellyfishSchool::new(h, 6, half).with_seed(seed),
                Transform::from_xyz(0.0, 5.0, 0.0),
            ));
        }
        if held {
            run(&mut app, 5);
            let placed = app.world().resource::<SpawnedAt>().0.len();
            assert_eq!(placed, 0, "placed while the other school's species loads");
            gate.store(true, Ordering::Release);
        }
        for _ in 0..500 {
            app.update();
            if app.world().resource::<SpawnedAt>().0.len() == 12 {
                break;
            }
            // Loading is asynchronous.
            std::thread::sleep(Duration::from_millis(5));
        }
        std::mem::take(&mut app.world_mut().resource_mut::<SpawnedAt>().0)
    };
    let (held, there) = (layout(true), layout(false));
    assert_eq!(held.len(), 12, "both schools filled");
    assert_eq!(held, there);
}

/// Files in memory whose reads wait until `open` is set: a species file still loading for
/// as many frames as a test needs (Bevy's own gated reader is for its tests only).
#[derive(Clone)]
struct Held {
    files: bevy::asset::io::memory::MemoryAssetReader,
    open: std::sync::Arc<std::sync::atomic::AtomicBool>,
}

impl bevy::asset::io::AssetReader for Held {
    async fn read<'a>(
        &'a self,
        path: &'a std::path::Path,
    ) -> Result<impl bevy::asset::io::Reader + 'a, bevy::asset::io::AssetReaderError> {
        while !self.open.load(std::sync::atomic::Ordering::Acquire) {
            bevy::tasks::futures_lite::future::yield_now().await;
        }
        self.files.read(path).await
    }

    async fn read_meta<'a>(
        &'a self,
        path: &'a std::path::Path,
    ) -> Result<impl bevy::asset::io::Reader + 'a, bevy::asset::io::AssetReaderError> {
        self.files.read_meta(path).await
    }

    async fn read_directory<'a>(
        &'a self,
        path: &'a std::path::Path,
    ) -> Result<Box<bevy::asset::io::PathStream>, bevy::asset::io::AssetReaderError> {
        self.files.read_directory(path).await
    }

    async fn is_directory<'a>(
        &'a self,
        path: &'a std::path::Path,
    ) -> Result<bool, bevy::asset::io::AssetReaderError> {
        self.files.is_directory(path).await
    }
}
