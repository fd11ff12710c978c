//! Compute styles, one unit each: a [`Compute`] says what it produces ([`Shape`]: a global
//! scalar, a global vector, per-atom values) and evaluates them on request ([`Eval`]).
//! Thermo, variables and fix ave/time read `c_ID` (the scalar) and `c_ID[k]` (vector
//! element k); dumps, compute reduce, fix ave/chunk and fix ave/atom read per-atom `c_ID`
//! (a per-atom vector) and `c_ID[k]` (column k of a per-atom array). Two styles keep their
//! own lists because their consumers read more than values: `compute rdf` ([`rdf`], a global
//! array read by fix ave/time) and `compute chunk/atom` ([`chunk`], read by fix ave/chunk).
//!
//! Adding a style: a file with its type implementing [`Compute`] and one line in
//! [`COMPUTE_STYLES`].

pub mod chunk;
pub mod cluster_atom;
pub mod com;
pub mod coord_atom;
pub mod count_type;
pub mod dpd;
pub mod gyration;
pub mod msd;
pub mod property_atom;
pub mod rdf;
pub mod reduce;
pub mod temp;

use self::chunk::ChunkAtom;
use self::rdf::Rdf;
use crate::base::args::Args;
use crate::base::region::Region;
use crate::base::units::Units;
use crate::styles::pair::AsAny;
use gendpde_integrators::System;
use gendpde_io::ScriptError;
use std::collections::HashMap;

/// What a compute produces (LAMMPS's scalar_flag, size_vector, peratom_flag and
/// size_peratom_cols, extscalar/extvector).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Shape {
    pub scalar: bool,
    /// Length of the global vector (0: none).
    pub vector: usize,
    /// Per-atom values: None, Some(0) a per-atom vector, Some(n) an array of n columns.
    pub per_atom: Option<usize>,
    /// Whether the global scalar is extensive (divided by N with `thermo_modify norm yes`).
    pub extensive: bool,
    /// Whether the global vector is (LAMMPS's extvector).
    pub extensive_vector: bool,
}

/// What a compute reads when it is evaluated. Every rank evaluates the same computes
/// (the global values are collective).
pub struct Eval<'a> {
    pub sys: &'a System,
    pub units: &'a Units,
    /// pe is the pair energy (LAMMPS's pairwise styles), else the internal energy u.
    pub pair_energy: bool,
    /// The per-atom values, by owned particle, of an input of compute reduce: a particle
    /// keyword (x, vx, fx, ...), `c_ID`, `c_ID[k]` or `v_name` of an atom-style variable.
    pub input: &'a dyn Fn(&str) -> Result<Vec<f64>, String>,
}

/// The kinetic sums of a temperature compute: its degrees of freedom and the tensor
/// sum m v_a v_b (xx, yy, zz, xy, xz, yz) in energy units, LAMMPS's compute temp vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Temperature {
    pub dof: f64,
    pub tensor: [f64; 6],
}

impl Temperature {
    /// Twice the kinetic energy of the counted components (the trace).
    pub fn mv2(&self) -> f64 {
        self.tensor[0] + self.tensor[1] + self.tensor[2]
    }

    /// LAMMPS's temperature: mv2 / (dof k_B), zero without degrees of freedom.
    pub fn value(&self, kb: f64) -> f64 {
        if self.dof > 0.0 { self.mv2() / (self.dof * kb) } else { 0.0 }
    }
}

/// A compute style.
pub trait Compute: AsAny + std::fmt::Debug {
    fn id(&self) -> &str;
    /// LAMMPS's style name.
    fn style(&self) -> &'static str;
    fn shape(&self) -> Shape;
    /// The global scalar (collective).
    fn scalar(&self, _e: &Eval) -> Result<f64, String> {
        Err(format!("compute {} ({}) has no global scalar", self.id(), self.style()))
    }
    /// The global vector (collective).
    fn vector(&self, _e: &Eval) -> Result<Vec<f64>, String> {
        Err(format!("compute {} ({}) has no global vector", self.id(), self.style()))
    }
    /// Per-atom column `col` (0 of a per-atom vector, 1.. of an array) by owned particle,
    /// 0 outside the group (collective: neighbour computes swap ghosts).
    fn per_atom(&self, _e: &Eval, _col: usize) -> Result<Vec<f64>, String> {
        Err(format!("compute {} ({}) has no per-atom values", self.id(), self.style()))
    }
    /// A temperature compute's kinetic sums (thermo_modify temp, the pressure).
    fn temperature(&self, _e: &Eval) -> Option<Temperature> {
        None
    }
    /// Group bit mask and extra dof of a compute temp of a group (fix_modify temp of fix
    /// nph reads them).
    fn temp_group(&self) -> Option<(u32, f64)> {
        None
    }
    /// One `compute_modify` keyword (`key` read); false if the style has no such keyword.
    fn modify(&mut self, _key: &str, _a: &mut Args) -> Result<bool, ScriptError> {
        Ok(false)
    }
}

/// What a compute style's parser reads besides its own words: the group names by bit,
/// the lattice spacings (LAMMPS's default lattice has spacing 1), the particles so far
/// (compute msd records their positions), the regions and the computes defined so far
/// (compute reduce reads them).
pub struct ComputeContext<'a> {
    pub id: String,
    pub group: &'a str,
    pub groups: &'a [String],
    pub computes: &'a [Box<dyn Compute>],
    pub regions: &'a HashMap<String, Region>,
    pub ntypes: usize,
    pub spacing: gendpde_engine::Vec3,
    pub system: Option<&'a System>,
    pub max_tag: u64,
}

impl ComputeContext<'_> {
    pub fn mask(&self, a: &Args) -> Result<u32, ScriptError> {
        crate::base::groups::mask(self.groups, self.group, a)
    }

    /// The system, for a compute that reads the particles when it is defined.
    pub fn system(&self, a: &Args, style: &str) -> Result<&System, ScriptError> {
        self.system.ok_or_else(|| a.err(format!("compute {style} before the box exists (create_box, read_data or read_restart)")))
    }

    /// A region by ID (LAMMPS: "Region ID for compute STYLE does not exist").
    pub fn region(&self, a: &mut Args, style: &str) -> Result<Region, ScriptError> {
        let id = a.word("a region ID")?;
        self.regions.get(id).cloned().ok_or_else(|| a.err(format!("Region {id} for compute {style} does not exist")))
    }
}

/// What a `compute` command defines.
pub enum Definition {
    Compute(Box<dyn Compute>),
    Rdf(Rdf),
    Chunk(ChunkAtom),
}

impl Definition {
    pub fn id(&self) -> &str {
        match self {
            Self::Compute(c) => c.id(),
            Self::Rdf(r) => &r.id,
            Self::Chunk(c) => &c.id,
        }
    }
}

/// Parses the words after `compute ID GROUP NAME`.
type ParseCompute = fn(a: &mut Args, c: &ComputeContext) -> Result<Definition, ScriptError>;

fn unit(c: impl Compute + 'static) -> Result<Definition, ScriptError> {
    Ok(Definition::Compute(Box::new(c)))
}

/// Every compute style, with its parser.
pub const COMPUTE_STYLES: &[(&str, ParseCompute)] = &[
    ("dpd", |a, c| unit(dpd::Dpd::parse(a, c)?)),
    ("dpd/atom", |a, c| unit(dpd::DpdAtom::parse(a, c)?)),
    ("tint", |a, c| unit(dpd::Tint::parse(a, c)?)),
    ("temp", |a, c| unit(temp::Temp::parse(a, c, "temp")?)),
    ("temp/partial", |a, c| unit(temp::Temp::parse(a, c, "temp/partial")?)),
    ("temp/com", |a, c| unit(temp::Temp::parse(a, c, "temp/com")?)),
    ("temp/region", |a, c| unit(temp::Temp::parse(a, c, "temp/region")?)),
    ("com", |a, c| unit(com::Com::parse(a, c)?)),
    ("gyration", |a, c| unit(gyration::Gyration::parse(a, c)?)),
    ("count/type", |a, c| unit(count_type::CountType::parse(a, c)?)),
    ("ke/atom", |a, c| unit(property_atom::PropertyAtom::single(a, c, "ke/atom")?)),
    ("pe/atom", |a, c| unit(property_atom::PropertyAtom::single(a, c, "pe/atom")?)),
    ("edpd/temp/atom", |a, c| unit(property_atom::PropertyAtom::single(a, c, "edpd/temp/atom")?)),
    ("property/atom", |a, c| unit(property_atom::PropertyAtom::parse(a, c)?)),
    ("reduce", |a, c| unit(reduce::Reduce::parse(a, c, false)?)),
    ("reduce/region", |a, c| unit(reduce::Reduce::parse(a, c, true)?)),
    ("msd", |a, c| unit(msd::Msd::parse(a, c, "msd")?)),
    ("vacf", |a, c| unit(msd::Msd::parse(a, c, "vacf")?)),
    ("coord/atom", |a, c| unit(coord_atom::CoordAtom::parse(a, c)?)),
    ("cluster/atom", |a, c| unit(cluster_atom::ClusterAtom::parse(a, c)?)),
    ("rdf", |a, c| match c.group {
        "all" => Ok(Definition::Rdf(Rdf::parse(c.id.clone(), a)?)),
        group => Err(a.err(format!("compute rdf on group {group}: only group all is supported"))),
    }),
    ("chunk/atom", |a, c| Ok(Definition::Chunk(ChunkAtom::parse(c.id.clone(), c.mask(a)?, a, c.spacing)?))),
];

/// `compute ID GROUP STYLE args...` with what the parsers read besides the words
/// ([`ComputeContext`] without its `id` and `group`, which are read here).
pub fn parse(a: &mut Args, mut c: ComputeContext) -> Result<Definition, ScriptError> {
    c.id = a.word("a compute ID")?.to_string();
    let group = a.word("a group")?;
    let c = ComputeContext { group, ..c };
    let name = a.word("a compute style")?;
    match COMPUTE_STYLES.iter().find(|(n, _)| *n == name) {
        Some((_, parse)) => parse(a, &c),
        None => {
            let known: Vec<&str> = COMPUTE_STYLES.iter().map(|(n, _)| *n).collect();
            Err(a.err(format!("unknown compute style '{name}'; known: {}", known.join(", "))))
        }
    }
}

/// A reference `c_ID`, `c_ID[k]` (k from 1), `f_ID[k]` or `v_NAME[k]` split into its kind
/// ('c', 'f', 'v'), ID and index (None: no brackets). `[*]` gives index 0.
pub fn reference(name: &str) -> Option<(char, &str, Option<usize>)> {
    let kind = match name.get(..2)? {
        "c_" => 'c',
        "f_" => 'f',
        "v_" => 'v',
        _ => return None,
    };
    let rest = &name[2..];
    match rest.strip_suffix(']').and_then(|r| r.split_once('[')) {
        Some((id, "*")) => Some((kind, id, Some(0))),
        Some((id, k)) => Some((kind, id, Some(k.parse::<usize>().ok().filter(|&k| k > 0)?))),
        None => Some((kind, rest, None)),
    }
}

/// Finds compute `id`.
pub fn find<'a>(computes: &'a [Box<dyn Compute>], id: &str) -> Option<&'a dyn Compute> {
    computes.iter().find(|c| c.id() == id).map(|c| c.as_ref())
}

/// Global value `c_ID` (the scalar) or `c_ID[k]` (vector element k), and whether it is
/// extensive; None if `name` names no such value. Collective.
pub fn global(computes: &[Box<dyn Compute>], e: &Eval, name: &str) -> Option<Result<(f64, bool), String>> {
    let ('c', id, index) = reference(name)? else { return None };
    let c = find(computes, id)?;
    let shape = c.shape();
    let value = match index {
        None if shape.scalar => c.scalar(e).map(|v| (v, shape.extensive)),
        Some(k) if (1..=shape.vector).contains(&k) => c.vector(e).map(|v| (v[k - 1], shape.extensive_vector)),
        _ => return None,
    };
    Some(value)
}

/// Per-atom values `c_ID` (a per-atom vector) or `c_ID[k]` (column k of a per-atom array)
/// by owned particle; None if `name` names no such values. Collective.
pub fn per_atom(computes: &[Box<dyn Compute>], e: &Eval, name: &str) -> Option<Result<Vec<f64>, String>> {
    let ('c', id, index) = reference(name)? else { return None };
    let c = find(computes, id)?;
    match (c.shape().per_atom?, index) {
        (0, None) => Some(c.per_atom(e, 0)),
        (n, Some(k)) if (1..=n).contains(&k) => Some(c.per_atom(e, k)),
        _ => None,
    }
}

/// Checks that `name` (`c_ID` or `c_ID[k]`) names per-atom values of a compute so far, for
/// the input of `what` (e.g. "compute reduce"), with LAMMPS's messages.
pub fn check_per_atom(computes: &[Box<dyn Compute>], name: &str, what: &str) -> Result<(), String> {
    let Some(('c', id, index)) = reference(name) else { return Err(format!("{name}: expected c_ID or c_ID[k]")) };
    let c = find(computes, id).ok_or_else(|| format!("Compute ID {id} for {} does not exist", what.to_lowercase()))?;
    match (c.shape().per_atom, index) {
        (None, _) => Err(format!("{what} compute {id} does not calculate per-atom values")),
        (Some(0), None) => Ok(()),
        (Some(0), Some(_)) => Err(format!("{what} compute {id} does not calculate a per-atom array")),
        (Some(_), None) => Err(format!("{what} compute {id} does not calculate a per-atom vector")),
        (Some(n), Some(k)) if k > n || k == 0 => Err(format!("{what} compute {id} array is accessed out-of-range")),
        _ => Ok(()),
    }
}

/// `compute_modify ID KEYWORD VALUE ...`: LAMMPS's extra/dof (extra) and dynamic/dof
/// (dynamic) of temperature computes.
pub fn modify(computes: &mut [Box<dyn Compute>], a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a compute ID")?;
    let c = computes.iter_mut().find(|c| c.id() == id).ok_or_else(|| a.err(format!("Could not find compute_modify ID {id}")))?;
    if a.remaining() == 0 {
        return Err(a.err("Illegal compute_modify command: expected a keyword (extra/dof, dynamic/dof)"));
    }
    while a.remaining() > 0 {
        let key = a.word("a keyword")?;
        if c.modify(key, a)? {
            continue;
        }
        // LAMMPS takes both for every compute; only temperatures read them
        match key {
            "extra/dof" | "extra" => drop(a.f64("the extra degrees of freedom")?),
            "dynamic/dof" | "dynamic" => drop(a.yes_no("dynamic/dof")?),
            _ => return Err(a.err(format!("Compute {id} {} does not support compute_modify {key} command", c.style()))),
        }
    }
    Ok(())
}
