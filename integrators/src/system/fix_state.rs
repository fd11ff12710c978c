//! The state fixes accumulate over a run and restart files keep, by fix ID: the energy a
//! `fix heat/reservoir` has put in, the `fix nph` barostat.

use crate::passes::barostat::state::NphState;

/// One fix's accumulated state.
#[derive(Clone, Debug, PartialEq)]
pub enum FixRecord {
    /// Energy a `fix heat/reservoir` has put into the particles since it was defined (all
    /// ranks, the same on each).
    Reservoir(f64),
    /// The state of a `fix nph` barostat (kept across runs and in restart files, as
    /// LAMMPS keeps it in the fix).
    Nph(Box<NphState>),
}

/// The fixes' states in the order they were created.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FixState {
    records: Vec<(String, FixRecord)>,
}

impl FixState {
    /// The state of fix `id`.
    pub fn get(&self, id: &str) -> Option<&FixRecord> {
        self.records.iter().find(|(name, _)| name == id).map(|(_, r)| r)
    }

    /// Sets the state of fix `id` (created at the end if new).
    pub fn set(&mut self, id: &str, record: FixRecord) {
        match self.records.iter_mut().find(|(name, _)| name == id) {
            Some((_, r)) => *r = record,
            None => self.records.push((id.to_string(), record)),
        }
    }

    /// Drops the state of fix `id` (`unfix`).
    pub fn remove(&mut self, id: &str) {
        self.records.retain(|(name, _)| name != id);
    }

    /// Every fix's state, in creation order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &FixRecord)> {
        self.records.iter().map(|(id, r)| (id.as_str(), r))
    }

    /// The energy tally of reservoir `id` (created at 0).
    pub fn reservoir_tally(&mut self, id: &str) -> &mut f64 {
        let k = self.records.iter().position(|(name, _)| name == id).unwrap_or_else(|| {
            self.records.push((id.to_string(), FixRecord::Reservoir(0.0)));
            self.records.len() - 1
        });
        if !matches!(self.records[k].1, FixRecord::Reservoir(_)) {
            self.records[k].1 = FixRecord::Reservoir(0.0);
        }
        let FixRecord::Reservoir(total) = &mut self.records[k].1 else { unreachable!("set just above") };
        total
    }

    /// The barostat of fix `id`, if it has one.
    pub fn barostat(&self, id: &str) -> Option<&NphState> {
        match self.get(id) {
            Some(FixRecord::Nph(st)) => Some(st),
            _ => None,
        }
    }

    /// The one barostat defined, if any (a run has at most one `fix nph`).
    pub fn any_barostat(&self) -> Option<&NphState> {
        self.records.iter().find_map(|(_, r)| if let FixRecord::Nph(st) = r { Some(&**st) } else { None })
    }

    /// Takes the barostat of fix `id` out for a step (put it back with [`FixState::set`]).
    pub fn take_barostat(&mut self, id: &str) -> Option<NphState> {
        let k = self.records.iter().position(|(name, r)| name == id && matches!(r, FixRecord::Nph(_)))?;
        match self.records.remove(k).1 {
            FixRecord::Nph(st) => Some(*st),
            FixRecord::Reservoir(_) => None,
        }
    }
}
