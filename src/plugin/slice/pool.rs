//! One shared copy of each species the slices simulate.
//!
//! Thousands of jellyfish of a few species: the levels of detail and the far tier's
//! recorded frames ask each frame which species a jellyfish has, and comparing two equal
//! species field by field, ten thousand times a frame, was a tenth of a 10,002-jellyfish
//! frame. Interned, equal species are one `Arc`, so the question is a pointer comparison
//! ([`same`]).

use crate::species::Species;
use bevy::prelude::*;
use std::sync::{Arc, Weak};

/// The species slices hold, each once.
#[derive(Resource, Default)]
pub(crate) struct SpeciesPool(Vec<Weak<Species>>);

impl SpeciesPool {
    /// The pool's copy of `species`: the one already held by a slice if it is equal, else
    /// a new one.
    pub(crate) fn intern(&mut self, species: &Species) -> Arc<Species> {
        self.0.retain(|held| held.strong_count() > 0);
        if let Some(held) = self
            .0
            .iter()
            .filter_map(Weak::upgrade)
            .find(|held| **held == *species)
        {
            return held;
        }
        let new = Arc::new(species.clone());
        self.0.push(Arc::downgrade(&new));
        new
    }
}

/// Whether two slices' species are equal: the same copy, or (not interned together) equal
/// field by field.
pub(crate) fn same(a: &Arc<Species>, b: &Arc<Species>) -> bool {
    Arc::ptr_eq(a, b) || a == b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_species_are_one_copy_and_a_dropped_one_is_forgotten() {
        let mut pool = SpeciesPool::default();
        let a = pool.intern(&Species::aurelia());
        let b = pool.intern(&Species::aurelia());
        assert!(Arc::ptr_eq(&a, &b));
        let other = pool.intern(&Species::sarsia());
        assert!(!same(&a, &other));
        let edited = Species {
            diameter: 0.05,
            ..Species::aurelia()
        };
        let c = pool.intern(&edited);
        assert!(!Arc::ptr_eq(&a, &c) && !same(&a, &c));
        drop((other, c));
        pool.intern(&Species::aurelia());
        assert_eq!(pool.0.len(), 1, "dropped species are forgotten");
        // Equal but interned apart (two pools) still compare equal.
        let elsewhere = SpeciesPool::default().intern(&Species::aurelia());
        assert!(same(&a, &elsewhere));
    }
}
