//! The paper's findings on its own model: staggering, the Reynolds number, and the
//! frequency sweep at three stiffnesses.

use crate::run::{distance_in, parallel, swim};
use crate::tables::against_unison;
use bevy_jellyfish::Species;

pub fn calibration(base: &Species) {
    let [staggered, unison] = against_unison(base, 20, 40);
    println!("\n### Calibration ({})\n", base.name);
    println!(
        "- swim per cycle, cycles 20–40: staggered {:.3} (cv {:.1}%), unison {:.3} (cv {:.1}%): staggered {:+.0}%",
        staggered.mean(),
        100.0 * staggered.cv(),
        unison.mean(),
        100.0 * unison.cv(),
        100.0 * (staggered.mean() / unison.mean() - 1.0)
    );
    let re =
        |s: &Species| s.density * s.contraction_frequency * s.diameter * s.diameter / s.viscosity;
    for target in [1.0f32, 10.0, 100.0] {
        let viscosity =
            base.density * base.contraction_frequency * base.diameter * base.diameter / target;
        let s = Species {
            viscosity,
            ..base.clone()
        };
        let r = swim(&s, 1.0 / 60.0, 10, 20);
        println!(
            "- Re {:.0} (viscosity {viscosity:.3e} Pa·s): {:.3} D per cycle",
            re(&s),
            r.mean()
        );
    }
    println!(
        "- Re {:.0} (sea water): {:.3} D per cycle",
        re(base),
        staggered.mean()
    );
    let frequencies: Vec<f32> = (2..=16).map(|k| k as f32 / 10.0).collect();
    for (label, modulus) in [
        ("E = 1186 Pa", base.elastic_modulus),
        ("E × 2", 2.0 * base.elastic_modulus),
        ("E / 2", 0.5 * base.elastic_modulus),
    ] {
        let jobs: Vec<Species> = frequencies
            .iter()
            .map(|&f| Species {
                contraction_frequency: f,
                elastic_modulus: modulus,
                ..base.clone()
            })
            .collect();
        let d = parallel(jobs, |s| distance_in(s, 1.0, 20.0));
        let (peak, best) = d
            .iter()
            .enumerate()
            .fold((0, f32::MIN), |m, (i, &x)| if x > m.1 { (i, x) } else { m });
        let cells: Vec<String> = frequencies
            .iter()
            .zip(&d)
            .map(|(f, x)| format!("{f:.1}:{x:.2}"))
            .collect();
        println!(
            "- sweep {label}: peak {:.1} Hz ({best:.2} D in 20 s; ends {:.2} and {:.2}: {:+.0}% / {:+.0}%)\n  {}",
            frequencies[peak],
            d[0],
            d[d.len() - 1],
            100.0 * (best / d[0] - 1.0),
            100.0 * (best / d[d.len() - 1] - 1.0),
            cells.join(" ")
        );
    }
}
