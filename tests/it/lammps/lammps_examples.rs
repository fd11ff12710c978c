//! LAMMPS's own DPD example scripts (scripts/lammps/examples/, verbatim): the ones gendpde
//! supports pass `gendpde check` unchanged; every other one stops at its first unsupported
//! line with a clean `file:line:` error, never a panic. The side-by-side numbers with the
//! reference LAMMPS come from scripts/lammps/examples.py (docs/LAMMPS_EXAMPLES.md).

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// Examples that run unchanged (folder under scripts/lammps/examples/, input).
const SUPPORTED: &[&str] = &[
    "dpd-basic/dpd/in.dpd",
    "dpd-basic/dpd_tstat/in.dpd_tstat",
    "dpd-basic/dpdext/in.dpdext",
    "dpd-basic/dpdext_tstat/in.dpdext_tstat",
    "dpd-meso/edpd/in.edpd",
    "dpd-meso/edpd/in.edpd-region",
    "dpd-meso/mdpd/in.mdpd",
    "dpd-react/dpd-shardlow/in.dpd-shardlow",
    "dpd-react/dpd-vv/in.dpd-vv",
    "dpd-react/dpde-shardlow/in.dpde-shardlow",
    "dpd-react/dpde-vv/in.dpde-vv",
    "dpd-react/dpdh-shardlow/in.dpdh-shardlow",
    "dpd-react/dpdp-shardlow/in.dpdp-shardlow",
    "dpd-react/multi-lucy/in.multi-lucy",
];

fn examples() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/lammps/examples");
    let mut found = Vec::new();
    for package in std::fs::read_dir(&root).expect("scripts/lammps/examples exists") {
        let package = package.unwrap().path();
        if !package.is_dir() {
            continue;
        }
        for folder in std::fs::read_dir(&package).unwrap() {
            for file in std::fs::read_dir(folder.unwrap().path()).unwrap() {
                let file = file.unwrap().path();
                if file.file_name().unwrap().to_string_lossy().starts_with("in.") {
                    found.push(file);
                }
            }
        }
    }
    found.sort();
    found
}

/// Copies the example's folder into a fresh directory, unpacking gzipped data files.
fn stage(input: &Path, name: &str) -> PathBuf {
    let dir = common::tempdir(&format!("example-{name}"));
    for f in std::fs::read_dir(input.parent().unwrap()).unwrap() {
        let f = f.unwrap().path();
        let file = f.file_name().unwrap().to_string_lossy().to_string();
        if let Some(stem) = file.strip_suffix(".gz") {
            let out = Command::new("gzip").arg("-dc").arg(&f).output().expect("gzip runs");
            assert!(out.status.success(), "gzip -dc {}", f.display());
            std::fs::write(dir.join(stem), out.stdout).unwrap();
        } else {
            std::fs::copy(&f, dir.join(&file)).unwrap();
        }
    }
    dir
}

#[test]
fn lammps_examples_check_or_stop_cleanly() {
    let all = examples();
    assert!(all.len() >= 12, "the example folders are present ({} inputs)", all.len());
    let mut failures = Vec::new();
    for input in &all {
        let rel = input.strip_prefix(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/lammps/examples")).unwrap();
        let rel = rel.to_string_lossy().to_string();
        let file = input.file_name().unwrap().to_string_lossy().to_string();
        let dir = stage(input, &file[3..]);
        let out = common::gendpde(&dir, &["check", &file]);
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        let supported = SUPPORTED.contains(&rel.as_str());
        if supported && !out.status.success() {
            failures.push(format!("{rel}: expected to run, got: {stderr}"));
        }
        if !supported {
            let clean = out.status.code() == Some(1) && stderr.contains(&format!("{file}:")) && !stderr.contains("panicked");
            if out.status.success() {
                failures.push(format!("{rel}: now passes check; add it to SUPPORTED and to docs/LAMMPS_EXAMPLES.md"));
            } else if !clean {
                failures.push(format!("{rel}: not a clean file:line error (status {:?}): {stderr}", out.status.code()));
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
