//! Dumps on groups, dump dcd and dump xtc, write_dump of every style and the dump_modify
//! keywords flush, header, pad, delay, region and colname: the same files as the reference LAMMPS on a
//! deterministic scene (byte for byte but the DCD title lines, which name the writer and
//! the time), the same bytes on 1 and 3 ranks, and MDAnalysis reads the DCD and XTC
//! positions back. dump image: PNG pictures of the group's types, the same on 3 ranks
//! (the reference LAMMPS writes no PNG; its JPEG of the same view looks alike).

use crate::common;

use common::lammps::{expect_success, parse_dump, run_lammps, scripts_dir};
use common::{mpirun, tempdir};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A two-type DPD mixture at T = 0 (no random force: deterministic in both codes), with
/// a group by region and one by type.
const SCENE: &str = "units lj
boundary p p p
atom_style atomic
comm_modify vel yes
read_data data.mix-dpd
mass 1 1.0
mass 2 2.0
pair_style dpd 0.0 1.0 4928459
pair_coeff * * 25.0 4.5 1.2
pair_coeff 2 1 30.0 3.0 1.3
pair_coeff 2* 2* 20.0 6.0
neighbor 0.3 bin
neigh_modify every 1 delay 0 check no
timestep 0.01
region slab block 0 3 INF INF INF INF
group left region slab
group heavy type 2
thermo 10
fix 1 all nve
";

/// `SCENE` then `rest`, staged in a fresh directory with the data file.
fn stage(name: &str, rest: &str) -> PathBuf {
    let d = tempdir(name);
    std::fs::copy(scripts_dir().join("data.mix-dpd"), d.join("data.mix-dpd")).unwrap();
    std::fs::write(d.join("in.dumps"), format!("{SCENE}{rest}")).unwrap();
    d
}

fn gendpde(dir: &Path) {
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(dir).args(["run", "in.dumps", "-log", "none"]).output().unwrap();
    assert!(out.status.success(), "gendpde failed:\n{}", String::from_utf8_lossy(&out.stderr));
}

fn bytes(d: &Path, f: &str) -> Vec<u8> {
    std::fs::read(d.join(f)).unwrap_or_else(|e| panic!("{}: {e}", d.join(f).display()))
}

/// Where a DCD file holds its two 80-character title lines.
const DCD_TITLES: std::ops::Range<usize> = 100..260;

/// A DCD file without its title lines, and the second (`REMARKS Created ...`).
fn dcd_parts(d: &Path, f: &str) -> (Vec<u8>, String) {
    let b = bytes(d, f);
    let rest = [&b[..DCD_TITLES.start], &b[DCD_TITLES.end..]].concat();
    (rest, String::from_utf8_lossy(&b[180..260]).into_owned())
}

const DUMPS: &str = "dump c left custom 10 c.dump id type x y z vx
dump_modify c format float %.17g sort id
dump a heavy atom 10 a.dump
dump_modify a sort id
dump x heavy xyz 10 x.xyz
dump_modify x sort id
dump d all dcd 10 d.dcd
dump d2 heavy dcd 10 d2.dcd
dump_modify d2 unwrap yes
dump t all xtc 10 t.xtc
dump t2 left xtc 10 t2.xtc
dump_modify t2 precision 100000 unwrap yes
run 30
write_dump heavy xyz w.xyz modify sort id format line \"%s %g %g %g\"
write_dump left atom w.atom modify sort id format line \"%d %d %g %g %g\"
write_dump left dcd w.dcd
write_dump heavy xtc w.xtc
";

#[test]
fn group_dumps_dcd_and_xtc_match_lammps_on_1_and_3_ranks() {
    let (dl, dg) = (stage("formats-lammps", DUMPS), stage("formats-gendpde", DUMPS));
    let dm = stage("formats-np3", DUMPS);
    expect_success("LAMMPS", &run_lammps(&dl, "in.dumps", &[]));
    gendpde(&dg);
    let out = mpirun(3, &dm, &["run", "in.dumps", "-log", "none"]);
    assert!(out.status.success(), "gendpde on 3 ranks:\n{}", String::from_utf8_lossy(&out.stderr));

    // text dumps of a group: LAMMPS's text, its group count as NUMBER OF ATOMS
    for f in ["a.dump", "x.xyz", "w.xyz", "w.atom"] {
        assert_eq!(String::from_utf8(bytes(&dl, f)).unwrap(), String::from_utf8(bytes(&dg, f)).unwrap(), "{f}");
    }
    let (cl, cg) = (parse_dump(&String::from_utf8(bytes(&dl, "c.dump")).unwrap()), parse_dump(&String::from_utf8(bytes(&dg, "c.dump")).unwrap()));
    assert_eq!(cl.len(), 4, "frames at steps 0, 10, 20, 30");
    let mut worst: f64 = 0.0;
    for (l, g) in cl.iter().zip(&cg) {
        assert!(l.atoms.len() > 100 && l.atoms.len() < 729, "group left: {} particles", l.atoms.len());
        assert_eq!(l.atoms.iter().map(|a| a.0).collect::<Vec<_>>(), g.atoms.iter().map(|a| a.0).collect::<Vec<_>>(), "step {}: the group's IDs", l.timestep);
        for ((_, vl), (_, vg)) in l.atoms.iter().zip(&g.atoms) {
            for (a, b) in vl.iter().zip(vg) {
                worst = worst.max((a - b).abs() / a.abs().max(1.0));
            }
        }
    }
    eprintln!("dump custom on group left: values {worst:.2e} (relative) from LAMMPS's");
    assert!(worst < 1e-12, "dump custom values differ from LAMMPS's by {worst:e}");

    // xtc: LAMMPS's bytes; dcd: LAMMPS's bytes but the title lines
    for f in ["t.xtc", "t2.xtc", "w.xtc"] {
        assert!(bytes(&dl, f) == bytes(&dg, f), "{f}: not LAMMPS's bytes");
    }
    for f in ["d.dcd", "d2.dcd", "w.dcd"] {
        let ((l, lt), (g, gt)) = (dcd_parts(&dl, f), dcd_parts(&dg, f));
        assert!(l == g, "{f}: not LAMMPS's bytes outside the titles");
        assert!(lt.starts_with("REMARKS Created ") && gt.starts_with("REMARKS Created "), "{f}: '{lt}' '{gt}'");
        assert_eq!(bytes(&dg, f)[100..118], *b"Written by gendpde");
    }
    // 3 ranks write the same bytes (the DCD creation time aside)
    for f in ["c.dump", "a.dump", "x.xyz", "w.xyz", "w.atom", "t.xtc", "t2.xtc", "w.xtc"] {
        assert!(bytes(&dg, f) == bytes(&dm, f), "{f}: 1 and 3 ranks differ");
    }
    for f in ["d.dcd", "d2.dcd", "w.dcd"] {
        assert!(dcd_parts(&dg, f).0 == dcd_parts(&dm, f).0, "{f}: 1 and 3 ranks differ");
    }
}

#[test]
fn dump_modify_keywords_and_write_dump_pad_match_lammps() {
    let rest = "dump h heavy custom 5 h.dump id type x
dump_modify h header no flush no sort id buffer no
dump p all atom 5 p.*.atom
dump_modify p pad 6 sort id
dump q heavy xyz 5 q.xyz
dump_modify q header no sort id
dump e heavy xyz 2 e.xyz
dump_modify e delay 5 first yes sort id
region ball sphere 3 3 3 2.0
dump r heavy custom 5 r.dump id type
dump_modify r region ball sort id
dump n all custom 5 n.dump id type
dump_modify n region ball region none sort id
dump k heavy custom 5 k.dump id type x y vx
dump_modify k sort id colname 1 ID colname x pos colname -1 last colname -2 yy format float %.3f
run 10
write_dump heavy custom w*.dump id x modify sort id pad 4 format float %g
";
    let (dl, dg) = (stage("modify-lammps", rest), stage("modify-gendpde", rest));
    expect_success("LAMMPS", &run_lammps(&dl, "in.dumps", &[]));
    gendpde(&dg);
    for f in ["h.dump", "p.000000.atom", "p.000005.atom", "p.000010.atom", "q.xyz", "e.xyz", "r.dump", "n.dump", "k.dump", "w0010.dump"] {
        assert_eq!(String::from_utf8(bytes(&dl, f)).unwrap(), String::from_utf8(bytes(&dg, f)).unwrap(), "{f}");
    }
    assert!(!String::from_utf8(bytes(&dg, "h.dump")).unwrap().contains("ITEM"), "header no");
    let steps: Vec<String> = String::from_utf8(bytes(&dg, "e.xyz")).unwrap().lines().filter_map(|l| l.strip_prefix(" Atoms. Timestep: ").map(String::from)).collect();
    assert_eq!(steps, ["6", "8", "10"], "delay 5: none before step 5, first yes too");
    let counts = |f: &str| parse_dump(&String::from_utf8(bytes(&dg, f)).unwrap()).iter().map(|s| s.atoms.len()).collect::<Vec<_>>();
    assert!(counts("r.dump").iter().all(|&n| n > 20 && n < 100), "region ball of group heavy: {:?}", counts("r.dump"));
    assert_eq!(counts("n.dump"), [729; 3], "region none: every particle");
}

/// Reads the DCD and XTC files of a run with MDAnalysis and prints, per frame, the
/// largest difference from the positions of the %.17g dump given.
const MDANALYSIS: &str = r#"
import sys, numpy as np, MDAnalysis as mda
dcd, xtc, dump, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
frames, lines = [], open(dump).read().split("\n")
k = 0
while k < len(lines) and lines[k]:
    m = int(lines[k + 3]); frames.append(np.array([[float(w) for w in l.split()[1:4]] for l in lines[k + 9:k + 9 + m]])); k += 9 + m
for fmt, f in (("DCD", dcd), ("XTC", xtc)):
    u = mda.Universe.empty(n, trajectory=True)
    u.load_new(f, format=fmt, convert_units=False)
    assert len(u.trajectory) == len(frames), (fmt, len(u.trajectory))
    for ts, want in zip(u.trajectory, frames):
        print(fmt, ts.frame, np.abs(ts.positions - want.astype(np.float32)).max(), " ".join(str(x) for x in ts.dimensions[:3]))
"#;

#[test]
fn mdanalysis_reads_the_dcd_and_xtc_positions() {
    let probe = Command::new("python3").args(["-c", "import MDAnalysis"]).output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("SKIPPED: MDAnalysis is missing (pip install MDAnalysis; scripts/test.sh installs it)");
        return;
    }
    let d = stage("mdanalysis", "dump f heavy custom 10 f.dump id x y z\ndump_modify f format float %.17g sort id\ndump d heavy dcd 10 d.dcd\ndump t heavy xtc 10 t.xtc\nrun 20\n");
    gendpde(&d);
    let n = parse_dump(&String::from_utf8(bytes(&d, "f.dump")).unwrap())[0].atoms.len().to_string();
    let p = |f: &str| d.join(f).to_str().unwrap().to_string();
    let out = Command::new("python3").args(["-c", MDANALYSIS, &p("d.dcd"), &p("t.xtc"), &p("f.dump"), &n]).output().unwrap();
    assert!(out.status.success(), "MDAnalysis:\n{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let rows: Vec<(String, f64, String)> = text.lines().map(|l| {
        let w: Vec<&str> = l.splitn(4, ' ').collect();
        (w[0].to_string(), w[2].parse().unwrap(), w[3].to_string())
    }).collect();
    assert_eq!(rows.len(), 6, "3 frames of each file:\n{text}");
    for (fmt, diff, box_len) in &rows {
        // DCD: the float32 positions; XTC: rounded to 1/1000 (its default precision)
        let tolerance = if fmt == "DCD" { 0.0 } else { 0.5e-3 + 1e-6 };
        assert!(*diff <= tolerance, "{fmt}: positions {diff} from the dump's");
        assert_eq!(box_len, "6.0 6.0 6.0", "{fmt}: the box");
    }
}

#[test]
fn bad_dumps_are_refused_with_lammps_messages() {
    let d = tempdir("formats-errors");
    for (cmd, want) in [
        ("dump c nope custom 10 c.dump id", "in.bad:2: dump: no group 'nope'"),
        ("dump d all dcd 10 d.*.dcd", "in.bad:2: dump: Invalid dump dcd filename"),
        ("dump d all dcd 10 d.dcd extra", "in.bad:2: dump: unexpected argument 'extra'"),
        ("dump d all dcd 10 d.dcd\ndump_modify d sort off", "in.bad:3: dump_modify: Dump dcd requires sorting by atom ID"),
        ("dump t all xtc 10 t.xtc\ndump_modify t precision 7", "in.bad:3: dump_modify: Illegal dump_modify command: precision 7"),
        ("dump t all xtc 10 t.xtc\ndump_modify t flush yes", "in.bad:3: dump_modify: Cannot set dump_modify flush for dump xtc"),
        ("dump t all xtc 10 t.xtc\ndump_modify t sfactor 0", "in.bad:3: dump_modify: Illegal dump_modify sfactor value (must be > 0.0)"),
        ("dump c all atom 10 c.dump\ndump_modify c region none", "in.bad:3: dump_modify: dump c: dump_modify keyword 'region' is not supported for this dump style"),
        ("dump c all custom 10 c.dump id x\ndump_modify c colname 3 X", "in.bad:3: dump_modify: Incorrect dump_modify arguments: colname 3 X"),
        ("dump c all atom 10 c.dump\ndump_modify c bogus 1", "in.bad:3: dump_modify: dump c: dump_modify keyword 'bogus' is unknown"),
        ("write_dump all cfg c.cfg", "in.bad:2: write_dump: unknown dump style 'cfg'"),
    ] {
        std::fs::write(d.join("in.bad"), format!("units lj\n{cmd}\n")).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(&d).args(["check", "in.bad"]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(want), "{cmd}: expected '{want}', got:\n{err}");
    }
}

/// The RGB pixels, width and height of a PNG file.
fn png_pixels(path: &Path) -> (Vec<u8>, u32, u32) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (buf, info.width, info.height)
}

#[test]
fn dump_image_draws_the_group_by_type_in_png_the_same_on_3_ranks() {
    let rest = "dump i all image 10 all.*.png type type
dump j heavy image 10 heavy.*.png type type size 400 300 view 80 -20 zoom 1.3 axes yes 0.5 0.03
dump_modify j acolor 2 orange adiam 2 0.8 backcolor white boxcolor black pad 3
run 10
";
    let (d1, d3) = (stage("image-np1", rest), stage("image-np3", rest));
    gendpde(&d1);
    let out = mpirun(3, &d3, &["run", "in.dumps", "-log", "none"]);
    assert!(out.status.success(), "gendpde on 3 ranks:\n{}", String::from_utf8_lossy(&out.stderr));
    for f in ["all.0.png", "all.10.png", "heavy.000.png", "heavy.010.png"] {
        assert!(bytes(&d1, f) == bytes(&d3, f), "{f}: 1 and 3 ranks differ");
    }
    // LAMMPS's defaults: 512 x 512, black, type 1 red and type 2 green
    let (all, w, h) = png_pixels(&d1.join("all.10.png"));
    assert_eq!((w, h), (512, 512));
    let px = |p: &[u8], i: usize| [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
    assert_eq!(px(&all, 0), [0, 0, 0], "background");
    let count = |p: &[u8], f: &dyn Fn([u8; 3]) -> bool| (0..p.len() / 3).filter(|&i| f(px(p, i))).count();
    let red = |c: [u8; 3]| c[0] > 60 && c[1] < c[0] / 4 && c[2] < c[0] / 4;
    let green = |c: [u8; 3]| c[1] > 30 && c[0] < c[1] / 4 && c[2] < c[1] / 4;
    let (nr, ng) = (count(&all, &red), count(&all, &green));
    eprintln!("dump image all: {nr} red and {ng} green pixels of {}", w * h);
    assert!(nr > 20_000 && ng > 20_000, "both types drawn: {nr} red, {ng} green");
    // the heavy group only, orange on white, in the size asked for
    let (heavy, w, h) = png_pixels(&d1.join("heavy.010.png"));
    assert_eq!((w, h), (400, 300));
    assert_eq!(px(&heavy, 0), [255, 255, 255], "backcolor white");
    let orange = |c: [u8; 3]| c[0] > 60 && c[1] > c[0] / 3 && c[1] < c[0] && c[2] < c[0] / 4;
    assert!(count(&heavy, &orange) > 20_000, "type 2 in orange");
    // green only on the y axis, blue on the z axis
    let blue = |c: [u8; 3]| c[2] > 60 && c[0] < c[2] / 4 && c[1] < c[2] / 4;
    let (ng, nb) = (count(&heavy, &green), count(&heavy, &blue));
    assert!(ng < 1000, "no type 1 in group heavy: {ng} green pixels");
    assert!(nb > 50, "the z axis: {nb} blue pixels");
}

#[test]
fn dump_image_refuses_what_it_does_not_draw() {
    let d = tempdir("image-errors");
    for (cmd, want) in [
        ("dump i all image 10 a.*.jpg type type", "gendpde writes PNG only"),
        ("dump i all image 10 a.png type type", "Dump image requires one snapshot per file"),
        ("dump i all image 10 a.*.png element type", "dump image color 'element': gendpde colours and sizes atoms by type only"),
        ("dump i all image 10 a.*.png type type bond atom 0.5", "dump image keyword 'bond' is not supported"),
        ("dump i all image 10 a.*.png type type ssao yes 1 0.5", "ssao yes: ambient occlusion is not supported"),
        ("dump i all image 10 a.*.png type type\ndump_modify i acolor 1 nocolor", "Invalid color name 'nocolor'"),
    ] {
        std::fs::write(d.join("in.bad"), format!("units lj\n{cmd}\n")).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(&d).args(["check", "in.bad"]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(want), "{cmd}: expected '{want}', got:\n{err}");
    }
}
