//! One full regeneration of a jellyfish's surfaces (umbrella + tentacles) from its slice, at
//! the default (Aurelia) resolution, against packing its shape for a template mesh (what
//! the CPU does per jellyfish when the GPU builds the surface). Prints the vertex and
//! triangle counts and the block's size.

use bevy_jellyfish::Species;
use bevy_jellyfish::shape::packed::{ShapePacker, block_len};
use bevy_jellyfish::shape::{JellyMesh, Resolution, SliceOutline, build_into};
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
    let res = Resolution::of(&aurelia);
    println!(
        "shape: the packed block is {} bytes",
        block_len(&res) * std::mem::size_of::<f32>()
    );
    let (mut packer, mut block, mut time) = (ShapePacker::default(), Vec::new(), 0.0);
    c.bench_function("shape/pack_for_template", |b| {
        b.iter(|| {
            time += 1.0 / 60.0;
            block.clear();
            packer
                .pack(black_box(&view), &aurelia, res, 1, time, &mut block)
                .expect("valid slice");
        })
    });
    black_box((&mesh, &block));
}

criterion_group!(benches, regenerate);
criterion_main!(benches);
