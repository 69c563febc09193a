//! A jellyfish's parts, its tentacles and its glow layer, are child entities that sit
//! exactly on their bell. They hold no `Transform`: Bevy's propagation would multiply
//! each by the identity after its bell (twenty thousand of them in a school of ten
//! thousand, most of the propagation's cost), where copying the bell's placement, once
//! propagation has made it, is a fraction of that (`docs/benchmarks.md`).

use super::meshes::{JellyfishGlow, JellyfishMeshes, JellyfishTentacles};
use bevy::camera::primitives::Aabb;
use bevy::camera::visibility::NoAutoAabb;
use bevy::prelude::*;

/// A jellyfish's part drawn by a child entity: its tentacles or its glow layer.
type Part = Or<(With<JellyfishTentacles>, With<JellyfishGlow>)>;

/// The tentacles' child: drawn with `mesh`, bounded like the umbrella.
pub(crate) fn tentacle_layer(parent: Entity, mesh: Mesh3d, bounds: Option<Aabb>) -> impl Bundle {
    (JellyfishTentacles, part(parent, mesh, bounds))
}

/// The glow layer's child: the umbrella's mesh again, bounded like the umbrella.
pub(crate) fn glow_layer(parent: Entity, mesh: Mesh3d, bounds: Option<Aabb>) -> impl Bundle {
    (JellyfishGlow, part(parent, mesh, bounds))
}

fn part(parent: Entity, mesh: Mesh3d, bounds: Option<Aabb>) -> impl Bundle {
    (
        mesh,
        bounds.unwrap_or_default(),
        NoAutoAabb,
        ChildOf(parent),
    )
}

/// Places every part where Bevy's propagation has just placed its bell, and bounds it
/// like the bell. A `Transform` a part is given (`Mesh3d` requires one, and inserts it
/// with itself) is taken away again, so propagation passes the part by.
pub(super) fn place_parts(
    mut parts: Query<(&mut GlobalTransform, &mut Aabb, &ChildOf), (Part, Without<JellyfishMeshes>)>,
    bells: Query<(&GlobalTransform, &JellyfishMeshes)>,
    given: Query<Entity, (Part, With<Transform>)>,
    mut commands: Commands,
) {
    parts
        .par_iter_mut()
        .for_each(|(mut placed, mut aabb, parent)| {
            if let Ok((bell, meshes)) = bells.get(parent.parent()) {
                placed.set_if_neq(*bell);
                if let Some(bounds) = meshes.bounds {
                    *aabb = bounds;
                }
            }
        });
    for part in &given {
        commands.entity(part).remove::<Transform>();
    }
}
