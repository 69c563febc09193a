//! The template surfaces' vertex shader and the tissue layer's fragment shader, composed
//! as Bevy composes them and validated by naga, with no GPU: an app with the render
//! plugins but no wgpu backend loads Bevy's shader libraries, the plugin adds
//! `bevy_jellyfish::packed`, and `surface.wgsl` is composed through naga_oil with them
//! for each pipeline it serves (forward, prepass, shadows, deferred), `tissue.wgsl` for
//! the main passes, with the shader defs Bevy gives our materials there, then validated.

use bevy::asset::LoadState;
use bevy::log::LogPlugin;
use bevy::pbr::MaterialExtension;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::settings::{RenderCreation, WgpuLimits, WgpuSettings};
use bevy::shader::{Shader, ShaderDefVal, ShaderImport, ShaderRef};
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use bevy_jellyfish::JellyfishPlugin;
use bevy_jellyfish::plugin::SurfaceExtension;
use naga::valid::{ValidationFlags, Validator};
use naga_oil::compose::{Composer, NagaModuleDescriptor, ShaderDefValue};
use std::collections::{HashMap, HashSet};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// `surface.wgsl`, `tissue.wgsl` and every shader they may import, directly or not, by
/// import path: what an app that renders has in `Assets<Shader>`.
struct Shaders {
    surface: Shader,
    tissue: Shader,
    by_import: HashMap<ShaderImport, Shader>,
}

impl Shaders {
    /// Loaded once for the tests here.
    fn get() -> &'static Self {
        static SHADERS: OnceLock<Shaders> = OnceLock::new();
        SHADERS.get_or_init(Self::load)
    }

    /// Loads them in an app without a GPU (`WgpuSettings::backends` none: Bevy's plugins
    /// load their shader libraries all the same).
    fn load() -> Self {
        let mut app = App::new();
        app.add_plugins(
            DefaultPlugins
                .set(WindowPlugin {
                    primary_window: None,
                    exit_condition: ExitCondition::DontExit,
                    ..default()
                })
                .set(RenderPlugin {
                    render_creation: RenderCreation::Automatic(Box::new(WgpuSettings {
                        backends: None,
                        ..default()
                    })),
                    ..default()
                })
                .disable::<WinitPlugin>()
                .disable::<LogPlugin>(),
        )
        .add_plugins(JellyfishPlugin::default());
        app.finish();
        app.cleanup();
        let ShaderRef::Path(path) = SurfaceExtension::vertex_shader() else {
            panic!("the template material's vertex shader is a file");
        };
        for stage in [
            SurfaceExtension::prepass_vertex_shader(),
            SurfaceExtension::deferred_vertex_shader(),
        ] {
            assert!(
                matches!(&stage, ShaderRef::Path(p) if *p == path),
                "the prepass and deferred vertex stages use the same file"
            );
        }
        let ShaderRef::Path(tissue) = SurfaceExtension::fragment_shader() else {
            panic!("the tissue layer's fragment shader is a file");
        };
        let server = app.world().resource::<AssetServer>();
        let handle: Handle<Shader> = server.load(path);
        let tissue: Handle<Shader> = server.load(tissue);
        let deadline = Instant::now() + Duration::from_secs(120);
        loop {
            app.update();
            let world = app.world();
            for (name, h) in [("surface.wgsl", &handle), ("tissue.wgsl", &tissue)] {
                if let Some(LoadState::Failed(error)) =
                    world.resource::<AssetServer>().get_load_state(h)
                {
                    panic!("{name} did not load: {error}");
                }
            }
            let assets = world.resource::<Assets<Shader>>();
            let by_import: HashMap<_, _> = assets
                .iter()
                .map(|(_, s)| (s.import_path.clone(), s.clone()))
                .collect();
            if let (Some(surface), Some(tissue)) = (assets.get(&handle), assets.get(&tissue)) {
                let mut missing = missing_imports(surface, &by_import);
                missing.extend(missing_imports(tissue, &by_import));
                if missing.is_empty() {
                    // `PipelineCache::extract_shaders`: the global defs on every shader.
                    let global = |s: &Shader| {
                        let mut s = s.clone();
                        s.shader_defs.extend(global_defs());
                        s
                    };
                    return Self {
                        surface: global(surface),
                        tissue: global(tissue),
                        by_import: by_import
                            .iter()
                            .map(|(k, s)| (k.clone(), global(s)))
                            .collect(),
                    };
                }
                assert!(
                    Instant::now() < deadline,
                    "shader imports never loaded: {missing:?}"
                );
            }
            assert!(Instant::now() < deadline, "the shaders never loaded");
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Composes `shader` with `defs` as Bevy's `ShaderCache` does (its imports added to a
    /// naga_oil `Composer` depth first, then the shader made into a naga module), and
    /// validates the module with naga. The error, readable, if either fails.
    fn compose(&self, shader: &Shader, defs: &[Def]) -> Result<naga::Module, String> {
        // Bevy's debug-build composer: naga_oil's, validating.
        let mut composer = Composer::default();
        for import in &shader.imports {
            self.add(&mut composer, import)?;
        }
        // `ShaderCache::get`: the pipeline's defs, then the shader's own.
        let shader_defs = defs
            .iter()
            .map(|d| d.naga_oil())
            .chain(shader.shader_defs.iter().map(naga_oil_def))
            .collect();
        let module = composer
            .make_naga_module(NagaModuleDescriptor {
                shader_defs,
                ..shader.into()
            })
            .map_err(|e| e.emit_to_string(&composer))?;
        Validator::new(ValidationFlags::all(), composer.capabilities)
            .validate(&module)
            .map_err(|e| format!("naga validation: {e:?}"))?;
        Ok(module)
    }

    /// Composes and validates `surface.wgsl` for every pipeline it serves: the failures,
    /// by pipeline.
    fn check(&self) -> Vec<String> {
        check(
            &self.surface,
            pipelines(),
            naga::ShaderStage::Vertex,
            |s, d| self.compose(s, d),
        )
    }

    /// Composes and validates `tissue.wgsl` for every main pass it serves: the failures,
    /// by pipeline.
    fn check_tissue(&self) -> Vec<String> {
        check(
            &self.tissue,
            main_passes(),
            naga::ShaderStage::Fragment,
            |s, d| self.compose(s, d),
        )
    }

    /// These shaders with `surface.wgsl`'s source, or the module `import`'s, edited.
    fn edited(&self, import: Option<&ShaderImport>, edit: impl Fn(&str) -> String) -> Self {
        let redo = |s: &Shader| {
            let source = edit(s.source.as_str());
            assert_ne!(source, s.source.as_str(), "the edit changes the source");
            Shader {
                shader_defs: s.shader_defs.clone(),
                ..Shader::from_wgsl(source, s.path.clone())
            }
        };
        let mut edited = Self {
            surface: self.surface.clone(),
            tissue: self.tissue.clone(),
            by_import: self.by_import.clone(),
        };
        match import {
            None => edited.surface = redo(&self.surface),
            Some(import) => {
                let module = redo(&self.by_import[import]);
                edited.by_import.insert(import.clone(), module);
            }
        }
        edited
    }

    /// `ShaderCache::add_import_to_composer`: the import's own imports first.
    fn add(&self, composer: &mut Composer, import: &ShaderImport) -> Result<(), String> {
        if composer.contains_module(&import.module_name()) {
            return Ok(());
        }
        let shader = self
            .by_import
            .get(import)
            .ok_or_else(|| format!("no shader defines {import:?}"))?;
        for inner in &shader.imports {
            self.add(composer, inner)?;
        }
        composer
            .add_composable_module(shader.into())
            .map(|_| ())
            .map_err(|e| e.emit_to_string(composer))
    }
}

/// Composes `shader` for each pipeline and checks it has the entry point of `stage` (named
/// `vertex` or `fragment`): the failures, by pipeline.
fn check(
    shader: &Shader,
    pipelines: Vec<(&'static str, Vec<Def>)>,
    stage: naga::ShaderStage,
    compose: impl Fn(&Shader, &[Def]) -> Result<naga::Module, String>,
) -> Vec<String> {
    let entry = match stage {
        naga::ShaderStage::Vertex => "vertex",
        _ => "fragment",
    };
    let mut failures = Vec::new();
    for (name, defs) in pipelines {
        match compose(shader, &defs) {
            Ok(module) => {
                let found = |e: &naga::EntryPoint| e.name == entry && e.stage == stage;
                if !module.entry_points.iter().any(found) {
                    failures.push(format!("{name}: no {stage:?} entry point `{entry}`"));
                }
            }
            Err(error) => failures.push(format!("{name}:\n{error}")),
        }
    }
    failures
}

/// The imports of `shader` (with theirs) that no shader in `by_import` defines.
fn missing_imports(shader: &Shader, by_import: &HashMap<ShaderImport, Shader>) -> Vec<String> {
    let mut seen = HashSet::new();
    let mut missing = Vec::new();
    let mut stack: Vec<&ShaderImport> = shader.imports.iter().collect();
    while let Some(import) = stack.pop() {
        if !seen.insert(import.clone()) {
            continue;
        }
        match by_import.get(import) {
            Some(s) => stack.extend(&s.imports),
            None => missing.push(import.module_name().into_owned()),
        }
    }
    missing
}

/// Bevy's def as naga_oil takes it (as `ShaderCache` converts them).
fn naga_oil_def(def: &ShaderDefVal) -> (String, ShaderDefValue) {
    match def.clone() {
        ShaderDefVal::Bool(k, v) => (k, ShaderDefValue::Bool(v)),
        ShaderDefVal::Int(k, v) => (k, ShaderDefValue::Int(v)),
        ShaderDefVal::UInt(k, v) => (k, ShaderDefValue::UInt(v)),
    }
}

/// A shader def as a pipeline passes it.
#[derive(Clone, Copy, Debug)]
enum Def {
    On(&'static str),
    UInt(&'static str, u32),
    Int(&'static str, i32),
}

impl Def {
    fn name(self) -> &'static str {
        match self {
            On(k) | UInt(k, _) | Int(k, _) => k,
        }
    }

    fn naga_oil(self) -> (String, ShaderDefValue) {
        match self {
            Def::On(k) => (k.into(), ShaderDefValue::Bool(true)),
            Def::UInt(k, v) => (k.into(), ShaderDefValue::UInt(v)),
            Def::Int(k, v) => (k.into(), ShaderDefValue::Int(v)),
        }
    }
}

use Def::{Int, On, UInt};

/// The pipeline cache's own defs, which Bevy adds to every shader's (modules' included):
/// the storage buffers a vertex stage may bind (wgpu's default limit).
fn global_defs() -> Vec<ShaderDefVal> {
    let limits = WgpuLimits::default();
    vec![ShaderDefVal::UInt(
        "AVAILABLE_STORAGE_BUFFER_BINDINGS".into(),
        limits.max_storage_buffers_per_shader_stage,
    )]
}

/// The defs Bevy 0.19 gave our material's main pass in the aquarium on llvmpipe, as the
/// shader cache logged them (`RUST_LOG=bevy_shader=debug`, the render test): a template
/// mesh (positions, normals, UVs; since the tissue layer, a second UV channel), opaque, in
/// a multisampled perspective view.
const FORWARD: &[Def] = &[
    On("MESH_PIPELINE"),
    On("VERTEX_OUTPUT_INSTANCE_INDEX"),
    On("VERTEX_POSITIONS"),
    On("VERTEX_NORMALS"),
    On("VERTEX_UVS"),
    On("VERTEX_UVS_A"),
    On("VERTEX_UVS_B"),
    On("MULTISAMPLED"),
    On("VIEW_PROJECTION_PERSPECTIVE"),
    On("SHADOW_FILTER_METHOD_GAUSSIAN"),
    Int("SCREEN_SPACE_SPECULAR_TRANSMISSION_BLUR_TAPS", 8),
    On("DISTANCE_FOG"),
    On("IRRADIANCE_VOLUMES_ARE_USABLE"),
    UInt("MATERIAL_BIND_GROUP", 3),
];

/// Logged likewise: its directional light's shadow pass (a prepass pipeline).
const SHADOW: &[Def] = &[
    On("PREPASS_PIPELINE"),
    UInt("MATERIAL_BIND_GROUP", 3),
    On("VERTEX_OUTPUT_INSTANCE_INDEX"),
    On("VIEW_PROJECTION_ORTHOGRAPHIC"),
    On("DEPTH_PREPASS"),
    On("MAY_DISCARD"),
    On("VERTEX_POSITIONS"),
    On("VERTEX_UVS"),
    On("VERTEX_UVS_A"),
    On("VERTEX_UVS_B"),
];

/// Every pipeline the file serves, by name, with its defs: those logged above, and what
/// `MeshPipeline::specialize` and `PrepassPipeline::specialize` add for the cases the
/// aquarium does not draw (visibility ranges, a mesh without UVs, emulated unclipped
/// depth, point light shadows, the normal, motion vector and deferred prepasses).
fn pipelines() -> Vec<(&'static str, Vec<Def>)> {
    let with = |base: &[Def], more: &[Def]| [base, more].concat();
    let without = |base: &[Def], less: &[&str]| -> Vec<Def> {
        base.iter()
            .copied()
            .filter(|d| !less.contains(&d.name()))
            .collect()
    };
    let perspective = with(
        &without(SHADOW, &["VIEW_PROJECTION_ORTHOGRAPHIC", "MAY_DISCARD"]),
        &[On("VIEW_PROJECTION_PERSPECTIVE")],
    );
    vec![
        ("forward", FORWARD.to_vec()),
        (
            "forward, blended",
            with(
                FORWARD,
                &[On("PREMULTIPLY_ALPHA"), On("BLEND_PREMULTIPLIED_ALPHA")],
            ),
        ),
        (
            "forward, visibility ranges",
            with(FORWARD, &[On("VISIBILITY_RANGE_DITHER")]),
        ),
        (
            "forward, no UVs",
            without(FORWARD, &["VERTEX_UVS", "VERTEX_UVS_A", "VERTEX_UVS_B"]),
        ),
        (
            "forward, no tissue channel",
            without(FORWARD, &["VERTEX_UVS_B"]),
        ),
        ("directional shadow", SHADOW.to_vec()),
        (
            "directional shadow, unclipped depth emulated",
            with(SHADOW, &[On("UNCLIPPED_DEPTH_ORTHO_EMULATION")]),
        ),
        ("point light shadow", perspective.clone()),
        (
            "normal prepass",
            with(
                &perspective,
                &[
                    On("NORMAL_PREPASS"),
                    On("NORMAL_PREPASS_OR_DEFERRED_PREPASS"),
                    On("VERTEX_NORMALS"),
                ],
            ),
        ),
        (
            "motion vector prepass",
            with(
                &perspective,
                &[
                    On("MOTION_VECTOR_PREPASS_OR_DEFERRED_PREPASS"),
                    On("MOTION_VECTOR_PREPASS"),
                ],
            ),
        ),
        (
            "deferred prepass",
            with(
                &without(&perspective, &["DEPTH_PREPASS"]),
                &[
                    On("NORMAL_PREPASS_OR_DEFERRED_PREPASS"),
                    On("VERTEX_NORMALS"),
                    On("MOTION_VECTOR_PREPASS_OR_DEFERRED_PREPASS"),
                    On("DEFERRED_PREPASS"),
                    On("PREPASS_FRAGMENT"),
                ],
            ),
        ),
    ]
}

/// The main passes the tissue layer's fragment shader serves: a mesh with our tissue in
/// its second UV channel, opaque or blended (premultiplied, as `AlphaMode::Blend` and
/// `Add` are), with order-independent transparency, and without the channel.
fn main_passes() -> Vec<(&'static str, Vec<Def>)> {
    let with = |more: &[Def]| [FORWARD, more].concat();
    let untextured: Vec<Def> = FORWARD
        .iter()
        .copied()
        .filter(|d| d.name() != "VERTEX_UVS_B")
        .collect();
    vec![
        ("forward", FORWARD.to_vec()),
        (
            "forward, blended",
            with(&[On("PREMULTIPLY_ALPHA"), On("BLEND_PREMULTIPLIED_ALPHA")]),
        ),
        ("forward, order-independent", with(&[On("OIT_ENABLED")])),
        ("forward, no tissue channel", untextured),
    ]
}

/// `surface.wgsl` composes and validates for every pipeline it serves, its vertex entry
/// point reading the shape buffers and writing that pipeline's `VertexOutput`.
#[test]
fn the_surface_shader_composes_and_validates_without_a_gpu() {
    let failures = Shaders::get().check();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The check fails where the shader is broken: a type error, a constant the table does not
/// have, a table without a constant the shader uses, and an error only the motion vector
/// prepass compiles.
#[test]
fn a_broken_surface_shader_fails_the_check() {
    let shaders = Shaders::get();
    let packed = ShaderImport::Custom("bevy_jellyfish::packed".into());
    let type_error = shaders.edited(None, |s| {
        s.replacen(
            "    let tag = ",
            "    let broken: u32 = 1.5;\n    let tag = ",
            1,
        )
    });
    let unknown_constant =
        shaders.edited(None, |s| s.replacen("packed::H_SEED", "packed::H_SEEDS", 1));
    let table_without_it = shaders.edited(Some(&packed), |s| {
        s.lines()
            .filter(|l| !l.starts_with("const H_SEED:"))
            .collect::<Vec<_>>()
            .join("\n")
    });
    let prepass_only = shaders.edited(None, |s| {
        s.replacen(
            "out.previous_world_position =",
            "out.previous_position =",
            1,
        )
    });
    for (name, broken, pipelines) in [
        ("a type error", type_error, None),
        ("an unknown constant", unknown_constant, None),
        ("a constant missing from the table", table_without_it, None),
        ("a motion vector prepass error", prepass_only, Some(1)),
    ] {
        let failures = broken.check();
        match pipelines {
            None => assert_eq!(
                failures.len(),
                self::pipelines().len(),
                "{name}: {failures:?}"
            ),
            Some(n) => assert_eq!(failures.len(), n, "{name}: {failures:?}"),
        }
    }
}

/// The shader's constants come from `bevy_jellyfish::packed`: the file declares none of
/// its own at module scope (a copied constant would not be checked against the table).
#[test]
fn the_surface_shader_copies_no_constant() {
    let shaders = Shaders::get();
    let source = shaders.surface.source.as_str();
    let declared: Vec<&str> = source
        .lines()
        .filter(|l| l.starts_with("const ") || l.starts_with("override "))
        .collect();
    assert!(
        declared.is_empty(),
        "constants in surface.wgsl: {declared:?}"
    );
    let packed = ShaderImport::Custom("bevy_jellyfish::packed".into());
    assert!(shaders.surface.imports.contains(&packed));
    assert!(shaders.by_import.contains_key(&packed));
}

/// `tissue.wgsl` composes and validates for every main pass it serves; a type error in it
/// fails every one.
#[test]
fn the_tissue_shader_composes_and_validates_without_a_gpu() {
    let shaders = Shaders::get();
    let failures = shaders.check_tissue();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    let source = shaders.tissue.source.as_str();
    let edited = source.replacen("let band = in.uv_b.y;", "let band: u32 = in.uv_b.y;", 1);
    assert_ne!(edited, source, "the edit changes the source");
    let broken = Shaders {
        surface: shaders.surface.clone(),
        tissue: Shader {
            shader_defs: shaders.tissue.shader_defs.clone(),
            ..Shader::from_wgsl(edited, shaders.tissue.path.clone())
        },
        by_import: shaders.by_import.clone(),
    };
    assert_eq!(
        broken.check_tissue().len(),
        main_passes().len() - 1,
        "a type error read where the tissue channel is"
    );
}
