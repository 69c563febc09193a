//! [`Species`] as a Bevy asset: a RON loader that validates, and a message when a species
//! is refused (a bad file or a bad live edit), so jellyfish keep their last valid one.

use crate::species::{Species, SpeciesError};
use bevy::asset::{
    Asset, AssetLoadError, AssetLoadFailedEvent, AssetLoader, LoadContext, UntypedAssetId,
    VisitAssetDependencies, io::Reader,
};
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
#[derive(Message, Clone, Debug)]
pub struct SpeciesRejected {
    pub species: AssetId<Species>,
    pub error: SpeciesError,
}

pub(super) fn plugin(app: &mut App) {
    app.init_asset::<Species>()
        .register_asset_reflect::<Species>()
        .init_asset_loader::<SpeciesLoader>()
        .add_message::<SpeciesRejected>()
        .add_systems(
            PreUpdate,
            report_failed_loads.in_set(super::JellyfishSystems::Prepare),
        );
}

/// Bevy logs the loader's error; this says what happens next and tells listeners.
fn report_failed_loads(
    mut failed: MessageReader<AssetLoadFailedEvent<Species>>,
    mut rejected: MessageWriter<SpeciesRejected>,
) {
    for event in failed.read() {
        let AssetLoadError::AssetLoaderError(loader) = &event.error else {
            continue;
        };
        let Some(error) = loader.error().downcast_ref::<SpeciesError>() else {
            continue;
        };
        warn!(
            "species '{}' refused ({error}); jellyfish keep its last valid parameters",
            event.path
        );
        rejected.write(SpeciesRejected {
            species: event.id,
            error: error.clone(),
        });
    }
}
