//! Compute styles: `compute ID all dpd`, `compute ID GROUP tint` and `compute ID GROUP
//! temp`, global values read in thermo output as `c_ID` or `c_ID[k]`, `compute ID all rdf` ([`rdf`], read by
//! fix ave/time) and `compute ID GROUP chunk/atom` ([`chunk`], read by fix ave/chunk).

pub mod chunk;
pub mod com;
pub mod msd;
pub mod rdf;
pub mod reduce;

use self::chunk::ChunkAtom;
use self::msd::Msd;
use self::reduce::Reduce;
use self::rdf::Rdf;
use crate::base::args::Args;
use gendpde_engine::exact_sums;
use gendpde_integrators::System;
use gendpde_io::ScriptError;

/// A defined compute.
#[derive(Clone, Debug, PartialEq)]
pub struct Compute {
    pub id: String,
    pub style: ComputeStyle,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ComputeStyle {
    /// LAMMPS's compute dpd (group all): sum uCond, sum uMech, 0, N / sum(1/theta), N.
    Dpd,
    /// Over a group (bit `mask`, `u32::MAX` for all): mean theta, mean u, count.
    Tint { mask: u32 },
    /// LAMMPS's compute temp of a group: sum m v^2 / (dof k_B) with dof = 3 N_group -
    /// `extra_dof` (3 unless `compute_modify ID extra/dof`).
    Temp { mask: u32, extra_dof: f64 },
    /// LAMMPS's compute com: the group's centre of mass from unwrapped positions.
    Com { mask: u32 },
    /// LAMMPS's compute ke/atom: m v^2 / 2 (0 outside the group).
    KeAtom { mask: u32 },
    /// LAMMPS's compute pe/atom: half the energy of each pair a particle is in (pairwise
    /// styles), or its internal energy u (GenDPDE, whose pe is the sum of u); 0 outside
    /// the group.
    PeAtom { mask: u32 },
    /// LAMMPS DPD-MESO's compute edpd/temp/atom: the eDPD temperature T (0 outside the
    /// group).
    EdpdTempAtom { mask: u32 },
}

/// The kinetic sums of a group: its count and the diagonal of sum p p^T / m.
#[derive(Clone, Copy, Debug)]
pub struct Kinetic {
    pub count: f64,
    pub mv2_diag: [f64; 3],
}

impl Kinetic {
    /// Sums over the particles of group bit `mask` on all ranks (collective).
    pub fn measure(sys: &System, mask: u32) -> Self {
        let s = &sys.store;
        let rows = (0..s.nlocal).filter(|&i| s.in_group(i, mask)).map(|i| {
            let (p, m) = (s.p[i], s.mass[i]);
            [1.0, p[0] * p[0] / m, p[1] * p[1] / m, p[2] * p[2] / m]
        });
        let [count, xx, yy, zz] = exact_sums(sys.comm.transport(), rows);
        Self { count, mv2_diag: [xx, yy, zz] }
    }

    pub fn mv2(&self) -> f64 {
        self.mv2_diag.iter().sum()
    }

    /// LAMMPS's temperature with dof = 3 N - `extra_dof` (zero without degrees of freedom).
    pub fn temperature(&self, kb: f64, extra_dof: f64) -> f64 {
        let dof = 3.0 * self.count - extra_dof;
        if dof > 0.0 { self.mv2() / (dof * kb) } else { 0.0 }
    }
}

/// What a `compute` command defines.
pub enum Definition {
    Value(Compute),
    Rdf(Rdf),
    Chunk(ChunkAtom),
    Msd(Msd),
    Reduce(Reduce),
}

impl Definition {
    pub fn id(&self) -> &str {
        match self {
            Self::Value(c) => &c.id,
            Self::Rdf(r) => &r.id,
            Self::Chunk(c) => &c.id,
            Self::Msd(m) => &m.id,
            Self::Reduce(r) => &r.id,
        }
    }
}

/// What a compute style's parser reads besides its own words: the group names by bit,
/// the lattice spacings (LAMMPS's default lattice has spacing 1), the particles so far
/// (compute msd records their positions) and the computes defined so far (compute
/// reduce reads them).
pub struct ComputeContext<'a> {
    pub id: String,
    pub group: &'a str,
    pub groups: &'a [String],
    pub computes: &'a [Compute],
    pub spacing: gendpde_engine::Vec3,
    pub system: Option<&'a System>,
    pub max_tag: u64,
}

impl ComputeContext<'_> {
    fn mask(&self, a: &Args) -> Result<u32, ScriptError> {
        crate::base::groups::mask(self.groups, self.group, a)
    }

    /// A global or per-atom value compute of style `style` (no more words).
    fn value(&self, a: &mut Args, style: ComputeStyle) -> Result<Definition, ScriptError> {
        a.done()?;
        Ok(Definition::Value(Compute { id: self.id.clone(), style }))
    }
}

/// Parses the words after `compute ID GROUP NAME`.
type ParseCompute = fn(a: &mut Args, c: &ComputeContext) -> Result<Definition, ScriptError>;

/// Every compute style, with its parser.
pub const COMPUTE_STYLES: &[(&str, ParseCompute)] = &[
    ("dpd", |a, c| match c.group {
        "all" => c.value(a, ComputeStyle::Dpd),
        group => Err(a.err(format!("compute dpd on group '{group}': only group all is supported"))),
    }),
    ("tint", |a, c| c.value(a, ComputeStyle::Tint { mask: c.mask(a)? })),
    ("temp", |a, c| c.value(a, ComputeStyle::Temp { mask: c.mask(a)?, extra_dof: 3.0 })),
    ("com", |a, c| c.value(a, ComputeStyle::Com { mask: c.mask(a)? })),
    ("ke/atom", |a, c| c.value(a, ComputeStyle::KeAtom { mask: c.mask(a)? })),
    ("pe/atom", |a, c| {
        // LAMMPS's keywords select energy terms; gendpde's pair (or internal) energy is all of pe
        while let Some(k) = a.peek() {
            match k {
                "pair" | "bond" | "angle" | "dihedral" | "improper" | "kspace" | "fix" => a.word("a keyword")?,
                k => return Err(a.err(format!("unknown keyword '{k}'; known: pair, bond, angle, dihedral, improper, kspace, fix"))),
            };
        }
        c.value(a, ComputeStyle::PeAtom { mask: c.mask(a)? })
    }),
    ("reduce", |a, c| {
        let per_atom = |cid: &str| c.computes.iter().find(|k| k.id == cid).map(Compute::is_per_atom);
        Ok(Definition::Reduce(Reduce::parse(c.id.clone(), c.mask(a)?, a, per_atom)?))
    }),
    ("rdf", |a, c| match c.group {
        "all" => Ok(Definition::Rdf(Rdf::parse(c.id.clone(), a)?)),
        group => Err(a.err(format!("compute rdf on group {group}: only group all is supported"))),
    }),
    ("chunk/atom", |a, c| Ok(Definition::Chunk(ChunkAtom::parse(c.id.clone(), c.mask(a)?, a, c.spacing)?))),
    ("msd", |a, c| {
        let sys = c.system.ok_or_else(|| a.err("compute msd before the box exists (create_box, read_data or read_restart)"))?;
        Ok(Definition::Msd(Msd::parse(c.id.clone(), c.mask(a)?, a, sys, c.max_tag)?))
    }),
    ("edpd/temp/atom", |a, c| c.value(a, ComputeStyle::EdpdTempAtom { mask: c.mask(a)? })),
];

/// `compute ID GROUP STYLE args...` with what the parsers read besides the words
/// ([`ComputeContext`], whose `id` and `group` are read here).
pub fn parse(a: &mut Args, groups: &[String], computes: &[Compute], spacing: gendpde_engine::Vec3, system: Option<&System>, max_tag: u64) -> Result<Definition, ScriptError> {
    let id = a.word("a compute ID")?.to_string();
    let group = a.word("a group")?;
    let name = a.word("a compute style")?;
    let c = ComputeContext { id, group, groups, computes, spacing, system, max_tag };
    match COMPUTE_STYLES.iter().find(|(n, _)| *n == name) {
        Some((_, parse)) => parse(a, &c),
        None => {
            let known: Vec<&str> = COMPUTE_STYLES.iter().map(|(n, _)| *n).collect();
            Err(a.err(format!("unknown compute style '{name}'; known: {}", known.join(", "))))
        }
    }
}

impl Compute {
    /// Whether it has per-atom values (ke/atom, pe/atom) and no global ones.
    pub fn is_per_atom(&self) -> bool {
        matches!(self.style, ComputeStyle::KeAtom { .. } | ComputeStyle::PeAtom { .. } | ComputeStyle::EdpdTempAtom { .. })
    }

    /// The value of particle `i` of a per-atom compute (ke/atom, pe/atom, edpd/temp/atom; 0 outside its
    /// group), None for global computes. `mvv2e` converts m v^2 to energy; `pair_energy`:
    /// pe is the pair energy (pairwise styles), else the internal energy u.
    pub fn per_atom(&self, sys: &System, i: usize, mvv2e: f64, pair_energy: bool) -> Option<f64> {
        let s = &sys.store;
        let (mask, pe) = match self.style {
            ComputeStyle::KeAtom { mask } => (mask, false),
            ComputeStyle::PeAtom { mask } => (mask, true),
            ComputeStyle::EdpdTempAtom { mask } => return Some(if s.in_group(i, mask) { s.edpd_temp.get(i).copied().unwrap_or(0.0) } else { 0.0 }),
            _ => return None,
        };
        Some(match (s.in_group(i, mask), pe) {
            (false, _) => 0.0,
            (true, false) => 0.5 * mvv2e * s.p[i].iter().map(|p| p * p).sum::<f64>() / s.mass[i],
            (true, true) if pair_energy => s.epair.get(i).copied().unwrap_or(0.0),
            (true, true) => s.u[i],
        })
    }
}

/// The global sums a thermo line needs from the whole system (`output::thermo`).
pub struct Totals {
    /// Boltzmann's constant of the units.
    pub kb: f64,
    pub atoms: f64,
    pub u: f64,
    pub u_cond: f64,
    pub inv_theta: f64,
}

/// Value of `c_ID` (= `c_ID[1]`) or `c_ID[k]`; None if `name` is no such reference.
/// Collective: every rank must evaluate the same names.
pub fn value(computes: &[Compute], sys: &System, totals: &Totals, name: &str) -> Option<f64> {
    let rest = name.strip_prefix("c_")?;
    let (id, k) = match rest.strip_suffix(']').and_then(|r| r.split_once('[')) {
        Some((id, k)) => (id, k.parse::<usize>().ok()?),
        None => (rest, 1),
    };
    let c = computes.iter().find(|c| c.id == id)?;
    match c.style {
        ComputeStyle::Dpd => Some(match k {
            1 => totals.u_cond,
            2 => totals.u - totals.u_cond,
            3 => 0.0,
            4 => totals.atoms / totals.inv_theta,
            5 => totals.atoms,
            _ => return None,
        }),
        ComputeStyle::Tint { mask } => {
            if !(1..=3).contains(&k) {
                return None;
            }
            let s = &sys.store;
            let rows = (0..s.nlocal).filter(|&i| s.in_group(i, mask)).map(|i| [1.0, s.theta[i], s.u[i]]);
            let [count, theta, u] = exact_sums(sys.comm.transport(), rows);
            let mean = |x: f64| if count > 0.0 { x / count } else { 0.0 };
            Some([mean(theta), mean(u), count][k - 1])
        }
        // the scalar only (LAMMPS's vector, the kinetic energy tensor, is not provided)
        ComputeStyle::Temp { mask, extra_dof } => (rest == id).then(|| Kinetic::measure(sys, mask).temperature(totals.kb, extra_dof)),
        // the vector only, as LAMMPS
        ComputeStyle::Com { mask } => (rest != id && (1..=3).contains(&k)).then(|| com::centre_of_mass(sys, mask)[k - 1]),
        // per-atom values only (compute reduce)
        ComputeStyle::KeAtom { .. } | ComputeStyle::PeAtom { .. } | ComputeStyle::EdpdTempAtom { .. } => None,
    }
}

/// `c_ID[k]` (k = 1..4) of a compute msd; None if `name` is no such reference.
/// Collective.
pub fn msd_value(msds: &[Msd], sys: &System, name: &str) -> Option<f64> {
    let (id, k) = name.strip_prefix("c_")?.strip_suffix(']')?.split_once('[')?;
    let k = k.parse::<usize>().ok().filter(|k| (1..=4).contains(k))?;
    Some(msds.iter().find(|m| m.id == id)?.vector(sys)[k - 1])
}

/// `c_ID` or `c_ID[k]` of a compute reduce and whether it is extensive (divided by the
/// particle count with `thermo_modify norm yes`); None if `name` is no such reference.
/// Collective; `mvv2e` and `pair_energy` as for [`Compute::per_atom`].
/// `variable(name)` gives the values of an atom-style variable per owned particle (None:
/// no such variable, or its evaluation fails).
pub fn reduce_value(reduces: &[Reduce], computes: &[Compute], sys: &System, mvv2e: f64, pair_energy: bool, variable: &dyn Fn(&str) -> Option<Vec<f64>>, name: &str) -> Option<(f64, bool)> {
    let (r, k) = reduces.iter().find_map(|r| Some((r, r.index(name)?)))?;
    if let Some(v) = r.variable_input(k) {
        let values = variable(v)?;
        return Some((r.value(k, sys, |i| values[i]), r.extensive()));
    }
    // None if the per-atom compute was redefined as another style
    let compute = match r.compute_input(k) {
        Some(cid) => Some(computes.iter().find(|c| c.id == cid && c.is_per_atom())?),
        None => None,
    };
    let per_atom = |i| compute.and_then(|c| c.per_atom(sys, i, mvv2e, pair_energy)).unwrap_or(0.0);
    Some((r.value(k, sys, per_atom), r.extensive()))
}

/// `compute_modify ID extra/dof N` (or `extra N`) of a compute temp.
pub fn modify(computes: &mut [Compute], a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a compute ID")?;
    let c = computes.iter_mut().find(|c| c.id == id).ok_or_else(|| a.err(format!("no compute with ID '{id}'")))?;
    let ComputeStyle::Temp { extra_dof, .. } = &mut c.style else {
        return Err(a.err(format!("compute {id}: compute_modify applies to compute temp only")));
    };
    if a.remaining() == 0 {
        return Err(a.err("missing argument: expected extra/dof"));
    }
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "extra/dof" | "extra" => *extra_dof = a.f64("the extra degrees of freedom")?,
            k => return Err(a.err(format!("unknown keyword '{k}'; known: extra/dof"))),
        }
    }
    Ok(())
}
