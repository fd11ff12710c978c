//! One GenDPDE step (eSSA, eq 82): the reversible velocity-Verlet part with the
//! papers' pairwise work split (eq 84), then the Shardlow sweep and the reservoir.

use crate::error::StepError;
use crate::heat::{Fourier, HeatFlow, HeatModel, NoHeat, Original};
use crate::settings::Settings;
use crate::system::System;
use crate::{many_body, sweep, verlet};
use gendpde_engine::Fields;
use gendpde_potentials::{Eos, Weight};

/// A scene's dynamics, monomorphised over its EOS and weight function.
pub trait Physics {
    fn settings(&self) -> &Settings;
    /// Lays the grid, builds lists, derives u from given theta and computes the forces.
    fn setup(&self, sys: &mut System) -> Result<(), SetupError>;
    /// Advances one time step. Every rank returns an error when any rank failed.
    fn step(&self, sys: &mut System) -> Result<(), StepError>;
    /// Largest list radius (cutoff plus skin), for memory estimates.
    fn list_radius(&self) -> f64;
}

/// Why a run cannot start.
#[derive(Debug)]
pub enum SetupError {
    /// The box cannot hold the cell grid or be split over the ranks.
    Grid(String),
    State(StepError),
}

impl std::fmt::Display for SetupError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Grid(e) => e.fmt(f),
            Self::State(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for SetupError {}

/// The generalised DPDE of the 2019 paper with EOS `E` and density weight `W`.
pub struct GenDpde<E: Eos, W: Weight> {
    pub eos: E,
    pub weight: W,
    pub settings: Settings,
}

impl<E: Eos, W: Weight> GenDpde<E, W> {
    fn many_body(&self) -> bool {
        self.eos.density_dependent()
    }

    fn heat_model(&self) -> Option<HeatModel> {
        let s = &self.settings;
        s.dissipation.as_ref().map(|d| d.heat).or(s.reservoir.as_ref().map(|r| r.heat))
    }

    fn radii(&self) -> (Option<f64>, Option<f64>) {
        let skin = self.settings.skin;
        let density = self.many_body().then(|| self.weight.cutoff() + skin);
        let sweep = self.settings.dissipation.as_ref().map(|d| d.cutoff() + skin);
        (density, sweep)
    }

    fn rebuild(&self, sys: &mut System, at_step: u64) {
        let (density, sweep) = self.radii();
        sys.rebuild(density, sweep, at_step);
    }

    /// Density, particle state and forces at the current positions and energies.
    fn conservative(&self, sys: &mut System) -> Result<(), StepError> {
        if self.many_body() {
            many_body::density(&self.weight, sys);
        }
        let state = many_body::refresh_state(&self.eos, sys);
        sys.comm.forward(&mut sys.store, Fields::DENSITY | Fields::PRESSURE | sweep::SWEPT);
        if self.many_body() {
            many_body::forces(&self.weight, sys);
        }
        state
    }

    /// LAMMPS's rule: at most every `every` steps, not within `delay` steps of the last
    /// build, and (with `check`) only once some particle moved more than skin/2.
    fn needs_rebuild(&self, sys: &System, step: u64) -> bool {
        let p = &self.settings.rebuild;
        if step - sys.last_build < p.delay.max(1) || step % p.every.max(1) != 0 {
            return false;
        }
        !p.check || 2.0 * sys.comm.max(sys.displacement_since_build()) > self.settings.skin
    }

    /// Velocity-Verlet part (eq 84). The sweep of the previous step changed theta and
    /// so pi: the first half kick uses forces refreshed for the current state.
    fn reversible(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        let many_body = self.many_body();
        let mut before = Ok(());
        if many_body {
            before = many_body::refresh_state(&self.eos, sys);
            sys.comm.forward(&mut sys.store, Fields::PRESSURE);
            many_body::refresh_forces_and_work(sys, 0.25 * dt);
        }
        verlet::kick(sys, 0.5 * dt);
        let drifted = verlet::drift(sys, dt);
        sys.settle(before.and(drifted))?;
        let next = sys.step + 1;
        if self.needs_rebuild(sys, next) {
            self.rebuild(sys, next);
        } else {
            sys.comm.forward(&mut sys.store, Fields::POSITION);
        }
        let state = self.conservative(sys);
        verlet::kick(sys, 0.5 * dt);
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
        if many_body {
            many_body::work(sys, 0.25 * dt);
        }
        let refreshed = many_body::refresh_state(&self.eos, sys);
        sys.comm.forward(&mut sys.store, sweep::SWEPT);
        state.and(refreshed)
    }

    fn irreversible<H: HeatFlow>(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        let mut outcome = Ok(());
        if let Some(d) = &self.settings.dissipation {
            outcome = sweep::sweep::<E, H>(&self.eos, d, sys, dt);
        }
        if let Some(r) = &self.settings.reservoir {
            outcome = outcome.and(sweep::reservoir::<E, H>(&self.eos, r, sys, dt));
        }
        outcome
    }
}

impl<E: Eos, W: Weight> Physics for GenDpde<E, W> {
    fn settings(&self) -> &Settings {
        &self.settings
    }

    fn list_radius(&self) -> f64 {
        let (density, sweep) = self.radii();
        density.unwrap_or(0.0).max(sweep.unwrap_or(0.0))
    }

    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        let (density, sweep) = self.radii();
        let cut = density.unwrap_or(0.0).max(sweep.unwrap_or(0.0)).max(self.settings.skin);
        sys.lay_grid(cut).map_err(SetupError::Grid)?;
        let mut fields = Fields::THETA;
        if self.many_body() {
            fields = fields | Fields::DENSITY | Fields::PRESSURE;
        }
        if self.heat_model() == Some(HeatModel::Original) {
            fields = fields | Fields::INV_TAU;
        }
        sys.store.enable(fields);
        self.rebuild(sys, sys.step);
        if self.many_body() {
            many_body::density(&self.weight, sys);
        }
        many_body::resolve_theta(&self.eos, sys);
        let state = self.conservative(sys);
        sys.settle(state).map_err(SetupError::State)
    }

    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        if self.settings.verlet {
            let outcome = self.reversible(sys);
            sys.settle(outcome)?;
        }
        let heat_on = |model| {
            let s = &self.settings;
            s.dissipation.as_ref().is_some_and(|d| d.kappa > 0.0 && d.heat == model)
                || s.reservoir.as_ref().is_some_and(|r| r.heat == model)
        };
        let outcome = if heat_on(HeatModel::Original) {
            self.irreversible::<Original>(sys)
        } else if heat_on(HeatModel::Fourier) {
            self.irreversible::<Fourier>(sys)
        } else {
            self.irreversible::<NoHeat>(sys)
        };
        sys.settle(outcome)?;
        sys.step += 1;
        sys.time += self.settings.dt;
        Ok(())
    }
}
