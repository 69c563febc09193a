//! Offscreen rendering: no window, no runner; we pump the app ourselves and capture the
//! camera's image target to PNG (Bevy's `externally_driven_headless_renderer` example).
//! Without a GPU it runs on Mesa's software Vulkan (`mesa-vulkan-drivers`). Shared by the
//! examples and the render test (`#[path]`-included as `mod screenshot`).
#![allow(dead_code)] // each example or test that includes it uses a part

use bevy::{
    app::SubApps,
    asset::RenderAssetUsages,
    camera::RenderTarget,
    prelude::*,
    render::{
        RenderPlugin,
        render_resource::{Extent3d, PollType, TextureDimension, TextureFormat, TextureUsages},
        renderer::{RenderDevice, initialize_renderer},
        settings::{RenderCreation, RenderResources, WgpuSettings},
        view::screenshot::{Screenshot, save_to_disk},
    },
    time::TimeUpdateStrategy,
    window::ExitCondition,
    winit::WinitPlugin,
};
use std::path::Path;
use std::time::Duration;

/// Replaces the scene's cameras with a row of `count` panels side by side across a
/// picture `size` wide, each its own camera in ambient light of `brightness` (the first
/// clears the picture, the others draw over it), and returns them in order so the
/// example can aim each at its jellyfish.
pub fn panel_cameras(world: &mut World, count: usize, size: UVec2, brightness: f32) -> Vec<Entity> {
    let cell = UVec2::new(size.x / count.max(1) as u32, size.y);
    let target = world.resource::<OffscreenTarget>().0.clone();
    let mut cameras = world.query_filtered::<Entity, With<Camera3d>>();
    let old: Vec<Entity> = cameras.iter(world).collect();
    for e in old {
        world.despawn(e);
    }
    (0..count)
        .map(|k| {
            world
                .spawn(panel_camera(k, cell, target.clone(), brightness))
                .id()
        })
        .collect()
}

/// The `k`-th camera of [`panel_cameras`], `cell` wide, drawing into `target`.
fn panel_camera(k: usize, cell: UVec2, target: RenderTarget, brightness: f32) -> impl Bundle {
    (
        Camera3d::default(),
        Camera {
            order: k as isize,
            clear_color: if k == 0 {
                ClearColorConfig::Custom(Color::srgb(0.01, 0.03, 0.07))
            } else {
                ClearColorConfig::None
            },
            viewport: Some(bevy::camera::Viewport {
                physical_position: UVec2::new(k as u32 * cell.x, 0),
                physical_size: cell,
                ..default()
            }),
            ..default()
        },
        AmbientLight {
            brightness,
            ..default()
        },
        target,
        Transform::default(),
    )
}

/// Why no picture can be rendered here.
#[derive(Debug)]
pub struct NoAdapter(pub String);

/// Render into this image instead of the window: the scene's camera looks for it.
#[derive(Resource, Clone)]
pub struct OffscreenTarget(pub RenderTarget);

impl std::fmt::Display for NoAdapter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "no GPU or Vulkan adapter found ({}); offscreen rendering needs one: install Mesa's \
             software Vulkan (`apt-get install mesa-vulkan-drivers`) on a machine without a GPU",
            self.0
        )
    }
}

/// Creates the renderer, or says why it cannot. Bevy panics when there is no adapter;
/// the panic is caught (and kept off stderr) so callers can report and exit cleanly, and
/// the renderer found is handed to Bevy rather than made twice.
fn find_renderer() -> Result<RenderResources, NoAdapter> {
    let settings = WgpuSettings::default();
    let backends = settings
        .backends
        .ok_or_else(|| NoAdapter("no wgpu backend enabled".into()))?;
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let found = std::panic::catch_unwind(|| {
        bevy::tasks::block_on(initialize_renderer(backends, None, &settings))
    });
    std::panic::set_hook(hook);
    found.map_err(|panic| {
        let message = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "the renderer could not start".into());
        // Bevy's message ends with advice about drivers; ours replaces it.
        let reason = message.split('!').next().unwrap_or_default();
        NoAdapter(reason.trim().to_string())
    })
}

/// An app rendering into an image, advanced by a fixed 1/60 s per frame.
pub struct Offscreen {
    apps: SubApps,
    image: Handle<Image>,
    /// The adapter's name, e.g. "llvmpipe (LLVM 19.1.7, 256 bits)".
    pub adapter: String,
}

impl Offscreen {
    /// `scene` adds the plugins and resources that make the scene; the camera finds the
    /// image in [`OffscreenTarget`].
    pub fn new(width: u32, height: u32, scene: impl FnOnce(&mut App)) -> Result<Self, NoAdapter> {
        let resources = find_renderer()?;
        let adapter = resources.2.name.clone();
        let mut app = App::new();
        app.add_plugins(
            DefaultPlugins
                .set(WindowPlugin {
                    primary_window: None,
                    exit_condition: ExitCondition::DontExit,
                    ..default()
                })
                .set(RenderPlugin {
                    render_creation: RenderCreation::Manual(resources),
                    synchronous_pipeline_compilation: true,
                    ..default()
                })
                .disable::<WinitPlugin>(),
        )
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            1.0 / 60.0,
        )));
        let mut image = Image::new_uninit(
            Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::RENDER_WORLD,
        );
        image.texture_descriptor.usage |= TextureUsages::RENDER_ATTACHMENT;
        let image = app.world_mut().resource_mut::<Assets<Image>>().add(image);
        app.insert_resource(OffscreenTarget(RenderTarget::from(image.clone())));
        scene(&mut app);
        app.finish();
        app.cleanup();
        Ok(Self {
            apps: std::mem::take(app.sub_apps_mut()),
            image,
            adapter,
        })
    }

    pub fn world_mut(&mut self) -> &mut World {
        self.apps.main.world_mut()
    }

    pub fn world(&self) -> &World {
        self.apps.main.world()
    }

    /// One frame, then wait for the GPU (or llvmpipe) to finish it.
    pub fn update(&mut self) {
        self.apps.update();
        self.apps
            .main
            .world()
            .resource::<RenderDevice>()
            .wgpu_device()
            .poll(PollType::Wait {
                submission_index: None,
                timeout: None,
            })
            .expect("device poll");
    }

    /// Captures the image to a PNG at `path` (a few more frames pass while it is read back).
    pub fn capture(&mut self, path: &Path) -> Result<(), String> {
        let _ = std::fs::remove_file(path);
        let (image, owned) = (self.image.clone(), path.to_path_buf());
        self.world_mut()
            .spawn(Screenshot::image(image))
            .observe(save_to_disk(owned));
        for _ in 0..30 {
            self.update();
            if path.exists() {
                return Ok(());
            }
        }
        Err(format!("no screenshot was written to {}", path.display()))
    }
}
