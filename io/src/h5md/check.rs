//! Checking an H5MD file against the H5MD 1.1 structure (`check_h5md`).

use super::*;

/// What [`check_h5md`] found in a valid file.
#[derive(Debug, Clone, PartialEq)]
pub struct H5mdSummary {
    /// Number of particles (second dimension of every `value`).
    pub particles: usize,
    /// Completed frames (length of `step`).
    pub frames: usize,
    /// Names of the time-dependent elements under `/particles/all`, sorted.
    pub elements: Vec<String>,
    /// `step` of every completed frame.
    pub steps: Vec<i64>,
    /// `time` of every completed frame.
    pub times: Vec<f64>,
    /// `/particles/all/box/edges` (of the first frame when time dependent).
    pub edges: Vec<f64>,
    /// Names under `/observables`.
    pub observables: Vec<String>,
    /// `/h5md/creator` name and version.
    pub creator: (String, String),
    /// `/h5md/author` name.
    pub author: String,
    /// False if the file is still marked "open for writing" (its writer is
    /// running or was killed): plain HDF5 readers then refuse it and only
    /// SWMR-read mode opens it, until [`repair_h5md`] (or `h5clear -s`).
    pub clean: bool,
}

fn open_for_reading(path: &Path) -> Result<(File, bool), H5mdError> {
    silence();
    match File::open(path) {
        Ok(f) => Ok((f, true)),
        // A file whose SWMR writer was killed (or is still running) keeps the
        // "open for writing" superblock flag; SWMR read mode accepts it.
        Err(first) => File::open_as(path, hdf5::OpenMode::ReadSWMR)
            .map(|f| (f, false))
            .map_err(|_| error(path, format_args!("cannot open: {first}"))),
    }
}

fn read_string_attr(path: &Path, attr: &Attribute, what: &str) -> Result<String, H5mdError> {
    let v = read_strings(path, attr, what)?;
    if attr.ndim() != 0 || v.len() != 1 {
        return Err(error(path, format_args!("{what} is not a scalar string")));
    }
    Ok(v.into_iter().next().unwrap_or_default())
}

/// Reads a string (array) attribute stored fixed- or variable-length.
fn read_strings(path: &Path, attr: &Attribute, what: &str) -> Result<Vec<String>, H5mdError> {
    let dt = h5(path, &format!("reading the type of {what}"), attr.dtype())?;
    let d = h5(
        path,
        &format!("reading the type of {what}"),
        dt.to_descriptor(),
    )?;
    let r = match d {
        TypeDescriptor::VarLenUnicode => attr
            .read_raw::<VarLenUnicode>()
            .map(|v| v.iter().map(|s| s.to_string()).collect()),
        TypeDescriptor::VarLenAscii => attr
            .read_raw::<VarLenAscii>()
            .map(|v| v.iter().map(|s| s.to_string()).collect()),
        TypeDescriptor::FixedAscii(_) => attr
            .read_raw::<FixedAscii<1024>>()
            .map(|v| v.iter().map(|s| s.to_string()).collect()),
        TypeDescriptor::FixedUnicode(_) => attr
            .read_raw::<FixedUnicode<1024>>()
            .map(|v| v.iter().map(|s| s.to_string()).collect()),
        other => {
            return Err(error(
                path,
                format_args!("{what} is not a string but {other}"),
            ))
        }
    };
    h5(path, &format!("reading {what}"), r)
}

fn attr(path: &Path, loc: &Group, name: &str, what: &str) -> Result<Attribute, H5mdError> {
    loc.attr(name)
        .map_err(|_| error(path, format_args!("missing attribute {what}")))
}

fn int_kind(d: &TypeDescriptor) -> bool {
    matches!(d, TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_))
}

/// Checks the H5MD 1.1 structure of `path` and summarises `/particles/all`:
/// `/h5md` version 1.x, author name, creator name and version;
/// `/particles/all/box` with `dimension` and `boundary` (and `edges` when
/// periodic); every time-dependent element with `value`, integer `step` and
/// (optional) `time`, all elements with the same number of frames,
/// `value` and `time` at least as long as `step` (a longer one is an
/// incomplete trailing frame of a killed writer) and `value`'s second
/// dimension equal to the particle count.
pub fn check_h5md(path: &Path) -> Result<H5mdSummary, H5mdError> {
    let (file, clean) = open_for_reading(path)?;

    let h5md = file
        .group("h5md")
        .map_err(|_| error(path, "missing group /h5md"))?;
    let v = attr(path, &h5md, "version", "/h5md version")?;
    let d = h5(
        path,
        "reading /h5md version type",
        v.dtype().and_then(|t| t.to_descriptor()),
    )?;
    if !int_kind(&d) {
        return Err(error(path, "/h5md version is not an integer array"));
    }
    let version = h5(path, "reading /h5md version", v.read_raw::<i32>())?;
    if version.len() != 2 || version[0] != 1 {
        return Err(error(
            path,
            format_args!("/h5md version is {version:?}, expected [1, x]"),
        ));
    }
    let author_g = h5md
        .group("author")
        .map_err(|_| error(path, "missing group /h5md/author"))?;
    let author = read_string_attr(
        path,
        &attr(path, &author_g, "name", "/h5md/author name")?,
        "/h5md/author name",
    )?;
    let creator_g = h5md
        .group("creator")
        .map_err(|_| error(path, "missing group /h5md/creator"))?;
    let cname = read_string_attr(
        path,
        &attr(path, &creator_g, "name", "/h5md/creator name")?,
        "/h5md/creator name",
    )?;
    let cversion = read_string_attr(
        path,
        &attr(path, &creator_g, "version", "/h5md/creator version")?,
        "/h5md/creator version",
    )?;

    let all = file
        .group("particles/all")
        .map_err(|_| error(path, "missing group /particles/all"))?;
    let bx = all
        .group("box")
        .map_err(|_| error(path, "missing group /particles/all/box"))?;
    let dim_a = attr(path, &bx, "dimension", "box dimension")?;
    let dim = h5(path, "reading box dimension", dim_a.read_scalar::<i32>())?;
    if !(1..=3).contains(&dim) {
        return Err(error(path, format_args!("box dimension is {dim}")));
    }
    let boundary = read_strings(
        path,
        &attr(path, &bx, "boundary", "box boundary")?,
        "box boundary",
    )?;
    if boundary.len() != dim as usize {
        return Err(error(
            path,
            format_args!(
                "box boundary has {} entries for dimension {dim}",
                boundary.len()
            ),
        ));
    }
    if let Some(b) = boundary.iter().find(|b| *b != "periodic" && *b != "none") {
        return Err(error(
            path,
            format_args!("box boundary {b:?} is neither \"periodic\" nor \"none\""),
        ));
    }
    // edges: a time-dependent element [frames, 3] (gendpde) or a fixed dataset
    let d = dim as usize;
    let (edges, edge_frames) = if let Ok(v) = bx.dataset("edges/value") {
        let shape = v.shape();
        if shape.len() != 2 || shape[1] != d {
            return Err(error(path, format_args!("box/edges/value has shape {shape:?}, expected [frames, {d}]")));
        }
        let rows = h5(path, "reading box edges", v.read_raw::<f64>())?;
        (rows.get(..d).map_or_else(Vec::new, <[f64]>::to_vec), Some(shape[0]))
    } else if let Ok(e) = bx.dataset("edges") {
        let shape = e.shape();
        if shape != [d] && shape != [d, d] {
            return Err(error(path, format_args!("box edges has shape {shape:?}")));
        }
        (h5(path, "reading box edges", e.read_raw::<f64>())?, None)
    } else if bx.link_exists("edges") {
        return Err(error(path, "box edges is neither a dataset nor an element with a value"));
    } else {
        if boundary.iter().any(|b| b == "periodic") {
            return Err(error(path, "periodic box without edges"));
        }
        (Vec::new(), None)
    };

    let mut elements = Vec::new();
    let mut particles: Option<(usize, String)> = None;
    let mut steps: Option<(Vec<i64>, String)> = None;
    let mut times: Option<Vec<f64>> = None;
    let names = h5(path, "listing /particles/all", all.member_names())?;
    for name in names.iter().filter(|s| *s != "box") {
        let n_here;
        if let Ok(g) = all.group(name) {
            let where_ = format!("/particles/all/{name}");
            let value = g
                .dataset("value")
                .map_err(|_| error(path, format_args!("{where_} has no value dataset")))?;
            let step = g
                .dataset("step")
                .map_err(|_| error(path, format_args!("{where_} has no step dataset")))?;
            let sd = h5(
                path,
                "reading step type",
                step.dtype().and_then(|t| t.to_descriptor()),
            )?;
            if !int_kind(&sd) || step.ndim() != 1 {
                return Err(error(
                    path,
                    format_args!("{where_}/step is not a 1-d integer dataset"),
                ));
            }
            let s = h5(
                path,
                &format!("reading {where_}/step"),
                step.read_raw::<i64>(),
            )?;
            let frames = s.len();
            let shape = value.shape();
            if shape.len() < 2 {
                return Err(error(
                    path,
                    format_args!("{where_}/value has shape {shape:?}, expected [frames, N, ...]"),
                ));
            }
            if shape[0] < frames {
                return Err(error(
                    path,
                    format_args!(
                        "{where_}/value has {} frames but step has {frames}",
                        shape[0]
                    ),
                ));
            }
            if let Ok(time) = g.dataset("time") {
                if time.ndim() != 1 || time.size() < frames {
                    return Err(error(
                        path,
                        format_args!(
                            "{where_}/time has {} entries but step has {frames}",
                            time.size()
                        ),
                    ));
                }
                let t = h5(
                    path,
                    &format!("reading {where_}/time"),
                    time.read_slice_1d::<f64, _>(0..frames),
                )?;
                times.get_or_insert(t.to_vec());
            }
            match &steps {
                None => steps = Some((s, name.clone())),
                Some((s0, n0)) if s0.len() != frames => {
                    return Err(error(
                        path,
                        format_args!(
                            "{where_} has {frames} frames but /particles/all/{n0} has {}",
                            s0.len()
                        ),
                    ))
                }
                _ => {}
            }
            n_here = shape[1];
        } else if let Ok(ds) = all.dataset(name) {
            // Time-independent element: [N, ...].
            let shape = ds.shape();
            if shape.is_empty() {
                return Err(error(
                    path,
                    format_args!("/particles/all/{name} is a scalar"),
                ));
            }
            n_here = shape[0];
        } else {
            return Err(error(
                path,
                format_args!("/particles/all/{name} is neither a group nor a dataset"),
            ));
        }
        match &particles {
            None => particles = Some((n_here, name.clone())),
            Some((n0, name0)) if *n0 != n_here => {
                return Err(error(
                    path,
                    format_args!("/particles/all/{name} has {n_here} particles but /particles/all/{name0} has {n0}"),
                ))
            }
            _ => {}
        }
        elements.push(name.clone());
    }
    elements.sort();
    let steps = steps.map(|s| s.0).unwrap_or_default();
    if edge_frames.is_some_and(|f| f < steps.len()) {
        return Err(error(path, format_args!("box/edges/value has fewer frames than step ({})", steps.len())));
    }
    let mut observables = Vec::new();
    if let Ok(g) = file.group("observables") {
        for name in h5(path, "listing /observables", g.member_names())? {
            let v = g.dataset(&format!("{name}/value")).map_err(|_| error(path, format_args!("/observables/{name} has no value dataset")))?;
            if v.ndim() != 1 || v.size() < steps.len() {
                return Err(error(path, format_args!("/observables/{name}/value has shape {:?} for {} frames", v.shape(), steps.len())));
            }
            observables.push(name);
        }
    }
    Ok(H5mdSummary {
        particles: particles.map_or(0, |p| p.0),
        frames: steps.len(),
        elements,
        times: times.unwrap_or_default(),
        steps,
        edges,
        observables,
        creator: (cname, cversion),
        author,
        clean,
    })
}
