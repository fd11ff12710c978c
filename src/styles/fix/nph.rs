//! `fix ID all nph KEYWORD VALUES ...` (LAMMPS fix_nh.cpp's constructor, its defaults and
//! checks, for an orthogonal box) and `fix_modify ID temp CID`.

use crate::base::args::Args;
use gendpde_integrators::{Couple, Nph};
use gendpde_io::ScriptError;

/// The words after `fix ID GROUP nph`; `dilate` groups resolve through `groups`. The fixed
/// point, when not given, is the box centre at the definition (set by the fix command).
pub fn parse_nph(id: &str, a: &mut Args, kb: f64, groups: &[String]) -> Result<(Nph, Option<[f64; 3]>), ScriptError> {
    let mut nph = Nph {
        id: id.to_string(),
        p_start: [0.0; 3],
        p_stop: [0.0; 3],
        p_freq: [0.0; 3],
        p_flag: [false; 3],
        couple: Couple::None,
        deviatoric: false,
        pchain: 3,
        mtk: true,
        ploop: 1,
        nreset: 0,
        drag: 0.0,
        ptemp: None,
        dilate: u32::MAX,
        temp_mask: u32::MAX,
        extra_dof: 3.0,
        kb,
        nktv2p: 1.0,
    };
    let mut period = [0.0; 3];
    let mut fixedpoint = None;
    if a.remaining() == 0 {
        return Err(a.err("expected a pressure style: iso, aniso, x, y or z"));
    }
    while let Some(k) = a.peek() {
        a.word("keyword")?;
        match k {
            "iso" | "aniso" => {
                nph.couple = if k == "iso" { Couple::Xyz } else { Couple::None };
                let (start, stop, damp) = (a.f64("Pstart")?, a.f64("Pstop")?, a.f64("Pdamp")?);
                (nph.p_start, nph.p_stop, period, nph.p_flag) = ([start; 3], [stop; 3], [damp; 3], [true; 3]);
            }
            "x" | "y" | "z" => {
                let d = (k.as_bytes()[0] - b'x') as usize;
                (nph.p_start[d], nph.p_stop[d], period[d]) = (a.f64("Pstart")?, a.f64("Pstop")?, a.f64("Pdamp")?);
                nph.p_flag[d] = true;
                nph.deviatoric = true;
            }
            "couple" => {
                nph.couple = match a.word("xyz, xy, yz, xz or none")? {
                    "xyz" => Couple::Xyz,
                    "xy" => Couple::Xy,
                    "yz" => Couple::Yz,
                    "xz" => Couple::Xz,
                    "none" => Couple::None,
                    w => return Err(a.err(format!("Illegal fix nph couple option: {w}"))),
                }
            }
            "drag" => {
                nph.drag = a.f64("the drag factor")?;
                if nph.drag < 0.0 {
                    return Err(a.err(format!("Invalid fix nph drag argument: {}", nph.drag)));
                }
            }
            "ptemp" => nph.ptemp = Some(a.positive("the ptemp temperature")?),
            "dilate" => {
                let g = a.word("all or a group ID")?;
                nph.dilate = crate::base::groups::mask(groups, g, a)?;
            }
            "pchain" => nph.pchain = a.u64("the barostat chain length")? as usize,
            "mtk" => nph.mtk = a.yes_no("mtk")?,
            "ploop" => nph.ploop = a.u64("the barostat chain loops")? as u32,
            "tchain" => {
                // LAMMPS parses it for every fix nh style; nph has no thermostat to chain
                if a.u64("the thermostat chain length")? < 1 {
                    return Err(a.err("Invalid fix nph tchain argument"));
                }
            }
            "tloop" => {
                a.u64("the thermostat chain loops")?;
            }
            "nreset" => nph.nreset = a.u64("the reset interval of the reference cell")?,
            "fixedpoint" => fixedpoint = Some([a.f64("x")?, a.f64("y")?, a.f64("z")?]),
            "flip" => {
                a.yes_no("flip")?;
            }
            "temp" => return Err(a.err("Temperature control can not be used with fix nph")),
            "tri" | "xy" | "xz" | "yz" | "scalexy" | "scalexz" | "scaleyz" => {
                return Err(a.err(format!(
                    "'{k}' needs a triclinic box, which gendpde does not have; supported: iso, aniso, x, y, z, couple, drag, ptemp, dilate, pchain, mtk, tchain, tloop, ploop, nreset, fixedpoint, flip"
                )))
            }
            "update" | "disc" | "erate" | "strain" | "ext" | "psllod" => {
                return Err(a.err(format!("'{k}' belongs to other fix nh styles (sphere, uef, sllod)")));
            }
            _ => return Err(a.err(format!("Unknown fix nph keyword: {k}"))),
        }
    }
    if nph.ploop == 0 {
        // LAMMPS accepts 0 and then divides by it
        return Err(a.err("Invalid fix nph ploop argument: 0 (at least 1)"));
    }
    let f = nph.p_flag;
    if !f.iter().any(|&x| x) {
        return Err(a.err("Pressure control must be used with fix nph"));
    }
    let bad = match nph.couple {
        Couple::Xyz => !(f[0] && f[1] && f[2]),
        Couple::Xy => !(f[0] && f[1]),
        Couple::Yz => !(f[1] && f[2]),
        Couple::Xz => !(f[0] && f[2]),
        Couple::None => false,
    };
    if bad {
        return Err(a.err("Invalid fix nph command pressure settings"));
    }
    let same = |i: usize, j: usize| nph.p_start[i] == nph.p_start[j] && nph.p_stop[i] == nph.p_stop[j] && period[i] == period[j];
    let unequal = match nph.couple {
        Couple::Xyz => !(same(0, 1) && same(0, 2)),
        Couple::Xy => !same(0, 1),
        Couple::Yz => !same(1, 2),
        Couple::Xz => !same(0, 2),
        Couple::None => false,
    };
    if unequal {
        return Err(a.err("Invalid fix nph pressure settings"));
    }
    for d in 0..3 {
        if f[d] {
            if period[d] <= 0.0 {
                return Err(a.err("Fix nph damping parameters must be > 0.0"));
            }
            nph.p_freq[d] = 1.0 / period[d];
        }
    }
    Ok((nph, fixedpoint))
}
