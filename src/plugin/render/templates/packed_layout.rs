//! The WGSL module `bevy_jellyfish::packed`, written from `shape::packed::layout`'s table:
//! the packed block's offsets and the constants the vertex shader shares with the CPU
//! mesh, for `surface.wgsl` (or a game's own shader) to `#import`.

use crate::shape::packed::layout;
use bevy::asset::uuid_handle;
use bevy::prelude::*;
use bevy::shader::Shader;

/// Where the module is kept: a fixed id, so it lives as long as the app.
const PACKED_LAYOUT: Handle<Shader> = uuid_handle!("6b1f0c3e-5a8d-4e2b-9c47-d3a1e8f05b72");

/// Adds the module to `Assets<Shader>`, where Bevy's shader cache finds imports.
pub(super) fn add(app: &mut App) {
    let module = Shader::from_wgsl(layout::wgsl(), "bevy_jellyfish/packed.wgsl");
    app.world_mut()
        .resource_mut::<Assets<Shader>>()
        .insert(&PACKED_LAYOUT, module)
        .expect("an asset with a UUID id is always inserted");
}
