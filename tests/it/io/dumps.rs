//! Periodic text dumps (`dump custom|atom|xyz`, `dump_modify`): the same files as the
//! reference LAMMPS on a deterministic scene, and OVITO's Python module reads every frame
//! and column of a `dump custom` file.

use crate::common;

use common::lammps::{expect_success, parse_dump, run_lammps, stage_with};
use std::path::{Path, PathBuf};
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-dumps-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gendpde(dir: &Path, input: &str) -> std::process::Output {
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(dir).args(["run", input, "-log", "none"]).output().expect("gendpde runs");
    assert!(out.status.success(), "gendpde failed on {input}:\n{}", String::from_utf8_lossy(&out.stderr));
    out
}

/// scripts/lammps/in.dpde-deterministic with `dumps` before its run (and no write_dump),
/// staged in `dir` as in.dumps.
fn dump_scene(dir: &Path, dumps: &str) {
    stage_with(dir, "in.dpde-deterministic", "in.dumps", dumps, "");
}

/// The frames of a text dump: (lines other than particle rows, particle rows sorted).
fn frames(path: &Path, xyz: bool) -> Vec<(Vec<String>, Vec<String>)> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().peekable();
    let mut out = Vec::new();
    while lines.peek().is_some() {
        let mut head = Vec::new();
        let n: usize = if xyz {
            let n = lines.next().unwrap();
            head.push(n.to_string());
            head.push(lines.next().unwrap().to_string());
            n.parse().unwrap()
        } else {
            let mut n = 0;
            loop {
                let l = lines.next().unwrap().to_string();
                let atoms = l.starts_with("ITEM: ATOMS");
                if l == "ITEM: NUMBER OF ATOMS" {
                    let v = lines.next().unwrap();
                    n = v.parse().unwrap();
                    head.extend([l, v.to_string()]);
                } else {
                    head.push(l);
                }
                if atoms {
                    break n;
                }
            }
        };
        let mut rows: Vec<String> = (0..n).map(|_| lines.next().unwrap().to_string()).collect();
        rows.sort_by_key(|r| r.split_whitespace().next().and_then(|t| t.trim().parse::<u64>().ok()).unwrap_or(0));
        if xyz {
            rows.sort();
        }
        out.push((head, rows));
    }
    out
}

#[test]
fn text_dumps_match_lammps() {
    let dumps = "dump c all custom 50 c.dump id type mass x y z xu yu zu ix iy iz vx vy vz fx fy fz\n\
                 dump_modify c format float %.17g sort id units yes time yes\n\
                 dump a all atom 50 a.dump\n\
                 dump x all xyz 50 x.xyz\n\
                 dump_modify x element Ar time yes\n\
                 dump s all custom 50 s.*.dump id type x vx\n\
                 dump_modify s format 3 %.4f format int %5d every 25 first yes\n\
                 dump l all custom 100 l.dump id x y z\n\
                 dump_modify l format line \"%d %.3f %.3e %10.5f\"\n";
    let (dl, dg) = (dir("lammps"), dir("gendpde"));
    for d in [&dl, &dg] {
        dump_scene(d, dumps);
    }
    expect_success("LAMMPS", &run_lammps(&dl, "in.dumps", &[]));
    gendpde(&dg, "in.dumps");

    // dump custom at %.17g: the same headers; the same values to round-off
    let (l, g) = (frames(&dl.join("c.dump"), false), frames(&dg.join("c.dump"), false));
    assert_eq!(l.len(), 3, "frames at steps 0, 50, 100");
    assert_eq!(l.len(), g.len());
    let (pl, pg) = (parse_dump(&std::fs::read_to_string(dl.join("c.dump")).unwrap()), parse_dump(&std::fs::read_to_string(dg.join("c.dump")).unwrap()));
    let mut worst: f64 = 0.0;
    for ((fl, fg), (sl, sg)) in l.iter().zip(&g).zip(pl.iter().zip(&pg)) {
        // the time: LAMMPS's step * dt, gendpde's sum of the steps' dt
        let time = |h: &[String]| h.iter().position(|l| l == "ITEM: TIME").map(|k| h[k + 1].parse::<f64>().unwrap());
        let (tl, tg) = (time(&fl.0).expect("ITEM: TIME"), time(&fg.0).expect("ITEM: TIME"));
        assert!((tl - tg).abs() <= 1e-14 * tl.abs().max(1.0), "times {tl} and {tg}");
        let other = |h: &[String]| -> Vec<String> { h.iter().filter(|l| l.parse::<f64>().ok().is_none_or(|t| t != tl && t != tg)).cloned().collect() };
        assert_eq!(other(&fl.0), other(&fg.0), "dump custom headers");
        assert_eq!(sl.atoms.len(), sg.atoms.len());
        for ((il, vl), (ig, vg)) in sl.atoms.iter().zip(&sg.atoms) {
            assert_eq!(il, ig);
            for (a, b) in vl.iter().zip(vg) {
                worst = worst.max((a - b).abs() / a.abs().max(1.0));
            }
        }
    }
    assert!(worst < 1e-9, "dump custom values differ from LAMMPS's by {worst:e} (relative)");
    // the first frame of each other file is the same text; later frames the same headers
    for (file, xyz) in [("a.dump", false), ("x.xyz", true), ("s.0.dump", false), ("l.dump", false)] {
        let (l, g) = (frames(&dl.join(file), xyz), frames(&dg.join(file), xyz));
        assert_eq!(l.len(), g.len(), "{file}: frames");
        assert_eq!(l[0], g[0], "{file}: first frame");
        for (a, b) in l.iter().zip(&g) {
            assert_eq!(a.0, b.0, "{file}: headers");
        }
    }
    // `*` makes one file per frame, at the steps `every 25` and `first yes` give
    for step in [0, 25, 50, 75, 100] {
        for d in [&dl, &dg] {
            assert!(d.join(format!("s.{step}.dump")).exists(), "s.{step}.dump in {}", d.display());
        }
    }
}

/// Opens `file` with OVITO's Python module; returns one (timestep, properties) per frame,
/// each property its name and values (all components of a particle, particle after
/// particle, in the file's order). None when OVITO is not installed.
fn ovito_frames(file: &Path) -> Option<Vec<(u64, Vec<(String, Vec<f64>)>)>> {
    let script = "import sys\n\
                  from ovito.io import import_file\n\
                  p = import_file(sys.argv[1])\n\
                  for f in range(p.source.num_frames):\n\
                  \x20   d = p.compute(f)\n\
                  \x20   print('FRAME', d.attributes['Timestep'])\n\
                  \x20   for name in d.particles.keys():\n\
                  \x20       print('PROP', name.replace(' ', '_'), ' '.join(repr(float(v)) for v in d.particles[name][...].flatten()))\n";
    let probe = Command::new("python3").args(["-c", "import ovito"]).output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("SKIPPED: OVITO's Python module is missing (pip install ovito; scripts/test.sh installs it)");
        return None;
    }
    let out = Command::new("python3").args(["-c", script, file.to_str().unwrap()]).output().expect("python3 runs");
    assert!(out.status.success(), "OVITO cannot read {}:\n{}", file.display(), String::from_utf8_lossy(&out.stderr));
    let mut frames: Vec<(u64, Vec<(String, Vec<f64>)>)> = Vec::new();
    for line in String::from_utf8(out.stdout).unwrap().lines() {
        let mut w = line.split(' ');
        match w.next() {
            Some("FRAME") => frames.push((w.next().unwrap().parse().unwrap(), Vec::new())),
            Some("PROP") => {
                let name = w.next().unwrap().replace('_', " ");
                let values = w.filter(|t| !t.is_empty()).map(|t| t.parse().unwrap()).collect();
                frames.last_mut().unwrap().1.push((name, values));
            }
            _ => {}
        }
    }
    Some(frames)
}

#[test]
fn ovito_reads_every_frame_and_column_of_dump_custom() {
    let d = dir("ovito");
    let columns = "id type mass x y z ix iy iz vx vy vz fx fy fz px py pz u theta dpdTheta uCond uMech";
    dump_scene(&d, &format!("dump c all custom 20 c.dump {columns}\ndump u all custom 50 u.dump id xu yu zu\n"));
    gendpde(&d, "in.dumps");
    let Some(frames) = ovito_frames(&d.join("c.dump")) else { return };
    let ours = parse_dump(&std::fs::read_to_string(d.join("c.dump")).unwrap());
    assert_eq!(frames.len(), 6, "frames at steps 0, 20, ..., 100");
    // OVITO's names of LAMMPS's columns; the others keep their names
    let standard = [
        ("Particle Identifier", &["id"][..]),
        ("Particle Type", &["type"]),
        ("Mass", &["mass"]),
        ("Position", &["x", "y", "z"]),
        ("Periodic Image", &["ix", "iy", "iz"]),
        ("Velocity", &["vx", "vy", "vz"]),
        ("Force", &["fx", "fy", "fz"]),
    ];
    for ((step, props), snap) in frames.iter().zip(&ours) {
        assert_eq!(*step, snap.timestep);
        let mut seen = Vec::new();
        for (name, values) in props {
            // OVITO lower-cases the names of other columns
            let cols: Vec<&str> = match standard.iter().find(|(n, _)| n == name) {
                Some((_, c)) => c.to_vec(),
                None if name == "Velocity Magnitude" => continue,
                None => vec![columns.split(' ').find(|c| c.eq_ignore_ascii_case(name)).unwrap_or_else(|| panic!("OVITO column {name}"))],
            };
            // OVITO keeps the file's row order: ours is sorted by id
            let want: Vec<f64> = snap
                .atoms
                .iter()
                .flat_map(|(id, v)| cols.iter().map(|c| if *c == "id" { *id as f64 } else { v[snap.column_index(c).unwrap_or_else(|| panic!("column {c}"))] }).collect::<Vec<_>>())
                .collect();
            assert_eq!(values, &want, "step {step}: {name}");
            seen.extend(cols);
        }
        seen.sort_unstable();
        let mut all: Vec<&str> = columns.split(' ').collect();
        all.sort_unstable();
        assert_eq!(seen, all, "step {step}: OVITO read every column");
    }
    // unwrapped positions are positions to OVITO
    let frames = ovito_frames(&d.join("u.dump")).unwrap();
    let ours = parse_dump(&std::fs::read_to_string(d.join("u.dump")).unwrap());
    for ((_, props), snap) in frames.iter().zip(&ours) {
        let pos = &props.iter().find(|(n, _)| n == "Position").expect("Position").1;
        let want: Vec<f64> = snap.atoms.iter().flat_map(|(_, v)| v.clone()).collect();
        assert_eq!(pos, &want);
    }
}

#[test]
fn bad_dump_commands_are_refused_with_their_line() {
    let d = dir("errors");
    for (cmd, want) in [
        ("dump c all custom 10 c.dump id bogus", "in.bad:2: dump: unknown keyword 'bogus'"),
        ("dump c all cfg 10 c.dump", "in.bad:2: dump: unknown dump style 'cfg'"),
        ("dump c all custom 0 c.dump id", "in.bad:2: dump: the output interval must be positive"),
        ("dump c all atom 10 c.dump\ndump_modify c format 7 %g", "in.bad:3: dump_modify: format 7: expected"),
        ("dump c all atom 10 c.dump\ndump_modify c sort 2", "in.bad:3: dump_modify: sort 2"),
        ("dump c all atom 10 c.dump\ndump_modify c author me", "in.bad:3: dump_modify: dump c: dump_modify keyword 'author' is not supported for this dump style"),
        ("dump_modify nope every 2", "in.bad:2: dump_modify: no dump with ID 'nope'"),
        ("dump c all xyz 10 c.dump\ndump c all xyz 10 d.dump", "in.bad:3: dump: dump ID 'c' is in use"),
    ] {
        std::fs::write(d.join("in.bad"), format!("units lj\n{cmd}\n")).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(&d).args(["check", "in.bad"]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(want), "{cmd}: expected '{want}', got:\n{err}");
    }
}

#[test]
fn first_every_append_and_undump_schedule_frames() {
    let d = dir("schedule");
    let after = "dump f all custom 5 f.dump id x\ndump_modify f first yes\n\
                 dump a all xyz 4 a.xyz\ndump_modify a append yes every 10\n\
                 run 10\nrun 5\nundump a\nrun 10\n";
    stage_with(&d, "in.dpde-deterministic", "in.dumps", "", after);
    std::fs::write(d.join("a.xyz"), "kept\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(&d).args(["run", "in.dumps", "-log", "none", "-var", "steps", "7"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let steps: Vec<u64> = parse_dump(&std::fs::read_to_string(d.join("f.dump")).unwrap()).iter().map(|s| s.timestep).collect();
    // first yes: the first setup (step 7) only; then the multiples of 5 up to step 32
    assert_eq!(steps, [7, 10, 15, 20, 25, 30]);
    let xyz = std::fs::read_to_string(d.join("a.xyz")).unwrap();
    let frames: Vec<&str> = xyz.lines().filter(|l| l.starts_with(" Atoms. Timestep: ")).collect();
    assert!(xyz.starts_with("kept\n"), "append yes keeps the file");
    assert_eq!(frames, [" Atoms. Timestep: 10", " Atoms. Timestep: 20"], "every 10, until undump");
}
