//! The least a game needs: the plugin, a camera, a light and one moon jelly, from the
//! preset in code (no asset files).
//!
//! `cargo run --release --features examples --example minimal`. In a game of its own it
//! needs only `bevy` (default features) and `bevy_jellyfish` as dependencies.

use bevy::prelude::*;
use bevy_jellyfish::prelude::*;

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, JellyfishPlugin::default()))
        .add_systems(Startup, setup)
        .run();
}

fn setup(mut commands: Commands, mut species: ResMut<Assets<Species>>) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 1.0, 4.0).looking_at(Vec3::new(0.0, 1.0, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight::default(),
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // A moon jelly 4 cm across, drawn 30 times life size. It swims along its local +Y and
    // would leave the picture in a few seconds: heading for a point in front of the camera,
    // it turns a little each stroke and circles there.
    let aurelia = species.add(Species::aurelia());
    commands.spawn((
        Jellyfish::new(aurelia),
        Steering::towards(Vec3::new(0.0, 1.0, 0.0)),
        Transform::from_xyz(0.0, 0.5, 0.0).with_scale(Vec3::splat(30.0)),
    ));
}
