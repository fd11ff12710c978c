//! Verlet neighbour lists, rebuilt when a particle has moved more than half the skin
//! (the decision is the integrator's).
//!
//! The list holds each pair with an owned particle once, in the order of the half pass
//! of [`crate::pair_search`]. A loop over it that adds a pair term to i and its mirror
//! (f_ji = -f_ij, the same bits) to j, for whichever of them is owned, gives every owned
//! particle its sum over all neighbours in an order no decomposition can change, at
//! half the pair evaluations of a full list. Pairs of an owned particle and a ghost are
//! evaluated on both ranks (as LAMMPS's newton off), so no force travels back.

#[derive(Clone, Debug, Default)]
pub struct NeighborList {
    /// List radius: interaction cutoff plus skin.
    pub radius: f64,
    /// Pairs (i, j) closer than `radius` with i or j owned.
    pub pairs: Vec<[u32; 2]>,
}
