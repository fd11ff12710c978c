//! The finite-volume model as a run's dynamics (`pair_style voronoi/fv` + `fix
//! nve/voronoi`): the particles are the cells; their per-particle `mass` is the dynamic M,
//! the field-table row `entropy` holds S, `u` the cell energy E(M, S, V), `theta` T,
//! `volume` the cell volume (dump `vol`) and `virial` p dV/d epsilon (its trace 3 p V),
//! so thermo's pe + ke is the model's energy (eq 64) and press its pressure. One rank
//! only (docs/models/voronoi.md, plan for ranks).

use super::finite_volume::{same_bits, Cells, FiniteVolume, CellFrame, ModelError};
use crate::error::StepError;
use crate::settings::Settings;
use crate::system::System;
use crate::{Physics, SetupError};
use gendpde_engine::Fields;
use gendpde_potentials::CellEnergy;
use std::cell::RefCell;

/// The Voronoi finite-volume dynamics with cell relation `E`.
pub struct VoronoiFv<E> {
    pub model: FiniteVolume<E>,
    pub settings: Settings,
    /// The frame of the last refresh and what it was computed from.
    last: RefCell<Option<Refreshed>>,
}

/// A frame with the cells and box it tessellated: the next step's first frame while they
/// are unchanged to the bit (so a step tessellates twice, not three times, and a run that
/// reads a restart, which recomputes it at the set-up, follows the same trajectory).
struct Refreshed {
    cells: Cells,
    lo: [f64; 3],
    len: [f64; 3],
    frame: CellFrame,
}

impl<E: CellEnergy> VoronoiFv<E> {
    pub fn new(model: FiniteVolume<E>, settings: Settings) -> Self {
        Self { model, settings, last: RefCell::new(None) }
    }

    /// The owned particles in tag order (so no storage order reaches the sums).
    fn gather(sys: &System) -> (Cells, Vec<usize>) {
        let s = &sys.store;
        let mut order: Vec<usize> = (0..s.nlocal).collect();
        order.sort_by_key(|&i| s.tag[i]);
        let cells = Cells {
            tag: order.iter().map(|&i| s.tag[i]).collect(),
            r: order.iter().map(|&i| s.r[i]).collect(),
            p: order.iter().map(|&i| s.p[i]).collect(),
            m: order.iter().map(|&i| s.mass[i]).collect(),
            s: order.iter().map(|&i| s.entropy[i]).collect(),
        };
        (cells, order)
    }

    /// Tessellates the current positions, writes E into u, T into theta and the virial,
    /// and keeps the frame for the next step.
    fn refresh(&self, sys: &mut System) -> Result<(), ModelError> {
        let (cells, order) = Self::gather(sys);
        let (lo, len) = (sys.domain.lo, sys.domain.len());
        let frame = CellFrame::new(&cells, &self.model.energy, lo, len)?;
        let virial = frame.virial();
        for (k, &i) in order.iter().enumerate() {
            sys.store.u[i] = frame.thermo[k].energy;
            sys.store.theta[i] = frame.thermo[k].temperature;
            sys.store.virial[i] = virial[k];
            sys.store.volume[i] = frame.tess.volumes[k];
        }
        *self.last.borrow_mut() = Some(Refreshed { cells, lo, len, frame });
        Ok(())
    }

    /// The frame of `cells` in the box [lo, lo + len): the last refresh's if it saw the
    /// same bits, else a new tessellation.
    fn frame(&self, cells: &Cells, lo: [f64; 3], len: [f64; 3]) -> Result<CellFrame, ModelError> {
        match self.last.take() {
            Some(r) if r.cells.same_bits(cells) && same_bits(&r.lo, &lo) && same_bits(&r.len, &len) => Ok(r.frame),
            _ => CellFrame::new(cells, &self.model.energy, lo, len),
        }
    }

    fn error(sys: &System, e: ModelError) -> StepError {
        let tag = match &e {
            ModelError::State { tag, .. } => *tag,
            ModelError::Tessellation(_) => sys.store.tag[..sys.store.nlocal].iter().copied().min().unwrap_or(0),
        };
        let i = (0..sys.store.nlocal).find(|&i| sys.store.tag[i] == tag).unwrap_or(0);
        StepError::state(&sys.store, i, sys.clock.step, &e.to_string())
    }
}

impl<E: CellEnergy> Physics for VoronoiFv<E> {
    fn settings(&self) -> &Settings {
        &self.settings
    }

    /// No neighbour lists: the grid only carries migration and periodic wrapping.
    /// The cells interact through the tessellation, not within a cutoff.
    fn cutoff(&self) -> f64 {
        0.0
    }

    fn list_radius(&self) -> f64 {
        0.0
    }

    fn rebuild(&self, sys: &mut System, at_step: u64) {
        sys.rebuild(None, None, at_step);
    }

    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        if sys.comm.size() > 1 {
            return Err(SetupError::Grid(format!(
                "pair voronoi/fv runs on one MPI rank only (this run has {}); see docs/commands/pair_style_voronoi_fv.md",
                sys.comm.size()
            )));
        }
        let len = sys.domain.len();
        sys.lay_grid(len.iter().fold(f64::MAX, |a, &l| a.min(l)) / 4.5).map_err(SetupError::Grid)?;
        sys.store.enable(Fields::THETA | Fields::ENTROPY);
        self.rebuild(sys, sys.clock.step);
        // Cells whose temperature was given (`set ... theta`) get S(M, V, T).
        if (0..sys.store.nlocal).any(|i| sys.store.theta_given[i]) {
            let (cells, order) = Self::gather(sys);
            let tess = super::Tessellation::build(&cells.r, sys.domain.lo, len).map_err(|e| SetupError::State(Self::error(sys, ModelError::Tessellation(e))))?;
            for (k, &i) in order.iter().enumerate() {
                let s = &mut sys.store;
                if s.theta_given[i] {
                    s.entropy[i] = self.model.energy.entropy(s.mass[i], tess.volumes[k], s.theta[i]);
                    s.theta_given[i] = false;
                }
            }
        }
        self.refresh(sys).map_err(|e| SetupError::State(Self::error(sys, e)))
    }

    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        let (mut cells, order) = Self::gather(sys);
        let (lo, len) = (sys.domain.lo, sys.domain.len());
        let stepped = self.frame(&cells, lo, len).and_then(|f0| self.model.step(&mut cells, &f0, lo, len, dt, sys.noise_step(sys.clock.step))).map_err(|e| Self::error(sys, e));
        sys.settle(stepped)?;
        for (k, &i) in order.iter().enumerate() {
            let s = &mut sys.store;
            s.r[i] = cells.r[k];
            s.p[i] = cells.p[k];
            s.mass[i] = cells.m[k];
            s.entropy[i] = cells.s[k];
        }
        self.rebuild(sys, sys.clock.step + 1);
        let refreshed = self.refresh(sys).map_err(|e| Self::error(sys, e));
        sys.settle(refreshed)?;
        Ok(())
    }
}
