//! What an H5MD file holds: the per-particle elements gendpde writes, the file's
//! metadata and units, and the storage type of each element's `value`.

use std::fmt;

use hdf5::types::TypeDescriptor;
use hdf5::Dataset;

use super::file::{h5, H5mdError};
use std::path::Path;

/// A per-particle quantity stored as an H5MD time-dependent element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum H5mdField {
    Position,
    Image,
    Velocity,
    Momentum,
    Mass,
    Id,
    Species,
    InternalEnergy,
    Temperature,
    Density,
}

/// What a file records besides the particles: its author, creator version,
/// units and the names of its observables.
#[derive(Clone, Debug, Default)]
pub struct H5mdMeta {
    pub author: String,
    pub email: Option<String>,
    pub creator_version: String,
    /// The unit system (`metal` gives unit attributes; None or `lj`: unitless).
    pub units: Option<String>,
    /// Observables written at every frame (`/observables/<name>`).
    pub observables: Vec<String>,
}

impl H5mdMeta {
    pub fn new(author: &str, creator_version: &str) -> Self {
        Self { author: author.into(), creator_version: creator_version.into(), ..Self::default() }
    }
}

/// The H5MD unit of an element (or "length", "time") in a unit system; None when unitless.
pub(super) fn unit(system: Option<&str>, of: &str) -> Option<&'static str> {
    if system != Some("metal") {
        return None;
    }
    // gendpde keeps masses in energy time^2 / length^2 and momenta in energy time / length
    Some(match of {
        "position" | "length" => "Angstrom",
        "time" => "ps",
        "velocity" => "Angstrom ps-1",
        "momentum" => "eV ps Angstrom-1",
        "mass" => "eV ps2 Angstrom-2",
        "internal_energy" => "eV",
        "temperature" => "K",
        "density" => "Angstrom-3",
        _ => return None,
    })
}

/// Storage type of an element's `value` dataset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    F64,
    I32,
    I64,
}

impl H5mdField {
    /// Every field, in the canonical order.
    pub const ALL: [H5mdField; 10] = [
        H5mdField::Position,
        H5mdField::Image,
        H5mdField::Velocity,
        H5mdField::Momentum,
        H5mdField::Mass,
        H5mdField::Id,
        H5mdField::Species,
        H5mdField::InternalEnergy,
        H5mdField::Temperature,
        H5mdField::Density,
    ];

    /// Parses an input-script word: `x|position`, `image`, `v|velocity`,
    /// `p|momentum`, `mass`, `id`, `type|species`, `u|internal_energy`,
    /// `theta|temperature`, `n|density`.
    pub fn parse(word: &str) -> Option<Self> {
        Some(match word {
            "x" | "position" => Self::Position,
            "image" => Self::Image,
            "v" | "velocity" => Self::Velocity,
            "p" | "momentum" => Self::Momentum,
            "mass" => Self::Mass,
            "id" => Self::Id,
            "type" | "species" => Self::Species,
            "u" | "internal_energy" => Self::InternalEnergy,
            "theta" | "temperature" => Self::Temperature,
            "n" | "density" => Self::Density,
            _ => return None,
        })
    }

    /// Values per particle: 3 for vectors, 1 for scalars.
    pub fn width(self) -> usize {
        match self {
            Self::Position | Self::Image | Self::Velocity | Self::Momentum => 3,
            _ => 1,
        }
    }

    /// Name of the element group under `/particles/all`.
    pub fn h5md_name(self) -> &'static str {
        match self {
            Self::Position => "position",
            Self::Image => "image",
            Self::Velocity => "velocity",
            Self::Momentum => "momentum",
            Self::Mass => "mass",
            Self::Id => "id",
            Self::Species => "species",
            Self::InternalEnergy => "internal_energy",
            Self::Temperature => "temperature",
            Self::Density => "density",
        }
    }

    /// Inverse of [`H5mdField::h5md_name`].
    pub fn from_h5md_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.h5md_name() == name)
    }

    pub(super) fn kind(self) -> Kind {
        match self {
            Self::Image | Self::Species => Kind::I32,
            Self::Id => Kind::I64,
            _ => Kind::F64,
        }
    }
}

impl fmt::Display for H5mdField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.h5md_name())
    }
}


pub(super) fn value_dtype_name(kind: Kind) -> &'static str {
    match kind {
        Kind::F64 => "float64",
        Kind::I32 => "int32",
        Kind::I64 => "int64",
    }
}

pub(super) fn dtype_kind(path: &Path, ds: &Dataset, name: &str) -> Result<Option<Kind>, H5mdError> {
    let dt = h5(
        path,
        &format!("reading the type of {name}/value"),
        ds.dtype(),
    )?;
    let d = h5(
        path,
        &format!("reading the type of {name}/value"),
        dt.to_descriptor(),
    )?;
    use hdf5::types::{FloatSize, IntSize};
    Ok(match d {
        TypeDescriptor::Float(FloatSize::U8) => Some(Kind::F64),
        TypeDescriptor::Integer(IntSize::U4) => Some(Kind::I32),
        TypeDescriptor::Integer(IntSize::U8) => Some(Kind::I64),
        _ => None,
    })
}
