//! `change_box GROUP parameter args ... [units lattice|box]` (LAMMPS's change_box, orthogonal
//! periodic boxes): x/y/z `final LO HI`, `delta DLO DHI`, `scale F` and `volume`, `boundary
//! p p p`, `ortho`, `set`, `remap`, applied in order as LAMMPS's change_box.cpp does.

use crate::base::args::Args;
use crate::base::groups;
use crate::model::sim::Sim;
use gendpde_engine::{Domain, Vec3};
use gendpde_io::ScriptError;

/// How one dimension changes.
enum Resize {
    Final(f64, f64),
    Delta(f64, f64),
    Scale(f64),
}

enum Op {
    /// A dimension's new bounds, then the dimensions (`volume`) rescaled to keep the volume
    /// the box had before this operation.
    Axis { dim: usize, resize: Resize, volume: Vec<usize> },
    Set,
    Remap,
}

/// Scales [lo, hi) of `dim` about its middle by `f`.
fn scale_about_middle(d: &mut Domain, dim: usize, f: f64) {
    let mid = 0.5 * (d.lo[dim] + d.hi[dim]);
    d.lo[dim] = mid + f * (d.lo[dim] - mid);
    d.hi[dim] = mid + f * (d.hi[dim] - mid);
}

pub fn change_box(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let group = a.word("a group ID")?;
    let mask = groups::mask(&sim.groups, group, a)?;
    let mut ops: Vec<Op> = Vec::new();
    let mut lattice_units = true;
    while let Some(w) = a.peek() {
        a.word("a change_box parameter")?;
        match w {
            "x" | "y" | "z" => {
                let dim = ["x", "y", "z"].iter().position(|&x| x == w).unwrap_or(0);
                let resize = match a.word("final, delta, scale or volume")? {
                    "final" => Resize::Final(a.f64("the lower bound")?, a.f64("the upper bound")?),
                    "delta" => Resize::Delta(a.f64("the lower shift")?, a.f64("the upper shift")?),
                    "scale" => Resize::Scale(a.positive("the scale factor")?),
                    "volume" => match ops.last_mut() {
                        Some(Op::Axis { volume, .. }) if volume.len() < 2 => {
                            volume.push(dim);
                            continue;
                        }
                        _ => return Err(a.err(format!("{w} volume: it follows the x, y or z change it compensates (at most two volume dimensions)"))),
                    },
                    s => return Err(a.err(format!("{w}: expected final, delta, scale or volume, got '{s}'"))),
                };
                ops.push(Op::Axis { dim, resize, volume: Vec::new() });
            }
            "boundary" => {
                for axis in ["x", "y", "z"] {
                    let b = a.word(&format!("the boundary along {axis}"))?;
                    if b != "p" {
                        return Err(a.err(format!("boundary '{b}' along {axis}: only periodic (p) is supported")));
                    }
                }
            }
            // the box is orthogonal already
            "ortho" => {}
            "xy" | "xz" | "yz" | "triclinic" => return Err(a.err(format!("{w}: only orthogonal boxes are supported"))),
            "set" => ops.push(Op::Set),
            "remap" => ops.push(Op::Remap),
            "units" => {
                lattice_units = match a.word("lattice or box")? {
                    "lattice" => true,
                    "box" => false,
                    u => return Err(a.err(format!("units: expected lattice or box, got '{u}'"))),
                };
                if let Some(k) = a.peek() {
                    return Err(a.err(format!("unexpected argument '{k}' after the units keyword")));
                }
            }
            _ => return Err(a.err(format!("unknown change_box parameter '{w}'; known: x, y, z, boundary, ortho, set, remap, units"))),
        }
    }
    if ops.is_empty() {
        return Err(a.err("nothing to change: give x, y, z, set or remap"));
    }
    let spacing: Vec3 = if lattice_units { sim.lattice_spacing() } else { [1.0; 3] };
    let sys = sim.system.as_mut().ok_or_else(|| a.err("change_box before the box exists (create_box, read_data or read_restart)"))?;
    let mut box_ = sys.domain.clone();
    let mut saved = box_.clone();
    let s = &mut sys.store;
    for op in &ops {
        match op {
            Op::Axis { dim, resize, volume } => {
                let (d, before) = (*dim, box_.volume());
                match *resize {
                    Resize::Final(lo, hi) => (box_.lo[d], box_.hi[d]) = (spacing[d] * lo, spacing[d] * hi),
                    Resize::Delta(lo, hi) => (box_.lo[d], box_.hi[d]) = (box_.lo[d] + spacing[d] * lo, box_.hi[d] + spacing[d] * hi),
                    Resize::Scale(f) => scale_about_middle(&mut box_, d, f),
                }
                if !volume.is_empty() {
                    let f = (before / box_.volume()).powf(1.0 / volume.len() as f64);
                    for &v in volume {
                        scale_about_middle(&mut box_, v, f);
                    }
                }
                if box_.hi[d] <= box_.lo[d] || !box_.volume().is_finite() || box_.volume() <= 0.0 {
                    return Err(a.err(format!("the box would be empty along {}: [{}, {})", ["x", "y", "z"][d], box_.lo[d], box_.hi[d])));
                }
            }
            Op::Set => saved = box_.clone(),
            Op::Remap => {
                // fractional coordinates in the saved box, positions in the current one
                let (from, to) = (saved.len(), box_.len());
                for i in 0..s.nlocal {
                    if s.in_group(i, mask) {
                        for d in 0..3 {
                            s.r[i][d] = box_.lo[d] + (s.r[i][d] - saved.lo[d]) / from[d] * to[d];
                        }
                    }
                }
                saved = box_.clone();
            }
        }
    }
    // the cells of a restart no longer hold: the next run locates every particle afresh
    sys.control.restored = false;
    s.truncate_ghosts();
    for i in 0..s.nlocal {
        box_.wrap(&mut s.r[i], &mut s.image[i]);
    }
    log::info!("changed box: ({:?}) to ({:?})", box_.lo, box_.hi);
    sys.domain = box_;
    Ok(())
}
