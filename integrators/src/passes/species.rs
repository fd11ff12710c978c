//! One EOS per particle type (mixtures of particles with different C_V, 2021 PRE sec.
//! III.C and validation scene V5), or one for all types.
//!
//! The EOS trait takes (u, n) and no particle index; the per-type choice happens here,
//! where the passes read the particle's type.

use gendpde_potentials::Eos;

/// The EOS of each particle type (index type - 1), or a single EOS for every type.
#[derive(Clone, Debug)]
pub struct Species<E> {
    per_type: Vec<E>,
}

impl<E: Eos> Species<E> {
    /// `per_type[t - 1]` is the EOS of type t; a single entry serves all types. All must
    /// share k_B. None if `per_type` is empty.
    pub fn new(per_type: Vec<E>) -> Option<Self> {
        (!per_type.is_empty()).then_some(Self { per_type })
    }

    /// The EOS of particles of type `kind` (1-based; the caller checked the range with
    /// [`Species::covers`]).
    #[inline(always)]
    pub fn of(&self, kind: u32) -> &E {
        if self.per_type.len() == 1 { &self.per_type[0] } else { &self.per_type[kind as usize - 1] }
    }

    /// Whether every type up to `max_kind` has an EOS.
    pub fn covers(&self, max_kind: u32) -> bool {
        self.per_type.len() == 1 || (max_kind as usize) <= self.per_type.len()
    }

    pub fn kb(&self) -> f64 {
        self.per_type[0].kb()
    }

    pub fn density_dependent(&self) -> bool {
        self.per_type.iter().any(Eos::density_dependent)
    }
}
