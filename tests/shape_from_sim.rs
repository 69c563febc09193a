//! The rendering model fed by the simulation rather than by a hand-made outline.

use bevy_jellyfish::shape::{JellyMesh, build_into};
use bevy_jellyfish::{SliceSim, Species};

#[test]
fn every_frame_of_a_simulated_stroke_meshes_cleanly() {
    let species = Species {
        grid_resolution: 64,
        ..Species::aurelia()
    };
    let mut sim = SliceSim::new(&species).unwrap();
    let mut mesh = JellyMesh::new();
    let mut first = None;
    let mut moved = 0.0f32;
    let frames = (species.period() * 30.0) as usize;
    for frame in 0..frames {
        sim.advance(1.0 / 30.0);
        build_into(&mut mesh, &sim.view(), &species, 7, sim.time())
            .expect("a simulated slice is valid input");
        let finite = |b: &[[f32; 3]]| b.iter().flatten().all(|x| x.is_finite());
        assert!(
            finite(&mesh.umbrella.positions) && finite(&mesh.umbrella.normals),
            "frame {frame}"
        );
        assert!(finite(&mesh.tentacles.positions), "frame {frame}");
        assert!(mesh.umbrella.vertex_count() > 0 && mesh.tentacles.vertex_count() > 0);
        // The bell changes shape over a stroke (and is back near its rest at the end).
        let first = first.get_or_insert_with(|| mesh.umbrella.positions.clone());
        let furthest = first
            .iter()
            .zip(&mesh.umbrella.positions)
            .map(|(a, b)| (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0f32, f32::max))
            .fold(0.0f32, f32::max);
        moved = moved.max(furthest);
    }
    assert!(
        moved > 0.1 * species.diameter,
        "largest vertex move {moved} m"
    );
}
