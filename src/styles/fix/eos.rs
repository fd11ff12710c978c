//! The particle EOS of `fix ID all eos/MODEL ...`: the analytic models of
//! `potentials/src/eos/`, their tables (`table` keyword) and one EOS per type
//! (`eos/cv CV1 CV2 ...`).
//!
//! A new EOS is one file in `potentials/src/eos/`, one arm in `parse_model` and, if it
//! is a new Rust type, one variant of [`EosModel`] with its arms in [`each_eos`] and
//! the builders of the pair styles that take an EOS (`styles::pair::gendpde`,
//! `styles::pair::sdpd_generic`; see docs/ARCHITECTURE.md).

use crate::base::args::Args;
use gendpde_io::ScriptError;
use gendpde_potentials::eos::Lth;
use gendpde_potentials::{Eos, LennardJones, LinearTheta, TableError, TableErrors, TableGrid, Tabulated};

/// The EOS fix styles (the arms of `parse_model`).
pub const EOS_STYLES: &[&str] = &["eos/vdw", "eos/vdw/reduced", "eos/lj", "eos/lth", "eos/ideal", "eos/cv", "eos/density", "eos/linear"];

/// A particle EOS chosen by a `fix eos/...`, analytic or through a table (`table`
/// keyword).
#[derive(Clone, Debug, PartialEq)]
pub enum EosModel {
    Linear(LinearTheta),
    Lj(LennardJones),
    Lth(Lth),
    LinearTable(Tabulated<LinearTheta>),
    LjTable(Tabulated<LennardJones>),
    LthTable(Tabulated<Lth>),
    /// `eos/cv CV1 CV2 ...`: one linear EOS per particle type (index type - 1).
    PerType(Vec<LinearTheta>),
}

/// Evaluates `$body` with `$e` bound to the concrete EOS of `$model`.
macro_rules! each_eos {
    ($model:expr, $e:ident => $body:expr) => {
        match $model {
            $crate::styles::fix::eos::EosModel::Linear($e) => $body,
            $crate::styles::fix::eos::EosModel::Lj($e) => $body,
            $crate::styles::fix::eos::EosModel::Lth($e) => $body,
            $crate::styles::fix::eos::EosModel::LinearTable($e) => $body,
            $crate::styles::fix::eos::EosModel::LjTable($e) => $body,
            $crate::styles::fix::eos::EosModel::LthTable($e) => $body,
            // describe and bound by type 1 (build_physics takes every type)
            $crate::styles::fix::eos::EosModel::PerType(v) => {
                let $e = &v[0];
                $body
            }
        }
    };
}
pub(crate) use each_eos;


impl EosModel {
    /// Largest mean number density the model admits, if bounded.
    pub fn max_density(&self) -> Option<f64> {
        each_eos!(self, e => e.max_density())
    }

    /// The state at (theta, n), or at (u, n) when `u` is given: `name value` pairs as
    /// `gendpde eos` prints them (with the table's measured errors for a table).
    pub fn describe(&self, theta: Option<f64>, u: Option<f64>, n: f64) -> Result<Vec<(&'static str, f64)>, String> {
        let mut out = each_eos!(self, e => describe(e, theta, u, n))?;
        if let Some(err) = self.table_errors() {
            out.extend([("table_error_u", err.u.rel), ("table_error_pn2", err.pn2.rel), ("table_error_cv", err.cv.rel), ("table_error_theta", err.theta.rel)]);
        }
        Ok(out)
    }

    /// The largest relative errors of a table against its analytic model, sampled at 4 x 4
    /// states per cell (None for an analytic model).
    pub fn table_errors(&self) -> Option<TableErrors> {
        match self {
            Self::LinearTable(t) => Some(t.max_error(4)),
            Self::LjTable(t) => Some(t.max_error(4)),
            Self::LthTable(t) => Some(t.max_error(4)),
            _ => None,
        }
    }

    /// Replaces the model by its table on `grid`.
    fn tabulate(self, grid: TableGrid) -> Result<Self, TableError> {
        Ok(match self {
            Self::Linear(e) => Self::LinearTable(Tabulated::new(e, grid)?),
            Self::Lj(e) => Self::LjTable(Tabulated::new(e, grid)?),
            Self::Lth(e) => Self::LthTable(Tabulated::new(e, grid)?),
            Self::PerType(_) => return Err(TableError::Grid("a table of a per-type EOS (give one C_V)".into())),
            table => table,
        })
    }
}

/// u, theta, n, the particle (excess) pressure pi, the total pressure n k_B theta + pi,
/// C_V, the dressed temperature tau (eq 23) and the entropy s.
fn describe<E: Eos>(eos: &E, theta: Option<f64>, u: Option<f64>, n: f64) -> Result<Vec<(&'static str, f64)>, String> {
    let u = match (theta, u) {
        (_, Some(u)) => u,
        (Some(t), None) => eos.u(t, n),
        (None, None) => return Err("give --theta or --u".into()),
    };
    let st = eos.state(u, n, theta.unwrap_or(1.0)).map_err(|e| e.to_string())?;
    let pi = st.pn2 * n * n;
    let mut out = vec![("u", u), ("theta", st.theta), ("n", n), ("pi", pi), ("pressure", n * eos.kb() * st.theta + pi), ("cv", st.cv)];
    out.push(("tau", 1.0 / eos.inv_tau(st.theta, st.cv)));
    out.push(("s", eos.entropy(u, n).unwrap_or(f64::NAN)));
    Ok(out)
}

/// The EOS fixes: `eos/vdw CV A B [excess|full] [cap F]`, `eos/lj CV`, `eos/ideal CV`, `eos/cv CV`,
/// `eos/density CV c1 [c2 ...]`, `eos/linear CV Q R B [c1 ...]`,
/// `eos/lth CV ALPHA KAPPA_T PI00 THETA0 N00`, each optionally followed by
/// `table THETA_MIN THETA_MAX N_THETA N_MIN N_MAX N_N`.
pub fn parse_eos(style: &str, a: &mut Args, kb: f64) -> Result<EosModel, ScriptError> {
    let model = parse_model(style, a, kb)?;
    if a.peek() != Some("table") {
        return Ok(model);
    }
    a.word("keyword")?;
    let theta = (a.positive("the table's smallest theta")?, a.positive("the table's largest theta")?, a.u64("the number of theta nodes")? as usize);
    let n = (a.non_negative("the table's smallest density")?, a.positive("the table's largest density")?, a.u64("the number of density nodes")? as usize);
    if let Some(w) = a.peek() {
        return Err(a.err(format!("unexpected '{w}' after the table grid")));
    }
    let table = model.tabulate(TableGrid { theta, n }).map_err(|e| a.err(e.to_string()))?;
    if let Some(err) = table.table_errors() {
        log::info!("EOS table: {err}");
    }
    Ok(table)
}

fn parse_model(style: &str, a: &mut Args, kb: f64) -> Result<EosModel, ScriptError> {
    if style == "eos/vdw/reduced" {
        return vdw_reduced(a, kb);
    }
    let cv = a.positive("the heat capacity C_V")?;
    if cv <= kb {
        return Err(a.err(format!("C_V = {cv:?} must exceed k_B = {kb:?} (the dressed temperature of eq 23 diverges at C_V = k_B)")));
    }
    let mut eos = match style {
        "eos/vdw" => {
            let (va, b) = (a.non_negative("the vdW attraction a")?, a.positive("the vdW excluded volume b")?);
            let mut e = LinearTheta::vdw_excess(cv, va, b);
            while let Some(k) = a.peek().filter(|&k| k != "table") {
                a.word("keyword")?;
                match k {
                    "excess" => e = LinearTheta { cap: e.cap, ..LinearTheta::vdw_excess(cv, va, b) },
                    "full" => e = LinearTheta { cap: e.cap, ..LinearTheta::vdw_full(cv, va, b) },
                    "cap" => {
                        let f = a.positive("the cap fraction of 1/b")?;
                        if f >= 1.0 {
                            return Err(a.err(format!("cap {f:?} must lie below 1 (a fraction of 1/b)")));
                        }
                        e.cap = f;
                    }
                    _ => return Err(a.err(format!("unknown keyword '{k}'; known: excess, full, cap, table"))),
                }
            }
            e
        }
        "eos/lj" if kb != 1.0 => return Err(a.err("eos/lj is in reduced Lennard-Jones units: use units lj")),
        "eos/lj" => return Ok(EosModel::Lj(LennardJones::new(cv))),
        "eos/lth" => {
            let alpha = a.f64("the particle expansion coefficient alpha")?;
            let kappa_t = a.positive("the particle compressibility kappa_T")?;
            let pi00 = a.f64("the reference particle pressure pi00")?;
            let theta0 = a.positive("the reference temperature theta0")?;
            let n00 = a.positive("the reference density n00")?;
            return Ok(EosModel::Lth(Lth { kb, ..Lth::new(cv, alpha, kappa_t, pi00, theta0, n00) }));
        }
        "eos/ideal" => LinearTheta::ideal(cv),
        "eos/cv" => {
            let mut per_type = vec![LinearTheta { kb, ..LinearTheta::cv_only(cv) }];
            while a.remaining() > 0 && a.peek() != Some("table") {
                let cv = a.positive("the heat capacity C_V of the next type")?;
                if cv <= kb {
                    return Err(a.err(format!("C_V = {cv:?} must exceed k_B = {kb:?}")));
                }
                per_type.push(LinearTheta { kb, ..LinearTheta::cv_only(cv) });
            }
            if per_type.len() > 1 {
                return Ok(EosModel::PerType(per_type));
            }
            LinearTheta::cv_only(cv)
        }
        "eos/density" => LinearTheta::density_only(cv, coefficients(a)?),
        "eos/linear" => {
            let q = a.f64("the exponent q of n in psi")?;
            let r = a.f64("the exponent r of 1/(1 - b n) in psi")?;
            let b = a.non_negative("the excluded volume b")?;
            LinearTheta { q, r, b, v_coeffs: coefficients(a)?, ..LinearTheta::cv_only(cv) }
        }
        other => return Err(a.err(format!("unknown EOS fix '{other}'; known: {}", EOS_STYLES.join(", ")))),
    };
    eos.cv = cv;
    eos.kb = kb;
    Ok(EosModel::Linear(eos))
}

/// `eos/vdw/reduced N0 [dim D] [cap F]`: a fluid particle of N0 van der Waals molecules
/// in the reduced units of Serrano-Espanol eqs 160-162 (k_B T~, n~ = 3 b n; energies in
/// 8a/27b, so k_B = 1): u = N0 (D/2) theta - (9/8) N0^2 n, P = n~ theta/(1 - n~/3) -
/// (9/8) n~^2 = (3/8) P~ with n~ = N0 n (eqs 157-159). The linear family with
/// C_V = N0 D/2, q = r = N0, b = N0/3, V(n) = -(9/8) N0^2 n; the constant c of eq 163
/// only shifts each particle's entropy.
fn vdw_reduced(a: &mut Args, kb: f64) -> Result<EosModel, ScriptError> {
    if kb != 1.0 {
        return Err(a.err("eos/vdw/reduced is in the reduced units of eqs 160-162 (k_B = 1): use units lj"));
    }
    let n0 = a.positive("the molecules per particle N0")?;
    let mut dim = 3.0;
    let mut cap = gendpde_potentials::eos::DEFAULT_CAP;
    while let Some(k) = a.peek().filter(|&k| k != "table") {
        a.word("keyword")?;
        match k {
            "dim" => dim = a.positive("the dimension D")?,
            "cap" => {
                cap = a.positive("the cap fraction of 1/b")?;
                if cap >= 1.0 {
                    return Err(a.err(format!("cap {cap:?} must lie below 1 (a fraction of 1/b)")));
                }
            }
            _ => return Err(a.err(format!("unknown keyword '{k}'; known: dim, cap, table"))),
        }
    }
    let cv = n0 * dim / 2.0;
    if cv <= kb {
        return Err(a.err(format!("C_V = N0 D/2 = {cv:?} must exceed k_B = 1")));
    }
    Ok(EosModel::Linear(LinearTheta { q: n0, r: n0, b: n0 / 3.0, v_coeffs: vec![-9.0 / 8.0 * n0 * n0], cap, ..LinearTheta::cv_only(cv) }))
}

fn coefficients(a: &mut Args) -> Result<Vec<f64>, ScriptError> {
    let mut c = Vec::new();
    while a.remaining() > 0 && a.peek() != Some("table") {
        c.push(a.f64("a coefficient c_k of V(n) = sum_k c_k n^k")?);
    }
    Ok(c)
}
