//! Static groups (LAMMPS `group`) select the particles of `set` and `velocity`: the
//! flash-heating scene of the 2019 paper heats a centred slab of half the particles.

use crate::common;

#[test]
fn a_centred_slab_group_is_heated_and_the_rest_is_not() {
    let mut it = common::run_script(
        "units lj
lattice sc 0.5
region box block 0 12 0 12 0 12
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.5 11 dist gaussian
set group all theta 1.5
region slab block 3 9 INF INF INF INF
group hot region slab
velocity hot create 5.0 12 dist gaussian
set group hot theta 5.0
group cold id 1:10
",
    );
    let sys = it.system().unwrap();
    let s = &sys.store;
    let l = sys.domain.len()[0];
    let (mut hot, mut ke_hot, mut ke_cold) = (0usize, 0.0, 0.0);
    for i in 0..s.nlocal {
        let x = s.r[i][0] / l;
        let in_slab = (0.25..=0.75).contains(&x);
        assert_eq!(s.groups[i] & 1 != 0, in_slab, "membership of particle {}", s.tag[i]);
        let ke: f64 = s.p[i].iter().map(|p| p * p).sum::<f64>() / s.mass[i];
        if in_slab {
            hot += 1;
            ke_hot += ke;
            assert_eq!(s.theta[i], 5.0);
        } else {
            ke_cold += ke;
            assert_eq!(s.theta[i], 1.5);
        }
        assert_eq!(s.groups[i] & 2 != 0, s.tag[i] <= 10);
    }
    let cold = s.nlocal - hot;
    assert_eq!(hot, 12 * 12 * 7, "x lattice planes 3..9 inclusive");
    // T = sum m v^2 / (3 N - 3) within each group
    assert!((ke_hot / (3.0 * hot as f64 - 3.0) - 5.0).abs() < 1e-9);
    assert!((ke_cold / (3.0 * cold as f64) - 1.5).abs() < 0.1);
}
