//! `velocity all create T SEED [dist uniform|gaussian] [mom yes|no] [loop all|local|geom]`.
//!
//! Each particle's draw is keyed by (seed, tag), so the velocities do not depend on
//! the rank count (LAMMPS's `loop geom` has the same aim). As in LAMMPS, each
//! component is scaled by 1/sqrt(m), the centre-of-mass momentum is removed (mom yes),
//! and the result is scaled to the exact temperature with 3N - 3 degrees of freedom.

use crate::base::args::Args;
use crate::base::groups;
use crate::model::sim::Sim;
use gendpde_engine::exact_sums;
use gendpde_integrators::rng::{normal_pair, stream, uniform4};
use gendpde_io::ScriptError;

pub fn velocity(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let group = a.word("a group")?;
    let mask = groups::mask(&sim.groups, group, a)?;
    match a.word("a velocity style (create)")? {
        "create" => {}
        s => return Err(a.err(format!("unknown velocity style '{s}'; known: create"))),
    }
    let t = a.non_negative("the temperature")?;
    let seed = a.u64("the random seed")?;
    if seed == 0 {
        return Err(a.err("the random seed must be positive"));
    }
    let (mut gaussian, mut mom) = (false, true);
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "dist" => match a.word("uniform or gaussian")? {
                "uniform" => gaussian = false,
                "gaussian" => gaussian = true,
                d => return Err(a.err(format!("expected dist uniform or gaussian, got '{d}'"))),
            },
            "mom" => mom = a.yes_no("mom")?,
            "rot" => {
                if a.yes_no("rot")? {
                    return Err(a.err("rot yes is not supported"));
                }
            }
            "loop" => match a.word("all, local or geom")? {
                "all" | "local" | "geom" => {}
                l => return Err(a.err(format!("expected loop all, local or geom, got '{l}'"))),
            },
            k => return Err(a.err(format!("unknown keyword '{k}'; known: dist, mom, rot, loop"))),
        }
    }
    let sim_kb = sim.units.kb;
    let sys = sim.system.as_mut().ok_or_else(|| a.err("velocity before create_box"))?;
    let s = &mut sys.store;
    if let Some(i) = (0..s.nlocal).find(|&i| !s.mass[i].is_finite()) {
        return Err(a.err(format!("the mass of type {} is not set", s.kind[i])));
    }
    let members: Vec<usize> = (0..s.nlocal).filter(|&i| s.in_group(i, mask)).collect();
    let n = members.len();
    let mut v = vec![[0.0; 3]; n];
    for (k, vi) in v.iter_mut().enumerate() {
        let i = members[k];
        let tag = s.tag[i];
        let x = if gaussian {
            let (a, b) = normal_pair(seed, 0, tag, 0, stream::VELOCITY);
            [a, b, normal_pair(seed, 1, tag, 0, stream::VELOCITY).0]
        } else {
            let [a, b] = uniform4(seed, 0, tag, 0, stream::VELOCITY);
            [a - 0.5, b - 0.5, uniform4(seed, 1, tag, 0, stream::VELOCITY)[0] - 0.5]
        };
        let f = 1.0 / s.mass[i].sqrt();
        *vi = [x[0] * f, x[1] * f, x[2] * f];
    }
    let t_ = sys.comm.transport();
    if mom {
        let [px, py, pz, mass] = exact_sums(t_, (0..n).map(|k| {
            let m = s.mass[members[k]];
            [m * v[k][0], m * v[k][1], m * v[k][2], m]
        }));
        for vi in v.iter_mut() {
            for (k, pk) in [px, py, pz].iter().enumerate() {
                vi[k] -= pk / mass;
            }
        }
    }
    let [mv2, count] = exact_sums(t_, (0..n).map(|k| [s.mass[members[k]] * (v[k][0] * v[k][0] + v[k][1] * v[k][1] + v[k][2] * v[k][2]), 1.0]));
    let dof = 3.0 * count - 3.0;
    let scale = if mv2 > 0.0 && dof > 0.0 { (t * sim_kb * dof / mv2).sqrt() } else { 0.0 };
    for (k, &i) in members.iter().enumerate() {
        s.p[i] = [0, 1, 2].map(|c| s.mass[i] * v[k][c] * scale);
    }
    Ok(())
}
