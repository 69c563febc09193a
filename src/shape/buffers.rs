//! Flat vertex buffers in the layout a Bevy `Mesh` takes, rewritten in place each frame.

/// One surface: positions and normals (m, unit), UVs, and a triangle list with
/// counter-clockwise (outward) winding.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceBuffers {
    /// Vertex positions, metres in the jellyfish's frame.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals.
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates: u around the axis, v from apex (or root) to margin (or tip).
    pub uvs: Vec<[f32; 2]>,
    /// What the tissue material reads ([`tissue`](super::tissue)): the tissue's thickness
    /// here relative to its reference (the mesoglea at the apex; a tube at its root), and
    /// the glow band's share.
    pub tissue: Vec<[f32; 2]>,
    /// Triangles, three indices each.
    pub indices: Vec<u32>,
}

impl SurfaceBuffers {
    /// Vertices in the buffers.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Triangles in the buffers.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Sizes the vertex buffers for a new topology and empties the index list. Only called
    /// when the resolution changes; frames after that overwrite in place.
    pub(crate) fn reset(&mut self, vertices: usize) {
        self.positions.clear();
        self.positions.resize(vertices, [0.0; 3]);
        self.normals.clear();
        self.normals.resize(vertices, [0.0, 1.0, 0.0]);
        self.uvs.clear();
        self.uvs.resize(vertices, [0.0; 2]);
        self.tissue.clear();
        self.tissue.resize(vertices, [1.0, 0.0]);
        self.indices.clear();
    }

    /// The quad `a b / c d` as triangles `(a, b, c)`, `(b, d, c)`, both facing along
    /// `(b − a) × (c − a)`.
    pub(crate) fn quad(&mut self, a: usize, b: usize, c: usize, d: usize) {
        self.indices.extend([a, b, c, b, d, c].map(|i| i as u32));
    }

    pub(crate) fn triangle(&mut self, a: usize, b: usize, c: usize) {
        self.indices.extend([a, b, c].map(|i| i as u32));
    }
}
