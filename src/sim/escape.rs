//! The escape: a touched medusa beats deeper and quicker for a few strokes, then eases back
//! into its rhythm. It is the slice's own muscles that do it (physics the water feels,
//! never a push), in the species' fixed steps: a quicker rhythm moves the muscle drive's
//! phase on by an extra step now and then ([`FixedClock::hurry`](super::clock::FixedClock::hurry)),
//! and a deeper stroke shortens the muscle further.

use crate::species::Species;

/// One escape under way, counted in fixed steps so that it is the same however time is
/// split into frames.
#[derive(Clone, Debug, PartialEq)]
pub struct Escape {
    /// How strong a touch started it, 0 to 1.
    strength: f32,
    /// Fixed steps it lasts.
    steps: u32,
    /// Fixed steps it has run.
    taken: u32,
    /// Fixed steps of the last stroke, over which it eases back.
    easing: u32,
    /// The stroke steps the quicker rhythm owes, less than one.
    owed: f32,
}

impl Escape {
    /// An escape of `strength` (clamped to 0..1) for `species`, whose stroke takes
    /// `steps_per_cycle` fixed steps; `None` where the species has no escape or the touch
    /// no strength.
    pub fn new(species: &Species, steps_per_cycle: u32, strength: f32) -> Option<Self> {
        let strength = if strength.is_finite() {
            strength.clamp(0.0, 1.0)
        } else {
            0.0
        };
        if species.escape_strokes == 0 || strength == 0.0 {
            return None;
        }
        // The strokes at the escape's rhythm, the last easing back at the species' own.
        let quick = steps_per_cycle as f32 / species.escape_rhythm.max(1.0);
        let steps = ((species.escape_strokes - 1) as f32 * quick).round() as u32 + steps_per_cycle;
        Some(Self {
            strength,
            steps,
            taken: 0,
            easing: steps_per_cycle.max(1),
            owed: 0.0,
        })
    }

    /// How strong it is now, 0 to 1: its strength until the last stroke, then easing to 0.
    pub fn envelope(&self) -> f32 {
        let left = self.steps.saturating_sub(self.taken);
        let x = (left as f32 / self.easing as f32).min(1.0);
        self.strength * x * x * (3.0 - 2.0 * x)
    }

    /// Whether it has run its course.
    pub fn done(&self) -> bool {
        self.taken >= self.steps
    }

    /// The muscle's depth now, as a multiple of the stroke's own (1: the species' stroke).
    pub fn depth(&self, species: &Species) -> f32 {
        1.0 + species.escape_depth * self.envelope()
    }

    /// Counts one fixed step and returns the stroke steps it moves the muscle drive's phase
    /// on: one, and an extra one whenever the quicker rhythm has gained a whole step.
    pub fn step(&mut self, species: &Species) -> u32 {
        let quicker = (species.escape_rhythm - 1.0).max(0.0) * self.envelope();
        self.taken += 1;
        self.owed += quicker;
        let extra = self.owed.floor();
        self.owed -= extra;
        1 + extra as u32
    }

    /// The same escape, as far along, for a stroke of `to` fixed steps instead of `from`
    /// (a jellyfish moved to a level of detail with another step).
    pub fn retimed(&self, from: u32, to: u32) -> Self {
        let k = to.max(1) as f32 / from.max(1) as f32;
        let scale = |n: u32| (n as f32 * k).round() as u32;
        Self {
            steps: scale(self.steps),
            taken: scale(self.taken),
            easing: scale(self.easing).max(1),
            ..self.clone()
        }
    }

    /// A new touch during the escape: the stronger of the two, from the start.
    pub fn renew(&mut self, fresh: Escape) {
        let strength = self.envelope().max(fresh.strength);
        *self = Self { strength, ..fresh };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sarsia() -> Species {
        Species::sarsia()
    }

    #[test]
    fn none_without_a_response_or_a_touch() {
        let mut s = sarsia();
        assert!(Escape::new(&s, 40, 0.0).is_none());
        assert!(Escape::new(&s, 40, f32::NAN).is_none());
        s.escape_strokes = 0;
        assert!(Escape::new(&s, 40, 1.0).is_none());
    }

    #[test]
    fn quicker_by_the_rhythm_then_eases_back_to_the_stroke() {
        let s = sarsia();
        let per_cycle = 40;
        let mut e = Escape::new(&s, per_cycle, 1.0).unwrap();
        let mut stroke_steps = 0;
        let mut fixed = 0;
        let mut depths = Vec::new();
        while !e.done() {
            depths.push(e.depth(&s));
            stroke_steps += e.step(&s);
            fixed += 1;
        }
        // All but the last stroke at the escape's rhythm, the last easing from it to 1.
        let quick = (s.escape_strokes - 1) as f32 * per_cycle as f32;
        let expected = quick + per_cycle as f32 * (1.0 + (s.escape_rhythm - 1.0) * 0.5);
        assert!(
            (stroke_steps as f32 - expected).abs() <= 2.0,
            "{stroke_steps} stroke steps in {fixed} fixed steps, expected {expected}"
        );
        assert_eq!(depths[0], 1.0 + s.escape_depth);
        assert!(
            depths.windows(2).all(|w| w[1] <= w[0]),
            "it only eases back"
        );
        assert!(
            e.depth(&s) == 1.0 && e.step(&s) == 1,
            "then the species' own stroke"
        );
    }

    #[test]
    fn a_new_touch_renews_it_at_the_stronger_strength() {
        let s = sarsia();
        let mut e = Escape::new(&s, 40, 0.8).unwrap();
        (0..20).for_each(|_| {
            e.step(&s);
        });
        e.renew(Escape::new(&s, 40, 0.3).unwrap());
        assert_eq!(e.envelope(), 0.8);
        assert!(!e.done());
    }
}
