//! Compute styles: `compute ID all dpd` and `compute ID GROUP tint`, global values read
//! in thermo output as `c_ID` or `c_ID[k]`, and `compute ID all rdf` ([`rdf`], read by
//! fix ave/time).

pub mod rdf;

use self::rdf::Rdf;
use crate::base::args::Args;
use crate::styles::COMPUTE_STYLES;
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
}

/// What a `compute` command defines.
pub enum Definition {
    Value(Compute),
    Rdf(Rdf),
}

impl Definition {
    pub fn id(&self) -> &str {
        match self {
            Self::Value(c) => &c.id,
            Self::Rdf(r) => &r.id,
        }
    }
}

/// The words of `compute ID GROUP STYLE args...`; `groups` are the group names by bit.
pub fn parse(a: &mut Args, groups: &[String]) -> Result<Definition, ScriptError> {
    let id = a.word("a compute ID")?.to_string();
    let group = a.word("a group")?;
    let style = match a.word("a compute style")? {
        "dpd" if group == "all" => ComputeStyle::Dpd,
        "dpd" => return Err(a.err(format!("compute dpd on group '{group}': only group all is supported"))),
        "tint" => ComputeStyle::Tint { mask: crate::base::groups::mask(groups, group, a)? },
        "rdf" if group == "all" => return Ok(Definition::Rdf(Rdf::parse(id, a)?)),
        "rdf" => return Err(a.err(format!("compute rdf on group {group}: only group all is supported"))),
        other => return Err(a.err(format!("unknown compute style '{other}'; known: {COMPUTE_STYLES}"))),
    };
    a.done()?;
    Ok(Definition::Value(Compute { id, style }))
}

/// The global sums a thermo line needs from the whole system (`output::thermo`).
pub struct Totals {
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
    }
}
