use super::*;
use crate::shape::{JellyMesh, SliceOutline};

/// The shader's arithmetic (mirrored here) rebuilds every vertex of the CPU mesh: the
/// same positions to a micrometre (the CPU blends its noise between time knots, the
/// shader evaluates it at the time itself) and the same normals.
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
                    Vec3::new(0.002 * m, 0.0001 * m * g as f32, -0.001 * m * m / 6.0)
                })
                .collect();
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
            let b = Block(&block);
            let tolerance = 1e-6 + 2e-3 * b.0[H_UNSTRUCTURED];
            for (name, buffers, vertex) in [
                (
                    "umbrella",
                    &mesh.umbrella,
                    umbrella_vertex as fn(Block, usize) -> _,
                ),
                ("tentacles", &mesh.tentacles, tentacle_vertex),
            ] {
                let mut worst = (0.0f32, 1.0f32);
                for i in 0..buffers.vertex_count() {
                    let (p, n) = vertex(b, i);
                    let (cpu_p, cpu_n) = (
                        Vec3::from_array(buffers.positions[i]),
                        Vec3::from_array(buffers.normals[i]),
                    );
                    worst.0 = worst.0.max(p.distance(cpu_p));
                    worst.1 = worst.1.min(n.dot(cpu_n));
                }
                assert!(
                    worst.0 < tolerance && worst.1 > 0.999,
                    "{name} of {} at {time} s: worst position error {:.2e} m, worst \
                     normal cosine {}",
                    species.name,
                    worst.0,
                    worst.1
                );
            }
        }
    }
}

fn sarsia_like() -> Species {
    Species {
        name: "tall, four tentacles".into(),
        height: 0.045,
        diameter: 0.03,
        tentacle_count: 4,
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
