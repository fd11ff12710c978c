//! `compute ID GROUP chunk/atom bin/1d|bin/2d|bin/3d DIM ORIGIN DELTA ... [units
//! box|lattice|reduced]`: each particle of the group gets the spatial bin it lies in, as
//! LAMMPS's compute chunk/atom with its default `discard mixed` in a periodic box (a
//! particle outside the bins along a dimension goes to the first or last bin).
//!
//! Bins are laid out from the origin (lower, center, upper or a coordinate) in steps of
//! DELTA to cover the box; chunk m = (i1 * n2 + i2) * n3 + i3, and its coordinates are the
//! bin centres. Read by fix ave/chunk.

use crate::base::args::Args;
use gendpde_engine::{Domain, Vec3};
use gendpde_io::ScriptError;

/// Where the bins along a dimension start.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Origin {
    Lower,
    Center,
    Upper,
    At(f64),
}

/// One binned dimension: axis 0..3, origin and bin width (box or reduced units).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Axis {
    dim: usize,
    origin: Origin,
    delta: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ChunkAtom {
    pub id: String,
    /// Group bit mask (`u32::MAX` for all).
    pub mask: u32,
    axes: Vec<Axis>,
    /// `units reduced`: bins in fractions of the box.
    reduced: bool,
}

/// The bins of a chunk/atom compute in the current box.
#[derive(Clone, Debug, PartialEq)]
pub struct Bins {
    /// Lower edge and count of the bins along each binned dimension.
    offset: Vec<f64>,
    count: Vec<usize>,
    /// Bin centres, one row of `ndim` coordinates per chunk.
    pub coords: Vec<Vec<f64>>,
    /// Volume of one bin (LAMMPS's chunk_volume_scalar).
    pub volume: f64,
}

impl Bins {
    pub fn nchunk(&self) -> usize {
        self.coords.len()
    }
}

const AXES: [&str; 3] = ["x", "y", "z"];

/// Largest number of bins accepted (arrays of them are held on every rank).
const MAX_BINS: f64 = (1u64 << 24) as f64;

impl ChunkAtom {
    /// The words after `compute ID GROUP chunk/atom`; `spacing` is the lattice spacing
    /// (`units lattice`, the default).
    pub fn parse(id: String, mask: u32, a: &mut Args, spacing: Vec3) -> Result<Self, ScriptError> {
        let ndim = match a.word("a chunk style (bin/1d, bin/2d or bin/3d)")? {
            "bin/1d" => 1,
            "bin/2d" => 2,
            "bin/3d" => 3,
            s => return Err(a.err(format!("chunk style '{s}': only bin/1d, bin/2d and bin/3d are supported"))),
        };
        let mut axes = Vec::with_capacity(ndim);
        for _ in 0..ndim {
            let d = a.word("a dimension (x, y or z)")?;
            let dim = AXES.iter().position(|&x| x == d).ok_or_else(|| a.err(format!("expected a dimension x, y or z, got '{d}'")))?;
            if axes.iter().any(|x: &Axis| x.dim == dim) {
                return Err(a.err(format!("dimension {d} is binned twice")));
            }
            let origin = match a.word("an origin (lower, center, upper or a coordinate)")? {
                "lower" => Origin::Lower,
                "center" => Origin::Center,
                "upper" => Origin::Upper,
                w => Origin::At(w.parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| a.err(format!("expected an origin (lower, center, upper or a coordinate), got '{w}'")))?),
            };
            let delta = a.positive("the bin width")?;
            axes.push(Axis { dim, origin, delta });
        }
        let mut units = "lattice";
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                "units" => {
                    units = a.word("box, lattice or reduced")?;
                    if !["box", "lattice", "reduced"].contains(&units) {
                        return Err(a.err(format!("expected units box, lattice or reduced, got '{units}'")));
                    }
                }
                k => return Err(a.err(format!("unknown keyword '{k}'; known: units"))),
            }
        }
        let reduced = units == "reduced";
        if units == "lattice" {
            for x in &mut axes {
                x.delta *= spacing[x.dim];
                if let Origin::At(o) = &mut x.origin {
                    *o *= spacing[x.dim];
                }
            }
        }
        Ok(Self { id, mask, axes, reduced })
    }

    /// The bins covering the box `d` (LAMMPS's setup_xyz_bins and bin_volumes).
    pub fn bins(&self, d: &Domain) -> Result<Bins, String> {
        let len = d.len();
        let (mut offset, mut count) = (Vec::new(), Vec::new());
        let mut volume = len.iter().product::<f64>();
        let mut nbins = 1.0;
        for x in &self.axes {
            let (blo, bhi) = if self.reduced { (0.0, 1.0) } else { (d.lo[x.dim], d.hi[x.dim]) };
            let inv = 1.0 / x.delta;
            let origin = match x.origin {
                Origin::Lower => blo,
                Origin::Upper => bhi,
                Origin::Center => 0.5 * (blo + bhi),
                Origin::At(o) => o,
            };
            // LAMMPS truncates toward zero (static_cast<int>)
            let lo = if origin < blo {
                origin + ((blo - origin) * inv).trunc() * x.delta
            } else {
                let lo = origin - ((origin - blo) * inv).trunc() * x.delta;
                if lo > blo { lo - x.delta } else { lo }
            };
            let hi = if origin < bhi {
                let hi = origin + ((bhi - origin) * inv).trunc() * x.delta;
                if hi < bhi { hi + x.delta } else { hi }
            } else {
                origin - ((origin - bhi) * inv).trunc() * x.delta
            };
            let n = ((hi - lo) * inv + 0.5).trunc();
            nbins *= n;
            if !(n >= 1.0 && nbins <= MAX_BINS) {
                return Err(format!("compute {} chunk/atom: {n} bins along {} (from {lo} to {hi}); at least 1 and at most {MAX_BINS} in all", self.id, AXES[x.dim]));
            }
            offset.push(lo);
            count.push(n as usize);
            volume *= x.delta / if self.reduced { 1.0 } else { len[x.dim] };
        }
        let mut coords = vec![Vec::new()];
        for (k, x) in self.axes.iter().enumerate() {
            let (lo, n) = (offset[k], count[k]);
            coords = coords.into_iter().flat_map(|c| (0..n).map(move |i| [c.clone(), vec![lo + (i as f64 + 0.5) * x.delta]].concat())).collect();
        }
        Ok(Bins { offset, count, coords, volume })
    }

    /// The chunk (0-based) of position `r` in box `d` (LAMMPS's atom2bin1d/2d/3d).
    pub fn chunk(&self, bins: &Bins, d: &Domain, r: Vec3) -> usize {
        let len = d.len();
        let mut chunk = 0;
        for (k, x) in self.axes.iter().enumerate() {
            let (lo, hi, period) = if self.reduced { (0.0, 1.0, 1.0) } else { (d.lo[x.dim], d.hi[x.dim], len[x.dim]) };
            // LAMMPS multiplies by inverses (x2lamda, invdelta): the same bins to the bit
            let mut c = if self.reduced { (1.0 / len[x.dim]) * (r[x.dim] - d.lo[x.dim]) } else { r[x.dim] };
            if c < lo {
                c += period;
            }
            if c >= hi {
                c -= period;
            }
            let mut i = ((c - bins.offset[k]) * (1.0 / x.delta)).trunc() as i64;
            if c < bins.offset[k] {
                i -= 1;
            }
            chunk = chunk * bins.count[k] + i.clamp(0, bins.count[k] as i64 - 1) as usize;
        }
        chunk
    }
}
