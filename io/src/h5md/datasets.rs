//! Creating the groups and datasets of the H5MD layout, and converting frame values
//! to the integer types they are stored as.

use std::collections::BTreeSet;
use std::path::Path;

use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Extent, File, Group, H5Type, SimpleExtents};

use super::field::{H5mdField, H5mdMeta, Kind};
use super::file::{error, h5, vlen, write_str_attr, H5mdError, CHUNK_BYTES, STEP_CHUNK};

/// Writes `/h5md` and `/particles/all/box` (without its edges).  A separate
/// function so every attribute handle is closed before SWMR mode starts
/// (HDF5 refuses to start it with open attributes).
pub(super) fn write_metadata(path: &Path, file: &File, meta: &H5mdMeta) -> Result<(), H5mdError> {
    // /h5md
    let h5md = h5(path, "creating /h5md", file.create_group("h5md"))?;
    let version = h5(
        path,
        "creating /h5md version",
        h5md.new_attr::<i32>().shape(2).create("version"),
    )?;
    h5(path, "writing /h5md version", version.write_raw(&[1i32, 1]))?;
    let g = h5(path, "creating /h5md/author", h5md.create_group("author"))?;
    write_str_attr(path, &g, "name", &meta.author)?;
    if let Some(email) = &meta.email {
        write_str_attr(path, &g, "email", email)?;
    }
    let g = h5(path, "creating /h5md/creator", h5md.create_group("creator"))?;
    write_str_attr(path, &g, "name", "gendpde")?;
    write_str_attr(path, &g, "version", &meta.creator_version)?;

    // /particles/all/box
    let all = h5(
        path,
        "creating /particles/all",
        file.create_group("particles/all"),
    )?;
    let bx = h5(path, "creating box", all.create_group("box"))?;
    let dim = h5(
        path,
        "creating box dimension",
        bx.new_attr::<i32>().create("dimension"),
    )?;
    h5(path, "writing box dimension", dim.write_scalar(&3i32))?;
    let periodic = vlen(path, "periodic")?;
    let boundary = h5(
        path,
        "creating box boundary",
        bx.new_attr::<VarLenUnicode>().shape(3).create("boundary"),
    )?;
    h5(
        path,
        "writing box boundary",
        boundary.write_raw(&[periodic.clone(), periodic.clone(), periodic]),
    )?;
    Ok(())
}

/// The H5MD `unit` attribute of a dataset (none when unitless).
pub(super) fn set_unit(path: &Path, ds: &Dataset, unit: Option<&str>) -> Result<(), H5mdError> {
    let Some(unit) = unit else { return Ok(()) };
    let v = vlen(path, unit)?;
    let attr = h5(path, "creating a unit attribute", ds.new_attr::<VarLenUnicode>().create("unit"))?;
    h5(path, "writing a unit attribute", attr.write_scalar(&v))
}

pub(super) fn check_fields(path: &Path, fields: &[H5mdField]) -> Result<(), H5mdError> {
    if fields.is_empty() {
        return Err(error(path, "no fields to write"));
    }
    let mut seen = BTreeSet::new();
    for f in fields {
        if !seen.insert(*f) {
            return Err(error(path, format_args!("field {f} listed twice")));
        }
    }
    Ok(())
}

pub(super) fn create_value(path: &Path, g: &Group, field: H5mdField, n: usize) -> Result<Dataset, H5mdError> {
    let width = field.width();
    let rows = (CHUNK_BYTES / (8 * width)).clamp(1, n.max(1));
    // A fixed particle axis of length 0 cannot hold a chunk of 1 row, so an
    // empty system gets an unlimited particle axis.
    let particle_axis = if n == 0 {
        Extent::new(0, None)
    } else {
        Extent::fixed(n)
    };
    let mut extents = vec![Extent::new(0, None), particle_axis];
    let mut chunk = vec![1, rows];
    if width == 3 {
        extents.push(Extent::fixed(3));
        chunk.push(3);
    }
    let b = match field.kind() {
        Kind::F64 => g.new_dataset::<f64>(),
        Kind::I32 => g.new_dataset::<i32>(),
        Kind::I64 => g.new_dataset::<i64>(),
    };
    let what = format!("creating {}/value", field.h5md_name());
    h5(
        path,
        &what,
        b.chunk(chunk)
            .shape(SimpleExtents::from_vec(extents))
            .create("value"),
    )
}

pub(super) fn create_series<T: H5Type>(path: &Path, g: &Group, name: &str) -> Result<Dataset, H5mdError> {
    h5(
        path,
        &format!("creating {name}"),
        g.new_dataset::<T>()
            .chunk(STEP_CHUNK)
            .shape(0..)
            .create(name),
    )
}

pub(super) fn to_int<T: TryFrom<i64>>(x: f64) -> Option<T> {
    // i64::MAX as f64 rounds to 2^63, the first value that does not fit.
    let limit = i64::MAX as f64;
    if !x.is_finite() || x.fract() != 0.0 || !(-limit..limit).contains(&x) {
        return None;
    }
    T::try_from(x as i64).ok()
}

pub(super) fn convert<T>(data: &[f64], f: fn(f64) -> Option<T>) -> Result<Vec<T>, f64> {
    data.iter().map(|&x| f(x).ok_or(x)).collect()
}

/// Writes integer rows (`width` 1 or 3) of frame `frame`; Err holds a value that is not
/// an integer of type T.
pub(super) fn write_ints<T: H5Type + Copy + TryFrom<i64>>(
    ds: &Dataset,
    data: &[f64],
    width: usize,
    frame: usize,
    rows: std::ops::Range<usize>,
) -> Result<hdf5::Result<()>, f64> {
    if width == 3 {
        let v = as_triples(data, |x| to_int::<T>(x).ok_or(x))?;
        Ok(ds.write_slice::<_, T, _, _>(v.as_slice(), (frame, rows, ..)))
    } else {
        let v = convert(data, to_int::<T>)?;
        Ok(ds.write_slice(v.as_slice(), (frame, rows)))
    }
}

pub(super) fn as_triples<T: Copy, E>(data: &[f64], f: impl Fn(f64) -> Result<T, E>) -> Result<Vec<[T; 3]>, E> {
    data.chunks_exact(3)
        .map(|c| Ok([f(c[0])?, f(c[1])?, f(c[2])?]))
        .collect()
}

