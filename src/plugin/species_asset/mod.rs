//! [`Species`] as a Bevy asset: a RON loader that validates, and a message when a species
//! is refused (a bad file or a bad live edit), so jellyfish keep their last valid one.

use super::schedule::JellyfishSystems;
use crate::species::{Species, SpeciesError};
use bevy::asset::{
    Asset, AssetLoadError, AssetLoadFailedEvent, AssetLoader, LoadContext, UntypedAssetId,
    VisitAssetDependencies, io::Reader,
};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;

// `TypePath` comes from the `Reflect` derive on `Species`.
impl VisitAssetDependencies for Species {
    fn visit_dependencies(&self, _visit: &mut impl FnMut(UntypedAssetId)) {}
}

impl Asset for Species {}

/// Loads `*.species.ron` files (a game's other `.ron` files are its own); a file that does not parse or validate fails to load, with
/// an error naming the field. On a reload the asset keeps its last valid value.
#[derive(Default, TypePath)]
pub struct SpeciesLoader;

impl AssetLoader for SpeciesLoader {
    type Asset = Species;
    type Settings = ();
    type Error = SpeciesError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        _context: &mut LoadContext<'_>,
    ) -> Result<Species, SpeciesError> {
        let mut bytes = Vec::new();
        reader
            .read_to_end(&mut bytes)
            .await
            .map_err(|e| SpeciesError::Parse(e.to_string()))?;
        let text = std::str::from_utf8(&bytes).map_err(|e| SpeciesError::Parse(e.to_string()))?;
        Species::from_ron(text)
    }

    fn extensions(&self) -> &[&str] {
        &["species.ron"]
    }
}

/// A species that living jellyfish did not take: a file that failed to load or reload, or
/// an edit of the asset that does not validate. They keep their last valid parameters.
///
/// Sent once per refusal: not again for the same error until the species changes, however
/// many jellyfish refuse it or how many times the watcher reloads the same bad file.
#[derive(Message, Clone, Debug)]
pub struct SpeciesRejected {
    /// The species refused.
    pub species: AssetId<Species>,
    /// Why, naming the field.
    pub error: SpeciesError,
}

/// The last refusal said of each species, so that each is said (logged and sent) once.
#[derive(Resource, Default)]
pub(crate) struct Refusals(HashMap<AssetId<Species>, SpeciesError>);

impl Refusals {
    /// Says `error` of `species` unless it is what was last said of it; true if said.
    pub(crate) fn say(
        &mut self,
        species: AssetId<Species>,
        error: &SpeciesError,
        rejected: &mut MessageWriter<SpeciesRejected>,
    ) -> bool {
        if self.0.get(&species) == Some(error) {
            return false;
        }
        self.0.insert(species, error.clone());
        rejected.write(SpeciesRejected {
            species,
            error: error.clone(),
        });
        true
    }
}

/// A species that changed (an edit, a good reload, a removal) may be refused anew.
fn forget_changed(mut events: MessageReader<AssetEvent<Species>>, mut refusals: ResMut<Refusals>) {
    for event in events.read() {
        if let AssetEvent::Added { id } | AssetEvent::Modified { id } | AssetEvent::Removed { id } =
            event
        {
            refusals.0.remove(id);
        }
    }
}

/// [`Species`] as an asset: `*.species.ron` files loaded and validated, and
/// [`SpeciesRejected`] sent once per refusal.
#[derive(Clone, Copy, Debug, Default)]
pub struct SpeciesAssetPlugin;

impl Plugin for SpeciesAssetPlugin {
    fn build(&self, app: &mut App) {
        app.init_asset::<Species>()
            .register_asset_reflect::<Species>()
            .init_asset_loader::<SpeciesLoader>()
            .add_message::<SpeciesRejected>()
            .init_resource::<Refusals>()
            .add_systems(
                PreUpdate,
                (forget_changed, report_failed_loads)
                    .chain()
                    .in_set(JellyfishSystems::LoadSpecies),
            );
    }
}

/// Bevy logs the loader's error; this says what happens next and tells listeners.
fn report_failed_loads(
    mut failed: MessageReader<AssetLoadFailedEvent<Species>>,
    mut refusals: ResMut<Refusals>,
    mut rejected: MessageWriter<SpeciesRejected>,
) {
    for event in failed.read() {
        let AssetLoadError::AssetLoaderError(loader) = &event.error else {
            continue;
        };
        let Some(error) = loader.error().downcast_ref::<SpeciesError>() else {
            continue;
        };
        if refusals.say(event.id, error, &mut rejected) {
            warn!(
                "species '{}' refused ({error}); jellyfish keep its last valid parameters",
                event.path
            );
        }
    }
}
