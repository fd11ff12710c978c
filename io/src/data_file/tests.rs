//! Tests of `data_file`.

use super::*;

/// A small dpd-style file in the layout LAMMPS writes.
const SMALL: &str = "\
LAMMPS data file via write_data, atom_style dpd

3 atoms
2 atom types

0.0 10.0 xlo xhi
-5.0 5.0 ylo yhi
0.0 2.5e1 zlo zhi

Masses

1 1.0
2 2.5

Atoms # dpd

1 1 1.0 0.5 0.5 0.5 0 0 0
2 2 1.25 9.75 -4.0 3.0 1 -1 2
3 1 0.999 5.0 0.0 12.5

Velocities

1 0.1 -0.2 0.3
3 0.0 0.0 1e-3
2 -1.5 2.0 0.0
";

fn parse(text: &str) -> Result<DataFile, ScriptError> {
    parse_data("data.dpde", text, AtomStyle::Dpd)
}

fn error(text: &str) -> String {
    match parse(text) {
        Ok(data) => panic!("expected an error, got {data:?}"),
        Err(e) => e.to_string(),
    }
}

/// SMALL with line `line` (1-based) replaced by `with`.
fn replace_line(line: usize, with: &str) -> String {
    SMALL
        .lines()
        .enumerate()
        .map(|(i, l)| if i + 1 == line { with } else { l })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A fresh scratch directory for file-based tests.
fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gendpde-io-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A LAMMPS-DPDE-style file: `n`^3 atoms on a lattice in a 40^3 box.
fn dpde_file(n: usize) -> String {
    let mut text = format!(
        "DPD-E test\n\n{} atoms\n1 atom types\n\n\
         0.0 40.0 xlo xhi\n0.0 40.0 ylo yhi\n0.0 40.0 zlo zhi\n\n\
         Masses\n\n1 100.0\n\nAtoms\n\n",
        n * n * n
    );
    let spacing = 40.0 / n as f64;
    let mut id = 0;
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                id += 1;
                let theta = 1.0 + 0.001 * (id % 17) as f64;
                let _ = writeln!(
                    text,
                    "{id} 1 {theta} {} {} {}",
                    (i as f64 + 0.5) * spacing,
                    (j as f64 + 0.5) * spacing,
                    (k as f64 + 0.5) * spacing
                );
            }
        }
    }
    text.push_str("\nVelocities\n\n");
    for id in 1..=n * n * n {
        let v = (id as f64 * 0.37).sin();
        let _ = writeln!(text, "{id} {v} {} {}", -v / 3.0, v * 1e-7);
    }
    text
}

#[test]
fn reads_small_file() {
    let data = parse(SMALL).unwrap();
    assert_eq!(
        data.title,
        "LAMMPS data file via write_data, atom_style dpd"
    );
    assert_eq!((data.natoms, data.ntypes), (3, 2));
    assert_eq!(data.lo, [0.0, -5.0, 0.0]);
    assert_eq!(data.hi, [10.0, 5.0, 25.0]);
    assert_eq!(data.masses, vec![Some(1.0), Some(2.5)]);
    assert_eq!(
        data.atoms[1],
        DataAtom {
            tag: 2,
            kind: 2,
            theta: Some(1.25),
            edpd: None,
            sph_rho: None,
            r: [9.75, -4.0, 3.0],
            image: [1, -1, 2],
        }
    );
    assert_eq!(data.atoms[2].image, [0, 0, 0]);
    assert_eq!(data.atoms[2].theta, Some(0.999));
    let v = data.velocities.unwrap();
    assert_eq!(v[1], (3, [0.0, 0.0, 1e-3]));
}

#[test]
fn dpde_header_and_round_trip() {
    let text = dpde_file(10);
    let data = parse(&text).unwrap();
    assert_eq!(
        (data.natoms, data.ntypes, data.atoms.len()),
        (1000, 1, 1000)
    );
    assert_eq!((data.lo, data.hi), ([0.0; 3], [40.0; 3]));
    assert_eq!(data.masses, vec![Some(100.0)]);
    assert_eq!(data.velocities.as_ref().map(Vec::len), Some(1000));

    let dir = scratch("dpde-round-trip");
    let path = dir.join("data.dpde");
    write_data(&path, &data, AtomStyle::Dpd).unwrap();
    assert!(!dir.join("data.dpde.tmp").exists());
    let back = read_data(&path, AtomStyle::Dpd).unwrap();
    assert_eq!(back, data);
    let written = std::fs::read_to_string(&path).unwrap();
    assert!(written.starts_with("DPD-E test\n\n1000 atoms\n1 atom types\n"));
    assert!(written.contains("\nAtoms # dpd\n\n1 1 1.001 "));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn round_trip_keeps_awkward_floats() {
    let mut data = parse(SMALL).unwrap();
    data.atoms[0].r = [0.1 + 0.2, 1.0 / 3.0, 7.0e-300];
    data.atoms[0].theta = Some(1e300);
    data.atoms[1].r = [-0.0, 9.999_999_999_999_998, 123_456_789_012_345_680.0];
    data.lo[0] = -1e-20;
    let dir = scratch("awkward-round-trip");
    let path = dir.join("data.out");
    write_data(&path, &data, AtomStyle::Dpd).unwrap();
    assert_eq!(read_data(&path, AtomStyle::Dpd).unwrap(), data);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn atomic_style_round_trip() {
    let text = "atomic\n2 atoms\n1 atom types\n0 1 xlo xhi\n\nAtoms # atomic\n\n\
                7 1 0.25 0.5 0.75\n3 1 0.5 0.5 0.5 -1 0 4\n";
    let data = parse_data("data.atomic", text, AtomStyle::Atomic).unwrap();
    assert_eq!(data.atoms[0].theta, None);
    assert_eq!(data.atoms[1].image, [-1, 0, 4]);
    assert_eq!(data.masses, vec![None]);
    assert_eq!(data.velocities, None);
    // Defaults for the dimensions the header leaves out.
    assert_eq!((data.lo, data.hi), ([0.0, -0.5, -0.5], [1.0, 0.5, 0.5]));
    let dir = scratch("atomic-round-trip");
    let path = dir.join("data.atomic");
    write_data(&path, &data, AtomStyle::Atomic).unwrap();
    let written = std::fs::read_to_string(&path).unwrap();
    assert!(!written.contains("Masses") && !written.contains("Velocities"));
    assert!(written.contains("Atoms # atomic"));
    assert_eq!(read_data(&path, AtomStyle::Atomic).unwrap(), data);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn write_refuses_what_it_cannot_read_back() {
    let dir = scratch("write-refuses");
    let path = dir.join("data.bad");
    let good = parse(SMALL).unwrap();
    let mut cases = Vec::new();
    let mut d = good.clone();
    d.natoms = 4;
    cases.push(d);
    let mut d = good.clone();
    d.masses[1] = None;
    cases.push(d);
    let mut d = good.clone();
    d.atoms[0].theta = None;
    cases.push(d);
    let mut d = good.clone();
    d.atoms[0].r[1] = f64::NAN;
    cases.push(d);
    let mut d = good.clone();
    d.velocities.as_mut().unwrap().pop();
    cases.push(d);
    for d in cases {
        let e = write_data(&path, &d, AtomStyle::Dpd).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
        assert!(!path.exists());
    }
    // The atomic style simply drops dpdTheta.
    let mut d = good.clone();
    d.atoms[0].theta = None;
    write_data(&path, &d, AtomStyle::Atomic).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn empty_system_round_trip() {
    let data = DataFile {
        title: "empty".into(),
        natoms: 0,
        ntypes: 2,
        lo: [0.0; 3],
        hi: [1.0, 2.0, 3.0],
        masses: vec![Some(1.0), Some(2.0)],
        pair_coeffs: None,
        atoms: vec![],
        velocities: Some(vec![]),
    };
    let dir = scratch("empty-round-trip");
    let path = dir.join("data.empty");
    write_data(&path, &data, AtomStyle::Dpd).unwrap();
    assert_eq!(read_data(&path, AtomStyle::Dpd).unwrap(), data);
    let data = DataFile {
        velocities: None,
        ..data
    };
    write_data(&path, &data, AtomStyle::Dpd).unwrap();
    assert_eq!(read_data(&path, AtomStyle::Dpd).unwrap(), data);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_file() {
    let e = read_data(Path::new("/nonexistent/data.dpde"), AtomStyle::Dpd).unwrap_err();
    assert!(e
        .to_string()
        .starts_with("cannot open data file '/nonexistent/data.dpde'"));
}

#[test]
fn comments_blank_lines_and_ignored_header_keywords() {
    let text = "# title with # signs\n\
                \n   # a comment\n\
                1 atom types # trailing\n\
                0 bonds\n0 angles\n5 bond types\n2 extra bond per atom\n\
                2 atoms\n\
                0 4 xlo xhi\n0 4 ylo yhi\n0 4 zlo zhi\n\
                Atoms\n\
                # comment inside a section\n\
                1 1 2.0 1 1 1\n\n\
                2 1 2.0 2 2 2 # trailing comment\n";
    let data = parse(text).unwrap();
    assert_eq!(data.title, "# title with # signs");
    assert_eq!(data.atoms.len(), 2);
    assert_eq!(data.atoms[1].r, [2.0, 2.0, 2.0]);
}

#[test]
fn column_errors() {
    assert_eq!(
        error(&replace_line(17, "1 1 1.0 0.5 0.5")),
        "data.dpde:17: Atoms: expected 6 columns (id type dpdTheta x y z), got 5"
    );
    assert_eq!(
        error(&replace_line(17, "1 1 1.0 0.5 0.5 0.5 0")),
        "data.dpde:17: Atoms: expected 6 or 9 columns (id type dpdTheta x y z [ix iy iz]), got 7"
    );
    let e = parse_data("data.atomic", SMALL, AtomStyle::Atomic).unwrap_err();
    assert_eq!(
        e.to_string(),
        "data.dpde:15: Atoms: the section is marked '# dpd' but atom_style atomic was requested"
            .replace("data.dpde", "data.atomic")
    );
    let unmarked = replace_line(15, "Atoms");
    let e = parse_data("d", &unmarked, AtomStyle::Atomic).unwrap_err();
    assert_eq!(
        e.to_string(),
        "d:17: Atoms: expected 5 or 8 columns (id type x y z [ix iy iz]), got 9"
    );
    assert_eq!(
        error(&replace_line(12, "1 1.0 7")),
        "data.dpde:12: Masses: expected 2 columns (type mass), got 3"
    );
    assert_eq!(
        error(&replace_line(23, "1 0.1 -0.2")),
        "data.dpde:23: Velocities: expected 4 columns (id vx vy vz), got 3"
    );
}

#[test]
fn value_errors() {
    let cases = [
        (17, "1 3 1.0 0.5 0.5 0.5", "data.dpde:17: Atoms: atom type 3 is outside 1..2"),
        (17, "1 0 1.0 0.5 0.5 0.5", "data.dpde:17: Atoms: atom type 0 is outside 1..2"),
        (
            17,
            "1 x 1.0 0.5 0.5 0.5",
            "data.dpde:17: Atoms: expected an integer atom type, got 'x'",
        ),
        (
            18,
            "1 2 1.0 0.5 0.5 0.5",
            "data.dpde:18: Atoms: duplicate atom id 1 (first at line 17)",
        ),
        (
            17,
            "0 1 1.0 0.5 0.5 0.5",
            "data.dpde:17: Atoms: expected a positive integer atom id, got '0'",
        ),
        (
            17,
            "-1 1 1.0 0.5 0.5 0.5",
            "data.dpde:17: Atoms: expected a positive integer atom id, got '-1'",
        ),
        (
            17,
            "1 1 0.0 0.5 0.5 0.5",
            "data.dpde:17: Atoms: dpdTheta must be positive, got 0",
        ),
        (
            17,
            "1 1 -2 0.5 0.5 0.5",
            "data.dpde:17: Atoms: dpdTheta must be positive, got -2",
        ),
        (17, "1 1 1.0 0.5 nan 0.5", "data.dpde:17: Atoms: y: 'nan' is not a finite number"),
        (17, "1 1 1.0 0.5 0.5 inf", "data.dpde:17: Atoms: z: 'inf' is not a finite number"),
        (17, "1 1 1.0 1e999 0.5 0.5", "data.dpde:17: Atoms: x: '1e999' is not a finite number"),
        (17, "1 1 NaN 0.5 0.5 0.5", "data.dpde:17: Atoms: dpdTheta: 'NaN' is not a finite number"),
        (17, "1 1 1.0 0.5 0.5 0.5z", "data.dpde:17: Atoms: z: expected a number, got '0.5z'"),
        (
            17,
            "1 1 1.0 0.5 0.5 0.5 0 0 1.5",
            "data.dpde:17: Atoms: iz: expected an integer image flag, got '1.5'",
        ),
        (12, "3 1.0", "data.dpde:12: Masses: atom type 3 is outside 1..2"),
        (13, "1 2.0", "data.dpde:13: Masses: second mass for type 1 (the first is at line 12)"),
        (12, "1 -1.0", "data.dpde:12: Masses: mass must be positive, got -1"),
        (12, "1 inf", "data.dpde:12: Masses: mass: 'inf' is not a finite number"),
        (
            23,
            "4 0.1 -0.2 0.3",
            "data.dpde:23: Velocities: velocity for atom id 4, which is not in the Atoms section",
        ),
        (
            24,
            "1 0.0 0.0 1e-3",
            "data.dpde:24: Velocities: second velocity for atom id 1 (the first is at line 23)",
        ),
        (25, "2 -1.5 2.0 -inf", "data.dpde:25: Velocities: vz: '-inf' is not a finite number"),
    ];
    for (line, with, expected) in cases {
        assert_eq!(
            error(&replace_line(line, with)),
            expected,
            "line {line}: {with}"
        );
    }
}

#[test]
fn header_errors() {
    let cases = [
        (
            5,
            "10.0 0.0 xlo xhi",
            "data.dpde:5: 'xlo xhi': the lower bound 10 is not below the upper bound 0",
        ),
        (
            6,
            "5 5 ylo yhi",
            "data.dpde:6: 'ylo yhi': the lower bound 5 is not below the upper bound 5",
        ),
        (
            7,
            "0 nan zlo zhi",
            "data.dpde:7: 'zlo zhi': 'nan' is not a finite number",
        ),
        (
            7,
            "0 zlo zhi",
            "data.dpde:7: 'zlo zhi' needs 2 values before it, got 1",
        ),
        (
            8,
            "0.0 0.0 0.0 xy xz yz",
            "data.dpde:8: 'xy xz yz': triclinic boxes are not supported",
        ),
        (
            8,
            "12 bonds",
            "data.dpde:8: the header gives 12 bonds, but gendpde supports none",
        ),
        (
            8,
            "1 angles",
            "data.dpde:8: the header gives 1 angles, but gendpde supports none",
        ),
        (
            8,
            "3 atoms",
            "data.dpde:8: 'atoms' given twice (first at line 3)",
        ),
        (
            8,
            "7 widgets",
            "data.dpde:8: unknown header line '7 widgets'",
        ),
        (
            3,
            "3.5 atoms",
            "data.dpde:3: 'atoms' needs a non-negative integer, got '3.5'",
        ),
        (
            3,
            "-3 atoms",
            "data.dpde:3: 'atoms' needs a non-negative integer, got '-3'",
        ),
        (
            4,
            "0 atom types",
            "data.dpde:4: the number of atom types must be between 1 and 1000000, got 0",
        ),
        (4, "1", "data.dpde:4: unknown header line '1'"),
        (4, "", "data.dpde:10: the header has no 'atom types' line"),
    ];
    for (line, with, expected) in cases {
        assert_eq!(
            error(&replace_line(line, with)),
            expected,
            "line {line}: {with}"
        );
    }
}

#[test]
fn section_errors() {
    assert_eq!(
        error(&replace_line(19, "")),
        "data.dpde:15: Atoms: expected 3 lines (3 atoms in the header), \
         found 2 before section 'Velocities' at line 21"
    );
    assert_eq!(
        error(&replace_line(13, "")),
        "data.dpde:10: Masses: expected 2 lines (2 atom types in the header), \
         found 1 before section 'Atoms' at line 15"
    );
    assert_eq!(
        error(&replace_line(3, "2 atoms")),
        "data.dpde:19: Atoms: more than 2 lines (2 atoms in the header)"
    );
    assert_eq!(
        error(&format!("{SMALL}4 0 0 0\n")),
        "data.dpde:26: Velocities: more than 3 lines (3 atoms in the header)"
    );
    assert_eq!(
        error(&format!("{SMALL}\nBonds\n\n1 1 1 2\n")),
        "data.dpde:27: unsupported section 'Bonds': gendpde reads only Masses, Pair Coeffs, PairIJ Coeffs, Atoms and Velocities"
    );
    assert_eq!(
        error(&format!("{SMALL}\nMasses\n\n1 1.0\n2 1.0\n")),
        "data.dpde:27: Masses: second Masses section (the first is at line 10)"
    );
    // Truncated in the middle of a section.
    let truncated: String = SMALL.lines().take(18).map(|l| format!("{l}\n")).collect();
    assert_eq!(
        error(&truncated),
        "data.dpde:15: Atoms: expected 3 lines (3 atoms in the header), \
         found 2 before the end of the file at line 18"
    );
    let truncated: String = SMALL.lines().take(23).collect::<Vec<_>>().join("\n");
    assert_eq!(
        error(&truncated),
        "data.dpde:21: Velocities: expected 3 lines (3 atoms in the header), \
         found 1 before the end of the file at line 23"
    );
    // No Atoms section at all.
    let header_only: String = SMALL.lines().take(14).map(|l| format!("{l}\n")).collect();
    assert_eq!(
        error(&header_only),
        "data.dpde:3: the header gives 3 atoms but the file has no Atoms section"
    );
    // Velocities before Atoms.
    let text = "t\n1 atoms\n1 atom types\nVelocities\n\n1 0 0 0\nAtoms\n\n1 1 1 0 0 0\n";
    assert_eq!(
        error(text),
        "data.dpde:4: Velocities: the Atoms section must come before Velocities"
    );
}

#[test]
fn degenerate_inputs() {
    assert_eq!(
        error(""),
        "data.dpde:1: the header has no 'atom types' line"
    );
    let data = parse("title only\n1 atom types\n").unwrap();
    assert_eq!((data.natoms, data.atoms.len()), (0, 0));
    let data = parse("t\r\n0 atoms\r\n1 atom types\r\n\r\nAtoms # dpd\r\n\r\n").unwrap();
    assert!(data.atoms.is_empty());
    assert!(parse("t\n1 atom types\n99999999999999999999 atoms\n").is_err());
    assert!(parse("t\n4294967296 atom types\n").is_err());
}

#[test]
fn mutated_files_never_panic() {
    let base = SMALL.as_bytes();
    const JUNK: &[&str] = &[
        "",
        " ",
        "\n",
        "#",
        "-",
        "0",
        "1",
        "9",
        ".",
        "e",
        "nan",
        "inf",
        "Atoms",
        "Masses",
        "Velocities",
        "Atoms # atomic",
        "xlo xhi",
        "atom types",
        "atoms",
        "bonds",
        "\r",
        "\t",
        "é",
        "😀",
        "\0",
        "99999999999999999999",
        "-2147483649",
        "1e400",
        "+",
        "xy xz yz",
    ];
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut rand = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 33) as usize
    };
    // Every truncation of a valid file.
    for end in (0..=SMALL.len()).filter(|&i| SMALL.is_char_boundary(i)) {
        let _ = parse(&SMALL[..end]);
    }
    let mut accepted = 0;
    for round in 0..4000 {
        let mut text = String::from_utf8_lossy(base).into_owned();
        let edits = 1 + rand() % 4;
        for _ in 0..edits {
            let mut at = rand() % (text.len() + 1);
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            match rand() % 5 {
                0 => text.truncate(at),
                1 => {
                    let mut end = (at + 1 + rand() % 12).min(text.len());
                    while !text.is_char_boundary(end) {
                        end -= 1;
                    }
                    text.replace_range(at..end, "");
                }
                2 => text.insert_str(at, JUNK[rand() % JUNK.len()]),
                3 => {
                    // Duplicate a random line.
                    let lines: Vec<&str> = text.lines().collect();
                    if !lines.is_empty() {
                        let l = lines[rand() % lines.len()].to_string();
                        text.insert_str(at, &format!("\n{l}\n"));
                    }
                }
                _ => {
                    // Replace a byte-sized char with a digit.
                    let digit = char::from(b'0' + (rand() % 10) as u8);
                    if text[at..].chars().next().is_some_and(|c| c.is_ascii()) {
                        text.replace_range(at..at + 1, &digit.to_string());
                    }
                }
            }
        }
        let style = if round % 7 == 0 {
            AtomStyle::Atomic
        } else {
            AtomStyle::Dpd
        };
        if let Ok(data) = parse_data("fuzz", &text, style) {
            accepted += 1;
            assert_eq!(data.natoms, data.atoms.len());
            assert_eq!(data.ntypes, data.masses.len());
        }
    }
    // Some mutations (e.g. in comments or the title) leave the file valid.
    assert!(accepted > 0);
}

/// SMALL with `section` inserted before its Atoms section.
fn with_pair_section(section: &str) -> String {
    SMALL.replace("Atoms # dpd", &format!("{section}\nAtoms # dpd"))
}

#[test]
fn pair_coeff_sections_are_read_and_written_back() {
    let data = parse(&with_pair_section("Pair   Coeffs # dpd\n\n2 20.0 6.0\n1 25.0 4.5\n")).unwrap();
    let p = data.pair_coeffs.as_ref().unwrap();
    assert!(!p.ij);
    assert_eq!(p.style.as_deref(), Some("dpd"));
    assert_eq!(p.rows, vec![vec!["2", "20.0", "6.0"], vec!["1", "25.0", "4.5"]]);
    assert_eq!(p.lines, vec![17, 18]);
    let ij = parse(&with_pair_section("PairIJ Coeffs\n\n1 1 25 4.5 1.2\n2 1 30 3 1.3\n2 2 20 6\n")).unwrap();
    let q = ij.pair_coeffs.as_ref().unwrap();
    assert!(q.ij && q.style.is_none() && q.rows.len() == 3);
    let dir = scratch("pair-coeffs");
    for d in [data, ij] {
        let path = dir.join("data.pair");
        write_data(&path, &d, AtomStyle::Dpd).unwrap();
        assert_eq!(read_data(&path, AtomStyle::Dpd).unwrap(), d);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn pair_coeff_section_errors() {
    assert_eq!(
        error(&with_pair_section("Pair Coeffs\n\n1 25.0 4.5\n")),
        "data.dpde:15: Pair Coeffs: expected 2 lines (2 atom types in the header), found 1 before section 'Atoms' at line 19"
    );
    assert_eq!(
        error(&with_pair_section("PairIJ Coeffs\n\n1 1 25 4.5\n2 2 20 6\n")),
        "data.dpde:15: PairIJ Coeffs: expected 3 lines (3 type pairs I <= J for the atom types in the header), \
         found 2 before section 'Atoms' at line 20"
    );
    assert_eq!(
        error(&with_pair_section("PairIJ Coeffs\n\n1 1 25 4.5\n2 1 20 6\n1 2 20 6\n")),
        "data.dpde:19: PairIJ Coeffs: second line for types 1 2 (the first is at line 18)"
    );
    assert_eq!(
        error(&with_pair_section("Pair Coeffs\n\n1 25.0 4.5\n3 20.0 6.0\n")),
        "data.dpde:18: Pair Coeffs: atom type 3 is outside 1..2"
    );
    assert_eq!(
        error(&with_pair_section("PairIJ Coeffs\n\n1 1 25 4.5\n1 2\n2 2 20 6\n")),
        "data.dpde:18: PairIJ Coeffs: expected I J coefficients, got 2 words"
    );
}
