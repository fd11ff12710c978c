//! `gendpde lth-macro`: the macroscopic state of an LTh fluid (argon paper eqs 78, 85-91,
//! 99) from a pair distribution function g(r), read from a file (a simulated g: Table 6)
//! or solved by the self-consistent HNC of eqs 119-120 (Table 8).

use gendpde_potentials::eos::Lth;
use gendpde_potentials::hnc::{HncOptions, LthFluid, MacroState, RadialGrid};
use gendpde_potentials::volume::PartitionVolume;
use gendpde_potentials::Quadratic;
use std::path::Path;

/// Grid of the transforms: 2048 points of 0.005 (r up to 10.24).
const GRID: (usize, f64) = (2048, 0.005);

/// Where g(r) comes from.
pub enum Source<'a> {
    File(&'a Path),
    Hnc,
}

/// The fluid: the LTh model, R_cut and f_cut of the corrected volume, the bulk density c
/// and the temperature.
pub fn fluid(eos: Lth, rc: f64, fcut: f64, density: f64, temperature: f64) -> Result<LthFluid<Quadratic>, String> {
    for (name, v) in [("--rc", rc), ("--fcut", fcut), ("--density", density), ("--temperature", temperature)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(format!("{name} must be a positive number, got {v}"));
        }
    }
    Ok(LthFluid { eos, weight: Quadratic::new(rc), volume: PartitionVolume::new(rc, fcut), density, temperature })
}

/// `name value` lines of the macroscopic state.
pub fn evaluate(f: &LthFluid<Quadratic>, source: Source) -> Result<Vec<(&'static str, f64)>, String> {
    let grid = RadialGrid::new(GRID.0, GRID.1);
    let (state, iterations) = match source {
        Source::File(path) => {
            let (r, g) = read_gr(path)?;
            (f.macro_state(&grid, &grid.sample(&r, &g)), None)
        }
        Source::Hnc => {
            let sol = f.hnc(&grid, &HncOptions::default()).map_err(|e| e.to_string())?;
            (sol.state, Some(sol.hnc.iterations as f64))
        }
    };
    let MacroState { mean_field, p_ex, pressure, energy } = state;
    let mut lines = vec![
        ("nb", mean_field.density.nb),
        ("n", mean_field.density.n),
        ("pi", mean_field.pi),
        ("p_ex_pair", p_ex[0]),
        ("p_ex_pair_w", p_ex[1]),
        ("p_ex_triplet", p_ex[2]),
        ("pressure", pressure),
        ("energy", energy),
    ];
    lines.extend(iterations.map(|i| ("iterations", i)));
    Ok(lines)
}

/// A g(r) table: lines `r g [...]` with r increasing; `#` starts a comment. LAMMPS's
/// `fix ave/time ... mode vector` output of `compute rdf` (lines `row r g coord`) is read
/// too: its last block.
pub fn read_gr(path: &Path) -> Result<(Vec<f64>, Vec<f64>), String> {
    let name = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {name}: {e}"))?;
    let mut rows: Vec<(usize, Vec<f64>)> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let body = line.split('#').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let values: Result<Vec<f64>, _> = body.split_whitespace().map(str::parse::<f64>).collect();
        match values {
            Ok(v) if v.len() >= 2 => rows.push((k + 1, v)),
            _ => return Err(format!("{name}:{}: expected numbers `r g`, got '{body}'", k + 1)),
        }
    }
    let lammps = rows.iter().any(|(_, v)| v.len() == 4);
    let table: Vec<(usize, f64, f64)> = if lammps {
        // blocks: `timestep nrows`, then nrows lines `row r g coord`; keep the last
        let start = rows.iter().rposition(|(_, v)| v.len() == 2).map_or(0, |p| p + 1);
        rows[start..].iter().map(|(k, v)| (*k, v[1], v[2])).collect()
    } else {
        rows.iter().map(|(k, v)| (*k, v[0], v[1])).collect()
    };
    if table.len() < 2 {
        return Err(format!("{name}: expected at least two lines `r g`"));
    }
    for w in table.windows(2) {
        if w[1].1 <= w[0].1 {
            return Err(format!("{name}:{}: r must increase ({} after {})", w[1].0, w[1].1, w[0].1));
        }
    }
    if let Some((k, _, g)) = table.iter().find(|(_, r, g)| !(r.is_finite() && *r >= 0.0 && g.is_finite() && *g >= 0.0)) {
        return Err(format!("{name}:{k}: expected r >= 0 and g >= 0, got g = {g}"));
    }
    Ok(table.into_iter().map(|(_, r, g)| (r, g)).unzip())
}
