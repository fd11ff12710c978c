//! GenDPDE integrators: the reversible velocity-Verlet step with the papers' pairwise
//! work split, the Shardlow (eSSA) pair sweep with its heat-flow models, and the heat
//! reservoir. Equation numbers: 2019 PCCP paper unless stated.

pub mod heat;
pub mod pair_update;
pub mod rng;
