//! Geometry of the tessellation (reading notes, target d): closure of every cell, the total
//! volume, eq 129 against finite differences, and the degenerate simple-cubic lattice.

use super::*;

/// Deterministic uniform numbers in [0, 1) for test configurations.
pub(super) struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` random points in the box [lo, lo + len).
pub(super) fn random_points(n: usize, lo: [f64; 3], len: [f64; 3], seed: u64) -> Vec<[f64; 3]> {
    let mut r = Lcg(seed);
    (0..n).map(|_| std::array::from_fn(|a| lo[a] + len[a] * r.next())).collect()
}

const LO: [f64; 3] = [-1.0, 0.5, 2.0];
const LEN: [f64; 3] = [5.0, 6.0, 7.0];

#[test]
fn every_cell_is_closed_sum_of_area_times_e_vanishes() {
    let pts = random_points(300, LO, LEN, 1);
    let t = Tessellation::build(&pts, LO, LEN).unwrap();
    for k in 0..t.len() {
        let mut s = [0.0; 3];
        let mut scale = 0.0;
        for f in t.faces_of(k) {
            let (e, _) = f.e_from(k);
            for a in 0..3 {
                s[a] += f.area * e[a];
            }
            scale += f.area;
        }
        for a in 0..3 {
            assert!(s[a].abs() < 1e-12 * scale, "cell {k}: sum A e = {s:?} (sum A = {scale})");
        }
        assert!(t.neighbours(k).count() >= 4);
    }
}

#[test]
fn volumes_add_up_to_the_box() {
    let pts = random_points(500, LO, LEN, 2);
    let t = Tessellation::build(&pts, LO, LEN).unwrap();
    let total: f64 = t.volumes.iter().sum();
    let box_v = LEN[0] * LEN[1] * LEN[2];
    assert!((total / box_v - 1.0).abs() < 1e-13, "sum V = {total}, box {box_v}");
    // Positions outside the box are wrapped: shifting by box vectors changes nothing.
    let shifted: Vec<[f64; 3]> = pts.iter().map(|p| [p[0] + 3.0 * LEN[0], p[1] - LEN[1], p[2]]).collect();
    let t2 = Tessellation::build(&shifted, LO, LEN).unwrap();
    for (a, b) in t.volumes.iter().zip(&t2.volumes) {
        assert!((a - b).abs() < 1e-12 * a);
    }
}

/// Eq 129: dV_mu/dR_nu = -A (c/R + e/2) for nu != mu, and the diagonal from the column sum,
/// against central differences of the volumes.
#[test]
fn volume_gradients_match_finite_differences_eq_129() {
    let n = 120;
    let pts = random_points(n, LO, LEN, 3);
    let t = Tessellation::build(&pts, LO, LEN).unwrap();
    let h = 1e-6;
    let mut checked = 0;
    for nu in [0usize, 7, 31] {
        // Analytic column nu: dV_mu/dR_nu for every mu.
        let mut grad = vec![[0.0f64; 3]; n];
        for f in &t.faces {
            let (gij, gji) = Tessellation::volume_gradients(f);
            if f.j == nu {
                for a in 0..3 {
                    grad[f.i][a] += gij[a];
                    grad[nu][a] -= gij[a];
                }
            }
            if f.i == nu {
                for a in 0..3 {
                    grad[f.j][a] += gji[a];
                    grad[nu][a] -= gji[a];
                }
            }
        }
        for a in 0..3 {
            let mut plus = pts.clone();
            let mut minus = pts.clone();
            plus[nu][a] += h;
            minus[nu][a] -= h;
            let vp = Tessellation::build(&plus, LO, LEN).unwrap().volumes;
            let vm = Tessellation::build(&minus, LO, LEN).unwrap().volumes;
            for mu in 0..n {
                let fd = (vp[mu] - vm[mu]) / (2.0 * h);
                assert!((fd - grad[mu][a]).abs() < 1e-6, "dV_{mu}/dR_{nu}[{a}]: fd {fd} vs eq 129 {}", grad[mu][a]);
                if grad[mu][a] != 0.0 {
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 60, "too few non-zero derivatives checked: {checked}");
}

/// A simple-cubic lattice is maximally degenerate (8 generators on every vertex sphere):
/// every cell must be the unit cube with its 6 faces and no slivers.
#[test]
fn simple_cubic_lattice_gives_unit_cubes() {
    let k = 5;
    let mut pts = vec![];
    for x in 0..k {
        for y in 0..k {
            for z in 0..k {
                pts.push([x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.5]);
            }
        }
    }
    let l = k as f64;
    let t = Tessellation::build(&pts, [0.0; 3], [l; 3]).unwrap();
    for c in 0..t.len() {
        assert!((t.volumes[c] - 1.0).abs() < 1e-14, "cell {c}: V = {}", t.volumes[c]);
        let faces: Vec<&Face> = t.faces_of(c).collect();
        assert_eq!(faces.len(), 6, "cell {c}");
        for f in faces {
            assert!((f.area - 1.0).abs() < 1e-14 && (f.dist - 1.0).abs() < 1e-14);
            assert!(f.offset.iter().all(|x| x.abs() < 1e-14));
        }
    }
    assert_eq!(t.faces.len(), 3 * k * k * k);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let pts = random_points(50, LO, LEN, 4);
    assert_eq!(Tessellation::build(&pts, LO, [1.0, 0.0, 1.0]).unwrap_err(), TessellationError::BadBox([1.0, 0.0, 1.0]));
    let mut bad = pts.clone();
    bad[3][1] = f64::NAN;
    assert_eq!(Tessellation::build(&bad, LO, LEN).unwrap_err(), TessellationError::BadPosition(3));
    let two = [[0.1, 0.1, 0.1], [0.6, 0.6, 0.6]];
    assert!(matches!(Tessellation::build(&two, [0.0; 3], [1.0; 3]), Err(TessellationError::SelfImage(_))));
}
