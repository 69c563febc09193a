//! The open-loop muscle controller (paper section 3.3, Fig. 4).
//!
//! Each muscle spring's rest length follows a periodic contraction function built from
//! cubic Hermite segments, normalised between 1 (relaxed) and the species' contraction
//! ratio (paper: 0.56). With `expansion_stagger` > 0, springs nearer the aperture start to
//! re-expand later and take longer, which gives the conical contracted bell the paper
//! reports travels 68% further per stroke than unison expansion.

use crate::species::Species;

/// The contraction functions of one species.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MuscleDrive {
    /// Fully contracted length over rest length.
    pub(crate) ratio: f32,
    /// Fraction of the cycle spent contracting.
    pub(crate) duty: f32,
    /// Fraction of the time between contractions a spring in unison takes to relax.
    pub(crate) span: f32,
    /// How much later and more slowly the springs nearer the aperture re-expand (0: in
    /// unison), `Species::expansion_stagger`.
    pub(crate) stagger: f32,
}

/// How far into the slack of the expansion window (what a spring in unison leaves unused)
/// the slowest (margin) spring starts re-expanding: the paper's margin waits a fifth of the
/// window when a spring in unison takes half of it.
const STAGGER_DELAY: f32 = 0.4;

impl MuscleDrive {
    /// The rhythm a species asks for.
    pub(crate) fn new(species: &Species) -> Self {
        Self {
            ratio: species.contraction_ratio,
            duty: species.contraction_duty,
            span: species.relaxation_span,
            stagger: species.expansion_stagger,
        }
    }

    /// Rest-length factor in `[ratio, 1]` at cycle phase `phase` (any real; period 1) for
    /// a spring at `level` (0 near the apex, 1 at the margin).
    pub(crate) fn rest_factor(&self, phase: f32, level: f32) -> f32 {
        let phi = phase.rem_euclid(1.0);
        let depth = 1.0 - self.ratio;
        if phi < self.duty {
            // Contraction: the whole ring fires together.
            return 1.0 - depth * hermite(phi / self.duty);
        }
        let window = 1.0 - self.duty;
        // A staggered spring starts later and ends no later than the next contraction:
        // the margin waits `delay` of the window and relaxes over the rest of it. (Written
        // so that the paper's span, a half, gives its drive to the last bit.)
        let lag = self.stagger * level.clamp(0.0, 1.0);
        let delay = STAGGER_DELAY * (1.0 - self.span);
        let start = self.duty + window * delay * lag;
        let length = window * (self.span + (1.0 - self.span - delay) * lag);
        if phi < start {
            self.ratio
        } else {
            self.ratio + depth * hermite(((phi - start) / length).min(1.0))
        }
    }
}

/// Cubic Hermite ease from 0 to 1 with zero end tangents, so the periodic function is C¹.
fn hermite(s: f32) -> f32 {
    let s = s.clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn drive(stagger: f32) -> MuscleDrive {
        let mut s = Species::paper();
        s.expansion_stagger = stagger;
        MuscleDrive::new(&s)
    }

    #[test]
    fn normalised_between_one_and_ratio() {
        let d = drive(1.0);
        let (mut lo, mut hi) = (f32::MAX, f32::MIN);
        for k in 0..=1000 {
            for level in [0.0, 0.5, 1.0] {
                let f = d.rest_factor(k as f32 / 1000.0, level);
                lo = lo.min(f);
                hi = hi.max(f);
            }
        }
        assert!(
            (lo - 0.56).abs() < 1e-6 && (hi - 1.0).abs() < 1e-6,
            "{lo}..{hi}"
        );
    }

    #[test]
    fn periodic_and_continuous() {
        let d = drive(1.0);
        for level in [0.0, 0.3, 1.0] {
            assert!((d.rest_factor(0.0, level) - d.rest_factor(1.0, level)).abs() < 1e-6);
            assert!((d.rest_factor(0.25, level) - d.rest_factor(2.25, level)).abs() < 1e-6);
            for k in 0..2000 {
                let a = d.rest_factor(k as f32 / 2000.0, level);
                let b = d.rest_factor((k + 1) as f32 / 2000.0, level);
                assert!((a - b).abs() < 0.01, "jump at {k}");
            }
        }
    }

    #[test]
    fn a_spring_in_unison_relaxes_over_its_span() {
        for span in [0.2, 0.5, 1.0] {
            let mut s = Species::aurelia();
            s.expansion_stagger = 0.0;
            s.relaxation_span = span;
            let d = MuscleDrive::new(&s);
            let done = d.duty + span * (1.0 - d.duty);
            let halfway = d.duty + 0.5 * span * (1.0 - d.duty);
            let f = d.rest_factor(halfway, 0.5);
            assert!(
                (f - 0.5 * (1.0 + d.ratio)).abs() < 1e-3,
                "span {span}: {f} halfway"
            );
            assert!(
                (d.rest_factor(done + 1e-4, 0.5) - 1.0).abs() < 1e-6,
                "span {span}"
            );
        }
    }

    #[test]
    fn the_paper_margin_waits_a_fifth_and_takes_four_fifths_of_the_window() {
        let d = drive(1.0);
        let window = 1.0 - d.duty;
        let start = d.duty + 0.2 * window;
        assert_eq!(d.rest_factor(start - 1e-4, 1.0), d.ratio);
        assert!(d.rest_factor(start + 0.01, 1.0) > d.ratio);
        assert!(d.rest_factor(0.999, 1.0) < 1.0);
        assert!((d.rest_factor(1.0 - 1e-6, 1.0) - 1.0).abs() < 1e-4);
    }

    #[test]
    fn staggered_margin_reexpands_later_and_slower() {
        let d = drive(1.0);
        let mid_expansion = 0.5 * (1.0 + d.duty);
        assert!(d.rest_factor(mid_expansion, 1.0) < d.rest_factor(mid_expansion, 0.25));
        // In unison every level is the same function.
        let u = drive(0.0);
        for k in 0..100 {
            let phi = k as f32 / 100.0;
            assert_eq!(u.rest_factor(phi, 1.0), u.rest_factor(phi, 0.3));
        }
    }
}
