//! Pair styles, each one unit: a file per style family parses `pair_style` and
//! `pair_coeff`, answers what the rest of the program asks of a pair style ([`Pair`]) and
//! builds the dynamics of a run from itself and the fixes it works with. [`PAIR_STYLES`]
//! is the one list of them: GenDPDE ([`gendpde`]), LAMMPS's pairwise DPD styles
//! ([`pairwise`]), tabulated potentials ([`table`], [`multi_lucy`]) and their overlays
//! ([`hybrid`]), eDPD ([`edpd`]), SDPD ([`sdpd_generic`], [`sdpd_taitwater`]) and Voronoi
//! fluid particles ([`voronoi`]).

pub mod edpd;
pub mod gendpde;
pub mod hybrid;
pub mod multi_lucy;
pub mod pairwise;
pub mod sdpd_generic;
pub mod sdpd_taitwater;
pub mod table;
pub mod type_pairs;
pub mod voronoi;

use crate::base::args::Args;
use crate::styles::fix::{Fix, FixStyle};
use gendpde_integrators::{Physics, RebuildPolicy, Settings};
use gendpde_io::{Command, PairCoeffs, ScriptError};
use std::any::Any;

/// What the program asks of a pair style, besides building its dynamics.
pub trait Pair: AsAny + std::fmt::Debug {
    /// The style's name, as `pair_style` gives it.
    fn name(&self) -> &str;
    /// `pair_coeff I J args...` for this style.
    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError>;
    /// Whether a fix of this style acts on this pair style.
    fn accepts(&self, fix: &FixStyle) -> bool;
    /// The fix styles it works with, as the message refusing another lists them.
    fn fixes(&self) -> &'static str;
    /// The dynamics of a run from the style and its fixes (all accepted).
    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String>;
    /// Whether thermo `pe` is the pair energy (LAMMPS's pairwise styles) rather than the
    /// internal energy of the particles' EOS.
    fn pe_is_pair(&self) -> bool {
        true
    }
    /// `pair_style` naming the style in force (`old`) again: as LAMMPS
    /// (`Input::pair_style` calls only the style's `settings()`), the coefficients stay
    /// and every cutoff a `pair_coeff` set is reset to the new global cutoff. False
    /// (nothing taken) where LAMMPS's `settings()` discards them too.
    fn keep_coefficients(&mut self, _old: &dyn Pair) -> bool {
        false
    }
    /// The `Pair Coeffs` (`ij` false) or `PairIJ Coeffs` section `write_data` writes
    /// (none by default: in LAMMPS only `pair dpd` writes one of these styles).
    fn data_section(&self, _ntypes: usize, _ij: bool) -> Result<Option<PairCoeffs>, String> {
        Ok(None)
    }
}

/// A style as `Any`, so that [`Pair::keep_coefficients`] can tell whether the style in
/// force is of its own type.
pub trait AsAny {
    fn as_any(&self) -> &dyn Any;
}

impl<T: Any> AsAny for T {
    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// Parses the words after `pair_style NAME` into the style.
type ParseStyle = fn(name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError>;

/// Every pair style: its name and its parser.
pub const PAIR_STYLES: &[(&str, ParseStyle)] = &[
    ("gendpde", gendpde::parse_style),
    ("sdpd/generic", sdpd_generic::parse_style),
    ("sdpd/taitwater/isothermal", sdpd_taitwater::parse_style),
    ("voronoi/fv", voronoi::parse_style),
    ("dpd", pairwise::parse_style),
    ("dpd/ext", pairwise::parse_style),
    ("dpd/tstat", pairwise::parse_style),
    ("dpd/ext/tstat", pairwise::parse_style),
    ("dpd/fdt", pairwise::parse_style),
    ("dpd/fdt/energy", pairwise::parse_style),
    ("table", table::parse_style),
    ("multi/lucy", multi_lucy::parse_style),
    ("hybrid/overlay", hybrid::parse_style),
    ("hybrid", hybrid::parse_style),
    ("edpd", edpd::parse_style),
];

/// The names of [`PAIR_STYLES`], as error messages list them.
pub fn known_styles() -> String {
    PAIR_STYLES.iter().map(|(name, _)| *name).collect::<Vec<_>>().join(", ")
}

/// `pair_style STYLE args...`.
pub fn parse_pair_style(cmd: &Command) -> Result<Box<dyn Pair>, ScriptError> {
    let mut a = Args::new(cmd);
    let name = a.word("a pair style")?;
    match PAIR_STYLES.iter().find(|(n, _)| *n == name) {
        Some((name, parse)) => parse(name, &mut a),
        None => Err(a.err(format!("unknown pair style '{name}'; known: {}", known_styles()))),
    }
}

/// What a run gives the pair style to build its dynamics from.
pub struct RunInputs<'a> {
    pub fixes: &'a [Fix],
    pub dt: f64,
    pub skin: f64,
    pub rebuild: RebuildPolicy,
    /// Boltzmann's constant and the mv^2 to energy factor of the units.
    pub kb: f64,
    pub mvv2e: f64,
    pub ntypes: usize,
}

impl RunInputs<'_> {
    /// The settings every model takes.
    pub fn settings(&self) -> Settings {
        Settings { dt: self.dt, skin: self.skin, rebuild: self.rebuild.clone() }
    }

    /// The one fix picked by `pick` (None if there is none), or an error naming `what`
    /// when there are more.
    pub fn one<T>(&self, what: &str, pick: impl Fn(&FixStyle) -> Option<T>) -> Result<Option<(&Fix, T)>, String> {
        let mut found = self.fixes.iter().filter_map(|f| pick(&f.style).map(|t| (f, t)));
        let first = found.next();
        if found.next().is_some() {
            return Err(format!("more than one fix {what} is defined"));
        }
        Ok(first)
    }

    /// Whether some fix is picked by `pick`.
    pub fn has(&self, pick: impl Fn(&FixStyle) -> bool) -> bool {
        self.fixes.iter().any(|f| pick(&f.style))
    }
}

/// The dynamics of a `run` (command `cmd`): the fixes a pair style does not work with
/// are refused, once, before it builds its model from the others.
pub fn build_physics(cmd: &Command, pair: Option<&dyn Pair>, run: &RunInputs) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: String| ScriptError::at(cmd, m);
    let pair = pair.ok_or_else(|| err("no pair style is defined (pair_style)".into()))?;
    if let Some(f) = run.fixes.iter().find(|f| !pair.accepts(&f.style)) {
        let (id, name) = (&f.id, pair.name());
        return Err(err(format!("fix {id} does not work with pair {name}: {} is not one of its fixes ({})", f.name, pair.fixes())));
    }
    pair.build(run).map_err(err)
}
