//! GenDPDE integrators: the reversible velocity-Verlet step with the papers' pairwise
//! work split, the Shardlow (eSSA) pair sweep with its heat-flow models, and the heat
//! reservoir. Equation numbers: 2019 PCCP paper unless stated.

pub mod classic;
pub mod error;
pub mod heat;
pub mod many_body;
pub mod pair_update;
pub mod physics;
pub mod rng;
pub mod settings;
pub mod sweep;
pub mod system;
pub mod verlet;

pub use classic::{ClassicDpd, Integration, PairForce, ShardlowDpd};
pub use error::StepError;
pub use heat::HeatModel;
pub use physics::{GenDpde, Physics, SetupError};
pub use settings::{Dissipation, RebuildPolicy, Reservoir, Settings};
pub use system::{Snapshot, System};
