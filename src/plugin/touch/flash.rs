//! A jellyfish's flash: bioluminescence after a touch, rising in a tenth of a second and
//! fading over the species' `flash_decay`, with a refractory time before the next.

use crate::plugin::slice::JellyfishSlice;
use crate::species::Species;
use bevy::prelude::*;

/// How long a flash takes to rise to its peak, s.
pub const FLASH_RISE: f32 = 0.1;

/// A jellyfish's light after a touch: read by its glow layer, and by games.
#[derive(Component, Clone, Debug, Default, PartialEq, Reflect)]
#[reflect(Component, Default)]
pub struct Flash {
    /// Brightness now, added to the species' `glow` in its units and colour (0: dark).
    pub brightness: f32,
    /// Where the touch came from, in the jellyfish's local frame (a direction from the
    /// bell's centre, unit length; zero before any touch).
    pub origin: Vec3,
    /// The brightest the current flash gets.
    pub peak: f32,
    /// When the current flash started, virtual seconds.
    pub started: Option<f64>,
}

impl Flash {
    /// Starts a flash of `strength` (0 to 1) of the species' `flash` at virtual time `now`,
    /// from world point `from`, unless the species does not luminesce or the last flash
    /// is within its refractory time. Returns whether it started.
    pub(super) fn start(
        &mut self,
        species: &Species,
        now: f64,
        strength: f32,
        from: Vec3,
        at: &GlobalTransform,
    ) -> bool {
        let peak = species.flash * strength.clamp(0.0, 1.0);
        let rested = self
            .started
            .is_none_or(|t| now - t >= species.flash_refractory as f64);
        if peak <= 0.0 || !rested {
            return false;
        }
        self.peak = peak;
        self.started = Some(now);
        let local = at.affine().inverse().transform_point3(from);
        self.origin = local.normalize_or(Vec3::Y);
        true
    }

    /// Brightness `age` seconds after the flash started: a smooth rise over
    /// [`FLASH_RISE`], then an exponential fade over `decay`.
    pub fn at_age(peak: f32, age: f32, decay: f32) -> f32 {
        if age < 0.0 {
            return 0.0;
        }
        let x = (age / FLASH_RISE).min(1.0);
        let rise = x * x * (3.0 - 2.0 * x);
        let fade = (-(age - FLASH_RISE).max(0.0) / decay.max(1e-3)).exp();
        peak * rise * fade
    }
}

/// Every flash's brightness at the frame's time; a faded one goes dark (exactly 0).
pub(super) fn fade(mut jellyfish: Query<(&JellyfishSlice, &mut Flash)>, time: Res<Time<Virtual>>) {
    let now = time.elapsed_secs_f64();
    for (slice, mut flash) in &mut jellyfish {
        let Some(started) = flash.started else {
            continue;
        };
        let decay = slice.species().map_or(1.0, |s| s.flash_decay);
        let b = Flash::at_age(flash.peak, (now - started) as f32, decay);
        let b = if b < 1e-3 * flash.peak.max(1e-6) {
            0.0
        } else {
            b
        };
        if flash.brightness != b {
            flash.brightness = b;
        }
    }
}
