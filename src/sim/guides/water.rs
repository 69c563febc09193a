//! The water along a guide, read where it matters: the water that moves a fringe (a
//! tank's current, a stir) varies over cells wider than a tentacle, so each guide reads it
//! at its root, middle and tip and takes it straight between.

use super::GUIDE_NODES;
use glam::Vec3;

/// The water at every node of guides drawn at `reference + offsets` (`guides ×
/// GUIDE_NODES` points), `read(point)` called three times a guide; zeros where the two do
/// not match.
pub fn read_along(
    reference: &[Vec3],
    offsets: &[Vec3],
    read: impl Fn(Vec3) -> Vec3,
    out: &mut Vec<Vec3>,
) {
    const MID: usize = (GUIDE_NODES - 1) / 2;
    out.clear();
    if offsets.len() != reference.len() {
        out.resize(reference.len(), Vec3::ZERO);
        return;
    }
    for (q, d) in reference
        .chunks(GUIDE_NODES)
        .zip(offsets.chunks(GUIDE_NODES))
    {
        let at = |m: usize| read(q[m] + d[m]);
        let (root, mid, tip) = (at(0), at(MID), at(GUIDE_NODES - 1));
        out.extend((0..GUIDE_NODES).map(|m| match m <= MID {
            true => root.lerp(mid, m as f32 / MID as f32),
            false => mid.lerp(tip, (m - MID) as f32 / (GUIDE_NODES - 1 - MID) as f32),
        }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_field_is_read_exactly_at_every_node() {
        let reference: Vec<Vec3> = (0..2 * GUIDE_NODES)
            .map(|k| Vec3::new(k as f32 * 0.3, -((k % GUIDE_NODES) as f32), 1.0))
            .collect();
        let offsets = vec![Vec3::new(0.1, 0.0, -0.2); reference.len()];
        let field = |p: Vec3| Vec3::new(2.0 * p.y, p.x - p.z, 0.5);
        let mut out = Vec::new();
        read_along(&reference, &offsets, field, &mut out);
        for (k, w) in out.iter().enumerate() {
            let exact = field(reference[k] + offsets[k]);
            assert!(w.distance(exact) < 1e-5, "node {k}: {w} against {exact}");
        }
        // Mismatched lengths read nothing.
        read_along(&reference, &offsets[1..], field, &mut out);
        assert_eq!(out, vec![Vec3::ZERO; reference.len()]);
    }
}
