//! GenDPDE integrators: the reversible velocity-Verlet step with the papers' pairwise
//! work split or at fixed entropy, the Shardlow (eSSA) pair sweep with its heat-flow
//! models, the heat reservoir, and the argon paper's velocity Verlet + Euler scheme.
//! Equation numbers: 2019 PCCP paper unless stated.

pub mod barostat;
pub mod barostat_state;
pub mod classic;
pub mod edpd;
pub mod error;
pub mod heat;
pub mod isentropic;
pub mod many_body;
pub mod noise;
pub mod pair_update;
pub mod physics;
pub mod rng;
pub mod sdpd;
pub mod sdpd_taitwater;
pub mod settings;
pub mod simd;
pub mod species;
pub mod sweep;
pub mod system;
pub mod tables;
pub mod type_table;
pub mod verlet;
pub mod voronoi;
pub mod vv_euler;

pub use barostat::{Couple, Nph, NphState};
pub use classic::{ClassicDpd, DpdCoeff, DpdEnergyCoeff, DpdExt, DpdExtCoeff, Integration, MdpdCoeff, PairForce, ShardlowCoeff, ShardlowDpd};
pub use edpd::{Edpd, EdpdCoeff, HeatSource, SourceShape};
pub use error::StepError;
pub use heat::HeatModel;
pub use noise::NoiseForm;
pub use physics::{GenDpde, Physics, SetupError};
pub use sdpd::{Sdpd, SdpdParams};
pub use sdpd_taitwater::SdpdTaitwater;
pub use isentropic::FixedEntropy;
pub use settings::{Dissipation, Motion, RebuildPolicy, Reservoir, Settings, Work};
pub use species::Species;
pub use system::{Snapshot, System};
pub use type_table::TypeTable;
pub use tables::PairTables;
