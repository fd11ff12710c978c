//! Tests of `h5md`.

use super::*;
use hdf5::types::IntSize;

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gendpde-h5md-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Deterministic test value of `field` for particle `i` in frame `f`.
fn val(field: H5mdField, f: usize, i: usize, c: usize) -> f64 {
    match field.kind() {
        Kind::F64 => (f * 1000 + i * 10 + c) as f64 + 0.25,
        Kind::I32 => (f as f64) - (i * 3 + c) as f64,
        Kind::I64 => (i + 1) as f64,
    }
}

fn rows(field: H5mdField, f: usize, r: std::ops::Range<usize>) -> Vec<f64> {
    let w = field.width();
    r.flat_map(|i| (0..w).map(move |c| val(field, f, i, c)))
        .collect()
}

fn write_frames(w: &mut H5mdWriter, first_frame: usize, count: usize, n: usize) {
    let split = n / 2;
    for f in first_frame..first_frame + count {
        w.begin_frame(10 * f as u64, 0.5 * f as f64).unwrap();
        for field in w.fields().to_vec() {
            // Two row blocks, the second written first.
            w.write_rows(field, split, &rows(field, f, split..n))
                .unwrap();
            w.write_rows(field, 0, &rows(field, f, 0..split)).unwrap();
        }
        w.end_frame().unwrap();
    }
}

fn descriptor(ds: &Dataset) -> TypeDescriptor {
    ds.dtype().unwrap().to_descriptor().unwrap()
}

#[test]
fn parse_names() {
    for f in H5mdField::ALL {
        assert_eq!(H5mdField::parse(f.h5md_name()), Some(f));
        assert_eq!(H5mdField::from_h5md_name(f.h5md_name()), Some(f));
    }
    assert_eq!(H5mdField::parse("x"), Some(H5mdField::Position));
    assert_eq!(H5mdField::parse("v"), Some(H5mdField::Velocity));
    assert_eq!(H5mdField::parse("p"), Some(H5mdField::Momentum));
    assert_eq!(H5mdField::parse("type"), Some(H5mdField::Species));
    assert_eq!(H5mdField::parse("u"), Some(H5mdField::InternalEnergy));
    assert_eq!(H5mdField::parse("theta"), Some(H5mdField::Temperature));
    assert_eq!(H5mdField::parse("n"), Some(H5mdField::Density));
    assert_eq!(H5mdField::parse("xyz"), None);
    assert_eq!(H5mdField::Image.width(), 3);
    assert_eq!(H5mdField::Mass.width(), 1);
}

#[test]
fn create_write_read_back() {
    let path = tmp("full.h5");
    let n = 7;
    let fields = H5mdField::ALL;
    let mut w =
        H5mdWriter::create(&path, n, [10.0, 11.0, 12.5], &fields, &H5mdMeta::new("Tester", "0.1.0")).unwrap();
    assert_eq!(w.fields(), &fields);
    write_frames(&mut w, 0, 3, n);
    assert_eq!(w.frames(), 3);
    drop(w);

    let s = check_h5md(&path).unwrap();
    assert_eq!(s.particles, n);
    assert_eq!(s.frames, 3);
    assert_eq!(s.steps, vec![0, 10, 20]);
    assert_eq!(s.times, vec![0.0, 0.5, 1.0]);
    assert_eq!(s.edges, vec![10.0, 11.0, 12.5]);
    assert_eq!(s.author, "Tester");
    assert_eq!(s.creator, ("gendpde".to_string(), "0.1.0".to_string()));
    let mut names: Vec<String> = fields.iter().map(|f| f.h5md_name().to_string()).collect();
    names.sort();
    assert_eq!(s.elements, names);

    // Direct read-back.
    let file = File::open(&path).unwrap();
    let h5md = file.group("h5md").unwrap();
    assert_eq!(
        h5md.attr("version").unwrap().read_raw::<i32>().unwrap(),
        vec![1, 1]
    );
    assert!(matches!(
        descriptor_attr(&h5md.attr("version").unwrap()),
        TypeDescriptor::Integer(IntSize::U4)
    ));
    let creator = file.group("h5md/creator").unwrap();
    assert_eq!(
        creator
            .attr("name")
            .unwrap()
            .read_scalar::<VarLenUnicode>()
            .unwrap()
            .as_str(),
        "gendpde"
    );
    let bx = file.group("particles/all/box").unwrap();
    assert_eq!(
        bx.attr("dimension").unwrap().read_scalar::<i32>().unwrap(),
        3
    );
    let b = bx
        .attr("boundary")
        .unwrap()
        .read_raw::<VarLenUnicode>()
        .unwrap();
    assert_eq!(
        b.iter().map(|s| s.as_str()).collect::<Vec<_>>(),
        ["periodic"; 3]
    );
    let edges = bx.dataset("edges/value").unwrap();
    assert_eq!(edges.shape(), vec![3, 3]);
    assert_eq!(edges.read_raw::<f64>().unwrap(), [10.0, 11.0, 12.5].repeat(3));
    let first = fields[0].h5md_name();
    for series in ["step", "time"] {
        assert_eq!(
            bx.dataset(&format!("edges/{series}")).unwrap().read_raw::<f64>().unwrap(),
            file.dataset(&format!("particles/all/{first}/{series}")).unwrap().read_raw::<f64>().unwrap()
        );
    }
    assert!(edges.attr("unit").is_err(), "lj files are unitless");

    for field in fields {
        let g = file
            .group(&format!("particles/all/{}", field.h5md_name()))
            .unwrap();
        let value = g.dataset("value").unwrap();
        let expect_shape = if field.width() == 3 {
            vec![3, n, 3]
        } else {
            vec![3, n]
        };
        assert_eq!(value.shape(), expect_shape, "{field}");
        assert!(value.is_resizable());
        assert!(value.is_chunked());
        let step = g.dataset("step").unwrap();
        let time = g.dataset("time").unwrap();
        assert!(step.is_chunked() && time.is_chunked());
        assert_eq!(step.read_raw::<i64>().unwrap(), vec![0, 10, 20]);
        assert_eq!(time.read_raw::<f64>().unwrap(), vec![0.0, 0.5, 1.0]);
        assert!(matches!(
            descriptor(&step),
            TypeDescriptor::Integer(IntSize::U8)
        ));
        let expected: Vec<f64> = (0..3).flat_map(|f| rows(field, f, 0..n)).collect();
        let d = descriptor(&value);
        match field.kind() {
            Kind::F64 => {
                assert_eq!(d, TypeDescriptor::Float(hdf5::types::FloatSize::U8));
                assert_eq!(value.read_raw::<f64>().unwrap(), expected, "{field}");
            }
            Kind::I32 => {
                assert_eq!(d, TypeDescriptor::Integer(IntSize::U4), "{field}");
                let got: Vec<f64> = value
                    .read_raw::<i32>()
                    .unwrap()
                    .into_iter()
                    .map(f64::from)
                    .collect();
                assert_eq!(got, expected, "{field}");
            }
            Kind::I64 => {
                assert_eq!(d, TypeDescriptor::Integer(IntSize::U8), "{field}");
                let got: Vec<f64> = value
                    .read_raw::<i64>()
                    .unwrap()
                    .into_iter()
                    .map(|x| x as f64)
                    .collect();
                assert_eq!(got, expected, "{field}");
            }
        }
    }
    let _ = std::fs::remove_file(&path);
}

fn descriptor_attr(a: &Attribute) -> TypeDescriptor {
    a.dtype().unwrap().to_descriptor().unwrap()
}

#[test]
fn append_adds_frames() {
    let path = tmp("append.h5");
    let n = 5;
    let fields = [H5mdField::Position, H5mdField::Id, H5mdField::Temperature];
    let mut w = H5mdWriter::create(&path, n, [1.0, 2.0, 3.0], &fields, &H5mdMeta::new("a", "v")).unwrap();
    write_frames(&mut w, 0, 2, n);
    drop(w);
    // Another field order is fine; the set matters.
    let order = [H5mdField::Temperature, H5mdField::Position, H5mdField::Id];
    let mut w = H5mdWriter::append(&path, n, &order).unwrap();
    assert_eq!(w.frames(), 2);
    write_frames(&mut w, 2, 2, n);
    assert_eq!(w.frames(), 4);
    drop(w);
    let s = check_h5md(&path).unwrap();
    assert_eq!(s.frames, 4);
    assert_eq!(s.steps, vec![0, 10, 20, 30]);
    let file = File::open(&path).unwrap();
    let pos = file.dataset("particles/all/position/value").unwrap();
    assert_eq!(pos.shape(), vec![4, n, 3]);
    let expected: Vec<f64> = (0..4)
        .flat_map(|f| rows(H5mdField::Position, f, 0..n))
        .collect();
    assert_eq!(pos.read_raw::<f64>().unwrap(), expected);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn append_overwrites_incomplete_frame() {
    let path = tmp("incomplete.h5");
    let n = 4;
    let fields = [H5mdField::Velocity, H5mdField::Mass];
    let mut w = H5mdWriter::create(&path, n, [1.0; 3], &fields, &H5mdMeta::new("a", "v")).unwrap();
    write_frames(&mut w, 0, 2, n);
    w.begin_frame(99, 9.9).unwrap();
    w.write_rows(H5mdField::Mass, 0, &[1.0, 2.0]).unwrap();
    drop(w); // no end_frame
    let s = check_h5md(&path).unwrap();
    assert_eq!(s.frames, 2);
    let w = H5mdWriter::append(&path, n, &fields).unwrap();
    assert_eq!(w.frames(), 2);
    drop(w);
    assert_eq!(check_h5md(&path).unwrap().frames, 2);
    let mut w = H5mdWriter::append(&path, n, &fields).unwrap();
    assert_eq!(w.frames(), 2);
    write_frames(&mut w, 2, 1, n);
    drop(w);
    let file = File::open(&path).unwrap();
    assert_eq!(
        file.dataset("particles/all/mass/value").unwrap().shape(),
        vec![3, n]
    );
    assert_eq!(check_h5md(&path).unwrap().steps, vec![0, 10, 20]);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn append_mismatch_is_error() {
    let path = tmp("mismatch.h5");
    let fields = [H5mdField::Position, H5mdField::Species];
    let mut w = H5mdWriter::create(&path, 6, [1.0; 3], &fields, &H5mdMeta::new("a", "v")).unwrap();
    write_frames(&mut w, 0, 1, 6);
    drop(w);
    let e = H5mdWriter::append(&path, 5, &fields).unwrap_err();
    assert!(
        e.0.contains("6 particles") && e.0.contains("mismatch.h5"),
        "{e}"
    );
    let e = H5mdWriter::append(&path, 6, &[H5mdField::Position]).unwrap_err();
    assert!(e.0.contains("species"), "{e}");
    let e = H5mdWriter::append(
        &path,
        6,
        &[H5mdField::Position, H5mdField::Species, H5mdField::Mass],
    )
    .unwrap_err();
    assert!(e.0.contains("mass"), "{e}");
    let e = H5mdWriter::append(&tmp("does-not-exist.h5"), 6, &fields).unwrap_err();
    assert!(e.0.contains("does-not-exist.h5"), "{e}");
    // The file is untouched by the failed attempts.
    let mut w = H5mdWriter::append(&path, 6, &fields).unwrap();
    write_frames(&mut w, 1, 1, 6);
    drop(w);
    assert_eq!(check_h5md(&path).unwrap().frames, 2);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn bad_writes_are_errors() {
    let path = tmp("bad.h5");
    let n = 4;
    let fields = [H5mdField::Position, H5mdField::Species, H5mdField::Id];
    assert!(H5mdWriter::create(&path, n, [1.0; 3], &[], &H5mdMeta::new("a", "v")).is_err());
    assert!(H5mdWriter::create(
        &path,
        n,
        [1.0; 3],
        &[H5mdField::Mass, H5mdField::Mass],
        &H5mdMeta::new("a", "v")
    )
    .is_err());
    let mut w = H5mdWriter::create(&path, n, [1.0; 3], &fields, &H5mdMeta::new("a", "v")).unwrap();
    // Outside a frame.
    assert!(w.write_rows(H5mdField::Position, 0, &[0.0; 3]).is_err());
    assert!(w.end_frame().is_err());
    w.begin_frame(1, 0.1).unwrap();
    assert!(w.begin_frame(2, 0.2).is_err());
    // Row range.
    assert!(w.write_rows(H5mdField::Position, 4, &[0.0; 3]).is_err());
    assert!(w.write_rows(H5mdField::Position, 3, &[0.0; 6]).is_err());
    assert!(w
        .write_rows(H5mdField::Position, usize::MAX, &[0.0; 3])
        .is_err());
    assert!(w.write_rows(H5mdField::Position, 4, &[]).is_ok());
    // Data length not a multiple of the width.
    let e = w.write_rows(H5mdField::Position, 0, &[0.0; 4]).unwrap_err();
    assert!(e.0.contains("bad.h5"), "{e}");
    // Field not in the file.
    assert!(w.write_rows(H5mdField::Mass, 0, &[0.0]).is_err());
    // Non-integral / out-of-range integer fields.
    assert!(w.write_rows(H5mdField::Species, 0, &[0.5]).is_err());
    assert!(w.write_rows(H5mdField::Species, 0, &[1e10]).is_err());
    assert!(w.write_rows(H5mdField::Id, 0, &[f64::NAN]).is_err());
    assert!(w.write_rows(H5mdField::Id, 0, &[1e19]).is_err());
    w.write_rows(H5mdField::Id, 0, &[1.0, 2.0, 3.0, 4.0])
        .unwrap();
    w.write_rows(H5mdField::Species, 0, &[-1.0, 0.0, 1.0, 2.0])
        .unwrap();
    w.write_rows(H5mdField::Position, 0, &[0.5; 12]).unwrap();
    w.end_frame().unwrap();
    assert_eq!(w.frames(), 1);
    drop(w);
    assert_eq!(check_h5md(&path).unwrap().frames, 1);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn zero_particles() {
    let path = tmp("empty.h5");
    let fields = [H5mdField::Position, H5mdField::Mass];
    let mut w = H5mdWriter::create(&path, 0, [2.0; 3], &fields, &H5mdMeta::new("a", "v")).unwrap();
    write_frames(&mut w, 0, 2, 0);
    assert!(w.begin_frame(30, 1.0).is_ok());
    assert!(w.write_rows(H5mdField::Mass, 0, &[1.0]).is_err());
    w.end_frame().unwrap();
    drop(w);
    let s = check_h5md(&path).unwrap();
    assert_eq!((s.particles, s.frames), (0, 3));
    let file = File::open(&path).unwrap();
    assert_eq!(
        file.dataset("particles/all/position/value")
            .unwrap()
            .shape(),
        vec![3, 0, 3]
    );
    drop(file);
    let mut w = H5mdWriter::append(&path, 0, &fields).unwrap();
    write_frames(&mut w, 3, 1, 0);
    drop(w);
    assert_eq!(check_h5md(&path).unwrap().frames, 4);
    let _ = std::fs::remove_file(&path);
}

/// Child half of `killed_writer_is_recoverable`: writes 3 frames, starts
/// a 4th and aborts (no destructors, like kill -9).
#[test]
#[ignore]
fn killed_writer_child() {
    let Some(path) = std::env::var_os("GENDPDE_H5MD_KILL_CHILD") else {
        return;
    };
    let path = PathBuf::from(path);
    let n = 50;
    let fields = [H5mdField::Position, H5mdField::Id];
    let mut w = H5mdWriter::create(&path, n, [3.0; 3], &fields, &H5mdMeta::new("a", "v")).unwrap();
    write_frames(&mut w, 0, 3, n);
    w.begin_frame(30, 1.5).unwrap();
    w.write_rows(H5mdField::Position, 0, &rows(H5mdField::Position, 3, 0..n))
        .unwrap();
    std::process::abort();
}

#[test]
fn killed_writer_is_recoverable() {
    let path = tmp("killed.h5");
    let status = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "h5md::tests::killed_writer_child",
            "--ignored",
            "--nocapture",
            "--test-threads=1",
        ])
        .env("GENDPDE_H5MD_KILL_CHILD", &path)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(!status.success());
    let s = check_h5md(&path).unwrap();
    assert_eq!((s.frames, s.particles), (3, 50));
    assert!(!s.clean, "a killed writer leaves the file marked open");
    let fields = [H5mdField::Id, H5mdField::Position];
    let mut w = H5mdWriter::append(&path, 50, &fields).unwrap();
    assert_eq!(w.frames(), 3);
    write_frames(&mut w, 3, 2, 50);
    drop(w);
    let s = check_h5md(&path).unwrap();
    assert_eq!(s.steps, vec![0, 10, 20, 30, 40]);
    assert!(s.clean);
    let file = File::open(&path).unwrap();
    let pos = file.dataset("particles/all/position/value").unwrap();
    let expected: Vec<f64> = (0..5)
        .flat_map(|f| rows(H5mdField::Position, f, 0..50))
        .collect();
    assert_eq!(pos.read_raw::<f64>().unwrap(), expected);
    drop((pos, file));
    // repair on a clean file is harmless
    repair_h5md(&path).unwrap();
    assert!(check_h5md(&path).unwrap().clean);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn check_rejects_non_h5md() {
    let path = tmp("plain.h5");
    let f = File::create(&path).unwrap();
    f.create_group("particles/all").unwrap();
    drop(f);
    let e = check_h5md(&path).unwrap_err();
    assert!(e.0.contains("/h5md") && e.0.contains("plain.h5"), "{e}");
    let e = H5mdWriter::append(&path, 1, &[H5mdField::Mass]).unwrap_err();
    assert!(e.0.contains("plain.h5"), "{e}");
    std::fs::write(&path, b"not hdf5").unwrap();
    let e = check_h5md(&path).unwrap_err();
    assert!(e.0.contains("plain.h5"), "{e}");
    let e = H5mdWriter::append(&path, 1, &[H5mdField::Mass]).unwrap_err();
    assert!(e.0.contains("plain.h5"), "{e}");
    let _ = std::fs::remove_file(&path);
}

#[test]
fn units_author_edges_and_observables() {
    let path = tmp("meta.h5");
    let n = 4;
    let fields = [H5mdField::Position, H5mdField::Velocity, H5mdField::Species];
    let meta = H5mdMeta {
        email: Some("a@b.org".into()),
        units: Some("metal".into()),
        observables: vec!["temp".into(), "c_x[1]".into()],
        ..H5mdMeta::new("Ann", "v")
    };
    let mut w = H5mdWriter::create(&path, n, [1.0, 2.0, 3.0], &fields, &meta).unwrap();
    write_frames(&mut w, 0, 1, n);
    w.set_edges([4.0, 5.0, 6.0]);
    w.begin_frame(10, 0.5).unwrap();
    w.write_observables(&[("temp", 1.5), ("other", 9.0)]).unwrap();
    w.end_frame().unwrap();
    drop(w);
    let mut w = H5mdWriter::append(&path, n, &fields).unwrap();
    assert_eq!(w.observables().collect::<Vec<_>>(), ["temp", "c_x[1]"]);
    w.begin_frame(20, 1.0).unwrap();
    w.write_observables(&[("temp", 2.5), ("c_x[1]", -1.0)]).unwrap();
    w.end_frame().unwrap();
    drop(w);

    let s = check_h5md(&path).unwrap();
    assert_eq!((s.frames, s.observables.clone()), (3, vec!["temp".to_string(), "c_x[1]".to_string()]));
    let file = File::open(&path).unwrap();
    let text = |ds: &str, a: &str| file.dataset(ds).unwrap().attr(a).unwrap().read_scalar::<VarLenUnicode>().unwrap().to_string();
    assert_eq!(text("particles/all/position/value", "unit"), "Angstrom");
    assert_eq!(text("particles/all/velocity/value", "unit"), "Angstrom ps-1");
    assert_eq!(text("particles/all/position/time", "unit"), "ps");
    assert_eq!(text("particles/all/box/edges/value", "unit"), "Angstrom");
    assert!(file.dataset("particles/all/species/value").unwrap().attr("unit").is_err());
    let author = file.group("h5md/author").unwrap();
    assert_eq!(author.attr("email").unwrap().read_scalar::<VarLenUnicode>().unwrap().as_str(), "a@b.org");
    assert_eq!(author.attr("name").unwrap().read_scalar::<VarLenUnicode>().unwrap().as_str(), "Ann");
    // the edges of each frame: the created box, the one set, kept by append
    let edges = file.dataset("particles/all/box/edges/value").unwrap().read_raw::<f64>().unwrap();
    assert_eq!(edges, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 4.0, 5.0, 6.0]);
    let temp = file.dataset("observables/temp/value").unwrap().read_raw::<f64>().unwrap();
    assert!(temp[0].is_nan() && temp[1..] == [1.5, 2.5], "{temp:?}");
    let cx = file.dataset("observables/c_x[1]/value").unwrap().read_raw::<f64>().unwrap();
    assert!(cx[0].is_nan() && cx[1].is_nan() && cx[2] == -1.0, "{cx:?}");
    assert_eq!(file.dataset("observables/temp/step").unwrap().read_raw::<i64>().unwrap(), [0, 10, 20]);
    let _ = std::fs::remove_file(&path);
}
