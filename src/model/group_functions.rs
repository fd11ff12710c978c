//! LAMMPS's group functions of equal-style variables: `count(g)`, `mass(g)`, `xcm(g,dim)`,
//! `vcm(g,dim)`, `fcm(g,dim)`, `bound(g,xmin|xmax|ymin|ymax|zmin|zmax)`, `gyration(g)`,
//! `ke(g)`, each also with a region as last argument (the group's particles in it now).
//! Centres of mass and the radius of gyration are of unwrapped positions, bounds of
//! wrapped ones, as LAMMPS's group.cpp. Collective, with exact sums.

use crate::model::sim::Sim;
use gendpde_engine::exact_sums;

/// The value of group function call `call` (as the expression parser passes it:
/// `name(arg,arg...)`); None if it is none, names no such group or region, or a wrong
/// argument.
pub fn value(sim: &Sim, call: &str) -> Option<f64> {
    let (name, args) = call.strip_suffix(')')?.split_once('(')?;
    let args: Vec<&str> = args.split(',').collect();
    let sys = sim.system.as_ref()?;
    let s = &sys.store;
    let mask = match args[0] {
        "all" => u32::MAX,
        g => 1 << sim.groups.iter().position(|n| n == g)?,
    };
    // the optional region is the last argument (after the dimension or bound, if any)
    let takes = match name {
        "count" | "mass" | "gyration" | "ke" => 1,
        "xcm" | "vcm" | "fcm" | "bound" => 2,
        _ => return None,
    };
    let region = match args.len() - takes {
        0 => None,
        1 => Some(sim.regions.get(*args.last()?)?),
        _ => return None,
    };
    let members: Vec<usize> = (0..s.nlocal).filter(|&i| s.in_group(i, mask) && region.is_none_or(|r| r.contains(s.r[i]))).collect();
    let t = sys.comm.transport();
    let axis = |w: &str| match w {
        "x" => Some(0),
        "y" => Some(1),
        "z" => Some(2),
        _ => None,
    };
    let mvv2e = sim.units.mvv2e;
    let centre = |members: &[usize]| {
        let rows = members.iter().map(|&i| {
            let (x, m) = (sys.domain.unwrap(s.r[i], s.image[i]), s.mass[i]);
            [m, m * x[0], m * x[1], m * x[2]]
        });
        let [m, mx, my, mz] = exact_sums(t, rows);
        if m > 0.0 { [mx / m, my / m, mz / m] } else { [0.0; 3] }
    };
    Some(match name {
        "count" => exact_sums(t, members.iter().map(|_| [1.0]))[0],
        "mass" => exact_sums(t, members.iter().map(|&i| [s.mass[i]]))[0] / mvv2e,
        "ke" => exact_sums(t, members.iter().map(|&i| [0.5 * s.p[i].iter().map(|p| p * p).sum::<f64>() / s.mass[i]]))[0],
        "xcm" => centre(&members)[axis(args[1])?],
        "vcm" => {
            let d = axis(args[1])?;
            let [m, p] = exact_sums(t, members.iter().map(|&i| [s.mass[i], s.p[i][d]]));
            if m > 0.0 { p / m } else { 0.0 }
        }
        "fcm" => {
            let d = axis(args[1])?;
            exact_sums(t, members.iter().map(|&i| [s.f[i][d]]))[0]
        }
        "bound" => {
            let (d, max) = match args[1].as_bytes() {
                [c @ b'x'..=b'z', b'm', b'i', b'n'] => (usize::from(c - b'x'), false),
                [c @ b'x'..=b'z', b'm', b'a', b'x'] => (usize::from(c - b'x'), true),
                _ => return None,
            };
            // LAMMPS's bounds of an empty group: +BIG for minima, -BIG for maxima
            let sign = if max { 1.0 } else { -1.0 };
            let mut m = [members.iter().map(|&i| sign * s.r[i][d]).fold(-1.0e20, f64::max)];
            t.max(&mut m);
            sign * m[0]
        }
        "gyration" => {
            let cm = centre(&members);
            let rows = members.iter().map(|&i| {
                let x = sys.domain.unwrap(s.r[i], s.image[i]);
                let d2: f64 = (0..3).map(|k| (x[k] - cm[k]) * (x[k] - cm[k])).sum();
                [s.mass[i], s.mass[i] * d2]
            });
            let [m, md2] = exact_sums(t, rows);
            if m > 0.0 { (md2 / m).sqrt() } else { 0.0 }
        }
        _ => return None,
    })
}
