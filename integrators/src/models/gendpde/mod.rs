//! One GenDPDE step (eSSA, eq 82): the reversible velocity-Verlet part with the
//! papers' pairwise work split (eq 84) or at fixed entropy, then the Shardlow sweep and
//! the reservoir; or the argon paper's velocity Verlet + Euler step, then the reservoir.

use crate::error::{lowest, StepError};
use crate::passes::heat::{Fourier, HeatFlow, HeatModel, NoHeat, Original};
use crate::passes::noise::{Arithmetic, Harmonic, Noise, NoiseForm};
use crate::passes::isentropic::{self, FixedEntropy};
use crate::passes::dissipation::{Dissipation, Reservoir};
use crate::settings::Settings;
use crate::passes::species::Species;
use crate::system::System;
use crate::passes::{many_body, sweep, verlet};
use crate::physics::{Physics, SetupError};

pub mod vv_euler;
use gendpde_engine::Fields;
use gendpde_potentials::volume::PartitionVolume;
use gendpde_potentials::{Eos, FixedDensity, Weight};

/// How the particles move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// No integrator fix: particles stay fixed (heat-only scenes), lists never rebuild.
    Fixed,
    /// `fix nve/gendpde`: the reversible velocity-Verlet part of the eSSA (eq 84); the
    /// dissipation, if any, is `fix shardlow`'s sweep.
    Verlet(Work),
    /// `fix vv/euler`: velocity Verlet for r and p with all pair forces, forward Euler for
    /// u (argon paper eqs 19-21); the dissipation acts through the pair forces.
    VvEuler,
}

/// How the reversible velocity-Verlet step changes the internal energies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Work {
    /// Each pair's work split equally between u_i and u_j (eq 84).
    Split,
    /// u_i = u(s_i, n_i) at the entropy s_i of the start of the step (SPEC section 6).
    Isentropic,
}

/// The generalised DPDE of the 2019 paper with EOS `E` and density weight `W`.
pub struct GenDpde<E: Eos, W: Weight> {
    /// The EOS of each particle type (or one for all).
    pub eos: Species<E>,
    pub weight: W,
    /// The corrected particle volume of the argon paper (eqs 2-3), if chosen.
    pub volume: Option<PartitionVolume>,
    pub settings: Settings,
    pub motion: Motion,
    /// Friction, noise and pair heat flow (`fix shardlow` or `fix vv/euler`), if any.
    pub dissipation: Option<Dissipation>,
    /// Heat baths, each on its own group (applied in this order after the sweep).
    pub reservoirs: Vec<Reservoir>,
}

impl<E: FixedEntropy + FixedDensity, W: Weight> GenDpde<E, W> {
    fn many_body(&self) -> bool {
        self.eos.density_dependent()
    }

    fn heat_model(&self) -> Option<HeatModel> {
        let s = self;
        s.dissipation.as_ref().map(|d| d.heat).or(s.reservoirs.first().map(|r| r.heat))
    }

    /// The sweep's friction/noise law (the papers' eq 76 without a sweep).
    fn noise(&self) -> NoiseForm {
        let s = self;
        s.dissipation.as_ref().filter(|_| s.motion != Motion::VvEuler).map_or(NoiseForm::Arithmetic, |d| d.noise)
    }

    /// Radii of the neighbour list and of the sweep pairs (cutoff plus skin). The pair
    /// forces of `fix vv/euler` run over the neighbour list, which then reaches them too.
    fn radii(&self) -> (Option<f64>, Option<f64>) {
        let skin = self.settings.skin;
        let density = self.many_body().then(|| self.weight.cutoff());
        let dissipation = self.dissipation.as_ref().map(|d| d.cutoff());
        if self.motion == Motion::VvEuler {
            let reach = density.into_iter().chain(dissipation).reduce(f64::max);
            return (reach.map(|r| r + skin), None);
        }
        (density.map(|r| r + skin), dissipation.map(|r| r + skin))
    }

    /// Density, particle state and forces at the current positions and energies; with
    /// `entropy_held`, u at the entropies [`isentropic::hold`] kept first.
    fn conservative(&self, sys: &mut System, entropy_held: bool) -> Result<(), StepError> {
        if self.many_body() {
            many_body::density(&self.weight, self.volume.as_ref(), sys);
        }
        let released = if entropy_held { isentropic::release(&self.eos, sys) } else { Ok(()) };
        let state = many_body::refresh_state(&self.eos, sys);
        sys.comm.forward(&mut sys.store, Fields::DENSITY | Fields::PRESSURE | sweep::SWEPT);
        if self.many_body() {
            many_body::forces(sys);
        }
        lowest(released, state)
    }

    /// Velocity-Verlet part (eq 84). The sweep of the previous step changed theta and
    /// so pi: the first half kick uses forces refreshed for the current state. `Split`
    /// moves each pair's work into u_i and u_j in halves; `Isentropic` sets u_i = u(s_i, n_i)
    /// after the density pass instead.
    fn reversible(&self, sys: &mut System, work: Work) -> Result<(), StepError> {
        let dt = self.settings.dt;
        let many_body = self.many_body();
        let isentropic = many_body && work == Work::Isentropic;
        let mut before = Ok(());
        if many_body {
            before = many_body::refresh_state(&self.eos, sys);
            sys.comm.forward(&mut sys.store, Fields::PRESSURE);
            many_body::refresh_forces(sys, (!isentropic).then_some(0.25 * dt));
        }
        verlet::kick(sys, 0.5 * dt);
        let drifted = verlet::drift(sys, dt);
        let mut moved = lowest(before, drifted);
        if isentropic {
            sys.settle(moved)?;
            moved = isentropic::hold(&self.eos, sys);
        }
        self.relist(sys, moved)?;
        let state = self.conservative(sys, isentropic);
        verlet::kick(sys, 0.5 * dt);
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
        if isentropic {
            return state;
        }
        if many_body {
            many_body::work(sys, 0.25 * dt);
        }
        let refreshed = many_body::refresh_state(&self.eos, sys);
        sys.comm.forward(&mut sys.store, sweep::SWEPT);
        lowest(state, refreshed)
    }

    /// `fix vv/euler` (see [`vv_euler`]).
    fn vv_euler<H: HeatFlow>(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        let dissipation = self.dissipation.as_ref();
        vv_euler::start::<H>(dissipation, self.eos.kb(), sys, dt);
        let drifted = vv_euler::first_half(sys, dt);
        self.relist(sys, drifted)?;
        let state = self.conservative(sys, false);
        if dissipation.is_some_and(|d| d.gamma > 0.0) {
            // the prediction of p(t+dt) for the friction: first_half added dt/2 F^D(t)
            verlet::kick(sys, 0.5 * dt);
            sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
        }
        vv_euler::friction(dissipation, sys);
        vv_euler::second_half(sys, dt);
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
        state
    }

    fn irreversible<H: HeatFlow, N: Noise>(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        let mut outcome = Ok(());
        if let Some(d) = self.dissipation.as_ref().filter(|_| self.motion != Motion::VvEuler) {
            outcome = sweep::sweep::<E, H, N>(&self.eos, d, sys, dt);
        }
        for r in &self.reservoirs {
            outcome = lowest(outcome, sweep::reservoir::<E, H, N>(&self.eos, r, sys, dt));
        }
        outcome
    }

    fn advance<H: HeatFlow, N: Noise>(&self, sys: &mut System) -> Result<(), StepError> {
        let moved = match self.motion {
            Motion::Fixed => Ok(()),
            Motion::Verlet(work) => self.reversible(sys, work),
            Motion::VvEuler => self.vv_euler::<H>(sys),
        };
        sys.settle(moved)?;
        let outcome = self.irreversible::<H, N>(sys);
        sys.settle(outcome)?;
        Ok(())
    }
}

impl<E: FixedEntropy + FixedDensity, W: Weight> Physics for GenDpde<E, W> {
    fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The density cutoff, or the friction and heat cutoffs if larger.
    fn cutoff(&self) -> f64 {
        let dissipation = self.dissipation.as_ref().map_or(0.0, |d| d.rc_friction.max(d.rc_heat));
        self.weight.cutoff().max(dissipation)
    }

    fn list_radius(&self) -> f64 {
        let (density, sweep) = self.radii();
        density.unwrap_or(0.0).max(sweep.unwrap_or(0.0))
    }

    fn rebuild(&self, sys: &mut System, at_step: u64) {
        let (density, sweep) = self.radii();
        sys.rebuild(density, sweep, at_step);
    }

    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        let (density, sweep) = self.radii();
        let cut = density.unwrap_or(0.0).max(sweep.unwrap_or(0.0)).max(self.settings.skin);
        let max_kind = sys.store.kind[..sys.store.nlocal].iter().copied().max().unwrap_or(1);
        let max_kind = sys.comm.max(max_kind as f64) as u32;
        if !self.eos.covers(max_kind) {
            return Err(SetupError::Types(format!("the EOS fix gives fewer heat capacities than particle types ({max_kind})")));
        }
        sys.lay_grid(cut).map_err(SetupError::Grid)?;
        let mut fields = Fields::THETA;
        if self.many_body() {
            fields = fields | Fields::DENSITY | Fields::PRESSURE;
        }
        if self.heat_model() == Some(HeatModel::Original) || self.noise() != NoiseForm::Arithmetic {
            fields = fields | Fields::INV_TAU;
        }
        sys.store.enable(fields);
        for r in &self.reservoirs {
            sys.fixes.reservoir_tally(&r.id);
        }
        self.rebuild(sys, sys.clock.step);
        if self.many_body() {
            many_body::density(&self.weight, self.volume.as_ref(), sys);
        }
        many_body::resolve_theta(&self.eos, sys);
        let state = self.conservative(sys, false);
        sys.settle(state).map_err(SetupError::State)
    }

    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        let heat_on = |model| {
            let s = self;
            s.dissipation.as_ref().is_some_and(|d| d.kappa > 0.0 && d.heat == model)
                || s.reservoirs.iter().any(|r| r.heat == model)
        };
        match (heat_on(HeatModel::Original), heat_on(HeatModel::Fourier), self.noise()) {
            (true, _, NoiseForm::Arithmetic) => self.advance::<Original, Arithmetic>(sys),
            (_, true, NoiseForm::Arithmetic) => self.advance::<Fourier, Arithmetic>(sys),
            (_, _, NoiseForm::Arithmetic) => self.advance::<NoHeat, Arithmetic>(sys),
            (true, _, NoiseForm::Harmonic { .. }) => self.advance::<Original, Harmonic>(sys),
            (_, true, NoiseForm::Harmonic { .. }) => self.advance::<Fourier, Harmonic>(sys),
            (_, _, NoiseForm::Harmonic { .. }) => self.advance::<NoHeat, Harmonic>(sys),
        }
    }
}
