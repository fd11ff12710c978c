//! The styles a script names, by family (LAMMPS's pair, fix and compute styles): each
//! family parses its commands into declarative types and never sees the model;
//! [`physics`] assembles the dynamics of a run from them.

pub mod compute;
pub mod fix;
pub mod pair;
pub mod physics;
pub mod sdpd;
pub mod voronoi;

/// The styles of each family, as error messages list them.
pub const PAIR_STYLES: &str = "gendpde, sdpd/generic, sdpd/taitwater/isothermal, voronoi/fv, dpd, dpd/ext, dpd/tstat, dpd/ext/tstat, dpd/fdt, dpd/fdt/energy, table, multi/lucy, hybrid/overlay (table with a pairwise style, or mdpd/rhosum mdpd), edpd";
pub const FIX_STYLES: &str = "eos/vdw, eos/vdw/reduced, eos/lj, eos/lth, eos/ideal, eos/cv, eos/density, eos/linear, nve/gendpde, nve/sdpd, nve/voronoi, nph, shardlow, vv/euler, heat/reservoir, \
     nve, mvv/dpd, dpd/energy, mvv/edpd, edpd/source, sph, ave/time, ave/chunk";
pub const COMPUTE_STYLES: &str = "dpd, tint, temp, com, ke/atom, pe/atom, reduce, rdf, chunk/atom, msd, edpd/temp/atom";
