//! One full regeneration of a jellyfish's surfaces (umbrella + tentacles) from its slice, at
//! the default (Aurelia) resolution. Prints the vertex and triangle counts it measured.

use bevy_jellyfish::Species;
use bevy_jellyfish::shape::{JellyMesh, SliceOutline, build_into};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn regenerate(c: &mut Criterion) {
    let aurelia = Species::aurelia();
    let plain = Species {
        structural_scale: 0.0,
        compression_scale: 0.0,
        unstructured_scale: 0.0,
        ..aurelia.clone()
    };
    let slice = SliceOutline::contracted(&aurelia, 25, 12, 0.5);
    let view = slice.view();
    let mut mesh = JellyMesh::from_slice(&view, &aurelia, 1, 0.0).expect("valid slice");
    println!(
        "shape: aurelia, {} rings x {} segments, {} tentacles x {} sides: umbrella {} vertices \
         {} triangles, tentacles {} vertices {} triangles",
        aurelia.mesh_rings,
        aurelia.mesh_segments,
        aurelia.tentacle_count,
        aurelia.tentacle_sides,
        mesh.umbrella.vertex_count(),
        mesh.umbrella.triangle_count(),
        mesh.tentacles.vertex_count(),
        mesh.tentacles.triangle_count(),
    );
    for (name, species) in [
        ("shape/regenerate_all_variation", &aurelia),
        ("shape/regenerate_plain", &plain),
    ] {
        let mut time = 0.0;
        c.bench_function(name, |b| {
            b.iter(|| {
                time += 1.0 / 60.0;
                build_into(&mut mesh, black_box(&view), species, 1, time).expect("valid slice");
            })
        });
    }
    black_box(&mesh);
}

criterion_group!(benches, regenerate);
criterion_main!(benches);
