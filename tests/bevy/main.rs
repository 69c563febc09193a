//! The Bevy integration tests, in one binary: every test binary links Bevy, so one binary
//! links it once. Run with `cargo test --features examples`.

// The aquarium example's modules, at the crate root where the example has them: the
// render test draws the example's own scene.
#[path = "../../examples/aquarium/camera.rs"]
mod camera;
#[path = "../../examples/aquarium/scene.rs"]
mod scene;
#[path = "../../examples/aquarium/school.rs"]
mod school;
#[path = "../../examples/common/offscreen.rs"]
mod screenshot;
#[path = "../../examples/aquarium/snow.rs"]
mod snow;
#[path = "../../examples/aquarium/stats.rs"]
mod stats;
#[path = "../../examples/aquarium/tank.rs"]
mod tank;
#[path = "../../examples/aquarium/water.rs"]
mod water;

#[path = "../common/mod.rs"]
mod common;

mod editor;
mod light;
mod plugin;
mod render;
mod shader;
mod tentacles;
mod water_and_steering;
