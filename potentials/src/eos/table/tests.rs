//! Tests of `table`.

use super::super::{AtDensity, AtN, Before, FixedDensity, LennardJones, LinearTheta};
use super::*;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[allow(clippy::approx_constant)] // b = 1.4142 of the paper, not sqrt(2)
fn vdw() -> LinearTheta {
    LinearTheta::vdw_excess(60.0, 2.4682, 1.4142)
}

/// vdW excess below its density cap (n_s = 0.95/b = 0.672), down to n = 0.
fn vdw_table(nt: usize, nn: usize) -> Tabulated<LinearTheta> {
    Tabulated::new(vdw(), TableGrid { theta: (0.5, 5.0, nt), n: (0.0, 0.65, nn) }).unwrap()
}

fn lj_grid(nt: usize, nn: usize) -> TableGrid {
    TableGrid { theta: (0.5, 5.0, nt), n: (0.05, 0.85, nn) }
}

fn lj_table(nt: usize, nn: usize) -> Tabulated<LennardJones> {
    Tabulated::new(LennardJones::new(60.0), lj_grid(nt, nn)).unwrap()
}

/// Deterministic states spread over the table, edges, corners and nodes included.
fn states<E: Eos>(t: &Tabulated<E>, count: usize) -> Vec<(f64, f64)> {
    let (tmin, tmax, _) = t.grid.theta;
    let (nmin, nmax, _) = t.grid.n;
    let mut out = vec![(tmin, nmin), (tmin, nmax), (tmax, nmin), (tmax, nmax)];
    out.extend(t.thetas.iter().map(|&th| (th, nmin + 0.3 * (nmax - nmin))));
    let mut x: u64 = 0x2545_f491_4f6c_dd1d;
    let mut unit = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..count {
        let theta = tmin * (tmax / tmin).powf(unit());
        out.push((theta.clamp(tmin, tmax), nmin + (nmax - nmin) * unit()));
    }
    out
}

#[test]
fn linear_in_theta_model_is_exact_in_theta() {
    let t = vdw_table(10, 27);
    let m = vdw();
    let e = t.max_error(4);
    eprintln!("vdW excess, 10 x 27 nodes: {e}");
    // u = C_V theta - a n and C_V are polynomials of degree <= 3: exact to round-off
    assert!(e.u.rel < 1e-14 && e.cv.rel < 1e-13 && e.theta.rel < 1e-14, "{e}");
    // pi/n^2 = b theta/(1 - b n) - a: linear in theta, interpolated in n (steep near
    // the pole at 1/b = 0.707)
    assert!(e.pn2.rel < 2e-3, "{e}");
    let fine = vdw_table(10, 53).max_error(4);
    eprintln!("vdW excess, 10 x 53 nodes: {fine}");
    let ratio = e.pn2.rel / fine.pn2.rel;
    eprintln!("halving dn divides the pi/n^2 error by {ratio:.1}");
    assert!(ratio > 12.0, "pi/n^2 error falls by {ratio} when dn halves");
    // at the density nodes pi/n^2 is linear in theta and exact at any theta
    for &(theta, _) in &states(&t, 200) {
        for j in [0, 10, 26] {
            let n = (0.65 * j as f64 / 26.0).min(0.65);
            let (a, b) = (t.pn2(theta, n), m.pn2(theta, n));
            assert!((a - b).abs() < 1e-13 * b.abs().max(1.0), "({theta}, {n}): {a} vs {b}");
            assert!(rel(t.u(theta, n), m.u(theta, n)) < 1e-14);
            assert!(rel(t.cv(theta, n), 60.0) < 1e-13);
        }
    }
    assert_eq!(t.kb(), m.kb());
    assert_eq!(t.max_density(), m.max_density());
    assert!(t.density_dependent());
    assert_eq!(t.inner(), &m);
}

#[test]
fn lennard_jones_errors_fall_at_the_expected_order() {
    let mut errors = Vec::new();
    for (nt, nn) in [(16, 17), (31, 33), (61, 65)] {
        let t = lj_table(nt, nn);
        let e = t.max_error(4);
        eprintln!("LJ C_V = 60, theta [0.5, 5] x n [0.05, 0.85], {nt} x {nn} nodes: {e}");
        errors.push(e);
    }
    for w in errors.windows(2) {
        let ratio = |f: fn(&TableErrors) -> f64| f(&w[0]) / f(&w[1]);
        let (ru, rp, rc, rt) = (
            ratio(|e| e.u.rel),
            ratio(|e| e.pn2.rel),
            ratio(|e| e.cv.rel),
            ratio(|e| e.theta.rel),
        );
        eprintln!(
            "halving the spacing divides the errors by u {ru:.1}, pi/n^2 {rp:.1}, \
             C_V {rc:.1}, theta {rt:.1}"
        );
        // O(h^4) for the interpolants and for theta(u), O(h^3) for C_V = du/dtheta
        assert!(ru > 12.0 && rp > 12.0 && rt > 12.0, "{ru} {rp} {rt}");
        assert!(rc > 6.0, "{rc}");
    }
    let fine = &errors[2];
    assert!(fine.u.rel < 3e-7 && fine.theta.rel < 2e-7, "{fine}");
    assert!(fine.pn2.rel < 2e-5 && fine.cv.rel < 2e-5, "{fine}");
}

#[test]
fn theta_round_trips_through_the_table() {
    for t in [lj_table(16, 17), lj_table(61, 65)] {
        let (tmin, tmax, _) = t.grid.theta;
        let mut worst = 0.0f64;
        for (theta, n) in states(&t, 3000) {
            let u = t.u(theta, n);
            for guess in [theta, tmin, tmax, 1.0, 0.0, -1.0, f64::NAN, f64::INFINITY, 1e3] {
                let back = t.theta(u, n, guess);
                worst = worst.max(rel(back, theta));
                assert!(rel(back, theta) < 1e-12, "({theta}, {n}) guess {guess}: {back}");
            }
            // and from a nearby energy with the old theta as guess (the sweep's case)
            let u2 = u * (1.0 + 1e-4);
            let t2 = t.theta(u2, n, theta);
            if t2.is_finite() {
                assert!(rel(t.u(t2, n), u2) < 1e-14);
            }
            let st = t.state(u, n, theta).unwrap();
            assert!(rel(st.theta, theta) < 1e-12);
            assert!(
                rel(st.pn2, t.pn2(theta, n)) < 1e-12
                    || (st.pn2 - t.pn2(theta, n)).abs() < 1e-13
            );
            assert!(rel(st.cv, t.cv(theta, n)) < 1e-12);
        }
        eprintln!("worst round-trip error of theta(u(theta, n), n): {worst:.2e}");
    }
    let t = vdw_table(10, 14);
    for (theta, n) in states(&t, 1000) {
        assert!(rel(t.theta(t.u(theta, n), n, 1.0), theta) < 1e-14);
    }
}

#[test]
fn heat_capacity_is_positive_and_u_increasing() {
    let t = lj_table(16, 17);
    let (k, (tmin, tmax, _), (nmin, nmax, _)) = (400, t.grid.theta, t.grid.n);
    let mut lowest = f64::INFINITY;
    for b in 0..=k {
        let n = (nmin + (nmax - nmin) * b as f64 / k as f64).min(nmax);
        let mut last = f64::NEG_INFINITY;
        for a in 0..=k {
            let theta = (tmin + (tmax - tmin) * a as f64 / k as f64).min(tmax);
            let cv = t.cv(theta, n);
            lowest = lowest.min(cv);
            assert!(cv > 0.0, "C_V = {cv} at ({theta}, {n})");
            let u = t.u(theta, n);
            assert!(u > last, "u not increasing at ({theta}, {n})");
            last = u;
        }
    }
    eprintln!("lowest tabulated C_V on a 401 x 401 sample: {lowest}");
}

#[test]
fn states_outside_the_table_are_errors() {
    let t = lj_table(16, 17);
    let n = 0.5;
    for (theta, nn) in
        [(0.4, n), (5.1, n), (1.0, 0.9), (1.0, 0.01), (f64::NAN, n), (1.0, f64::NAN)]
    {
        assert!(
            t.u(theta, nn).is_nan() && t.pn2(theta, nn).is_nan() && t.cv(theta, nn).is_nan()
        );
        let e = t.check(theta, nn).unwrap_err();
        let msg = e.to_string();
        eprintln!("{msg}");
        assert!(msg.contains(&format!("theta = {theta:e}, n = {nn:e}")), "{msg}");
        assert!(msg.contains("theta in [5e-1, 5e0], n in [5e-2, 8.5e-1]"), "{msg}");
    }
    assert!(t.check(0.5, 0.05).is_ok() && t.check(5.0, 0.85).is_ok());
    let (lo, hi) = (t.u(0.5, n), t.u(5.0, n));
    for u in [lo - 1e-9, hi + 1e-9, f64::NAN, f64::INFINITY, -1e300] {
        assert!(t.theta(u, n, 1.0).is_nan());
        assert!(matches!(t.state(u, n, 1.0), Err(EosError::NonPositiveTheta { .. })));
        assert!(t.entropy(u, n).is_none());
        let msg = t.theta_checked(u, n, 1.0).unwrap_err().to_string();
        eprintln!("{msg}");
        assert!(msg.contains(&format!("u = {u:e}, n = {n:e}")), "{msg}");
        assert!(msg.contains(&format!("[{lo:e}, {hi:e}]")), "{msg}");
    }
    assert_eq!(t.theta(lo, n, 3.0), 0.5);
    assert_eq!(t.theta(hi, n, 0.7), 5.0);
    assert_eq!(t.theta_checked(hi, n, 0.7), Ok(5.0));
    // isolated particles are evaluated at n = 1e-6: outside this table
    let msg = t.theta_checked(100.0, 1e-6, 1.0).unwrap_err().to_string();
    assert!(msg.contains("n = 1e-6") && msg.contains("n in [5e-2, 8.5e-1]"), "{msg}");
    assert!(t.state(100.0, 0.0, 1.0).is_err());
}

#[test]
fn isolated_particles_and_entropy() {
    let t = vdw_table(10, 14);
    let st = t.state(90.0, 0.0, 1.5).unwrap();
    assert_eq!(st.pn2, 0.0);
    assert!((st.theta - (90.0 + 2.4682e-6) / 60.0).abs() < 1e-14);
    let lj = lj_table(31, 33);
    for (theta, n) in states(&lj, 50) {
        let u = lj.u(theta, n);
        assert_eq!(lj.entropy(u, n), lj.inner().entropy(u, n));
    }
}

#[test]
fn invalid_grids_and_failing_models_are_errors() {
    let m = || LennardJones::new(60.0);
    for (theta, n) in [
        ((0.0, 5.0, 10), (0.0, 0.8, 10)),
        ((1.0, 0.5, 10), (0.0, 0.8, 10)),
        ((0.5, 5.0, 1), (0.0, 0.8, 10)),
        ((0.5, f64::INFINITY, 10), (0.0, 0.8, 10)),
        ((0.5, 5.0, 10), (-0.1, 0.8, 10)),
        ((0.5, 5.0, 10), (0.0, f64::NAN, 10)),
        ((0.5, 5.0, 10), (0.3, 0.3, 10)),
        ((0.5, 5.0, 1 << 12), (0.0, 0.8, 1 << 12)),
    ] {
        let e = Tabulated::new(m(), TableGrid { theta, n }).unwrap_err();
        eprintln!("{e}");
        assert!(matches!(e, TableError::Grid(_)));
    }
    // LJ outside its domain (packing fraction > 0.9 at theta = 0.02, n = 1.2)
    let e =
        Tabulated::new(m(), TableGrid { theta: (0.02, 2.0, 5), n: (0.0, 1.2, 5) }).unwrap_err();
    eprintln!("{e}");
    assert!(matches!(e, TableError::Inner { theta, .. } if theta == 0.02), "{e}");
    assert!(e.to_string().contains("node theta = 2e-2, n = 8.99"), "{e}");
    // the ideal gas has ln n: n = 0 fails, naming the node
    let e = Tabulated::new(
        LinearTheta::ideal(5.0),
        TableGrid { theta: (0.5, 5.0, 5), n: (0.0, 1.0, 5) },
    )
    .unwrap_err();
    eprintln!("{e}");
    assert!(matches!(e, TableError::Inner { n, .. } if n == 0.0));
}

/// u = theta + A sin(2 pi theta / w) w / (2 pi) with C_V = 1 + A at the nodes (spacing w)
/// but negative in between: the Hermite cubic decreases inside the cells.
#[derive(Debug)]
struct Wiggly {
    w: f64,
    a: f64,
}

impl Eos for Wiggly {
    fn kb(&self) -> f64 {
        1.0
    }
    fn density_dependent(&self) -> bool {
        false
    }
    fn theta(&self, u: f64, n: f64, guess: f64) -> f64 {
        let mut x = guess;
        for _ in 0..50 {
            x -= (self.u(x, n) - u) / self.cv(x, n);
        }
        x
    }
    fn u(&self, theta: f64, _n: f64) -> f64 {
        let k = 2.0 * std::f64::consts::PI / self.w;
        theta + self.a * (k * theta).sin() / k
    }
    fn pn2(&self, _theta: f64, _n: f64) -> f64 {
        0.0
    }
    fn cv(&self, theta: f64, _n: f64) -> f64 {
        1.0 + self.a * (2.0 * std::f64::consts::PI * theta / self.w).cos()
    }
    fn entropy(&self, _u: f64, _n: f64) -> Option<f64> {
        None
    }
    fn max_density(&self) -> Option<f64> {
        None
    }
}

#[test]
fn non_monotone_interpolant_is_refused() {
    // nodes uniform in ln theta on [1, 2] are not exactly w apart: use two nodes
    let grid = TableGrid { theta: (1.0, 2.0, 2), n: (0.0, 1.0, 2) };
    let e = Tabulated::new(Wiggly { w: 1.0, a: 2.5 }, grid).unwrap_err();
    eprintln!("{e}");
    assert_eq!(e, TableError::NotMonotone { theta: (1.0, 2.0), n: (0.0, 1.0) });
    // the same model is accepted where its C_V stays positive
    assert!(Tabulated::new(Wiggly { w: 1.0, a: 0.3 }, grid).is_ok());
}

use super::super::EosError;

/// The sweep's model at a state ([`FixedDensity::at_state`], the cubic of its cell at
/// hand) gives the bits of the full lookup, from the old theta and from the first-order
/// guess, for refreshes inside the cell, across cells and out of the table.
#[test]
fn cell_at_hand_gives_the_full_solve() {
    let t = lj_table(61, 65);
    let mut in_cell = 0;
    let mut count = 0;
    for (theta, n) in states(&t, 400) {
        let at = t.at_state(n, theta);
        let full = AtN { eos: &t, n };
        let cv = t.cv(theta, n);
        let inv_tau = t.inv_tau(theta, cv);
        for k in 0..=12 {
            let du = 0.1 * cv * theta * (if k % 2 == 0 { 1.0 } else { -1.0 }) * 10f64.powi(-(k / 2));
            let u = t.u(theta, n) + du;
            for guess in [theta, at.guess_after(theta, inv_tau, du), f64::NAN] {
                let bits = |(a, b): (f64, f64)| (a.to_bits(), b.to_bits());
                assert_eq!(bits(at.theta_inv_tau(u, guess)), bits(full.theta_inv_tau(u, guess)), "({theta}, {n}) u {u} guess {guess}");
                assert_eq!(at.theta(u, guess).to_bits(), full.theta(u, guess).to_bits());
                in_cell += usize::from(at.in_cell(u, guess).is_some());
                count += 1;
            }
        }
    }
    eprintln!("{in_cell} of {count} refreshes solved in the cell at hand");
    assert!(in_cell > count / 4 && in_cell < count, "{in_cell} of {count}");
}

/// The sweep's refresh from the state before ([`AtDensity::after_pair`], its Newton step
/// from the cubic's Taylor coefficients at the old theta) finds the full solve's theta
/// and 1/tau to round-off (both stop within 1e-15 theta of the root: at most 2e-15
/// apart), with and without 1/tau kept, inside the cell, across cells and out of the table.
#[test]
fn refresh_from_the_state_before_matches_the_full_solve() {
    let t = lj_table(61, 65);
    let (mut worst_theta, mut worst_inv_tau, mut in_cell, mut count) = (0.0f64, 0.0f64, 0, 0);
    for (theta, n) in states(&t, 400) {
        let at = t.at_state(n, theta);
        let full = AtN { eos: &t, n };
        let inv_tau = t.inv_tau(theta, t.cv(theta, n));
        let before = Before { theta, inv_tau, u: t.u(theta, n) };
        for k in 0..=12 {
            let du = 0.1 * t.cv(theta, n) * theta * (if k % 2 == 0 { 1.0 } else { -1.0 }) * 10f64.powi(-(k / 2));
            let u = before.u + du;
            let (want, _) = full.theta_inv_tau(u, theta);
            for keep in [true, false] {
                let [(got, got_inv_tau), other] = at.after_pair(&at, [before, before], [u, u], keep);
                assert_eq!(other.0.to_bits(), got.to_bits());
                if want.is_nan() {
                    assert!(got.is_nan(), "({theta}, {n}) u {u}: {got} outside the table");
                    continue;
                }
                worst_theta = worst_theta.max(rel(got, want));
                if keep {
                    worst_inv_tau = worst_inv_tau.max(rel(got_inv_tau, t.inv_tau(want, t.cv(want, n))));
                } else {
                    assert_eq!(got_inv_tau, 0.0);
                }
                in_cell += usize::from(at.in_cell_after(before, u, keep).is_some());
                count += 1;
            }
        }
    }
    eprintln!("{in_cell} of {count} refreshes in the cell at hand; worst theta {worst_theta:.1e}, 1/tau {worst_inv_tau:.1e}");
    assert!(worst_theta <= 2e-15 && worst_inv_tau <= 1e-14, "theta {worst_theta:e}, 1/tau {worst_inv_tau:e}");
    assert!(in_cell > count / 4 && in_cell < count, "{in_cell} of {count}");
}
