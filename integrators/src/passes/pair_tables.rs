//! `pair_style table` as a conservative pair force over the neighbour list: a
//! [`PairTable`] per type pair (LAMMPS's `tabindex`), alone or overlaid on a pairwise DPD
//! style (`pair_style hybrid/overlay table ... dpd ...`). Per pair (LAMMPS PairTable::compute):
//! f_i += (F/r)(r^2) d_ij, f_j -= the same, energy and virial split equally between i
//! and j; a pair closer than the table's inner distance stops the step, as LAMMPS's
//! "Pair distance < table inner cutoff".

use crate::error::{lowest, StepError};
use gendpde_engine::{dot, sub, Particles};
use gendpde_potentials::pair_table::{Outside, PairTable};

/// The tables of the type pairs.
#[derive(Clone, Debug, PartialEq)]
pub struct PairTables {
    pub tables: Vec<PairTable>,
    /// Index into `tables` of type pair (I, J), row-major over 1..=ntypes, symmetric;
    /// None: the pair has no table (another sub-style of the overlay acts on it).
    pub index: Vec<Option<usize>>,
    pub ntypes: usize,
}

impl PairTables {
    /// The largest table cutoff.
    pub fn cutoff(&self) -> f64 {
        self.tables.iter().map(|t| t.cut).fold(0.0, f64::max)
    }

    /// The index into `tables` of types `ti`, `tj`, if they have a table.
    #[inline(always)]
    pub(crate) fn slot(&self, ti: u32, tj: u32) -> Option<usize> {
        self.index.get((ti as usize - 1) * self.ntypes + tj as usize - 1).copied().flatten()
    }

    /// The table of types `ti`, `tj`, if they have one.
    #[inline(always)]
    pub(crate) fn of(&self, ti: u32, tj: u32) -> Option<&PairTable> {
        self.slot(ti, tj).map(|m| &self.tables[m])
    }

    /// Adds the table forces, energies (`epair`) and virials of the half list `pairs` to
    /// the owned particles; `step` names the failure of a pair outside a table.
    pub fn add_forces(&self, s: &mut Particles, pairs: &[[u32; 2]], step: u64) -> Result<(), StepError> {
        let n = s.nlocal;
        let mut outcome = Ok(());
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let Some(t) = self.of(s.kind[i], s.kind[j]) else { continue };
            let d = sub(s.r[i], s.r[j]);
            let rsq = dot(d, d);
            if rsq >= t.cut * t.cut {
                continue;
            }
            let (fpair, e) = match t.eval(rsq) {
                Ok(v) => v,
                Err(side) => {
                    let k = if s.tag[i] < s.tag[j] { i } else { j };
                    let (limit, r) = match side {
                        Outside::Inner => ("<", t.innersq.sqrt()),
                        Outside::Outer => (">", t.cut),
                    };
                    let what = format!(
                        "pair distance {:.9e} to particle {} {limit} table {} cutoff {r} (types {} {})",
                        rsq.sqrt(),
                        s.tag[i + j - k],
                        if side == Outside::Inner { "inner" } else { "outer" },
                        s.kind[i],
                        s.kind[j]
                    );
                    outcome = lowest(outcome, Err(StepError::state(s, k, step, &what)));
                    continue;
                }
            };
            let df = [fpair * d[0], fpair * d[1], fpair * d[2]];
            for (k, sign) in [(i, 1.0), (j, -1.0)] {
                if k < n {
                    for c in 0..3 {
                        s.f[k][c] += sign * df[c];
                        s.virial[k][c] += 0.5 * df[c] * d[c];
                    }
                    s.epair[k] += 0.5 * e;
                }
            }
        }
        outcome
    }
}
