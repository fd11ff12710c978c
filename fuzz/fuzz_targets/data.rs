//! Arbitrary bytes as a LAMMPS data file, read in every atom style: the
//! parser must return a located error or a consistent `DataFile`, never panic.
#![no_main]

use gendpde_io::{parse_data, AtomStyle};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let text = String::from_utf8_lossy(bytes);
    for style in [AtomStyle::Atomic, AtomStyle::Dpd, AtomStyle::Mdpd] {
        match parse_data("fuzz.data", &text, style) {
            Ok(data) => {
                // What a successful read promises.
                assert_eq!(data.masses.len(), data.ntypes);
                assert_eq!(data.atoms.len(), data.natoms);
                for a in &data.atoms {
                    assert!(a.tag > 0 && a.kind >= 1 && a.kind as usize <= data.ntypes);
                    assert_eq!(a.theta.is_some(), style == AtomStyle::Dpd);
                    assert!(a.r.iter().all(|x| x.is_finite()));
                }
                for d in 0..3 {
                    assert!(data.lo[d] < data.hi[d]);
                }
                if let Some(v) = &data.velocities {
                    assert_eq!(v.len(), data.natoms);
                }
            }
            Err(e) => {
                assert!(e.loc.is_some(), "unlocated error: {e}");
                let _ = e.to_string();
            }
        }
    }
});
