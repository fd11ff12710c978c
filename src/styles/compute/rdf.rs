//! `compute ID all rdf Nbin [* *] [cutoff Rc]`: the radial distribution function of all
//! particle pairs (one type pairing, all-all), as LAMMPS's compute rdf.
//!
//! A global array of Nbin rows: the bin centre r, g(r) and the cumulative coordination
//! number coord(r). Pairs are counted once for each owned partner from a list of radius
//! Rc + skin (LAMMPS's occasional list) and binned at int(r / dr); the integer counts are
//! summed over ranks, so the array does not depend on the decomposition. g(r) divides
//! each count by its ideal-gas share N (N - 1) V_shell / V, with LAMMPS's operation order.

use crate::base::args::Args;
use gendpde_engine::{build_lists, dot, sub, CellGrid, ListRequest, NeighborList};
use gendpde_integrators::System;
use gendpde_io::ScriptError;

/// Columns of the array: r, g(r), coord(r).
pub const COLUMNS: usize = 3;

/// Largest Nbin accepted (the array is held on every rank).
const MAX_BINS: u64 = 1 << 24;

#[derive(Clone, Debug, PartialEq)]
pub struct Rdf {
    pub id: String,
    pub nbin: usize,
    /// `cutoff Rc`; None: the pair style's cutoff.
    pub cutoff: Option<f64>,
}

impl Rdf {
    /// The words after `compute ID all rdf`.
    pub fn parse(id: String, a: &mut Args) -> Result<Self, ScriptError> {
        let nbin = a.u64("the number of bins Nbin")?;
        if nbin == 0 || nbin > MAX_BINS {
            return Err(a.err(format!("the number of bins Nbin must lie in 1..{MAX_BINS}, got {nbin}")));
        }
        let mut cutoff = None;
        while let Some(k) = a.peek() {
            a.word("keyword")?;
            match k {
                "cutoff" => cutoff = Some(a.positive("the cutoff Rc")?),
                "*" if a.peek() == Some("*") => {
                    a.word("*")?;
                }
                _ => return Err(a.err(format!("unexpected '{k}': only the all-all pairing ('* *' or none) and the keyword cutoff are supported"))),
            }
        }
        Ok(Self { id, nbin: nbin as usize, cutoff })
    }

    /// Rc: the `cutoff` keyword, else the interaction cutoff of the run's model.
    pub fn cutoff_for(&self, model: f64) -> f64 {
        self.cutoff.unwrap_or(model)
    }

    /// Checks that a box holds the cell grid for pairs out to `reach` = Rc + skin.
    pub fn check_reach(&self, sys: &System, reach: f64) -> Result<(), String> {
        CellGrid::new(&sys.domain, reach).map(|_| ()).map_err(|e| format!("compute {} rdf: cutoff + skin = {reach:.6}: {e}", self.id))
    }

    /// The rows (r, g, coord) at the current positions, on every rank. The grid's cells
    /// must be at least `reach` = Rc + skin wide (`sys.lists.min_cell`) and no particle
    /// may have moved more than skin/2 since the last list build.
    pub fn rows(&self, sys: &System, rc: f64, reach: f64) -> Result<Vec<[f64; COLUMNS]>, String> {
        let grid = sys.grid.as_ref().ok_or_else(|| format!("compute {}: no cell grid (the run is not set up)", self.id))?;
        let (s, nbin) = (&sys.store, self.nbin);
        let (lo, hi) = sys.comm.owned_cells(grid);
        let mut list = NeighborList::default();
        build_lists(s, &sys.bins, lo, hi, ListRequest { nlist: Some((&mut list, reach)), sweep: None });
        let delr = rc / nbin as f64;
        let delrinv = 1.0 / delr;
        // the last entry counts the owned particles
        let mut hist = vec![0u64; nbin + 1];
        hist[nbin] = s.nlocal as u64;
        for &[i, j] in &list.pairs {
            let (i, j) = (i as usize, j as usize);
            let d = sub(s.r[i], s.r[j]);
            let bin = (dot(d, d).sqrt() * delrinv) as usize;
            if bin < nbin {
                hist[bin] += (i < s.nlocal) as u64 + (j < s.nlocal) as u64;
            }
        }
        let mut total = vec![0u64; nbin + 1];
        for rank in sys.comm.transport().all_gather(&hist).chunks_exact(nbin + 1) {
            total.iter_mut().zip(rank).for_each(|(t, h)| *t += h);
        }
        let n = total[nbin] as f64;
        let [lx, ly, lz] = sys.domain.len();
        let constant = 4.0 * std::f64::consts::PI / (3.0 * lx * ly * lz);
        // LAMMPS's jcount - duplicates/icount, N - N/N
        let normfac = if n > 0.0 { n - 1.0 } else { 0.0 };
        let mut coord = 0.0;
        Ok((0..nbin)
            .map(|k| {
                let (rlower, rupper) = (k as f64 * delr, (k + 1) as f64 * delr);
                let vfrac = constant * (rupper * rupper * rupper - rlower * rlower * rlower);
                let g = if vfrac * normfac != 0.0 { total[k] as f64 / (vfrac * normfac * n) } else { 0.0 };
                coord += g * vfrac * normfac;
                [(k as f64 + 0.5) * delr, g, coord]
            })
            .collect())
    }
}
