//! Surfaces: culling, the template path against CPU meshes, switching paths, a game's
//! own material, and the geometry given to games.

use super::*;

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

/// Far jellyfish replay their species' recorded steps, so they share the recorded
/// cycle's frames: the renderer gets the cycle once and, from each far jellyfish, 64 bytes.
/// Near, each jellyfish sends its whole shape every frame. Spawned beyond the budget, they
/// send only that from their first frames: nothing was shown that a fade would hide.
#[test]
fn far_jellyfish_share_the_recorded_steps_they_show() {
    let bytes_per_jellyfish = |near: usize, frames: usize| {
        let mut app = template_app();
        app.world_mut().resource_mut::<JellyfishSettings>().detail = DetailLevels {
            near,
            mid: 0,
            ..default()
        };
        let h = add_species(&mut app, species());
        // In step: each shows the same recorded step as the others.
        for i in 0..6 {
            let at = Transform::from_xyz(2.0 * i as f32, 0.0, 0.0);
            app.world_mut()
                .spawn((Jellyfish::new(h.clone()).with_phase(0.25), at));
        }
        run(&mut app, frames);
        let mut q = app.world_mut().query::<&JellyfishSlice>();
        let far = q
            .iter(app.world())
            .filter(|s| s.tier() == Tier::Far)
            .count();
        assert_eq!(far, 6 - near, "near {near}");
        mesh_data_bytes(&app) / 6.0
    };
    let (near, far) = (bytes_per_jellyfish(6, 40), bytes_per_jellyfish(0, 40));
    // The cycle is uploaded in the first frame a far jellyfish shows it; the fifth sends
    // instances alone (a quarter-stroke fade from the shape a new slice starts in would
    // send whole shapes for twenty frames).
    let far_at_first = bytes_per_jellyfish(0, 5);
    println!(
        "{near:.0} bytes a frame per near jellyfish, {far:.0} per far one, {far_at_first:.0} \
         in its fifth frame"
    );
    assert!(near > 1000.0, "{near}");
    // Far: its instance and its slot's offset (the buffers' spare room shared out), no
    // frame of the cycle again.
    assert!(far < 0.1 * near, "far {far}, near {near}");
    assert!(
        far_at_first < 0.1 * near,
        "far {far_at_first} in its fifth frame, near {near}"
    );
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
        t.iter()
            .all(|(_, tag, m)| *tag == Some(CPU_MESH_TAG) && m.is_some()),
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
        .query_filtered::<(Entity, &Mesh3d, Option<&MeshTag>, &PartOf), With<JellyfishGlow>>();
    let glows: Vec<_> = glows
        .iter(app.world())
        .map(|(e, m, t, c)| (e, m.0.id(), t.map(|t| t.0), c.jellyfish()))
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

/// A jellyfish's tentacles sort half a bell diameter behind it in world units, so their
/// material follows the jellyfish's scale: shared by jellyfish of one scale, changed when
/// the scale changes, never put over a material of the game's own.
#[test]
fn tentacles_sort_behind_their_bell_at_every_scale() {
    let mut app = app();
    app.init_asset::<StandardMaterial>();
    let s = species();
    let diameter = s.diameter;
    let h = add_species(&mut app, s);
    let at = |scale: f32| Transform::from_xyz(scale, 0.0, 0.0).with_scale(Vec3::splat(scale));
    let one = app
        .world_mut()
        .spawn((Jellyfish::new(h.clone()), at(1.0)))
        .id();
    let big = app
        .world_mut()
        .spawn((Jellyfish::new(h.clone()), at(20.0)))
        .id();
    let twin = app
        .world_mut()
        .spawn((Jellyfish::new(h.clone()), at(20.0)))
        .id();
    run(&mut app, 6);
    let material = |app: &App, e: Entity| {
        let child = app
            .world()
            .get::<JellyfishMeshes>(e)
            .and_then(|m| m.tentacle_entity)
            .expect("a tentacle entity");
        let handle = app
            .world()
            .get::<MeshMaterial3d<StandardMaterial>>(child)
            .expect("the tentacles are dressed")
            .0
            .clone();
        let materials = app.world().resource::<Assets<StandardMaterial>>();
        let bias = materials
            .get(&handle)
            .expect("the material exists")
            .depth_bias;
        (handle, bias, child)
    };
    let offset = |scale: f32| -TENTACLE_SORT_OFFSET * diameter * scale;
    let (small, bias, _) = material(&app, one);
    assert_eq!(bias, offset(1.0));
    let (large, bias, _) = material(&app, big);
    assert!(
        (bias / offset(20.0) - 1.0).abs() < 0.05,
        "{bias} for {}",
        offset(20.0)
    );
    assert_eq!(material(&app, twin).0, large, "one scale, one material");
    assert_ne!(small, large);

    app.world_mut().get_mut::<Transform>(one).unwrap().scale = Vec3::splat(20.0);
    run(&mut app, 2);
    assert_eq!(material(&app, one).0, large, "it follows a new scale");

    let (_, _, child) = material(&app, twin);
    let game = app
        .world_mut()
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial::default());
    app.world_mut()
        .entity_mut(child)
        .insert(MeshMaterial3d(game.clone()));
    run(&mut app, 2);
    assert_eq!(material(&app, twin).0, game, "the game's own is kept");
}
