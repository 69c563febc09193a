use super::*;
use crate::shape::{JellyMesh, SliceOutline};

/// The shader's arithmetic (mirrored here) rebuilds every vertex of the CPU mesh: the
/// same positions to a micrometre (the CPU blends its noise between time knots, the
/// shader evaluates it at the time itself), the same normals and the same tissue.
#[test]
fn packed_block_rebuilds_the_cpu_mesh() {
    for (species, seed, time) in [
        (Species::aurelia(), 3, 0.4),
        (sarsia_like(), 11, 17.0),
        (Species::aurelia(), 12345, 250.0),
    ] {
        for contraction in [0.0, 0.7] {
            let mut slice = SliceOutline::contracted(&species, 31, 12, contraction);
            // A fringe swept sideways and back by its guides, each its own way (a
            // guide never moves its root).
            slice.trail = (0..species.guide_count() * GUIDE_NODES)
                .map(|k| {
                    let (g, m) = (k / GUIDE_NODES, (k % GUIDE_NODES) as f32);
                    halves(Vec3::new(
                        0.002 * m,
                        0.0001 * m * g as f32,
                        -0.001 * m * m / 6.0,
                    ))
                })
                .collect();
            // The oral tubes too, the manubrium's tip carrying the arms' mouth.
            slice.oral_trail = (0..species.oral_guide_count() * GUIDE_NODES)
                .map(|k| {
                    let (t, m) = (k / GUIDE_NODES, (k % GUIDE_NODES) as f32);
                    halves(Vec3::new(-0.001 * m, 0.0003 * m * t as f32, 0.0005 * m))
                })
                .collect();
            assert!(!slice.oral_trail.is_empty());
            let view = slice.view();
            let mesh = JellyMesh::from_slice(&view, &species, seed, time).unwrap();
            let mut block = Vec::new();
            ShapePacker::default()
                .pack(
                    &view,
                    &species,
                    Resolution::of(&species),
                    seed,
                    time,
                    &mut block,
                )
                .unwrap();
            assert_eq!(block.len(), block_len(&Resolution::of(&species)));
            let b = Block::own(&block);
            let tolerance = 1e-6 + 2e-3 * b.individual(H_UNSTRUCTURED);
            for (name, buffers, vertex) in [
                (
                    "umbrella",
                    &mesh.umbrella,
                    umbrella_vertex as fn(Block, usize) -> _,
                ),
                ("tentacles", &mesh.tentacles, tentacle_vertex),
            ] {
                let mut worst = (0.0f32, 1.0f32, 0.0f32);
                for i in 0..buffers.vertex_count() {
                    let gpu = vertex(b, i);
                    let (cpu_p, cpu_n, cpu_t) = (
                        Vec3::from_array(buffers.positions[i]),
                        Vec3::from_array(buffers.normals[i]),
                        Vec2::from_array(buffers.tissue[i]),
                    );
                    worst.0 = worst.0.max(gpu.position.distance(cpu_p));
                    worst.1 = worst.1.min(gpu.normal.dot(cpu_n));
                    worst.2 = worst.2.max((gpu.tissue - cpu_t).abs().max_element());
                }
                assert!(
                    worst.0 < tolerance && worst.1 > 0.999 && worst.2 < 1e-4,
                    "{name} of {} at {time} s: worst position error {:.2e} m, worst \
                     normal cosine {}, worst tissue error {:.2e}",
                    species.name,
                    worst.0,
                    worst.1,
                    worst.2
                );
            }
        }
    }
}

/// The oral trail moves each tube's centreline by its own guide: a tip moves by exactly
/// that much on both paths.
#[test]
fn oral_guides_move_their_tubes() {
    let species = Species::aurelia();
    let tubes = species.oral_guide_count();
    assert_eq!(tubes, 5, "the manubrium and four arms");
    let slice = SliceOutline::contracted(&species, 31, 12, 0.3);
    let mut moved = slice.clone();
    let tip = |t: usize| Vec3::new(0.001, -0.002, 0.003 * t as f32);
    moved.oral_trail = (0..tubes * GUIDE_NODES)
        .map(|k| {
            let (t, m) = (k / GUIDE_NODES, k % GUIDE_NODES);
            halves(tip(t) * m as f32 / (GUIDE_NODES - 1) as f32)
        })
        .collect();
    let res = Resolution::of(&species);
    let l = res.oral;
    let first = res.tentacles.vertex_count();
    let build = |s: &SliceOutline| JellyMesh::from_slice(&s.view(), &species, 7, 1.0).unwrap();
    let (still, swept) = (build(&slice), build(&moved));
    let pack = |s: &SliceOutline| {
        let mut block = Vec::new();
        let mut packer = ShapePacker::default();
        packer
            .pack(&s.view(), &species, res, 7, 1.0, &mut block)
            .unwrap();
        block
    };
    let swept_block = pack(&moved);
    for t in 0..tubes {
        let expected = halves(tip(t));
        let v = first + l.tip(t);
        let shift = Vec3::from_array(swept.tentacles.positions[v])
            - Vec3::from_array(still.tentacles.positions[v]);
        // The tip cap sits off the centre along the tangent, which the trail tilts a little.
        let thick = species.oral_arm_width;
        assert!(
            shift.distance(expected) < 0.25 * thick,
            "tube {t}: tip moved {shift} against {expected}"
        );
        let gpu = tentacle_vertex(Block::own(&swept_block), v).position;
        let cpu = Vec3::from_array(swept.tentacles.positions[v]);
        assert!(
            gpu.distance(cpu) < 1e-5,
            "tube {t}: packed {gpu} against CPU {cpu}"
        );
    }
}

/// A block carries only the trails that move something: a view whose guides all sit
/// where the slice draws them (still water), or that does not follow its oral arms (a far
/// jellyfish), packs none of them, and its vertices are the CPU mesh's all the same.
#[test]
fn a_block_leaves_out_trails_that_move_nothing() {
    let species = Species::aurelia();
    let res = Resolution::of(&species);
    let (guides, tubes) = (species.guide_count(), species.oral_guide_count());
    let mut slice = SliceOutline::contracted(&species, 31, 12, 0.5);
    let pack = |s: &SliceOutline| {
        let mut block = Vec::new();
        ShapePacker::default()
            .pack(&s.view(), &species, res, 7, 1.0, &mut block)
            .unwrap();
        block
    };
    let full = block_len(&res);
    // Followed, but nothing off the slice's drawing: no trail at all.
    slice.trail = vec![Vec3::ZERO; guides * GUIDE_NODES];
    slice.oral_trail = vec![Vec3::ZERO; tubes * GUIDE_NODES];
    let still = slice.clone();
    // The fringe trailing, the oral arms not followed: the fringe's trail alone.
    let mut far = slice;
    far.trail[GUIDE_NODES - 1] = Vec3::new(0.002, 0.0, 0.001);
    far.oral_trail.clear();
    for (s, carried, name) in [(&still, (0, 0), "still"), (&far, (guides, 0), "far")] {
        let block = pack(s);
        let b = Block::own(&block);
        assert_eq!(
            (b.count(H_GUIDES), b.count(H_ORAL_GUIDES)),
            carried,
            "{name}"
        );
        assert_eq!(
            block.len(),
            full - (guides - carried.0 + tubes) * TRAIL,
            "{name}"
        );
        let mesh = JellyMesh::from_slice(&s.view(), &species, 7, 1.0).unwrap();
        let worst = worst_tentacle_vertex(b, &mesh);
        assert!(
            worst < 1e-5,
            "{name}: a tentacle vertex {worst:.2e} m off the CPU's"
        );
    }
}

/// How far the block's tentacle vertices lie from the CPU mesh's, at worst (m).
fn worst_tentacle_vertex(b: Block, mesh: &JellyMesh) -> f32 {
    (0..mesh.tentacles.vertex_count())
        .map(|i| {
            let cpu = Vec3::from_array(mesh.tentacles.positions[i]);
            tentacle_vertex(b, i).position.distance(cpu)
        })
        .fold(0.0f32, f32::max)
}

/// `v` as the packed shape carries a trail: each component rounded to a half.
fn halves(v: Vec3) -> Vec3 {
    v.to_array().map(|x| half::f16::from_f32(x).to_f32()).into()
}

fn sarsia_like() -> Species {
    Species {
        name: "tall, four tentacles".into(),
        height: 0.045,
        diameter: 0.03,
        tentacle_count: 4,
        // Arms that reach out of its deep cavity, so that they have guides.
        oral_arm_length: 0.06,
        structural_abs: true,
        ..Species::aurelia()
    }
}

#[test]
fn a_block_is_a_few_kilobytes() {
    let res = Resolution::of(&Species::aurelia());
    let bytes = block_len(&res) * 4;
    assert!(bytes < 3072, "{bytes} bytes");
    // Against the rebuilt mesh's positions and normals alone.
    let vertices = res.umbrella_vertices() + res.tentacle_vertices();
    assert!(
        bytes * 50 < vertices * 24,
        "{bytes} bytes for {vertices} vertices"
    );
}

/// A far jellyfish's instance (its own words and its thinned trail) drawing the frame
/// its recorded step shares: the umbrella, bit for bit, of the block packed for it alone,
/// whichever individual, noise time and trails packed the shared frame; the tentacles of
/// the CPU mesh drawn from the same thinned trail; and 64 bytes at most.
#[test]
fn a_shared_frame_with_its_own_words_is_its_own_block() {
    let species = Species::aequorea();
    let res = Resolution::of(&species);
    let mut slice = SliceOutline::contracted(&species, 31, 12, 0.4);
    let trail = |scale: f32| -> Vec<Vec3> {
        (0..species.guide_count() * GUIDE_NODES)
            .map(|k| {
                let (g, m) = ((k / GUIDE_NODES) as f32, (k % GUIDE_NODES) as f32);
                halves(Vec3::new(
                    scale * m,
                    0.1 * scale * g,
                    -0.5 * scale * m * m / 6.0,
                ))
            })
            .collect()
    };
    // A far jellyfish does not follow its oral arms.
    slice.oral_trail.clear();
    let mut packer = ShapePacker::default();
    // The frame packed from an individual's view, trailing.
    slice.trail = trail(0.002);
    let mut frame = Vec::new();
    pack_frame(&mut packer, &slice.view(), &species, res, &mut frame).unwrap();
    assert!(
        instance_len(&res) * 4 <= 64,
        "{} values",
        instance_len(&res)
    );
    let mut thin = Vec::new();
    for (seed, time, scale) in [(1, 0.0, 0.0), (7, 3.25, 0.001), (99, 400.0, 0.003)] {
        slice.trail = trail(scale);
        let mut view = slice.view();
        let mut own = Vec::new();
        packer
            .pack(&view, &species, res, seed, time, &mut own)
            .unwrap();
        view.trail = view.trail.thin_into(far_guides(&res), &mut thin);
        assert_eq!(view.trail.guides(), FAR_GUIDES.min(species.guide_count()));
        let mut instance = Vec::new();
        pack_instance(&species, &res, seed, time, view.trail, &mut instance);
        assert_eq!(instance.len(), instance_len(&res));
        // Another individual's instance over the same trail, its words written again (as
        // a far jellyfish whose trail has not changed since): this one, bit for bit.
        let mut rewritten = Vec::new();
        pack_instance(
            &species,
            &res,
            seed ^ 0x5a5a,
            time + 1.5,
            view.trail,
            &mut rewritten,
        );
        assert_ne!(rewritten[..INSTANCE], instance[..INSTANCE]);
        write_instance_words(&species, seed, time, &mut rewritten);
        let words = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            words(&rewritten),
            words(&instance),
            "seed {seed} at {time} s"
        );
        let (far, own) = (Block::far(&instance, &frame), Block::own(&own));
        let bits = |v: Vertex| {
            [v.position, v.normal]
                .map(|p| p.to_array().map(f32::to_bits))
                .concat()
        };
        for i in 0..res.umbrella_vertices() {
            assert_eq!(
                bits(umbrella_vertex(far, i)),
                bits(umbrella_vertex(own, i)),
                "umbrella vertex {i}, seed {seed} at {time} s"
            );
        }
        let mesh = JellyMesh::from_slice(&view, &species, seed, time).unwrap();
        assert!(mesh.tentacles.vertex_count() > 0);
        let worst = worst_tentacle_vertex(far, &mesh);
        assert!(
            worst < 1e-5,
            "seed {seed} at {time} s: a tentacle vertex {worst:.2e} m off the CPU's"
        );
    }
}

/// A trail rounded to halves is each offset's components rounded one by one, however many
/// offsets (more than one batch of the conversion), rounding again changes nothing, and
/// packing the rounded trail carries it exactly: the CPU path draws what the templates
/// read back.
#[test]
fn a_rounded_trail_is_what_a_packed_shape_carries() {
    let offsets: Vec<Vec3> = (0..37)
        .map(|i| {
            let f = i as f32;
            Vec3::new(
                0.013 * (f * 0.7).sin(),
                -0.002 * f,
                1e-3 * (f * 1.3).cos() + 1e-7,
            )
        })
        .collect();
    let mut rounded = offsets.clone();
    round_to_halves(&mut rounded);
    for (a, b) in offsets.iter().zip(&rounded) {
        assert_eq!(halves(*a), *b);
    }
    assert!(offsets.iter().zip(&rounded).any(|(a, b)| a != b));
    let mut again = rounded.clone();
    round_to_halves(&mut again);
    assert_eq!(again, rounded);
    let mut packed = Vec::new();
    write_halves(&rounded[1..GUIDE_NODES], &mut packed);
    let unpacked: Vec<f32> = packed
        .iter()
        .flat_map(|v| {
            let bits = v.to_bits();
            [bits as u16, (bits >> 16) as u16].map(|h| half::f16::from_bits(h).to_f32())
        })
        .collect();
    let carried: Vec<f32> = rounded[1..GUIDE_NODES]
        .iter()
        .flat_map(|d| d.to_array())
        .collect();
    assert_eq!(unpacked[..carried.len()], carried[..]);
}
