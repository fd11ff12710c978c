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
    fn f64_3(&mut self) -> [f64; 3] {
        [self.f64(), self.f64(), self.f64()]
    }
    fn i32_3(&mut self) -> [i32; 3] {
        [self.next() as i32, self.next() as i32, self.next() as i32]
    }
}

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
    }
}

/// `natoms` particles with tags 3i + 1, random bits everywhere else.
fn particles(natoms: u64, seed: u64) -> ParticleRows {
    let mut g = Lcg(seed);
    let mut rows = ParticleRows::default();
    for i in 0..natoms {
        rows.tag.push(3 * i + 1);
        rows.kind.push(g.next() as u32);
        rows.mass.push(g.f64());
        rows.r.push(g.f64_3());
        rows.p.push(g.f64_3());
        rows.u.push(g.f64());
        rows.theta.push(g.f64());
        rows.image.push(g.i32_3());
        rows.cell.push(g.i32_3());
        rows.r_at_build.push(g.f64_3());
    }
    // A few values that must survive exactly.
    if natoms >= 4 {
        rows.mass[0] = f64::from_bits(0x7ff8_0000_dead_beef); // quiet NaN with payload
        rows.mass[1] = f64::from_bits(0x7ff0_0000_0000_0001); // signalling NaN
        rows.u[2] = -0.0;
        rows.theta[3] = f64::from_bits(0x0000_0000_0000_0003); // subnormal
        rows.r[0] = [f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE];
        rows.image[0] = [i32::MIN, i32::MAX, 0];
    }
    rows
}

fn slice_rows(all: &ParticleRows, a: usize, b: usize) -> ParticleRows {
    ParticleRows {
        tag: all.tag[a..b].to_vec(),
        kind: all.kind[a..b].to_vec(),
        mass: all.mass[a..b].to_vec(),
        r: all.r[a..b].to_vec(),
        p: all.p[a..b].to_vec(),
        u: all.u[a..b].to_vec(),
        theta: all.theta[a..b].to_vec(),
        image: all.image[a..b].to_vec(),
        cell: all.cell[a..b].to_vec(),
        r_at_build: all.r_at_build[a..b].to_vec(),
    }
}

fn append_rows(to: &mut ParticleRows, from: &ParticleRows) {
    to.tag.extend_from_slice(&from.tag);
    to.kind.extend_from_slice(&from.kind);
    to.mass.extend_from_slice(&from.mass);
    to.r.extend_from_slice(&from.r);
    to.p.extend_from_slice(&from.p);
    to.u.extend_from_slice(&from.u);
    to.theta.extend_from_slice(&from.theta);
    to.image.extend_from_slice(&from.image);
    to.cell.extend_from_slice(&from.cell);
    to.r_at_build.extend_from_slice(&from.r_at_build);
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn bits3(v: &[[f64; 3]]) -> Vec<[u64; 3]> {
    v.iter().map(|x| x.map(f64::to_bits)).collect()
}

fn rows_bit_identical(a: &ParticleRows, b: &ParticleRows) -> bool {
    a.tag == b.tag
        && a.kind == b.kind
        && bits(&a.mass) == bits(&b.mass)
        && bits3(&a.r) == bits3(&b.r)
        && bits3(&a.p) == bits3(&b.p)
        && bits(&a.u) == bits(&b.u)
        && bits(&a.theta) == bits(&b.theta)
        && a.image == b.image
        && a.cell == b.cell
        && bits3(&a.r_at_build) == bits3(&b.r_at_build)
}

fn assert_rows_bit_exact(a: &ParticleRows, b: &ParticleRows) {
    assert_eq!(a.tag, b.tag);
    assert_eq!(a.kind, b.kind);
    assert_eq!(bits(&a.mass), bits(&b.mass));
    assert_eq!(bits3(&a.r), bits3(&b.r));
    assert_eq!(bits3(&a.p), bits3(&b.p));
    assert_eq!(bits(&a.u), bits(&b.u));
    assert_eq!(bits(&a.theta), bits(&b.theta));
    assert_eq!(a.image, b.image);
    assert_eq!(a.cell, b.cell);
    assert_eq!(bits3(&a.r_at_build), bits3(&b.r_at_build));
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
    assert_eq!(a.cell_counts, b.cell_counts);
    assert_eq!(a.commands, b.commands);
    assert_eq!(a.creator_version, b.creator_version);
}

/// Writes `rows` to `path` in blocks ending at the given offsets.
fn write_restart(path: &Path, h: &RestartHeader, rows: &ParticleRows, ends: &[usize]) {
    let mut w = RestartWriter::create(path, h).unwrap();
    let mut a = 0;
    for &b in ends {
        w.write_rows(&slice_rows(rows, a, b)).unwrap();
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
    let mut got = ParticleRows::default();
    let mut block = ParticleRows::default();
    let mut start = 0;
    for len in [1, 99, 400, 0, 250, 1000] {
        r.read_rows(start, len, &mut block).unwrap();
        assert_eq!(block.len() as u64, len.min(1000 - start));
        append_rows(&mut got, &block);
        start += block.len() as u64;
    }
    assert_eq!(start, 1000);
    assert_rows_bit_exact(&got, &all);

    // Past the end: empty, and the buffer is cleared.
    r.read_rows(1000, 10, &mut block).unwrap();
    assert!(block.is_empty() && block.r.is_empty() && block.r_at_build.is_empty());
    r.read_rows(u64::MAX, u64::MAX, &mut block).unwrap();
    assert!(block.is_empty());
    r.read_rows(990, u64::MAX, &mut block).unwrap();
    assert_rows_bit_exact(&block, &slice_rows(&all, 990, 1000));
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
    write_restart(&path, &h, &ParticleRows::default(), &[]);
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
    write_restart(&path, &h2, &ParticleRows::default(), &[]);
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
        w.write_rows(&slice_rows(&particles(10, 1), 0, 5)).unwrap();
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
        w.write_rows(&slice_rows(&particles(20, 3), 0, 20)).unwrap();
        assert!(temp_path(&path).exists());
        // dropped without finish
    }
    assert_eq!(fs::read(&path).unwrap(), before);
    assert!(!temp_path(&path).exists());
    let r = RestartReader::open(&path).unwrap();
    let mut rows = ParticleRows::default();
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
    w.write_rows(&slice_rows(&all, 0, 9)).unwrap();
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
    let mut uneven = slice_rows(&all, 0, 3);
    uneven.theta.pop();
    assert_contains(&w.write_rows(&uneven).unwrap_err().0, "unequal lengths");
    w.write_rows(&slice_rows(&all, 0, 5)).unwrap();
    // Going backwards in tag order.
    assert_contains(
        &w.write_rows(&slice_rows(&all, 4, 6)).unwrap_err().0,
        "strictly increasing",
    );
    // Too many rows.
    let mut more = slice_rows(&all, 5, 10);
    append_rows(
        &mut more,
        &ParticleRows {
            tag: vec![1000],
            ..slice_rows(&all, 0, 1)
        },
    );
    assert_contains(&w.write_rows(&more).unwrap_err().0, "exceed natoms = 10");
    // A tag above max_tag.
    let mut big = slice_rows(&all, 5, 6);
    big.tag[0] = header(10).max_tag + 1;
    assert_contains(&w.write_rows(&big).unwrap_err().0, "exceeds max_tag");
    // Rejected blocks were not counted: the rest still completes the file.
    w.write_rows(&slice_rows(&all, 5, 10)).unwrap();
    w.finish().unwrap();
    let r = RestartReader::open(&path).unwrap();
    let mut rows = ParticleRows::default();
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
        g.new_dataset::<f64>().shape(99).create("u").unwrap();
    });
    assert_contains(
        &open_err(&p),
        "dataset 'particles/u' should have shape [100], found [99]",
    );

    let p = crafted(&dir, "short-r.h5", |f| {
        let g = f.group("particles").unwrap();
        g.unlink("r").unwrap();
        g.new_dataset::<f64>().shape((50, 3)).create("r").unwrap();
    });
    assert_contains(
        &open_err(&p),
        "dataset 'particles/r' should have shape [100, 3], found [50, 3]",
    );

    let p = crafted(&dir, "no-tag.h5", |f| {
        f.group("particles").unwrap().unlink("tag").unwrap()
    });
    assert_contains(&open_err(&p), "missing dataset 'particles/tag'");

    let p = crafted(&dir, "no-particles.h5", |f| f.unlink("particles").unwrap());
    assert_contains(
        &open_err(&p),
        "missing dataset 'particles/tag' ('/particles' does not exist)",
    );

    let p = crafted(&dir, "float-tags.h5", |f| {
        let g = f.group("particles").unwrap();
        g.unlink("tag").unwrap();
        g.new_dataset::<f64>().shape(100).create("tag").unwrap();
    });
    assert_contains(
        &open_err(&p),
        "dataset 'particles/tag' should be of type u64, found f64",
    );

    let p = crafted(&dir, "masses.h5", |f| {
        let g = f.group("types").unwrap();
        g.unlink("mass").unwrap();
        g.new_dataset_builder()
            .with_data(&[1.0f64, 2.0][..])
            .create("mass")
            .unwrap();
    });
    assert_contains(
        &open_err(&p),
        "dataset 'types/mass' should have shape [3], found [2]",
    );

    let p = crafted(&dir, "newer.h5", |f| {
        f.attr("format_version")
            .unwrap()
            .write_scalar(&2u32)
            .unwrap();
    });
    assert_contains(
        &open_err(&p),
        "format_version 2 is newer than this gendpde supports",
    );

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

#[test]
fn flipped_bytes_never_panic() {
    let dir = TempDir::new("fuzz");
    let path = dir.join("restart.h5");
    // Few particles, so that metadata makes up much of the file.
    let all = particles(40, 8);
    write_restart(&path, &header(40), &all, &[17, 40]);
    let good = fs::read(&path).unwrap();
    let bad = dir.join("bad.h5");
    let mut g = Lcg(0x5eed);
    let (mut opened, mut identical) = (0, 0);
    let nvar = 200;
    for variant in 0..nvar {
        let mut bytes = good.clone();
        let flips = 1 + g.below(4);
        for _ in 0..flips {
            // Half the flips land in the first 4 KiB (superblock, root
            // group, attributes), the rest anywhere.
            let span = if variant % 2 == 0 {
                bytes.len().min(4096)
            } else {
                bytes.len()
            };
            let at = g.below(span as u64) as usize;
            bytes[at] ^= 1 << g.below(8);
        }
        fs::write(&bad, &bytes).unwrap();
        if let Ok(r) = RestartReader::open(&bad) {
            opened += 1;
            let mut rows = ParticleRows::default();
            let mut got = ParticleRows::default();
            let mut ok = true;
            let mut start = 0;
            while start < r.header().natoms.min(1000) {
                match r.read_rows(start, 16, &mut rows) {
                    Ok(()) => append_rows(&mut got, &rows),
                    Err(_) => {
                        ok = false;
                        break;
                    }
                }
                start += 16;
            }
            if ok && rows_bit_identical(&got, &all) && r.header() == &header(40) {
                identical += 1;
            }
        }
    }
    eprintln!(
        "flipped-byte variants: {opened} of {nvar} opened, {identical} read back unchanged"
    );
}
