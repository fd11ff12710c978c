//! Spatial decomposition for GenDPDE: the periodic box, the SoA particle store, the
//! global cell grid with its 8-colour block ownership, neighbour lists and the
//! communication layer (`Comm`) through which even a single rank sees its ghosts.

pub mod cells;
pub mod comm;
pub mod domain;
pub mod fields;
pub mod neighbor;
pub mod pair_search;
pub mod particles;
pub mod sweep_pairs;

pub use cells::{CellGrid, GridError};
pub use comm::{exact_column_sums, exact_sums, Comm, Local, ProcGrid, Transport};
pub use domain::Domain;
pub use fields::Fields;
pub use neighbor::NeighborList;
pub use pair_search::{build_lists, ListRequest};
pub use particles::{stage, Column, FieldInfo, FieldReader, Particles, RecordColumn, SavedByTag, FIELDS};
pub use sweep_pairs::SweepPairs;

/// Three-component vector of the particle store.
pub type Vec3 = [f64; 3];

#[inline(always)]
pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
