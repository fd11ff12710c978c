//! The model a script builds: box, particles, styles and run settings (its outputs are
//! `output::Outputs`).

use crate::base::lattice::Lattice;
use crate::base::region::Region;
use crate::base::units::Units;
use crate::styles::compute::chunk::ChunkAtom;
use crate::styles::compute::rdf::Rdf;
use crate::styles::compute::Compute;
use crate::styles::fix::{Fix, FixStyle};
use crate::styles::pair::Pair;
use gendpde_engine::{Fields, Transport};
use gendpde_integrators::{FixRecord, NphState, RebuildPolicy, System};
use gendpde_io::AtomStyle;
use std::collections::HashMap;

/// Restart state name prefix of a `fix heat/reservoir` energy tally.
const RESERVOIR_STATE: &str = "heat/reservoir/";
/// Restart state name prefix of a `fix nph` barostat.
const NPH_STATE: &str = "nph/";

/// The values a fix publishes: global ones read as `f_ID` (the scalar) and `f_ID[k]`, each
/// with whether it is extensive (divided by N under `thermo_modify norm yes`), and
/// per-atom ones read by dumps and computes as `f_ID` or `f_ID[k]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FixValues {
    pub scalar: Option<(f64, bool)>,
    pub vector: Vec<(f64, bool)>,
    /// Per-atom values: the number of columns and the values by (tag - 1) x columns.
    pub per_atom: Option<(usize, Vec<f64>)>,
    /// The values change only on multiples of this step (LAMMPS's global_freq: thermo
    /// reads them only then).
    pub freq: u64,
}

/// Everything the commands of a script have defined so far.
pub struct Sim {
    /// The ranks, until the box is created (create_box, read_data or read_restart hands
    /// them to its communicator).
    transport: Option<Box<dyn Transport>>,
    pub lattice: Option<Lattice>,
    pub regions: HashMap<String, Region>,
    pub ntypes: usize,
    /// Mass of each type (index type - 1).
    pub masses: Vec<Option<f64>>,
    pub system: Option<System>,
    pub units: Units,
    pub pair: Option<Box<dyn Pair>>,
    pub fixes: Vec<Fix>,
    pub dt: f64,
    pub skin: f64,
    pub rebuild: RebuildPolicy,
    /// `neigh_modify one` and `page` (LAMMPS's defaults 2000 and 100000).
    pub neigh_pages: [u64; 2],
    /// Total energy at the first setup, for `edrift`.
    pub energy0: Option<f64>,
    /// Largest tag handed out.
    pub max_tag: u64,
    /// Ranks per dimension fixed by `processors` (None: chosen to minimise surface).
    pub procs: [Option<usize>; 3],
    /// Column layout of data files (`atom_style dpd` or `gendpde`: with dpdTheta).
    pub atom_style: AtomStyle,
    /// The `pair_style` and `pair_coeff` commands in force, as text (for restarts).
    pub pair_text: Vec<String>,
    /// `compute` definitions but rdf and chunk/atom (thermo `c_ID`, `c_ID[k]`, dump `c_ID`).
    pub computes: Vec<Box<dyn Compute>>,
    /// `compute ID all rdf` definitions.
    pub rdfs: Vec<Rdf>,
    /// `compute ID GROUP chunk/atom` definitions.
    pub chunks: Vec<ChunkAtom>,
    /// Group names by bit (an empty name is a free slot).
    pub groups: Vec<String>,
    /// The global values of the output fixes (`output::fix`) by fix ID, as of their
    /// last block.
    pub fix_values: HashMap<String, FixValues>,
    /// State of fixes read from a restart, taken by the fixes as they are defined.
    pub restored_state: Vec<(String, Vec<f64>)>,
    /// A run is being set up or stepped (LAMMPS's whichflag: ramp() reads its span).
    pub running: bool,
}

impl Sim {
    /// An empty model on the ranks of `transport`, with LAMMPS's lj-unit defaults:
    /// timestep 0.005, skin 0.3.
    pub fn new(transport: Box<dyn Transport>) -> Self {
        Self {
            transport: Some(transport),
            lattice: None,
            regions: HashMap::new(),
            ntypes: 0,
            masses: Vec::new(),
            system: None,
            units: Units::LJ,
            pair: None,
            fixes: Vec::new(),
            dt: 0.005,
            skin: 0.3,
            rebuild: RebuildPolicy::default(),
            neigh_pages: [2000, 100000],
            energy0: None,
            max_tag: 0,
            procs: [None; 3],
            atom_style: AtomStyle::Atomic,
            pair_text: Vec::new(),
            computes: Vec::new(),
            rdfs: Vec::new(),
            chunks: Vec::new(),
            groups: Vec::new(),
            fix_values: HashMap::new(),
            restored_state: Vec::new(),
            running: false,
        }
    }

    /// The lattice spacings for `units lattice`: LAMMPS's default lattice, `lattice none
    /// 1.0`, has spacing 1.
    pub fn lattice_spacing(&self) -> gendpde_engine::Vec3 {
        self.lattice.as_ref().map_or([1.0; 3], |l| l.spacing)
    }

    /// This rank's number (0 writes the files).
    pub fn rank(&self) -> usize {
        self.transport.as_ref().map_or_else(|| self.system.as_ref().map_or(0, |s| s.comm.rank()), |t| t.rank())
    }

    /// The ranks, for the box about to be created.
    pub fn take_transport(&mut self) -> Result<Box<dyn Transport>, String> {
        self.transport.take().ok_or_else(|| "the box exists already".into())
    }

    /// Deletes the box, the particles and every definition, back to the defaults of
    /// [`Sim::new`] on the same ranks (LAMMPS's `clear`).
    pub fn clear(&mut self) -> Result<(), String> {
        let transport = self.transport.take().or_else(|| self.system.take().map(|s| s.comm.into_transport()));
        *self = Sim::new(transport.ok_or("clear: the ranks are held by a box being read")?);
        Ok(())
    }

    /// The per-particle fields the atom style carries (atom_style edpd: eDPD's
    /// temperature, heat capacity and flux; sph: the SPH density and its rate).
    pub fn atom_style_fields(&self) -> Fields {
        match self.atom_style {
            AtomStyle::Edpd => Fields::EDPD,
            AtomStyle::Sph => Fields::RHO | Fields::SPH,
            _ => Fields::NONE,
        }
    }

    /// Whether thermo `pe` is a pair energy (LAMMPS's pairwise styles, tables and edpd).
    pub fn pe_is_pair(&self) -> bool {
        self.pair.as_ref().is_some_and(|p| p.pe_is_pair())
    }

    /// The accumulated state of fixes, for a restart file: each reservoir's energy
    /// tally (the same on every rank) as `heat/reservoir/ID`, the barostat of a `fix nph`
    /// as `nph/ID` ([`NphState::record`]).
    pub fn fix_state(&self) -> Vec<(String, Vec<f64>)> {
        let Some(sys) = &self.system else { return Vec::new() };
        let reservoirs = sys.fixes.iter().filter_map(|(id, r)| match r {
            FixRecord::Reservoir(total) => Some((format!("{RESERVOIR_STATE}{id}"), vec![*total])),
            FixRecord::Nph(_) => None,
        });
        let barostats = sys.fixes.iter().filter_map(|(id, r)| match r {
            FixRecord::Nph(b) if self.fixes.iter().any(|f| f.id == id) => Some((format!("{NPH_STATE}{id}"), b.record())),
            _ => None,
        });
        reservoirs.chain(barostats).collect()
    }

    /// Puts the reservoir tallies and the barostat of a restart back (the replayed fix
    /// nph has just created its state at rest).
    pub fn restore_fix_state(&mut self) {
        let Some(sys) = &mut self.system else { return };
        for (name, v) in &self.restored_state {
            if let (Some(id), [total]) = (name.strip_prefix(RESERVOIR_STATE), v.as_slice()) {
                *sys.fixes.reservoir_tally(id) = *total;
            }
            if let Some(b) = name.strip_prefix(NPH_STATE).and_then(|id| NphState::from_record(id, v)) {
                if sys.fixes.barostat(&b.id).is_some_and(|s| s.etap.len() == b.etap.len()) {
                    sys.fixes.set(&b.id.clone(), FixRecord::Nph(Box::new(b)));
                }
            }
        }
    }

    /// Commands that re-create the styles and run settings, for a restart file. Values
    /// print in round-trip form.
    pub fn style_commands(&self) -> Vec<String> {
        let mut c = vec![format!("units {}", self.units.name), format!("atom_style {}", self.atom_style.name())];
        c.extend(self.pair_text.iter().cloned());
        c.extend(self.fixes.iter().map(|f| f.text.clone()));
        c.push(format!("timestep {:?}", self.dt));
        c.push(format!("neighbor {:?} bin", self.skin));
        let r = &self.rebuild;
        c.push(format!("neigh_modify every {} delay {} check {}", r.every, r.delay, if r.check { "yes" } else { "no" }));
        c
    }

    /// Err when the mean density lies at or above the cap of the EOS (vdW: 1/b): such a
    /// box cannot start a run. Every rank must call.
    pub fn check_density_cap(&self) -> Result<(), String> {
        let Some(sys) = &self.system else { return Ok(()) };
        let n = sys.comm.count(sys.store.nlocal) as f64 / sys.domain.volume();
        for f in &self.fixes {
            if let FixStyle::Eos(e) = &f.style {
                if let Some(max) = e.max_density() {
                    if n >= max {
                        return Err(format!(
                            "mean number density N/V = {n:.6} lies beyond the density limit {max:.6} of the EOS of fix {} (van der Waals: 1/b)",
                            f.id
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}
