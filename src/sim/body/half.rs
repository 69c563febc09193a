//! A mirror-symmetric body solved on its half (every r–z body, and a planar one held
//! symmetric): which of its elements the solve counts, and how often. An element wholly
//! past the axis is the mirror image of one wholly before it, which adds exactly what it
//! adds; so the one past the axis is left out and its image counts twice (its stiffness
//! doubled: a power of two, exact). Elements on or across the axis (the apex's, every
//! hoop and muscle) count once, as does every element of a body free to tilt.

use super::Body;

/// Where a point lies against the axis.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    /// On the axis (the apex), or any point of a body free to tilt.
    Alone,
    /// Before the axis, with a partner past it that is its mirror image.
    Twinned,
    /// Past the axis: its partner's mirror image.
    Mirrored,
}

/// How many times each element counts in the solve, list by list in the body's order
/// (0, 1 or 2); empty lists count every element once.
#[derive(Clone, Debug, Default)]
pub(crate) struct Weights {
    pub(super) springs: Vec<f32>,
    pub(super) muscles: Vec<f32>,
    pub(super) hinges: Vec<f32>,
    pub(super) hoop_bends: Vec<f32>,
}

impl Weights {
    /// The weights of `body`'s elements from its points' partners past the axis (none for
    /// a body free to tilt: every element once).
    pub(super) fn of(body: &Body) -> Self {
        let partners = body.mirror_partners();
        if partners.is_empty() {
            return Self::default();
        }
        let mut sides = vec![Side::Alone; partners.len()];
        for (j, partner) in partners.iter().enumerate() {
            if let Some(i) = *partner {
                sides[j] = Side::Mirrored;
                sides[i] = Side::Twinned;
            }
        }
        let weight = |idx: &[usize]| {
            let all = |side: Side| idx.iter().all(|&i| sides.get(i) == Some(&side));
            if all(Side::Mirrored) {
                0.0
            } else if all(Side::Twinned) {
                2.0
            } else {
                1.0
            }
        };
        Self {
            springs: body.springs.iter().map(|s| weight(&[s.a, s.b])).collect(),
            muscles: body.muscles.iter().map(|m| weight(&[m.a, m.b])).collect(),
            hinges: body
                .hinges
                .iter()
                .map(|h| weight(&[h.a, h.b, h.c]))
                .collect(),
            hoop_bends: body
                .hoop_bends
                .iter()
                .map(|h| weight(&[h.a, h.b]))
                .collect(),
        }
    }

    /// Every weight, list after list.
    #[cfg(test)]
    pub(super) fn all(&self) -> impl Iterator<Item = f32> + '_ {
        let lists = [&self.springs, &self.muscles, &self.hinges, &self.hoop_bends];
        lists.into_iter().flatten().copied()
    }
}

/// The elements of `list` the solve counts, each with its weight (`weights`, or 1 where
/// it has none).
pub(super) fn counted<'a, T>(
    list: &'a [T],
    weights: &'a [f32],
) -> impl Iterator<Item = (&'a T, f32)> + 'a {
    let weights = weights.iter().copied().chain(std::iter::repeat(1.0));
    list.iter().zip(weights).filter(|(_, w)| *w > 0.0)
}
