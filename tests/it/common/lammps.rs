//! The LAMMPS side of the parity tests: running the reference LAMMPS (22 Jul 2025, installed on
//! demand by `/work/shared/lammps/setup.sh`), reading its thermo output and text dumps, and the
//! block-averaging statistics used to compare two stochastic runs.
//!
//! `parse_thermo` reads LAMMPS logs and gendpde's stdout alike (same layout: a header line whose
//! first word is the first column's heading, e.g. `Step`, then one line of numbers per output
//! step, ended by `Loop time of ...` or any other non-numeric line).
//!
//! The inputs live in `scripts/lammps/` (see its README.md); both programs run them unchanged.
//! Standard library only.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The setup script; `LAMMPS_SETUP` overrides it.
pub const DEFAULT_SETUP: &str = "/work/shared/lammps/setup.sh";

/// `scripts/lammps/` of this workspace (inputs, data files, run_reference.sh).
pub fn scripts_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scripts").join("lammps")
}

/// Path of the reference LAMMPS wrapper (`lmp`). Runs the (idempotent) setup script once per
/// test process and caches its answer (the last line it prints). Panics with the script's
/// output if the install fails.
pub fn lmp() -> PathBuf {
    static LMP: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let r = LMP.get_or_init(|| {
        let setup = std::env::var("LAMMPS_SETUP").unwrap_or_else(|_| DEFAULT_SETUP.to_string());
        let out = Command::new("bash")
            .arg(&setup)
            .output()
            .map_err(|e| format!("cannot start the LAMMPS setup script {setup}: {e}"))?;
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        if !out.status.success() {
            return Err(format!(
                "the LAMMPS setup script {setup} failed ({}):\n--- stdout\n{stdout}\n--- stderr\n{stderr}",
                out.status
            ));
        }
        let path = stdout
            .lines()
            .rev()
            .map(str::trim)
            .find(|l| !l.is_empty())
            .unwrap_or("");
        let path = PathBuf::from(path);
        if !path.is_file() {
            return Err(format!(
                "the LAMMPS setup script {setup} did not print the path of an existing `lmp` wrapper \
                 (got {path:?}):\n--- stdout\n{stdout}\n--- stderr\n{stderr}"
            ));
        }
        Ok(path)
    });
    match r {
        Ok(p) => p.clone(),
        Err(e) => panic!("reference LAMMPS unavailable: {e}"),
    }
}

/// Runs `lmp -in INPUT -log log.lammps -var K V ...` in `dir` (serial) and returns its output.
/// `input` is relative to `dir` (or absolute). Does not check the exit status: see
/// [`expect_success`].
pub fn run_lammps(dir: &Path, input: &str, vars: &[(&str, &str)]) -> Output {
    let lmp = lmp();
    let mut cmd = Command::new(&lmp);
    cmd.current_dir(dir).args(["-in", input, "-log", "log.lammps"]);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    cmd.output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", lmp.display()))
}

/// Panics with LAMMPS's stdout/stderr tails unless the run succeeded; returns stdout.
pub fn expect_success(what: &str, out: &Output) -> String {
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    if !out.status.success() || stdout.lines().any(|l| l.starts_with("ERROR")) {
        let tail = |s: &str| {
            s.lines()
                .rev()
                .take(40)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
                .join("\n")
        };
        panic!(
            "{what} failed ({}):\n--- stdout (tail)\n{}\n--- stderr (tail)\n{}",
            out.status,
            tail(&stdout),
            tail(&String::from_utf8_lossy(&out.stderr))
        );
    }
    stdout
}

/// Copies `scripts/lammps/<input>` and every `scripts/lammps/data.*` into `dir` (created).
pub fn stage_inputs(dir: &Path, input: &str) {
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
    let src = scripts_dir();
    let copy = |name: &std::ffi::OsStr| {
        std::fs::copy(src.join(name), dir.join(name))
            .unwrap_or_else(|e| panic!("cannot copy {} into {}: {e}", src.join(name).display(), dir.display()));
    };
    copy(std::ffi::OsStr::new(input));
    for entry in std::fs::read_dir(&src).unwrap_or_else(|e| panic!("cannot list {}: {e}", src.display())) {
        let name = entry.expect("directory entry").file_name();
        if name.to_string_lossy().starts_with("data.") {
            copy(&name);
        }
    }
}

/// `gendpde run INPUT -log none -var K V ...` in `dir`.
pub fn run_gendpde(dir: &Path, input: &str, vars: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_gendpde"));
    cmd.current_dir(dir).args(["run", input, "-log", "none"]);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    cmd.output().expect("gendpde runs")
}

/// Runs `input` in both codes, each in a fresh directory (`NAME-lammps`, `NAME-gendpde`)
/// staged as [`stage_inputs`] plus the `extra` files of scripts/lammps; returns both
/// directories and standard outputs (a failure of either stops the test with its output).
pub fn run_both(name: &str, input: &str, vars: &[(&str, &str)], extra: &[&str]) -> ((PathBuf, String), (PathBuf, String)) {
    let stage = |side: &str| {
        let d = super::tempdir(&format!("{name}-{side}"));
        stage_inputs(&d, input);
        for f in extra {
            std::fs::copy(scripts_dir().join(f), d.join(f)).unwrap_or_else(|e| panic!("cannot copy {f}: {e}"));
        }
        d
    };
    let (dl, dg) = (stage("lammps"), stage("gendpde"));
    let l = expect_success("LAMMPS", &run_lammps(&dl, input, vars));
    let out = run_gendpde(&dg, input, vars);
    assert!(out.status.success(), "gendpde failed on {input}:\n{}", String::from_utf8_lossy(&out.stderr));
    ((dl, l), (dg, String::from_utf8_lossy(&out.stdout).into_owned()))
}

/// Runs `input` (with the `extra` files of scripts/lammps/) in both codes; compares the
/// step-0 forces, every thermo row and the final positions (a dump `dump` of two frames:
/// step 0 and the last), and returns the
/// worst deviations (force, thermo, position). Tolerances: forces 1e-12 of the largest,
/// every thermo value 1e-11 relative, positions 1e-10 of the box.
pub fn compare_with_lammps(name: &str, input: &str, dump: &str, vars: &[(&str, &str)], extra: &[&str]) -> (f64, f64, f64) {
    let ((dl, l), (dg, g)) = run_both(name, input, vars, extra);
    let (tl, tg) = (parse_thermo(&l, "Step"), parse_thermo(&g, "Step"));
    assert_eq!(tl.len(), tg.len(), "thermo rows");
    let mut thermo: f64 = 0.0;
    for (a, b) in tl.iter().zip(&tg) {
        for (x, y) in a.iter().zip(b) {
            thermo = thermo.max((x - y).abs() / x.abs().max(1e-300));
        }
    }
    let read = |d: &Path| parse_dump(&std::fs::read_to_string(d.join(dump)).unwrap());
    let (sl, sg) = (read(&dl), read(&dg));
    assert_eq!((sl.len(), sg.len()), (2, 2), "two dump frames");
    let col = |s: &DumpSnapshot, c: &str| s.column_index(c).unwrap();
    let fmax = sl[0].atoms.iter().flat_map(|(_, v)| ["fx", "fy", "fz"].map(|c| v[col(&sl[0], c)].abs())).fold(0.0, f64::max);
    let (mut force, mut position): (f64, f64) = (0.0, 0.0);
    let box_len = sl[1].bounds[0][1] - sl[1].bounds[0][0];
    for ((ia, va), (ib, vb)) in sl[0].atoms.iter().zip(&sg[0].atoms) {
        assert_eq!(ia, ib);
        for c in ["fx", "fy", "fz"] {
            force = force.max((va[col(&sl[0], c)] - vb[col(&sg[0], c)]).abs() / fmax);
        }
    }
    for ((ia, va), (ib, vb)) in sl[1].atoms.iter().zip(&sg[1].atoms) {
        assert_eq!(ia, ib);
        for c in ["x", "y", "z"] {
            let mut d = va[col(&sl[1], c)] - vb[col(&sg[1], c)];
            d -= box_len * (d / box_len).round();
            position = position.max(d.abs() / box_len);
        }
    }
    eprintln!("{name}: forces at step 0 {force:.2e} of the largest, thermo rows {thermo:.2e} relative, positions {position:.2e} of the box");
    assert!(force < 1e-12, "{name}: step-0 forces differ by {force:e} of the largest");
    assert!(thermo < 1e-11, "{name}: thermo rows differ by {thermo:e}");
    assert!(position < 1e-10, "{name}: final positions differ by {position:e} of the box");
    (force, thermo, position)
}

/// Stages `input` (as [`stage_inputs`]) and writes it as `name` with `before` in front
/// of its `run` line, `after` behind it and its `write_dump` lines left out.
pub fn stage_with(dir: &Path, input: &str, name: &str, before: &str, after: &str) {
    stage_inputs(dir, input);
    let text = std::fs::read_to_string(dir.join(input)).unwrap_or_else(|e| panic!("{input}: {e}"));
    let text: String = text
        .lines()
        .filter(|l| !l.starts_with("write_dump"))
        .map(|l| if l.starts_with("run ") { format!("{before}{l}\n{after}") } else { format!("{l}\n") })
        .collect();
    std::fs::write(dir.join(name), text).unwrap_or_else(|e| panic!("cannot write {name}: {e}"));
}

/// Largest per-particle |dr| / L (minimum image, L the x length of `a`'s box) and
/// |dp| / |p| between two final dumps of the same particles.
pub fn compare_dumps(a: &Path, b: &Path) -> (f64, f64) {
    let (a, b) = (read_dump_snapshot(a), read_dump_snapshot(b));
    let len = a.bounds[0][1] - a.bounds[0][0];
    assert_eq!(a.atoms.len(), b.atoms.len());
    let col = |s: &DumpSnapshot, c: &str| s.column_index(c).unwrap();
    let (mut dr, mut dp): (f64, f64) = (0.0, 0.0);
    for ((ia, va), (ib, vb)) in a.atoms.iter().zip(&b.atoms) {
        assert_eq!(ia, ib);
        let (mut dv2, mut v2) = (0.0, 0.0);
        for (x, v) in [("x", "vx"), ("y", "vy"), ("z", "vz")] {
            let mut d = va[col(&a, x)] - vb[col(&b, x)];
            d -= len * (d / len).round();
            dr = dr.max(d.abs() / len);
            let (p, q) = (va[col(&a, v)], vb[col(&b, v)]);
            dv2 += (p - q) * (p - q);
            v2 += q * q;
        }
        dp = dp.max((dv2 / v2).sqrt());
    }
    (dr, dp)
}

/// One thermo block: the headings and the numeric rows under them.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermoBlock {
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl ThermoBlock {
    /// Index of a column by its heading (`"Temp"`, `"c_dpdU[4]"`, `"v_totEnergy"`).
    pub fn column_index(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// The values of one column; panics if there is no such heading.
    pub fn column(&self, name: &str) -> Vec<f64> {
        let k = self
            .column_index(name)
            .unwrap_or_else(|| panic!("no thermo column {name:?} in {:?}", self.header));
        self.rows.iter().map(|r| r[k]).collect()
    }
}

fn numeric_row(line: &str, width: usize) -> Option<Vec<f64>> {
    let row: Vec<f64> = line
        .split_whitespace()
        .map(|t| t.parse::<f64>())
        .collect::<Result<_, _>>()
        .ok()?;
    (row.len() == width).then_some(row)
}

/// Every thermo block whose header's first word is `first_column` (e.g. `"Step"`), in order.
/// A block's rows are the following lines that hold exactly one number per heading; lines
/// starting with `WARNING` are skipped (LAMMPS may print them between rows); any other line
/// ends the block. Blocks without rows are kept (with `rows` empty).
pub fn parse_thermo_blocks(log_text: &str, first_column: &str) -> Vec<ThermoBlock> {
    let mut blocks = Vec::new();
    let mut current: Option<ThermoBlock> = None;
    for line in log_text.lines() {
        if let Some(block) = current.as_mut() {
            if let Some(row) = numeric_row(line, block.header.len()) {
                block.rows.push(row);
                continue;
            }
            if line.trim_start().starts_with("WARNING") {
                continue;
            }
            blocks.push(current.take().unwrap());
        }
        let mut words = line.split_whitespace();
        if words.next() == Some(first_column) {
            current = Some(ThermoBlock {
                header: line.split_whitespace().map(String::from).collect(),
                rows: Vec::new(),
            });
        }
    }
    blocks.extend(current);
    blocks
}

/// The numeric rows of every thermo block whose header starts with `first_column`, blocks
/// concatenated in order (consecutive `run`s repeat the boundary step: the last row of one
/// block and the first of the next). Use [`parse_thermo_blocks`] to keep blocks and headings.
pub fn parse_thermo(log_text: &str, first_column: &str) -> Vec<Vec<f64>> {
    parse_thermo_blocks(log_text, first_column)
        .into_iter()
        .flat_map(|b| b.rows)
        .collect()
}

/// A snapshot of a LAMMPS text dump (`dump custom` / `write_dump custom`).
#[derive(Debug, Clone, PartialEq)]
pub struct DumpSnapshot {
    pub timestep: u64,
    /// `[lo, hi]` per dimension, from `ITEM: BOX BOUNDS` (orthogonal boxes).
    pub bounds: Vec<[f64; 2]>,
    /// The `ITEM: ATOMS` headings without `id`, in file order.
    pub columns: Vec<String>,
    /// `(id, values of columns)`, sorted by id.
    pub atoms: Vec<(u64, Vec<f64>)>,
}

impl DumpSnapshot {
    /// Index into each atom's value vector of a heading (`"x"`, `"vx"`, ...).
    pub fn column_index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }
}

/// Parses every snapshot of a LAMMPS text dump. Panics on malformed input.
pub fn parse_dump(text: &str) -> Vec<DumpSnapshot> {
    let mut snaps = Vec::new();
    let mut lines = text.lines().peekable();
    let mut timestep = 0u64;
    let mut natoms = 0usize;
    let mut bounds = Vec::new();
    while let Some(line) = lines.next() {
        let line = line.trim();
        if line == "ITEM: TIMESTEP" {
            timestep = lines
                .next()
                .and_then(|l| l.trim().parse().ok())
                .expect("dump: bad TIMESTEP");
        } else if line == "ITEM: NUMBER OF ATOMS" {
            natoms = lines
                .next()
                .and_then(|l| l.trim().parse().ok())
                .expect("dump: bad NUMBER OF ATOMS");
        } else if line.starts_with("ITEM: BOX BOUNDS") {
            bounds.clear();
            for _ in 0..3 {
                let v: Vec<f64> = lines
                    .next()
                    .expect("dump: short BOX BOUNDS")
                    .split_whitespace()
                    .map(|t| t.parse().expect("dump: bad box bound"))
                    .collect();
                bounds.push([v[0], v[1]]);
            }
        } else if let Some(rest) = line.strip_prefix("ITEM: ATOMS") {
            let heads: Vec<String> = rest.split_whitespace().map(String::from).collect();
            let id_col = heads.iter().position(|h| h == "id").expect("dump: no id column");
            let columns: Vec<String> = heads
                .iter()
                .enumerate()
                .filter(|(k, _)| *k != id_col)
                .map(|(_, h)| h.clone())
                .collect();
            let mut atoms = Vec::with_capacity(natoms);
            for _ in 0..natoms {
                let l = lines.next().expect("dump: fewer atom lines than NUMBER OF ATOMS");
                let toks: Vec<&str> = l.split_whitespace().collect();
                assert_eq!(
                    toks.len(),
                    heads.len(),
                    "dump: atom line {l:?} does not match {heads:?}"
                );
                let id: u64 = toks[id_col].parse().unwrap_or_else(|_| panic!("dump: bad id in {l:?}"));
                let vals = toks
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| *k != id_col)
                    .map(|(_, t)| {
                        t.parse::<f64>()
                            .unwrap_or_else(|_| panic!("dump: bad number {t:?} in {l:?}"))
                    })
                    .collect();
                atoms.push((id, vals));
            }
            atoms.sort_by_key(|a| a.0);
            snaps.push(DumpSnapshot {
                timestep,
                bounds: bounds.clone(),
                columns,
                atoms,
            });
        }
    }
    snaps
}

/// The last snapshot of a LAMMPS text dump file: `(id, remaining columns)` per atom, sorted by id.
pub fn read_dump(path: &Path) -> Vec<(u64, Vec<f64>)> {
    read_dump_snapshot(path).atoms
}

/// The last snapshot of a LAMMPS text dump file, with its headings and box.
pub fn read_dump_snapshot(path: &Path) -> DumpSnapshot {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read dump {}: {e}", path.display()));
    parse_dump(&text)
        .pop()
        .unwrap_or_else(|| panic!("no snapshot in dump {}", path.display()))
}

/// Largest |a - b| over a column of two dumps with the same ids; for a position column pass the
/// box length as `period` to compare by minimum image (None otherwise).
pub fn max_abs_diff(a: &DumpSnapshot, b: &DumpSnapshot, column: &str, period: Option<f64>) -> f64 {
    let ka = a
        .column_index(column)
        .unwrap_or_else(|| panic!("no column {column} in {:?}", a.columns));
    let kb = b
        .column_index(column)
        .unwrap_or_else(|| panic!("no column {column} in {:?}", b.columns));
    assert_eq!(a.atoms.len(), b.atoms.len(), "dumps hold different numbers of atoms");
    let mut worst = 0.0f64;
    for ((ia, va), (ib, vb)) in a.atoms.iter().zip(&b.atoms) {
        assert_eq!(ia, ib, "dumps hold different atom ids");
        let mut d = va[ka] - vb[kb];
        if let Some(l) = period {
            d -= l * (d / l).round();
        }
        worst = worst.max(d.abs());
    }
    worst
}

/// Block average: the series (its first `len % blocks` values dropped, so every block has the
/// same length) is cut into `blocks` contiguous blocks; returns the mean of the block means and
/// its standard error, sd(block means, n-1) / sqrt(blocks). Needs `blocks >= 2` and at least
/// one value per block.
pub fn block_average(series: &[f64], blocks: usize) -> (f64, f64) {
    assert!(blocks >= 2, "block_average needs at least 2 blocks");
    let len = series.len() / blocks;
    assert!(
        len >= 1,
        "block_average: {} values cannot fill {blocks} blocks",
        series.len()
    );
    let start = series.len() - len * blocks;
    let means: Vec<f64> = series[start..]
        .chunks_exact(len)
        .map(|c| c.iter().sum::<f64>() / len as f64)
        .collect();
    let b = blocks as f64;
    let mean = means.iter().sum::<f64>() / b;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (b - 1.0);
    (mean, (var / b).sqrt())
}

/// |ma - mb| <= k sqrt(sa^2 + sb^2) for `(mean, standard error)` pairs.
pub fn agree_within(a: (f64, f64), b: (f64, f64), k: f64) -> bool {
    (a.0 - b.0).abs() <= k * (a.1 * a.1 + b.1 * b.1).sqrt()
}

#[cfg(test)]
#[allow(clippy::excessive_precision)]
mod tests {
    use super::*;

    /// Excerpt of a real LAMMPS (22 Jul 2025 - Update 4) log of scripts/lammps/in.dpde-shardlow
    /// (equilibration run with default format, then a second run with `format float %.10g`),
    /// with a WARNING line inserted between rows as LAMMPS can print them.
    const LAMMPS_LOG: &str = "\
LAMMPS (22 Jul 2025 - Update 4)
  using 1 OpenMP thread(s) per MPI task
thermo_style    custom step temp press pe ke c_dpdU[1] c_dpdU[2] c_dpdU[4] v_totEnergy
thermo_modify   norm no
run             ${equil}
run             1000
Per MPI rank memory allocation (min/avg/max) = 5.911 | 5.911 | 5.911 Mbytes
   Step          Temp          Press          PotEng         KinEng       c_dpdU[1]      c_dpdU[2]      c_dpdU[4]     v_totEnergy  
         0   1.0230831      26.713264      23665.05       4602.3392      0              30000          1              58267.389    
      1000   1.1544613      24.041171      13980.361      5193.3443      7.8514972e-13  39068.347      1.1892342      58242.052    
Loop time of 9.00698 on 1 procs for 1000 steps with 3000 atoms

Performance: 95925.556 tau/day, 111.025 timesteps/s, 333.075 katom-step/s
reset_timestep  0
thermo          10
run             2000
Per MPI rank memory allocation (min/avg/max) = 5.911 | 5.911 | 5.911 Mbytes
   Step          Temp          Press          PotEng         KinEng       c_dpdU[1]      c_dpdU[2]      c_dpdU[4]     v_totEnergy  
         0  1.154461342 24.04117138 13980.36062 5193.344349 0 39068.34723 1.189234178 58242.0522
        10  1.20106048 24.2546352 13855.09271 5402.970569 5.519890101e-15 38983.78014 1.186607886 58241.84342
WARNING: Communication cutoff is shorter than a bond length based estimate (src/comm.cpp:1214)
        20  1.182473003 24.14201949 13863.84142 5319.354804 5.426215033e-15 39058.66187 1.188303132 58241.8581
Loop time of 14.9308 on 1 procs for 2000 steps with 3000 atoms
";

    /// gendpde's stdout uses the same layout (src/output/thermo.rs: integers `%10d `, floats `%.8g`
    /// in 14 columns, headings centred).
    const GENDPDE_OUT: &str = "\
Reading data file ...
   Step          Temp           Press          PotEng         KinEng    
         0   0.98445341    -8.7307605     -11094.251      3242.7895    
        10   1.0092606     -25.495506     -19554.741      3324.5044    
        20   1.0342423     -25.987105     -19543.393      3406.7943    
Loop time of 0.012345 on 1 procs for 20 steps with 2197 atoms
";

    #[test]
    fn parse_thermo_reads_lammps_log_blocks() {
        let blocks = parse_thermo_blocks(LAMMPS_LOG, "Step");
        assert_eq!(blocks.len(), 2);
        assert_eq!(blocks[0].header.len(), 9);
        assert_eq!(blocks[0].header[5], "c_dpdU[1]");
        assert_eq!(blocks[0].rows.len(), 2);
        assert_eq!(blocks[1].rows.len(), 3, "the WARNING line must not end the block");
        assert_eq!(
            blocks[1].column("c_dpdU[4]"),
            vec![1.189234178, 1.186607886, 1.188303132]
        );
        assert_eq!(blocks[1].column_index("v_totEnergy"), Some(8));

        let rows = parse_thermo(LAMMPS_LOG, "Step");
        assert_eq!(rows.len(), 5);
        assert_eq!(rows[1][0], 1000.0);
        assert_eq!(rows[1][5], 7.8514972e-13);
        assert_eq!(
            rows[4],
            vec![
                20.0,
                1.182473003,
                24.14201949,
                13863.84142,
                5319.354804,
                5.426215033e-15,
                39058.66187,
                1.188303132,
                58241.8581
            ]
        );
        // the echoed thermo_style line and the Performance line are not blocks
        assert!(parse_thermo(LAMMPS_LOG, "thermo_style").is_empty());
        assert!(parse_thermo(LAMMPS_LOG, "Temp").is_empty());
    }

    #[test]
    fn parse_thermo_reads_gendpde_stdout() {
        let rows = parse_thermo(GENDPDE_OUT, "Step");
        assert_eq!(rows.len(), 3);
        assert_eq!(rows[0], vec![0.0, 0.98445341, -8.7307605, -11094.251, 3242.7895]);
        assert_eq!(rows[2][0], 20.0);
        let b = &parse_thermo_blocks(GENDPDE_OUT, "Step")[0];
        assert_eq!(b.header, ["Step", "Temp", "Press", "PotEng", "KinEng"]);
        // a block cut off at the end of the text (no Loop time line) still counts
        let cut: String = GENDPDE_OUT.lines().take(4).map(|l| format!("{l}\n")).collect();
        assert_eq!(parse_thermo(&cut, "Step").len(), 2);
    }

    /// Head of a real `write_dump all custom F id x y z vx vy vz modify sort id format float
    /// %.17g` of LAMMPS 22 Jul 2025 (3 atoms kept, NUMBER OF ATOMS edited to match), with the
    /// atom lines shuffled and the id column moved to check sorting and id detection.
    const DUMP: &str = "\
ITEM: TIMESTEP
100
ITEM: NUMBER OF ATOMS
3
ITEM: BOX BOUNDS pp pp pp
0.0000000000000000e+00 9.0000000000000000e+00
0.0000000000000000e+00 9.0000000000000000e+00
0.0000000000000000e+00 9.0000000000000000e+00
ITEM: ATOMS x id y z vx vy vz
4.4431553043978704 3 8.6833596774656954 2.5398125322672724 -0.77373541768429888 1.5074668821796948 -0.66543917641964534
0.34816070660144915 1 2.7892096769707027 5.3404670709559836 0.94020676833696792 0.75599270890092873 -0.51366576365393446
7.7008102331858836 2 8.303353691070555 6.2475804862485314 2.6095821542797215 0.32392680175989508 -0.014407730354379811
";

    #[test]
    fn read_dump_sorts_by_id_and_keeps_full_precision() {
        let dir = std::env::temp_dir().join(format!("gendpde-lammps-rs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.dump");
        // two snapshots: read_dump returns the last
        let first = DUMP.replacen("100", "0", 1);
        std::fs::write(&path, format!("{first}{DUMP}")).unwrap();
        let atoms = read_dump(&path);
        let snap = read_dump_snapshot(&path);
        std::fs::remove_dir_all(&dir).ok();

        assert_eq!(atoms.iter().map(|a| a.0).collect::<Vec<_>>(), vec![1, 2, 3]);
        assert_eq!(
            atoms[0].1,
            vec![
                0.34816070660144915,
                2.7892096769707027,
                5.3404670709559836,
                0.94020676833696792,
                0.75599270890092873,
                -0.51366576365393446
            ]
        );
        assert_eq!(atoms[1].1[5], -0.014407730354379811);
        assert_eq!(snap.timestep, 100);
        assert_eq!(snap.columns, ["x", "y", "z", "vx", "vy", "vz"]);
        assert_eq!(snap.bounds[2], [0.0, 9.0]);
        assert_eq!(parse_dump(DUMP).len(), 1);

        // minimum-image comparison of positions
        let mut other = snap.clone();
        other.atoms[0].1[0] += 9.0 + 1e-12;
        assert!(max_abs_diff(&snap, &other, "x", None) > 8.0);
        assert!(max_abs_diff(&snap, &other, "x", Some(9.0)) < 2e-12);
        assert_eq!(max_abs_diff(&snap, &other, "vz", None), 0.0);
    }

    #[test]
    fn block_average_of_known_series() {
        // blocks [1,2] [3,4] [5,6] [7,8]: means 1.5 3.5 5.5 7.5 -> mean 4.5,
        // sd = sqrt(((9+1+1+9)/3)) = sqrt(20/3), se = sd/2
        let s: Vec<f64> = (1..=8).map(f64::from).collect();
        let (m, se) = block_average(&s, 4);
        assert!((m - 4.5).abs() < 1e-15);
        assert!((se - (20.0f64 / 3.0).sqrt() / 2.0).abs() < 1e-15);
        // a leading remainder is dropped: 0 first, then the same 8 values
        let mut t = vec![100.0];
        t.extend(&s);
        assert_eq!(block_average(&t, 4), (m, se));
        // a constant series has zero error
        assert_eq!(block_average(&[2.0; 10], 5), (2.0, 0.0));
    }

    #[test]
    fn agree_within_uses_combined_error() {
        assert!(agree_within((1.0, 0.3), (2.0, 0.4), 2.0)); // |1| <= 2 * 0.5
        assert!(!agree_within((1.0, 0.3), (2.0, 0.4), 1.9));
        assert!(agree_within((1.0, 0.0), (1.0, 0.0), 3.0));
    }

    #[test]
    #[should_panic(expected = "at least 2 blocks")]
    fn block_average_rejects_one_block() {
        block_average(&[1.0, 2.0], 1);
    }
}
