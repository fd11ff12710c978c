//! What every model answers: the `Physics` trait a run's dynamics implements (set-up,
//! one step, the lists it needs), and why a run cannot start.

use crate::error::StepError;
use crate::settings::Settings;
use crate::system::System;
use gendpde_engine::Fields;

/// A scene's dynamics, monomorphised over its EOS and weight function.
pub trait Physics {
    fn settings(&self) -> &Settings;
    /// Lays the grid, builds lists, derives u from given theta and computes the forces.
    fn setup(&self, sys: &mut System) -> Result<(), SetupError>;
    /// Advances the particles one time step, leaving the clock to [`Physics::advance`].
    /// Every rank returns an error when any rank failed.
    fn step(&self, sys: &mut System) -> Result<(), StepError>;
    /// One step, then the clock moved on by dt: what a run calls for every step.
    fn advance(&self, sys: &mut System) -> Result<(), StepError> {
        self.step(sys)?;
        sys.clock.advance(self.settings().dt);
        Ok(())
    }
    /// The largest interaction cutoff (LAMMPS's `cutforce`; `compute rdf`'s default).
    fn cutoff(&self) -> f64;
    /// Largest list radius (by default the cutoff plus the skin), for memory estimates.
    fn list_radius(&self) -> f64 {
        self.cutoff() + self.settings().skin
    }
    /// Migrates particles and builds ghosts and lists for the positions of step `at_step`
    /// (by default one pair list of radius [`Physics::list_radius`] and no sweep list).
    fn rebuild(&self, sys: &mut System, at_step: u64) {
        sys.rebuild(Some(self.list_radius()), None, at_step);
    }

    /// Agrees on the outcome of the move (`moved`, as [`System::settle`]) and lists for the
    /// positions of the next step, by LAMMPS's rule: at most every `every` steps, not
    /// within `delay` steps of the last build, and (with `check`) only once some particle
    /// moved more than skin/2, found in the same reduction; else the positions are
    /// forwarded.
    fn relist(&self, sys: &mut System, moved: Result<(), StepError>) -> Result<(), StepError> {
        let (settings, next) = (self.settings(), sys.clock.step + 1);
        let p = &settings.rebuild;
        let due = next - sys.lists.last >= p.delay.max(1) && next % p.every.max(1) == 0;
        let local = if due && p.check { 2.0 * sys.displacement_since_build() } else { 0.0 };
        let farthest = sys.settle_with(moved, local)?;
        if due && (!p.check || farthest > settings.skin) {
            if p.check && next - sys.lists.last == p.every.max(p.delay) {
                sys.lists.dangerous += 1;
            }
            self.rebuild(sys, next);
        } else {
            sys.comm.forward(&mut sys.store, Fields::POSITION);
        }
        Ok(())
    }
}

/// Why a run cannot start.
#[derive(Debug)]
pub enum SetupError {
    /// The box cannot hold the cell grid or be split over the ranks.
    Grid(String),
    /// Some particle type has no EOS (per-type EOS).
    Types(String),
    State(StepError),
}

impl std::fmt::Display for SetupError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Grid(e) | Self::Types(e) => e.fmt(f),
            Self::State(e) => e.describe(f, format_args!("at step {}", e.step)),
        }
    }
}

impl std::error::Error for SetupError {}
