//! Whole-surface properties of [`JellyMesh`]: symmetry, closure, winding, robustness,
//! determinism, attenuation and in-place reuse.

use super::*;
use crate::sim::SliceView;
use crate::species::Species;
use glam::{Quat, Vec2, Vec3};
use std::collections::HashMap;

fn plain(species: &Species) -> Species {
    Species {
        structural_scale: 0.0,
        compression_scale: 0.0,
        unstructured_scale: 0.0,
        tentacle_length_spread: 0.0,
        ..species.clone()
    }
}

fn build(view: &SliceView, species: &Species, seed: u32, time: f32) -> JellyMesh {
    JellyMesh::from_slice(view, species, seed, time).expect("valid slice")
}

fn v3(p: [f32; 3]) -> Vec3 {
    Vec3::from_array(p)
}

/// Checks a closed, consistently wound, outward surface: after welding equal positions, each
/// directed edge occurs once and its reverse once, and the enclosed volume is positive.
fn assert_closed_outward(buf: &SurfaceBuffers) {
    let mut id = HashMap::new();
    let weld: Vec<usize> = buf
        .positions
        .iter()
        .map(|p| {
            let key = p.map(f32::to_bits);
            let next = id.len();
            *id.entry(key).or_insert(next)
        })
        .collect();
    let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
    let mut volume = 0.0f64;
    for tri in buf.indices.chunks_exact(3) {
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize);
        for (p, q) in [(a, b), (b, c), (c, a)] {
            assert_ne!(weld[p], weld[q], "degenerate edge");
            *edges.entry((weld[p], weld[q])).or_default() += 1;
        }
        let [pa, pb, pc] = [a, b, c].map(|i| v3(buf.positions[i]).as_dvec3());
        volume += pa.dot(pb.cross(pc)) / 6.0;
    }
    for (&(p, q), &count) in &edges {
        assert_eq!(count, 1, "directed edge {p}->{q} used {count} times");
        assert_eq!(edges.get(&(q, p)), Some(&1), "edge {p}-{q} is open");
    }
    assert!(
        volume > 0.0,
        "volume {volume} is not positive: winding inward"
    );
}

fn assert_finite(mesh: &JellyMesh) {
    for buf in [&mesh.umbrella, &mesh.tentacles] {
        assert!(buf.positions.iter().flatten().all(|v| v.is_finite()));
        for n in &buf.normals {
            assert!((v3(*n).length() - 1.0).abs() < 1e-4, "normal {n:?}");
        }
    }
}

#[test]
fn symmetric_slice_gives_a_bell_symmetric_about_its_axis() {
    let sp = plain(&Species::aurelia());
    for amount in [0.0, 1.0] {
        let slice = SliceOutline::contracted(&sp, 25, 10, amount);
        let mesh = build(&slice.view(), &sp, 1, 0.0);
        let ring = sp.mesh_segments as usize + 1;
        let surface = 1 + sp.mesh_rings as usize * ring;
        for s in 0..2 {
            for k in 0..sp.mesh_rings as usize {
                let verts = &mesh.umbrella.positions[s * surface + 1 + k * ring..][..ring];
                let normals = &mesh.umbrella.normals[s * surface + 1 + k * ring..][..ring];
                let r0 = Vec2::new(verts[0][0], verts[0][2]).length();
                let n0 = v3(normals[0]);
                for (p, n) in verts.iter().zip(normals) {
                    let r = Vec2::new(p[0], p[2]).length();
                    assert!((r - r0).abs() < 1e-6, "surface {s} ring {k}: {r} vs {r0}");
                    assert!((p[1] - verts[0][1]).abs() < 1e-6);
                    // Normals too, seam included: same tilt and same radial part.
                    let radial = |n: Vec3, p: &[f32; 3]| n.dot(Vec3::new(p[0], 0.0, p[2]) / r0);
                    assert!(
                        (n[1] - n0.y).abs() < 1e-4,
                        "surface {s} ring {k}: {n:?} vs {n0}"
                    );
                    assert!((radial(v3(*n), p) - radial(n0, &verts[0])).abs() < 1e-4);
                }
            }
        }
    }
}

#[test]
fn each_pair_has_its_own_axis() {
    let sp = Species::aurelia();
    // A rigidly tilted slice gives the same jellyfish tilted, variation included.
    let slice = SliceOutline::contracted(&sp, 25, 10, 0.6);
    let turn = 0.4f32;
    let rot = |v: &Vec2| Vec2::from_angle(turn).rotate(*v);
    let tilted = SliceOutline {
        bell: slice.bell.iter().map(rot).collect(),
        rest_bell: slice.rest_bell.iter().map(rot).collect(),
        tentacles: slice.tentacles.clone().map(|c| c.iter().map(rot).collect()),
        oral_arms: slice.oral_arms.clone().map(|c| c.iter().map(rot).collect()),
        trail: Vec::new(),
        oral_trail: Vec::new(),
    };
    let a = build(&slice.view(), &sp, 5, 2.0);
    let b = build(&tilted.view(), &sp, 5, 2.0);
    let q = Quat::from_rotation_z(turn);
    for (ba, bb) in [(&a.umbrella, &b.umbrella), (&a.tentacles, &b.tentacles)] {
        for (pa, pb) in ba.positions.iter().zip(&bb.positions) {
            assert!((q * v3(*pa)).distance(v3(*pb)) < 2e-6);
        }
    }
    // An asymmetric slice (right side wider) gives an asymmetric bell.
    let mut lopsided = SliceOutline::rest(&sp, 25, 10);
    for p in &mut lopsided.bell[13..] {
        p.x *= 1.3;
    }
    let plain_sp = plain(&sp);
    let mesh = build(&lopsided.view(), &plain_sp, 5, 0.0);
    let margin_ex = sp.mesh_rings as usize * (sp.mesh_segments as usize + 1);
    let ring = &mesh.umbrella.positions[margin_ex - sp.mesh_segments as usize..=margin_ex];
    let xs: Vec<f32> = ring.iter().map(|p| p[0]).collect();
    let (lo, hi) = (
        xs.iter().cloned().fold(1.0, f32::min),
        xs.iter().cloned().fold(-1.0, f32::max),
    );
    assert!(hi + lo > 0.1 * sp.diameter, "margin spans {lo}..{hi}");
}

#[test]
fn surfaces_are_closed_with_outward_winding() {
    let sp = Species::aurelia();
    for species in [plain(&sp), sp.clone()] {
        for amount in [0.0, 1.0] {
            let slice = SliceOutline::contracted(&sp, 25, 12, amount);
            let mesh = build(&slice.view(), &species, 3, 1.5);
            assert_closed_outward(&mesh.umbrella);
            // Each tentacle is a closed tube of its own; together they are closed too.
            assert_closed_outward(&mesh.tentacles);
            assert_finite(&mesh);
        }
    }
}

#[test]
fn normals_face_out_of_the_mesoglea() {
    // The paper's dome: from a quarter of the way down every normal leans away from the
    // axis (a saucer's still face up there).
    let sp = plain(&Species::paper());
    let slice = SliceOutline::rest(&sp, 25, 10);
    let mesh = build(&slice.view(), &sp, 0, 0.0);
    let (rings, ring) = (sp.mesh_rings as usize, sp.mesh_segments as usize + 1);
    let surface = 1 + rings * ring;
    for k in rings / 4..rings {
        for j in 0..ring {
            for (s, sign) in [(0, 1.0), (1, -1.0)] {
                let i = s * surface + 1 + k * ring + j;
                let (p, n) = (v3(mesh.umbrella.positions[i]), v3(mesh.umbrella.normals[i]));
                let away = Vec3::new(p.x, 0.0, p.z).normalize();
                assert!(sign * n.dot(away) > 0.2, "surface {s} ring {k}: {n} at {p}");
            }
        }
    }
    // Seam twins share their normal.
    for k in 0..rings {
        let first = 1 + k * ring;
        assert_eq!(
            mesh.umbrella.normals[first],
            mesh.umbrella.normals[first + ring - 1]
        );
    }
}

#[test]
fn degenerate_slices_give_finite_surfaces() {
    let sp = Species::aurelia();
    let rest = SliceOutline::rest(&sp, 25, 10);
    let n = rest.bell.len();
    type Case = (&'static str, Vec<Vec2>, [Vec<Vec2>; 2]);
    let mut cases: Vec<Case> = vec![
        (
            "coincident",
            vec![Vec2::new(0.01, 0.02); n],
            rest.tentacles.clone(),
        ),
        (
            "flat",
            (0..n).map(|i| Vec2::new(i as f32 * 1e-3, 0.0)).collect(),
            rest.tentacles.clone(),
        ),
        (
            "zero-length pairs",
            (0..n)
                .map(|i| Vec2::new(0.0, i.abs_diff(12) as f32 * -1e-3))
                .collect(),
            rest.tentacles.clone(),
        ),
        (
            "inverted",
            rest.bell.iter().map(|p| Vec2::new(p.x, -p.y)).collect(),
            rest.tentacles.clone(),
        ),
        (
            "crossed",
            rest.bell.iter().map(|p| Vec2::new(-p.x, p.y)).collect(),
            rest.tentacles.clone(),
        ),
        ("no tentacles", rest.bell.clone(), [vec![], vec![]]),
        (
            "one-point tentacles",
            rest.bell.clone(),
            [vec![rest.bell[0]], vec![rest.bell[n - 1]]],
        ),
    ];
    cases.push((
        "three points",
        vec![Vec2::ZERO, Vec2::Y, Vec2::X],
        [vec![], vec![Vec2::X; 4]],
    ));
    for (name, bell, tentacles) in &cases {
        let rest_bell = if bell.len() == n { &rest.bell } else { bell };
        let view = SliceView {
            bell,
            rest_bell,
            tentacles: [&tentacles[0], &tentacles[1]],
            oral_arms: [&[], &[]],
            trail: crate::sim::guides::Trail::NONE,
            oral_trail: crate::sim::guides::Trail::NONE,
        };
        let mesh =
            JellyMesh::from_slice(&view, &sp, 9, 3.0).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_finite(&mesh);
    }
}

#[test]
fn bad_slices_are_clear_errors_and_keep_the_last_frame() {
    let sp = Species::aurelia();
    let rest = SliceOutline::rest(&sp, 25, 10);
    let mut mesh = build(&rest.view(), &sp, 1, 0.0);
    let before = mesh.umbrella.clone();
    let mut nan = rest.clone();
    nan.bell[4].y = f32::NAN;
    let mut tentacle_nan = rest.clone();
    tentacle_nan.tentacles[1][3].x = f32::INFINITY;
    let short = SliceOutline {
        bell: rest.bell[..1].to_vec(),
        rest_bell: rest.bell[..1].to_vec(),
        ..rest.clone()
    };
    let even = SliceOutline {
        bell: rest.bell[..24].to_vec(),
        rest_bell: rest.bell[..24].to_vec(),
        ..rest.clone()
    };
    let mismatch = SliceOutline {
        rest_bell: rest.bell[..23].to_vec(),
        ..rest.clone()
    };
    let cases = [
        (&nan, ShapeError::NonFinitePoint("bell")),
        (&tentacle_nan, ShapeError::NonFinitePoint("tentacles[1]")),
        (&short, ShapeError::TooFewPoints(1)),
        (&even, ShapeError::EvenPointCount(24)),
        (&mismatch, ShapeError::RestMismatch { bell: 25, rest: 23 }),
    ];
    for (slice, expect) in cases {
        assert_eq!(
            build_into(&mut mesh, &slice.view(), &sp, 1, 0.0),
            Err(expect)
        );
        assert_eq!(mesh.umbrella, before);
    }
    let bad_species = Species {
        thickness: f32::NAN,
        ..sp.clone()
    };
    assert_eq!(
        build_into(&mut mesh, &rest.view(), &bad_species, 1, 0.0),
        Err(ShapeError::NonFiniteSpecies("thickness"))
    );
    assert_eq!(
        build_into(&mut mesh, &rest.view(), &sp, 1, f32::NAN)
            .unwrap_err()
            .to_string(),
        "time NaN is not finite"
    );
    assert_eq!(mesh.umbrella, before);
}

#[test]
fn noise_is_attenuated_towards_the_apex() {
    let sp = Species::aurelia();
    let noisy = Species {
        structural_scale: 0.0,
        compression_scale: 0.0,
        ..sp.clone()
    };
    let slice = SliceOutline::rest(&sp, 25, 10);
    let base = build(&slice.view(), &plain(&sp), 0, 0.0);
    let (rings, ring) = (sp.mesh_rings as usize, sp.mesh_segments as usize + 1);
    // Ring k (1-based) of the exumbrella sits at latitude k / rings.
    let rms = |k: usize| {
        let mut sum = 0.0;
        for seed in 0..8 {
            let mesh = build(&slice.view(), &noisy, seed, 10.0 * seed as f32);
            for j in 0..ring {
                let i = 1 + (k - 1) * ring + j;
                sum +=
                    v3(mesh.umbrella.positions[i]).distance_squared(v3(base.umbrella.positions[i]));
            }
        }
        (sum / (8 * ring) as f32).sqrt()
    };
    let near_apex = rms(rings / 8);
    let margin = rms(rings);
    // Stated bound: at latitude 1/8 the rms displacement is under a quarter of the margin's.
    assert!(
        margin > 0.05 * noisy.unstructured_scale * sp.thickness,
        "margin rms {margin}"
    );
    assert!(
        near_apex < 0.25 * margin,
        "apex {near_apex} vs margin {margin}"
    );
    assert_eq!(
        build(&slice.view(), &noisy, 3, 1.0).umbrella.positions[0],
        base.umbrella.positions[0]
    );
}

#[test]
fn compression_ripples_only_the_contracted_exumbrella() {
    let sp = Species::aurelia();
    let only = Species {
        structural_scale: 0.0,
        unstructured_scale: 0.0,
        ..sp.clone()
    };
    let surface = 1 + sp.mesh_rings as usize * (sp.mesh_segments as usize + 1);
    let rest = SliceOutline::rest(&sp, 25, 10);
    assert_eq!(
        build(&rest.view(), &only, 1, 0.0).umbrella.positions,
        build(&rest.view(), &plain(&sp), 1, 0.0).umbrella.positions
    );
    let contracted = SliceOutline::contracted(&sp, 25, 10, 1.0);
    let rippled = build(&contracted.view(), &only, 1, 0.0).umbrella.positions;
    let smooth = build(&contracted.view(), &plain(&sp), 1, 0.0)
        .umbrella
        .positions;
    assert_eq!(rippled[surface..], smooth[surface..]);
    let moved = rippled[..surface]
        .iter()
        .zip(&smooth[..surface])
        .map(|(a, b)| v3(*a).distance(v3(*b)))
        .fold(0.0, f32::max);
    let full = sp.compression_scale * sp.thickness;
    assert!(
        moved > 0.5 * full && moved <= full * 1.0001,
        "moved {moved}"
    );
}

#[test]
fn same_seed_and_time_repeat_and_other_seeds_differ() {
    let sp = Species::aurelia();
    let slice = SliceOutline::contracted(&sp, 25, 10, 0.5);
    let a = build(&slice.view(), &sp, 42, 3.0);
    let b = build(&slice.view(), &sp, 42, 3.0);
    assert_eq!(a.umbrella, b.umbrella);
    assert_eq!(a.tentacles, b.tentacles);
    let c = build(&slice.view(), &sp, 43, 3.0);
    assert_ne!(a.umbrella.positions, c.umbrella.positions);
    assert_ne!(a.tentacles.positions, c.tentacles.positions);
    let d = build(&slice.view(), &sp, 42, 30.0);
    assert_ne!(a.umbrella.positions, d.umbrella.positions);
}

#[test]
fn frames_reuse_the_buffers() {
    let sp = Species::aurelia();
    let res = Resolution::of(&sp);
    let rest = SliceOutline::rest(&sp, 25, 10);
    let mut mesh = build(&rest.view(), &sp, 1, 0.0);
    assert_eq!(mesh.umbrella.vertex_count(), res.umbrella_vertices());
    assert_eq!(mesh.tentacles.vertex_count(), res.tentacle_vertices());
    let id = |m: &JellyMesh| {
        [&m.umbrella, &m.tentacles].map(|b| {
            [
                (b.positions.as_ptr() as usize, b.positions.capacity()),
                (b.normals.as_ptr() as usize, b.normals.capacity()),
                (b.uvs.as_ptr() as usize, b.uvs.capacity()),
                (b.indices.as_ptr() as usize, b.indices.capacity()),
            ]
        })
    };
    let before = id(&mesh);
    let indices = mesh.umbrella.indices.clone();
    for (i, amount) in [0.3, 1.0, 0.0].into_iter().enumerate() {
        let slice = SliceOutline::contracted(&sp, 25, 14, amount);
        build_into(&mut mesh, &slice.view(), &sp, 7 + i as u32, i as f32).unwrap();
        assert_eq!(id(&mesh), before);
    }
    assert_eq!(mesh.umbrella.indices, indices);
}

/// The plugin swaps these buffers with the mesh asset's each frame, so a frame must not
/// depend on what they held: every position and normal is rewritten.
#[test]
fn a_frame_rewrites_every_vertex() {
    let sp = Species::aurelia();
    let slice = SliceOutline::contracted(&sp, 25, 14, 0.4);
    let mut mesh = build(&slice.view(), &sp, 3, 0.0);
    let fresh = build(&slice.view(), &sp, 3, 0.5);
    for buf in [&mut mesh.umbrella, &mut mesh.tentacles] {
        buf.positions.fill([f32::NAN; 3]);
        buf.normals.fill([f32::NAN; 3]);
    }
    build_into(&mut mesh, &slice.view(), &sp, 3, 0.5).unwrap();
    assert_eq!(mesh.umbrella, fresh.umbrella);
    assert_eq!(mesh.tentacles, fresh.tentacles);
}

#[test]
fn tentacles_hang_from_the_aperture() {
    let sp = plain(&Species::aurelia());
    let slice = SliceOutline::contracted(&sp, 25, 10, 0.7);
    let mesh = build(&slice.view(), &sp, 0, 0.0);
    let sides = sp.tentacle_sides as usize;
    let per = Resolution::of(&sp).tentacles.vertex_count() / sp.tentacle_count as usize;
    // Tentacle 0 follows the right chain, tentacle count/2 the left one, ring by ring.
    for (t, chain) in [
        (0, &slice.tentacles[1]),
        (sp.tentacle_count as usize / 2, &slice.tentacles[0]),
    ] {
        let root_ring = &mesh.tentacles.positions[t * per + 1..][..sides];
        let centre = root_ring.iter().map(|p| v3(*p)).sum::<Vec3>() / sides as f32;
        assert!(
            centre.distance(chain[0].extend(0.0)) < 1e-6,
            "tentacle {t} root {centre}"
        );
        let tip = v3(mesh.tentacles.positions[(t + 1) * per - 1]);
        let end = chain[chain.len() - 1].extend(0.0);
        assert!(
            tip.distance(end) < 1.01 * sp.tentacle_radius,
            "tentacle {t} tip {tip}"
        );
    }
}

#[test]
fn a_fringe_keeps_its_roots_and_varies_in_length() {
    let spread = 0.5;
    let sp = Species {
        tentacle_length_spread: spread,
        ..plain(&Species::aurelia())
    };
    let slice = SliceOutline::contracted(&sp, 25, 10, 0.7);
    let layout = Resolution::of(&sp).tentacles;
    let centre = |mesh: &JellyMesh, t: usize, m: usize| {
        (0..layout.sides)
            .map(|i| v3(mesh.tentacles.positions[layout.ring(t, m, i)]))
            .sum::<Vec3>()
            / layout.sides as f32
    };
    let length = |mesh: &JellyMesh, t: usize| {
        (1..layout.points)
            .map(|m| centre(mesh, t, m).distance(centre(mesh, t, m - 1)))
            .sum::<f32>()
    };
    let even = build(&slice.view(), &plain(&sp), 3, 0.0);
    let fringe = build(&slice.view(), &sp, 3, 0.0);
    let reaches: Vec<f32> = (0..layout.count)
        .map(|t| {
            assert!(
                centre(&fringe, t, 0).distance(centre(&even, t, 0)) < 1e-6,
                "tentacle {t} hangs from the margin"
            );
            length(&fringe, t) / length(&even, t)
        })
        .collect();
    let (least, most) = reaches
        .iter()
        .fold((f32::MAX, f32::MIN), |(a, b), &r| (a.min(r), b.max(r)));
    // Each is drawn between 1 − spread and all of the chain, and they differ.
    assert!(
        least >= 1.0 - spread - 1e-3 && most <= 1.0 + 1e-3,
        "{least}..{most}"
    );
    assert!(most - least > 0.8 * spread, "{least}..{most}");
    // An individual's own: the same seed, the same fringe; another seed, another one.
    let again = build(&slice.view(), &sp, 3, 1.0);
    let other = build(&slice.view(), &sp, 4, 0.0);
    let tip = |mesh: &JellyMesh| centre(mesh, 5, layout.points - 1);
    assert!(tip(&again).distance(tip(&fringe)) < 1e-6);
    assert!(
        (0..layout.count).any(|t| (length(&other, t) / length(&even, t) - reaches[t]).abs() > 0.1)
    );
}

/// Reference normals: area-weighted sums of the triangle normals, seam twins welded.
fn area_weighted_normals(buf: &SurfaceBuffers) -> Vec<Vec3> {
    let mut id = HashMap::new();
    let weld: Vec<usize> = buf
        .positions
        .iter()
        .map(|p| {
            let next = id.len();
            *id.entry(p.map(f32::to_bits)).or_insert(next)
        })
        .collect();
    let mut sum = vec![Vec3::ZERO; id.len()];
    for tri in buf.indices.chunks_exact(3) {
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize);
        let [pa, pb, pc] = [a, b, c].map(|i| v3(buf.positions[i]));
        let n = (pb - pa).cross(pc - pa);
        for i in [a, b, c] {
            sum[weld[i]] += n;
        }
    }
    weld.iter().map(|&w| sum[w].normalize()).collect()
}

#[test]
fn grid_normals_match_area_weighted_normals() {
    let sp = Species::aurelia();
    for species in [plain(&sp), sp.clone()] {
        let slice = SliceOutline::contracted(&sp, 25, 10, 0.8);
        let mesh = build(&slice.view(), &species, 2, 0.5);
        let reference = area_weighted_normals(&mesh.umbrella);
        let cosines: Vec<f32> = mesh
            .umbrella
            .normals
            .iter()
            .zip(&reference)
            .map(|(n, r)| v3(*n).dot(*r))
            .collect();
        let worst = cosines.iter().cloned().fold(1.0, f32::min);
        let mean = cosines.iter().sum::<f32>() / cosines.len() as f32;
        // Within 20 degrees everywhere (the worst is on the rim, where the surface folds
        // over and noise makes kinks), apexes included, and much closer on average.
        assert!(worst > 0.94, "worst cosine {worst}");
        assert!(mean > 0.999, "mean cosine {mean}");
    }
}

#[test]
fn the_vertex_budget_counts_what_the_mesh_builds() {
    use crate::species::limits::mesh_vertices;
    for (rings, segments, count, sides, length) in [
        (24, 48, 48, 5, 0.03),
        (2, 3, 0, 3, 0.03),
        (64, 128, 256, 12, 0.05),
        (24, 48, 16, 5, 0.0),
    ] {
        let sp = Species {
            mesh_rings: rings,
            mesh_segments: segments,
            tentacle_count: count,
            tentacle_sides: sides,
            tentacle_length: length,
            ..Species::aurelia()
        };
        let rest = SliceOutline::rest(&sp, 25, if length > 0.0 { 10 } else { 0 });
        let mesh = build(&rest.view(), &sp, 1, 0.0);
        let built = mesh.umbrella.vertex_count() + mesh.tentacles.vertex_count();
        assert_eq!(
            built,
            mesh_vertices(&sp),
            "{rings} rings, {count} tentacles"
        );
    }
}
