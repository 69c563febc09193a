//! The open-loop muscle controller (paper section 3.3, Fig. 4).
//!
//! Each muscle spring's rest length follows a periodic contraction function built from
//! cubic Hermite segments, normalised between 1 (relaxed) and the species' contraction
//! ratio (paper: 0.56). With `expansion_stagger` > 0, springs nearer the aperture start to
//! re-expand later and take longer, which gives the conical contracted bell the paper
//! reports travels 68% further per stroke than unison expansion.
//!
//! Those functions are the natural cycle's. A species whose muscle times its stroke as a
//! twitch (`MuscleTiming::Twitch`) keeps their seconds when it beats at another rate:
//! slower, it rests relaxed between strokes; faster, it still contracts in its own time
//! and lets go in what is left of the cycle, so its bell's recoil is what limits it.

use crate::species::{MuscleLaw, SliceGeometry, Species};

/// The contraction functions of one species.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MuscleDrive {
    /// Fully contracted length over rest length.
    pub(crate) ratio: f32,
    /// Fraction of the natural cycle spent contracting.
    pub(crate) duty: f32,
    /// Fraction of the natural cycle's time between contractions a spring in unison takes
    /// to relax.
    pub(crate) span: f32,
    /// How much later and more slowly the springs nearer the aperture re-expand (0: in
    /// unison), `Species::expansion_stagger`.
    pub(crate) stagger: f32,
    /// The natural cycle's functions are the ones beaten ([`Species::cycle_stretch`] 1).
    pub(crate) natural: bool,
    /// Fraction of the cycle beaten spent contracting ([`Species::contraction_share`]).
    pub(crate) beat: f32,
    /// How fast the release runs through the natural cycle's, in its phase per phase of
    /// the cycle beaten: at its own seconds (the stretch); for a force generator whose
    /// seconds do not fit before the next stroke, just fast enough that they do.
    pub(crate) pace: f32,
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
            natural: species.cycle_stretch() == 1.0,
            beat: species.contraction_share(),
            pace: Self::pace(species),
        }
    }

    /// A commanded length (the plane's spring, or `MuscleLaw::Length`) lengthens again in
    /// its own seconds: its release stands for the bell's recoil, which no quicker beat
    /// hurries, so beaten faster it fires before it is back at rest. A force generator's
    /// release is only its activation, the recoil being the bell's own: it lets go in what
    /// is left of a quicker cycle. (Letting go in its own seconds too, its residual pull
    /// held the moon jelly's bell shut a seventh above its natural rate: 0.24 D a stroke
    /// at 0.8 Hz against 0.48 at 0.7, backwards at 0.9.)
    fn pace(species: &Species) -> f32 {
        let stretch = species.cycle_stretch();
        let force = species.slice_geometry == SliceGeometry::Axisymmetric
            && species.muscle_law == MuscleLaw::Force;
        if force {
            stretch.max((1.0 - species.contraction_duty) / (1.0 - species.contraction_share()))
        } else {
            stretch
        }
    }

    /// Rest-length factor in `[ratio, 1]` at cycle phase `phase` (any real; period 1) for
    /// a spring at `level` (0 near the apex, 1 at the margin).
    pub(crate) fn rest_factor(&self, phase: f32, level: f32) -> f32 {
        let phi = phase.rem_euclid(1.0);
        if self.natural {
            return self.natural_cycle(phi, level);
        }
        if phi < self.beat {
            // The whole ring fires together, from where the last stroke left it.
            let from = self.release(self.natural_phase(1.0), level);
            return from + (self.ratio - from) * hermite(phi / self.beat);
        }
        self.release(self.natural_phase(phi), level)
    }

    /// Where in the natural cycle the release is at phase `phi` (after the contraction) of
    /// the cycle beaten: from 1 on, let go.
    fn natural_phase(&self, phi: f32) -> f32 {
        self.duty + (phi - self.beat) * self.pace
    }

    /// The natural cycle's function.
    fn natural_cycle(&self, phi: f32, level: f32) -> f32 {
        if phi < self.duty {
            // Contraction: the whole ring fires together.
            return 1.0 - (1.0 - self.ratio) * hermite(phi / self.duty);
        }
        self.release(phi, level)
    }

    /// Letting go, at phase `phi` of the natural cycle after the contraction (relaxed from
    /// 1 on).
    fn release(&self, phi: f32, level: f32) -> f32 {
        if phi >= 1.0 {
            return 1.0;
        }
        let depth = 1.0 - self.ratio;
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

    /// Seconds a spring at `level` spends contracting and letting go (to within `1e-3`
    /// of its relaxed length).
    fn twitch_seconds(s: &Species, level: f32) -> (f32, f32) {
        let d = MuscleDrive::new(s);
        let period = s.period();
        let n = 20_000;
        let relaxed = (0..n)
            .map(|k| k as f32 / n as f32)
            .find(|&phi| phi > d.beat && d.rest_factor(phi, level) > 1.0 - 1e-3)
            .unwrap_or(1.0);
        (d.beat * period, (relaxed - d.beat) * period)
    }

    #[test]
    fn a_twitch_keeps_its_seconds_at_any_slower_rate() {
        let s = Species::aurelia();
        assert_eq!(s.natural_pulse_rate(), s.contraction_frequency);
        assert_eq!(s.cycle_stretch(), 1.0);
        assert_eq!(s.contraction_share(), s.contraction_duty);
        for level in [0.0, 0.5, 1.0] {
            let (contract, release) = twitch_seconds(&s, level);
            for f in [0.35, 0.5, 0.7] {
                let slower = Species {
                    contraction_frequency: f,
                    ..s.clone()
                };
                let (c, r) = twitch_seconds(&slower, level);
                assert!(
                    (c - contract).abs() < 1e-4,
                    "{f} Hz: contracts {c} s, not {contract}"
                );
                // To the sampling's 1/20000 of a cycle.
                assert!(
                    (r - release).abs() < 1e-4 / f,
                    "{f} Hz: lets go in {r} s, not {release}"
                );
            }
        }
        // The paper's stroke is a share of any cycle.
        let paper = Species {
            contraction_frequency: 0.35,
            ..Species::paper()
        };
        assert_eq!(paper.cycle_stretch(), 1.0);
        let (d, natural) = (
            MuscleDrive::new(&paper),
            MuscleDrive::new(&Species::paper()),
        );
        for k in 0..100 {
            let phi = k as f32 / 100.0;
            assert_eq!(d.rest_factor(phi, 0.7), natural.rest_factor(phi, 0.7));
        }
    }

    #[test]
    fn beaten_faster_the_muscle_contracts_in_its_own_time_and_lets_go_in_what_is_left() {
        let s = Species::aurelia();
        let (contract, _) = twitch_seconds(&s, 0.0);
        // At 1.2 Hz the cycle (0.83 s) is shorter than the natural one (1.43 s).
        let faster = Species {
            contraction_frequency: 1.2,
            ..s.clone()
        };
        let d = MuscleDrive::new(&faster);
        assert!((d.beat * faster.period() - contract).abs() < 1e-4);
        let natural = MuscleDrive::new(&s);
        for level in [0.0, 0.5, 1.0] {
            let n = 4000;
            let at = |d: &MuscleDrive, k: usize| d.rest_factor(k as f32 / n as f32, level);
            let factors: Vec<f32> = (0..=n).map(|k| at(&d, k)).collect();
            let least = factors.iter().cloned().fold(f32::MAX, f32::min);
            assert!((least - d.ratio).abs() < 1e-6);
            // Relaxed when it fires again, as at its own rate, and continuous throughout.
            assert!(
                (at(&d, n - 1) - 1.0).abs() < 1e-4,
                "level {level}: {}",
                at(&d, n - 1)
            );
            assert!((factors[0] - 1.0).abs() < 1e-6);
            for w in factors.windows(2) {
                assert!((w[0] - w[1]).abs() < 0.01, "level {level}");
            }
            // Its release runs through the natural one's, only quicker: the same lengths
            // in the same order.
            let release =
                |d: &MuscleDrive, share: f32| d.rest_factor(d.beat + share * (1.0 - d.beat), level);
            for share in [0.1, 0.3, 0.5, 0.7, 0.9] {
                let (quick, own) = (release(&d, share), release(&natural, share));
                assert!(
                    (quick - own).abs() < 1e-5,
                    "level {level} at {share}: {quick} vs {own}"
                );
            }
        }
    }

    #[test]
    fn a_commanded_length_beaten_faster_is_not_back_at_rest_when_it_fires_again() {
        for s in [
            Species::sarsia(),
            Species {
                slice_geometry: SliceGeometry::Planar,
                ..Species::aurelia()
            },
        ] {
            let faster = Species {
                contraction_frequency: 2.0 * s.natural_pulse_rate(),
                ..s.clone()
            };
            let d = MuscleDrive::new(&faster);
            for level in [0.0, 1.0] {
                let n = 4000;
                let factors: Vec<f32> = (0..=n)
                    .map(|k| d.rest_factor(k as f32 / n as f32, level))
                    .collect();
                let most = factors.iter().cloned().fold(f32::MIN, f32::max);
                assert!(
                    most < 1.0 - 1e-3,
                    "{} level {level}: back to {most}",
                    s.name
                );
                assert!((factors[0] - factors[n]).abs() < 1e-6);
                for w in factors.windows(2) {
                    assert!((w[0] - w[1]).abs() < 0.01, "{} level {level}", s.name);
                }
            }
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
