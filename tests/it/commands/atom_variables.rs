//! Atom-style variables and per-atom dump columns beside the reference LAMMPS (issue 17,
//! item 7): `dump custom` with `c_ID` (ke/atom, pe/atom) and `v_name` columns, `compute
//! reduce` and `fix ave/chunk` of `v_name`, and box keywords (`lx`, `xlo`, `vol`, ...) in
//! expressions give LAMMPS's numbers to round-off; misuse is a clear error with the line.

use crate::common;

use common::lammps::{expect_success, parse_dump, parse_thermo_blocks, run_lammps};
use common::{expect_errors, gendpde, random_data_file, tempdir};
use std::path::PathBuf;

/// Step-0 forces are deterministic: conservative dpd only (gamma 0, so no noise).
const SCENE: &str = "units lj
atom_style atomic
read_data data.v
comm_modify vel yes
pair_style dpd 1.0 0.9 34387
neighbor 0.2 bin
pair_coeff * * 25.0 0.0
velocity all create 1.5 4928459 loop geom
fix 1 all nve
";

fn stage(name: &str, script: &str) -> PathBuf {
    let dir = tempdir(name);
    std::fs::write(dir.join("in.x"), script).unwrap();
    std::fs::write(dir.join("data.v"), random_data_file(60, &[1.0, 2.5], false, 2463534242)).unwrap();
    dir
}

/// Runs `script` in both programs; returns their directories and standard outputs.
fn both(name: &str, script: &str) -> ((PathBuf, String), (PathBuf, String)) {
    let dg = stage(&format!("{name}-gendpde"), script);
    let out = gendpde(&dg, &["run", "in.x", "-log", "none"]);
    assert!(out.status.success(), "gendpde failed on {name}:\n{}", String::from_utf8_lossy(&out.stderr));
    let dl = stage(&format!("{name}-lammps"), script);
    let l = expect_success("LAMMPS", &run_lammps(&dl, "in.x", &[]));
    ((dg, String::from_utf8_lossy(&out.stdout).into_owned()), (dl, l))
}

#[test]
fn dump_columns_of_computes_and_atom_variables_match_lammps() {
    let script = format!(
        "{SCENE}compute ke all ke/atom
compute pe all pe/atom
variable g equal \"lx*ly+xlo+vol/zhi-yhi*ylo\"
variable a atom \"x*vx+mass*type-sqrt(id)+fx*v_g\"
variable b atom \"v_a^2+(type==2)*exp(-y)+atan2(vy,vz)\"
dump d all custom 1 out.dump id c_ke c_pe v_a v_b fx
dump_modify d format float %.17g
print \"g = $(v_g:%.17g) $(xlo) $(lz)\"
run 0
"
    );
    let ((dg, g), (dl, l)) = both("atomvar-dump", &script);
    let line = |t: &str| t.lines().find(|l| l.starts_with("g = ")).map(str::to_string);
    assert_eq!(line(&g), line(&l));
    assert_eq!(line(&g).as_deref(), Some("g = 54 0 6"));
    let read = |d: &PathBuf| parse_dump(&std::fs::read_to_string(d.join("out.dump")).unwrap()).remove(0);
    let (sg, sl) = (read(&dg), read(&dl));
    assert_eq!(sg.columns, ["c_ke", "c_pe", "v_a", "v_b", "fx"]);
    assert_eq!(sg.columns, sl.columns);
    for (c, name) in sg.columns.iter().enumerate() {
        for ((ig, rg), (il, rl)) in sg.atoms.iter().zip(&sl.atoms) {
            assert_eq!(ig, il);
            let scale = rl[c].abs().max(1.0);
            assert!((rg[c] - rl[c]).abs() < 1e-13 * scale, "{name} of particle {ig}: {} vs LAMMPS {}", rg[c], rl[c]);
        }
    }
}

#[test]
fn reduce_and_ave_chunk_of_atom_variables_match_lammps() {
    let script = format!(
        "{SCENE}variable a atom \"x*vx+mass*type+fx\"
variable e atom \"vx*vx*mass\"
compute r all reduce sum v_a v_e
compute m all reduce max v_a
compute cc all chunk/atom bin/1d x lower 1.0 units box
fix ac all ave/chunk 1 1 1 cc density/number v_a v_e file prof.txt format \" %.15g\"
thermo_style custom step c_r[1] c_r[2] c_m
thermo_modify format float %.15g
run 0
"
    );
    let ((dg, g), (dl, l)) = both("atomvar-reduce", &script);
    let (bg, bl) = (parse_thermo_blocks(&g, "Step").remove(0), parse_thermo_blocks(&l, "Step").remove(0));
    for col in ["c_r[1]", "c_r[2]", "c_m"] {
        let (x, y) = (bg.column(col)[0], bl.column(col)[0]);
        assert!((x - y).abs() < 1e-13 * y.abs().max(1.0), "{col}: {x} vs LAMMPS {y}");
    }
    let rows = |d: &PathBuf| -> Vec<Vec<f64>> {
        let text = std::fs::read_to_string(d.join("prof.txt")).unwrap();
        text.lines().filter(|l| !l.starts_with('#')).map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect()).filter(|r: &Vec<f64>| r.len() == 6).collect()
    };
    let (pg, pl) = (rows(&dg), rows(&dl));
    assert_eq!(pg.len(), 5);
    for (rg, rl) in pg.iter().zip(&pl) {
        for (x, y) in rg.iter().zip(rl) {
            assert!((x - y).abs() < 1e-13 * y.abs().max(1.0), "profile row {rg:?} vs LAMMPS {rl:?}");
        }
    }
}

#[test]
fn atom_variable_errors_name_the_line() {
    let cases = [
        ("variable a atom x*2\nprint \"$(v_a)\"", "atom-style"),
        ("variable a equal 2\ndump d all custom 1 o.dump id v_a\nrun 0", "variable 'a' is equal-style, not atom-style"),
        ("dump d all custom 1 o.dump id v_nope\nrun 0", "unknown variable 'nope'"),
        ("dump d all custom 1 o.dump id f_1", "Could not find dump custom fix ID: 1"),
        ("compute ke all ke/atom\ndump d all custom 1 o.dump id c_ke[2]", "Dump custom compute ke does not calculate a per-atom array"),
        ("dump d all custom 1 o.dump id c_nope", "Compute ID nope for dump custom does not exist"),
        ("compute t all temp\nwrite_dump all custom o.dump id c_t", "Dump custom compute t does not calculate per-atom values"),
        ("variable a atom x+nosuch\nwrite_dump all custom o.dump id v_a", "nosuch"),
        ("variable a atom 1/(x-x)\nwrite_dump all custom o.dump id v_a", "variable 'a'"),
    ];
    expect_errors(SCENE, &cases, |script| stage("atomvar-errors", script));
}
