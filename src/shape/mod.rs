//! Slice to 3D surface (paper sections 3.4–3.5).
