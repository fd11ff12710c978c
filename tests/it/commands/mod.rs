//! Commands of the input language: computes, atom variables, groups, `velocity` and `set`.

mod atom_variables;
mod computes;
mod groups;
mod rdf;
mod velocity_set;
