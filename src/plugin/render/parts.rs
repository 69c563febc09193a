//! A jellyfish's parts, its tentacles and its glow layer, are entities that sit exactly
//! on their bell ([`PartOf`]). They are not its children and hold no `Transform`: Bevy's
//! propagation would multiply each by the identity after its bell (twenty thousand of them
//! in a school of ten thousand), and even parts without a `Transform` cost it a visit of
//! every child of every jellyfish each frame; copying the bell's placement and visibility,
//! once Bevy has made them, is a fraction of that (`docs/benchmarks.md`).

use super::meshes::{JellyfishGlow, JellyfishMeshes, JellyfishTentacles};
use bevy::camera::primitives::Aabb;
use bevy::camera::visibility::NoAutoAabb;
use bevy::prelude::*;

/// A jellyfish's part: its tentacles or its glow layer.
type Part = Or<(With<JellyfishTentacles>, With<JellyfishGlow>)>;

/// The tentacles' part: drawn with `mesh`, bounded like the umbrella.
pub(crate) fn tentacle_layer(jellyfish: Entity, mesh: Mesh3d, bounds: Option<Aabb>) -> impl Bundle {
    (JellyfishTentacles, part(jellyfish, mesh, bounds))
}

/// The glow layer's part: the umbrella's mesh again, bounded like the umbrella.
pub(crate) fn glow_layer(jellyfish: Entity, mesh: Mesh3d, bounds: Option<Aabb>) -> impl Bundle {
    (JellyfishGlow, part(jellyfish, mesh, bounds))
}

fn part(jellyfish: Entity, mesh: Mesh3d, bounds: Option<Aabb>) -> impl Bundle {
    (
        mesh,
        bounds.unwrap_or_default(),
        NoAutoAabb,
        PartOf(jellyfish),
    )
}

/// The jellyfish a part is drawn on: it is placed, shown and hidden with it, and despawned
/// with it ([`JellyfishParts`]).
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
#[relationship(relationship_target = JellyfishParts)]
pub struct PartOf(#[entities] pub Entity);

impl PartOf {
    /// The jellyfish the part is drawn on.
    pub fn jellyfish(&self) -> Entity {
        self.0
    }
}

/// A jellyfish's parts ([`PartOf`]): despawned with it.
#[derive(Component, Debug, Default)]
#[relationship_target(relationship = PartOf, linked_spawn)]
pub struct JellyfishParts(Vec<Entity>);

/// Places every part where Bevy's propagation has just placed its bell, and bounds it
/// like the bell. A `Transform` a part is given (`Mesh3d` requires one, and inserts it
/// with itself) is taken away again, so propagation passes the part by.
pub(super) fn place_parts(
    mut parts: Query<(&mut GlobalTransform, &mut Aabb, &PartOf), (Part, Without<JellyfishMeshes>)>,
    bells: Query<(&GlobalTransform, &JellyfishMeshes)>,
    given: Query<Entity, (Part, With<Transform>)>,
    mut commands: Commands,
) {
    parts.par_iter_mut().for_each(|(mut placed, mut aabb, of)| {
        if let Ok((bell, meshes)) = bells.get(of.jellyfish()) {
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

/// A jellyfish (not a part) whose visibility Bevy has just changed.
type ChangedBell = (Changed<InheritedVisibility>, Without<PartOf>);

/// Shows and hides each part with its jellyfish, as a child would be: a part whose own
/// `Visibility` is `Inherited` takes its jellyfish's, one made `Visible` or `Hidden`
/// keeps its own. Only where either changed: a jellyfish's visibility, or a part's
/// (spawned, or set by Bevy's propagation, which reads it as a part without a parent).
pub(super) fn show_parts(
    bells: Query<(&InheritedVisibility, &JellyfishParts), ChangedBell>,
    jellyfish: Query<&InheritedVisibility, Without<PartOf>>,
    mut parts: Query<(&Visibility, &mut InheritedVisibility, Ref<PartOf>), Part>,
) {
    let show = |own: &Visibility, inherited: &mut Mut<InheritedVisibility>, bell: bool| {
        let visible = match own {
            Visibility::Visible => true,
            Visibility::Hidden => false,
            Visibility::Inherited => bell,
        };
        let wanted = match visible {
            true => InheritedVisibility::VISIBLE,
            false => InheritedVisibility::HIDDEN,
        };
        inherited.set_if_neq(wanted);
    };
    for (bell, own) in &bells {
        for part in own.iter() {
            if let Ok((visibility, mut inherited, _)) = parts.get_mut(part) {
                show(visibility, &mut inherited, bell.get());
            }
        }
    }
    for (visibility, mut inherited, of) in &mut parts {
        if inherited.is_changed() || of.is_changed() {
            let bell = jellyfish.get(of.jellyfish()).ok().is_none_or(|b| b.get());
            show(visibility, &mut inherited, bell);
        }
    }
}
