//! Tests of `restart`.

use super::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A scratch directory removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let k = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir()
            .join(format!("gendpde-restart-{}-{k}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }
    fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// Fixed 64-bit LCG (Knuth's MMIX constants).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 11
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn f64(&mut self) -> f64 {
        // Any bit pattern at all, so the round trip sees NaN payloads,
        // infinities, subnormals and -0.
        f64::from_bits(self.next() ^ (self.next() << 53))
    }
}

/// The columns of the test files (those of the engine's particle table, as of writing).
fn test_columns() -> Vec<ColumnSpec> {
    [("id", 1, true), ("type", 1, true), ("mass", 1, false), ("x", 3, false), ("p", 3, false), ("u", 1, false), ("theta", 1, false), ("image", 3, true), ("cell", 3, true), ("r_at_build", 3, false)]
        .into_iter()
        .map(|(name, width, integer)| ColumnSpec { name: name.into(), width, integer })
        .collect()
}

/// Values per row of [`test_columns`].
const W: usize = 20;

fn header(natoms: u64) -> RestartHeader {
    RestartHeader {
        step: 123_456_789_012,
        time: 0.1 + 0.2,
        dt: 1e-3 / 3.0,
        natoms,
        max_tag: 3 * natoms + 7,
        ntypes: 3,
        lo: [-5.5, -0.0, 1e-300],
        hi: [5.5, 10.0 / 3.0, 2.0],
        masses: vec![Some(1.0 / 3.0), None, Some(f64::from_bits(1))],
        energy0: Some(-1_234.567_890_123_456_7),
        last_build: 123_456_789_000,
        noise_shift: u64::MAX - 399,
        stale_tallies: true,
        cell_counts: Some([7, 3, 11]),
        commands: vec![
            "pair_style gendpde 1.0 12345".into(),
            "pair_coeff * * 25.0 4.5 1.0".into(),
            "fix 1 all shardlow".into(),
            "timestep 0.001".into(),
            "neighbor 0.3 bin".into(),
            "neigh_modify every 1 delay 0 check yes".into(),
            "".into(),
            "print \"unicode: θ ≈ 1\nsecond line\"".into(),
        ],
        creator_version: "gendpde 0.1.0 (test)".into(),
        columns: test_columns(),
        enabled: 0b1010_0000,
        groups: vec!["all".into(), "".into(), "hot slab".into()],
        state: vec![("heat/reservoir/hot".into(), vec![973.779697076279]), ("empty".into(), vec![]), ("window".into(), vec![1.0, -0.0, 5e-324])],
    }
}

/// `natoms` valid particles with tags 3i + 1 and random values (any finite bit
/// pattern where the column allows it).
fn particles(natoms: u64, seed: u64) -> Vec<f64> {
    let mut g = Lcg(seed);
    let h = header(natoms);
    let mut any = || loop {
        let x = g.f64();
        if x.is_finite() {
            return x;
        }
    };
    let mut rows = Vec::new();
    let mut g2 = Lcg(seed ^ 0xabcd);
    for i in 0..natoms {
        rows.push((3 * i + 1) as f64);
        rows.push((1 + g2.below(3)) as f64);
        rows.push(any().abs().max(f64::MIN_POSITIVE));
        for d in 0..3 {
            rows.push(h.lo[d] + (h.hi[d] - h.lo[d]) * (g2.below(1000) as f64 / 1000.0));
        }
        rows.extend([any(), any(), any(), any(), any()]);
        rows.extend((0..3).map(|_| g2.next() as i32 as f64));
        rows.extend((0..3).map(|d| g2.below(h.cell_counts.unwrap()[d] as u64) as f64));
        rows.extend([any(), any(), any()]);
    }
    // A few values that must survive exactly.
    if natoms >= 4 {
        rows[W + 9] = -0.0; // u
        rows[3 * W + 10] = f64::from_bits(3); // subnormal theta
        rows[2 * W + 2] = f64::MIN_POSITIVE; // mass
        rows[11..14].copy_from_slice(&[i32::MIN as f64, i32::MAX as f64, 0.0]); // image
    }
    rows
}

fn slice_rows(all: &[f64], a: usize, b: usize) -> &[f64] {
    &all[a * W..b * W]
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn assert_rows_bit_exact(a: &[f64], b: &[f64]) {
    assert_eq!(bits(a), bits(b));
}

fn assert_header_bit_exact(a: &RestartHeader, b: &RestartHeader) {
    let opt = |v: &[Option<f64>]| v.iter().map(|m| m.map(f64::to_bits)).collect::<Vec<_>>();
    assert_eq!(a.step, b.step);
    assert_eq!(a.time.to_bits(), b.time.to_bits());
    assert_eq!(a.dt.to_bits(), b.dt.to_bits());
    assert_eq!(
        (a.natoms, a.max_tag, a.ntypes),
        (b.natoms, b.max_tag, b.ntypes)
    );
    assert_eq!(a.lo.map(f64::to_bits), b.lo.map(f64::to_bits));
    assert_eq!(a.hi.map(f64::to_bits), b.hi.map(f64::to_bits));
    assert_eq!(opt(&a.masses), opt(&b.masses));
    assert_eq!(a.energy0.map(f64::to_bits), b.energy0.map(f64::to_bits));
    assert_eq!(a.last_build, b.last_build);
    assert_eq!(a.noise_shift, b.noise_shift);
    assert_eq!(a.stale_tallies, b.stale_tallies);
    assert_eq!(a.cell_counts, b.cell_counts);
    assert_eq!(a.commands, b.commands);
    assert_eq!(a.creator_version, b.creator_version);
    assert_eq!((&a.columns, a.enabled, &a.groups), (&b.columns, b.enabled, &b.groups));
    let state = |h: &RestartHeader| h.state.iter().map(|(n, v)| (n.clone(), bits(v))).collect::<Vec<_>>();
    assert_eq!(state(a), state(b));
}

/// Writes `rows` to `path` in blocks ending at the given offsets.
fn write_restart(path: &Path, h: &RestartHeader, rows: &[f64], ends: &[usize]) {
    let mut w = RestartWriter::create(path, h).unwrap();
    let mut a = 0;
    for &b in ends {
        w.write_rows(slice_rows(rows, a, b)).unwrap();
        a = b;
    }
    w.finish().unwrap();
}

fn open_err(path: &Path) -> String {
    match RestartReader::open(path) {
        Ok(_) => panic!("{} opened although it should not", path.display()),
        Err(e) => {
            assert!(
                e.0.contains(&path.display().to_string()),
                "error does not name the file: {e}"
            );
            e.0
        }
    }
}

fn assert_contains(msg: &str, want: &str) {
    assert!(
        msg.contains(want),
        "expected {want:?} in error message {msg:?}"
    );
}

#[test]
fn round_trip_is_bit_exact() {
    let dir = TempDir::new("round-trip");
    let path = dir.join("restart.h5");
    let h = header(1000);
    let all = particles(1000, 42);
    write_restart(&path, &h, &all, &[333, 334, 1000]);
    assert!(!temp_path(&path).exists(), "temporary file left behind");

    let r = RestartReader::open(&path).unwrap();
    assert_header_bit_exact(r.header(), &h);
    assert_eq!(
        r.header(),
        &RestartHeader {
            masses: r.header().masses.clone(),
            ..h.clone()
        }
    );

    // Read back in blocks unrelated to the written ones, the last one
    // running past natoms (clipped).
    let mut got = Vec::new();
    let mut block = Vec::new();
    let mut start = 0;
    for len in [1, 99, 400, 0, 250, 1000] {
        r.read_rows(start, len, &mut block).unwrap();
        assert_eq!((block.len() / W) as u64, len.min(1000 - start));
        got.extend_from_slice(&block);
        start += (block.len() / W) as u64;
    }
    assert_eq!(start, 1000);
    assert_rows_bit_exact(&got, &all);

    // Past the end: empty, and the buffer is cleared.
    r.read_rows(1000, 10, &mut block).unwrap();
    assert!(block.is_empty());
    r.read_rows(u64::MAX, u64::MAX, &mut block).unwrap();
    assert!(block.is_empty());
}

#[test]
fn optional_fields_and_empty_system_round_trip() {
    let dir = TempDir::new("optional");
    let path = dir.join("restart.h5");
    let h = RestartHeader {
        natoms: 0,
        max_tag: 0,
        ntypes: 2,
        masses: vec![None, None],
        energy0: None,
        cell_counts: None,
        commands: vec![],
        ..header(0)
    };
    write_restart(&path, &h, &[], &[]);
    let r = RestartReader::open(&path).unwrap();
    assert_eq!(r.header(), &h);
    let mut rows = particles(3, 1);
    r.read_rows(0, 10, &mut rows).unwrap();
    assert!(rows.is_empty());

    // Some(NaN) for energy0 stays distinct from None.
    let h2 = RestartHeader {
        energy0: Some(f64::NAN),
        ntypes: 0,
        masses: vec![],
        ..h
    };
    write_restart(&path, &h2, &[], &[]);
    let r = RestartReader::open(&path).unwrap();
    assert!(r.header().energy0.is_some_and(f64::is_nan));
    assert_eq!(r.header().masses, vec![]);
}

#[test]
fn unfinished_writer_leaves_no_file_and_keeps_existing_one() {
    let dir = TempDir::new("atomic");
    let path = dir.join("restart.h5");

    // Nothing there yet: a dropped writer leaves nothing behind.
    {
        let mut w = RestartWriter::create(&path, &header(10)).unwrap();
        w.write_rows(slice_rows(&particles(10, 1), 0, 5)).unwrap();
    }
    assert!(!path.exists());
    assert!(!temp_path(&path).exists());

    // A good file is untouched by a later writer that never finishes.
    let h = header(10);
    let all = particles(10, 2);
    write_restart(&path, &h, &all, &[10]);
    let before = fs::read(&path).unwrap();
    {
        let mut w = RestartWriter::create(&path, &header(20)).unwrap();
        w.write_rows(slice_rows(&particles(20, 3), 0, 20)).unwrap();
        assert!(temp_path(&path).exists());
        // dropped without finish
    }
    assert_eq!(fs::read(&path).unwrap(), before);
    assert!(!temp_path(&path).exists());
    let r = RestartReader::open(&path).unwrap();
    let mut rows = Vec::new();
    r.read_rows(0, 10, &mut rows).unwrap();
    assert_rows_bit_exact(&rows, &all);
}

#[test]
fn finish_with_too_few_rows_is_an_error() {
    let dir = TempDir::new("too-few");
    let path = dir.join("restart.h5");
    let all = particles(10, 4);
    write_restart(&path, &header(10), &all, &[10]);
    let before = fs::read(&path).unwrap();

    let mut w = RestartWriter::create(&path, &header(10)).unwrap();
    w.write_rows(slice_rows(&all, 0, 9)).unwrap();
    let e = w.finish().unwrap_err();
    assert_contains(&e.0, "only 9 of natoms = 10 particle rows were written");
    assert_contains(&e.0, &path.display().to_string());
    assert_eq!(fs::read(&path).unwrap(), before);
    assert!(!temp_path(&path).exists());
}

#[test]
fn writer_rejects_bad_rows_and_headers() {
    let dir = TempDir::new("bad-rows");
    let path = dir.join("restart.h5");
    let all = particles(10, 5);

    let mut w = RestartWriter::create(&path, &header(10)).unwrap();
    assert_contains(&w.write_rows(&slice_rows(&all, 0, 3)[1..]).unwrap_err().0, "do not make rows of 20");
    w.write_rows(slice_rows(&all, 0, 5)).unwrap();
    // Going backwards in tag order.
    assert_contains(&w.write_rows(slice_rows(&all, 4, 6)).unwrap_err().0, "strictly increasing");
    // Too many rows.
    let mut more = slice_rows(&all, 5, 10).to_vec();
    more.extend_from_slice(slice_rows(&all, 0, 1));
    more[5 * W] = 1000.0;
    assert_contains(&w.write_rows(&more).unwrap_err().0, "exceed natoms = 10");
    // A tag above max_tag.
    let mut big = slice_rows(&all, 5, 6).to_vec();
    big[0] = (header(10).max_tag + 1) as f64;
    assert_contains(&w.write_rows(&big).unwrap_err().0, "exceeds max_tag");
    // Rejected blocks were not counted: the rest still completes the file.
    w.write_rows(slice_rows(&all, 5, 10)).unwrap();
    w.finish().unwrap();
    let r = RestartReader::open(&path).unwrap();
    let mut rows = Vec::new();
    r.read_rows(0, 10, &mut rows).unwrap();
    assert_rows_bit_exact(&rows, &all);

    let bad = RestartHeader {
        masses: vec![Some(1.0)],
        ..header(10)
    };
    assert_contains(
        &RestartWriter::create(&path, &bad).unwrap_err().0,
        "expected 3 per-type masses",
    );
    let bad = RestartHeader {
        lo: [0.0; 3],
        hi: [1.0, 0.0, 1.0],
        ..header(10)
    };
    assert_contains(
        &RestartWriter::create(&path, &bad).unwrap_err().0,
        "lo < hi",
    );
    let bad = RestartHeader {
        masses: vec![None, Some(f64::NAN), None],
        ..header(10)
    };
    assert_contains(
        &RestartWriter::create(&path, &bad).unwrap_err().0,
        "cannot be stored",
    );
    let bad = RestartHeader {
        commands: vec!["a\0b".into()],
        ..header(10)
    };
    assert_contains(
        &RestartWriter::create(&path, &bad).unwrap_err().0,
        "script command",
    );
    assert!(!temp_path(&path).exists());
    let e =
        RestartWriter::create(&dir.join("no/such/dir/restart.h5"), &header(10)).unwrap_err();
    assert_contains(&e.0, "no/such/dir/restart.h5.tmp: cannot be created");
    // The good file is still there.
    RestartReader::open(&path).unwrap();
}

#[test]
fn open_missing_empty_and_text_files() {
    let dir = TempDir::new("not-hdf5");
    let missing = dir.join("missing.h5");
    assert_contains(&open_err(&missing), "does not exist");

    let empty = dir.join("empty.h5");
    fs::write(&empty, b"").unwrap();
    assert_contains(&open_err(&empty), "is empty");

    let text = dir.join("in.lj");
    fs::write(&text, "units lj\natom_style atomic\nlattice fcc 0.8442\n").unwrap();
    assert_contains(&open_err(&text), "is not an HDF5 file");

    let short = dir.join("short.h5");
    fs::write(&short, &HDF5_SIGNATURE[..5]).unwrap();
    assert_contains(&open_err(&short), "is not an HDF5 file");

    assert_contains(&open_err(&dir.0), "is not a regular file");
}

#[test]
fn open_truncated_restart() {
    let dir = TempDir::new("truncated");
    let path = dir.join("restart.h5");
    write_restart(&path, &header(1000), &particles(1000, 6), &[1000]);
    let bytes = fs::read(&path).unwrap();
    let n = bytes.len();
    let cut = dir.join("cut.h5");
    for len in [1, 8, 100, 512, 2048, n / 10, n / 3, n / 2, n - 100, n - 1] {
        fs::write(&cut, &bytes[..len]).unwrap();
        let msg = open_err(&cut);
        if len < 8 {
            assert_contains(&msg, "is not an HDF5 file");
        } else {
            assert_contains(&msg, "cannot be opened as HDF5 (truncated or corrupt?)");
        }
    }
}

#[test]
fn open_foreign_hdf5_files() {
    let dir = TempDir::new("foreign");
    hdf5::silence_errors(true);

    let plain = dir.join("plain.h5");
    {
        let f = File::create(&plain).unwrap();
        f.new_dataset_builder()
            .with_data(&[1.0f64, 2.0][..])
            .create("x")
            .unwrap();
    }
    assert_contains(
        &open_err(&plain),
        "is an HDF5 file but not a gendpde restart",
    );

    let other = dir.join("other.h5");
    {
        let f = File::create(&other).unwrap();
        write_attr(&f, "format", &FormatString::from_ascii("h5md").unwrap()).unwrap();
    }
    assert_contains(&open_err(&other), "root attribute 'format' is \"h5md\"");

    let wrong_type = dir.join("wrong-type.h5");
    {
        let f = File::create(&wrong_type).unwrap();
        write_attr(&f, "format", &1.5f64).unwrap();
    }
    assert_contains(
        &open_err(&wrong_type),
        "is not a gendpde restart: root attribute 'format' is a f64",
    );
}

/// Writes a valid 100-particle restart, then lets `edit` alter it.
fn crafted(dir: &TempDir, name: &str, edit: impl FnOnce(&File)) -> PathBuf {
    let path = dir.join(name);
    write_restart(&path, &header(100), &particles(100, 7), &[100]);
    hdf5::silence_errors(true);
    let f = File::open_rw(&path).unwrap();
    edit(&f);
    f.close().unwrap();
    path
}

#[test]
fn open_inconsistent_restarts() {
    let dir = TempDir::new("inconsistent");

    let p = crafted(&dir, "short-u.h5", |f| {
        let g = f.group("particles").unwrap();
        g.unlink("u").unwrap();
        checked(&g, "u", &[99], 0.0).unwrap();
    });
    assert_contains(&open_err(&p), "dataset 'particles/u' should have 100 rows of at most 16 values, found shape [99]");

    let p = crafted(&dir, "short-r.h5", |f| {
        let g = f.group("particles").unwrap();
        g.unlink("x").unwrap();
        checked(&g, "x", &[50, 3], 0.0).unwrap();
    });
    assert_contains(&open_err(&p), "dataset 'particles/x' should have 100 rows of at most 16 values, found shape [50, 3]");

    let p = crafted(&dir, "no-tag.h5", |f| f.group("particles").unwrap().unlink("id").unwrap());
    assert_contains(&open_err(&p), "missing dataset 'particles/id' of a listed particle column");

    let p = crafted(&dir, "no-particles.h5", |f| f.unlink("particles").unwrap());
    assert_contains(&open_err(&p), "missing dataset 'particles/columns' ('/particles' does not exist)");

    let p = crafted(&dir, "float-tags.h5", |f| {
        let g = f.group("particles").unwrap();
        g.unlink("id").unwrap();
        checked(&g, "id", &[100], 0.0).unwrap();
    });
    assert_contains(&open_err(&p), "lack the integer column 'id'");

    let p = crafted(&dir, "unchecked.h5", |f| {
        let g = f.group("particles").unwrap();
        g.unlink("u").unwrap();
        g.new_dataset::<f64>().shape(100).create("u").unwrap();
    });
    assert_contains(&open_err(&p), "dataset 'particles/u' has no checksum (Fletcher32 filter)");

    let p = crafted(&dir, "masses.h5", |f| {
        let g = f.group("types").unwrap();
        g.unlink("mass").unwrap();
        checked(&g, "mass", &[2], 1.0).unwrap().write_raw(&[1.0f64, 2.0]).unwrap();
    });
    assert_contains(
        &open_err(&p),
        "dataset 'types/mass' should have shape [3], found [2]",
    );

    let p = crafted(&dir, "newer.h5", |f| {
        f.attr("format_version")
            .unwrap()
            .write_scalar(&3u32)
            .unwrap();
    });
    assert_contains(
        &open_err(&p),
        "format_version 3 is newer than this gendpde supports",
    );

    let p = crafted(&dir, "older.h5", |f| f.attr("format_version").unwrap().write_scalar(&1u32).unwrap());
    assert_contains(&open_err(&p), "format_version 1 was written by an older gendpde");

    let p = crafted(&dir, "no-step.h5", |f| f.delete_attr("step").unwrap());
    assert_contains(&open_err(&p), "missing root attribute 'step'");

    let p = crafted(&dir, "float-step.h5", |f| {
        f.delete_attr("step").unwrap();
        write_attr(f, "step", &5.0f64).unwrap();
    });
    assert_contains(
        &open_err(&p),
        "root attribute 'step' should be of type u64, found f64",
    );

    let p = crafted(&dir, "cells.h5", |f| {
        f.delete_attr("cell_counts").unwrap();
        f.new_attr_builder()
            .with_data(&[1u64, 2][..])
            .create("cell_counts")
            .unwrap();
    });
    assert_contains(
        &open_err(&p),
        "root attribute 'cell_counts' should have shape [3], found [2]",
    );

    let p = crafted(&dir, "box.h5", |f| {
        f.dataset("box/hi")
            .unwrap()
            .write_raw(&[1.0f64, -1.0, 1.0][..])
            .unwrap();
    });
    assert_contains(&open_err(&p), "inconsistent header: box bounds");
}

/// Reads every row of a restart (in blocks of 16).
fn read_all_rows(r: &RestartReader) -> Result<Vec<f64>, RestartError> {
    let (mut rows, mut got, mut start) = (Vec::new(), Vec::new(), 0);
    while start < r.header().natoms {
        r.read_rows(start, 16, &mut rows)?;
        got.extend_from_slice(&rows);
        start += 16;
    }
    Ok(got)
}

#[test]
fn flipped_bits_are_refused_or_harmless() {
    let dir = TempDir::new("fuzz");
    let path = dir.join("restart.h5");
    // Few particles, so that metadata makes up much of the file.
    let all = particles(40, 8);
    write_restart(&path, &header(40), &all, &[17, 40]);
    let good = fs::read(&path).unwrap();
    let bad = dir.join("bad.h5");
    let mut g = Lcg(0x5eed);
    let (mut refused, mut harmless) = (0, 0);
    let nvar = 1000;
    for variant in 0..nvar {
        let mut bytes = good.clone();
        // Half the flips land in the first 4 KiB (superblock, root group,
        // attributes), the rest anywhere.
        let span = if variant % 2 == 0 { bytes.len().min(4096) } else { bytes.len() };
        let at = g.below(span as u64) as usize;
        bytes[at] ^= 1 << g.below(8);
        fs::write(&bad, &bytes).unwrap();
        match RestartReader::open(&bad).and_then(|r| read_all_rows(&r).map(|rows| (r, rows))) {
            Err(e) => {
                assert_contains(&e.0, &bad.display().to_string());
                refused += 1;
            }
            Ok((r, rows)) => {
                // accepted: then nothing the continuation uses has changed
                if bits(&rows) != bits(&all) {
                    let k = rows.iter().zip(&all).position(|(a, b)| a.to_bits() != b.to_bits());
                    let k = k.unwrap_or(0);
                    panic!("flip at byte {at} (bit {:#x}) of {} changed value {k}: {:e} -> {:e} ({:#x} -> {:#x})", bytes[at] ^ good[at], bytes.len(), all[k], rows[k], all[k].to_bits(), rows[k].to_bits());
                }
                assert_header_bit_exact(r.header(), &header(40));
                assert_rows_bit_exact(&rows, &all);
                harmless += 1;
            }
        }
    }
    eprintln!("flipped-bit variants: {refused} of {nvar} refused, {harmless} read back unchanged (bits outside the data)");
}

/// Writes a restart whose row `k` has `edit` applied.
fn with_row(dir: &TempDir, name: &str, k: usize, edit: impl FnOnce(&mut [f64])) -> PathBuf {
    let path = dir.join(name);
    let mut all = particles(10, 9);
    edit(&mut all[k * W..(k + 1) * W]);
    write_restart(&path, &header(10), &all, &[10]);
    path
}

fn read_err(path: &Path) -> String {
    let r = RestartReader::open(path).unwrap();
    let e = read_all_rows(&r).unwrap_err().0;
    assert_contains(&e, &path.display().to_string());
    e
}

#[test]
fn rows_are_validated_like_a_data_file() {
    let dir = TempDir::new("validate");
    assert_contains(&read_err(&with_row(&dir, "mass.h5", 3, |r| r[2] = -1.0)), "particle row 3: mass -1: expected a positive mass");
    assert_contains(&read_err(&with_row(&dir, "type.h5", 4, |r| r[1] = 4.0)), "particle row 4: type 4 is outside 1..=3");
    assert_contains(&read_err(&with_row(&dir, "zero-type.h5", 0, |r| r[1] = 0.0)), "type 0 is outside 1..=3");
    assert_contains(&read_err(&with_row(&dir, "nan.h5", 5, |r| r[9] = f64::NAN)), "particle row 5: column 'u' holds [NaN]; expected finite values");
    assert_contains(&read_err(&with_row(&dir, "far.h5", 6, |r| r[3] = 1e9)), "lies far outside the box");
    assert_contains(&read_err(&with_row(&dir, "cell.h5", 7, |r| r[16] = 11.0)), "particle row 7: cell [");
    // duplicate tags: the writer refuses them, so the file is edited afterwards
    let p = crafted(&dir, "dup.h5", |f| {
        let d = f.dataset("particles/id").unwrap();
        let mut ids = d.read_raw::<i64>().unwrap();
        ids[5] = ids[4];
        d.write_raw(&ids).unwrap();
    });
    let r = RestartReader::open(&p).unwrap();
    assert_contains(&read_all_rows(&r).unwrap_err().0, "particle row 5: id 13 after id 13: expected increasing ids");
    let p = crafted(&dir, "mass-type.h5", |f| f.dataset("types/mass").unwrap().write_raw(&[1.0, -2.0, f64::NAN][..]).unwrap());
    assert_contains(&open_err(&p), "a per-type mass of -2");
}
