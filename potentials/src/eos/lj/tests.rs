use super::super::EosError;
use super::*;

fn grid() -> Vec<(f64, f64)> {
    let mut g = Vec::new();
    for i in 0..=9 {
        let theta = 0.5 * (10.0f64).powf(i as f64 / 9.0); // 0.5 .. 5, log-spaced
        for k in 0..=17 {
            g.push((theta, 0.05 + 0.05 * k as f64)); // 0.05 .. 0.9
        }
    }
    g
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// SPEC sec 3 check values (Kolafa's published code): agreement to ~1e-5 relative.
#[test]
fn kolafa_nezbeda_check_values() {
    let m = LennardJones::new(60.0);
    let checks = [
        ("U/N(1.3, 0.2)", m.u_res(1.3, 0.2), -1.5371511277396868),
        ("U/N(1.3, 0.4)", m.u_res(1.3, 0.4), -2.806016725054152),
        ("P(1.3, 0.2)", m.pressure(1.3, 0.2), 0.12147936810578708),
        ("P(1.3, 0.4)", m.pressure(1.3, 0.4), 0.11253334756806482),
    ];
    for (name, got, want) in checks {
        let r = (got - want) / want;
        eprintln!("{name}: {got:.16} vs {want:.16}, relative deviation {r:+.3e}");
        assert!(r.abs() < 1e-5, "{name}: {got} vs {want}");
    }
    // independent evaluation quoted in SPEC
    assert!((m.u_res(1.3, 0.2) + 1.5371513).abs() < 1e-7);
    assert!((m.pressure(1.3, 0.4) - 0.1125328).abs() < 1e-7);
}

/// d^2 f_res/dtheta^2 from the full jet.
fn ftt(theta: f64, n: f64) -> f64 {
    LennardJones::f_res_jet(Jet::var_t(theta), Jet::var_n(n)).tt
}

/// The closed-form evaluation at a fixed density agrees with the full jet to round-off
/// (u, C_V), and its dC_V/dtheta with a finite difference of C_V.
#[test]
fn fixed_density_evaluation_is_the_full_one() {
    let m = LennardJones::new(60.0);
    let mut worst = [0.0f64; 3];
    for (theta, n) in grid() {
        let r = LennardJones::eval(theta, n);
        let at = m.at_density(n);
        let e = at.eval(theta);
        let fd_dcv = d1(|t| at.eval(t).cv, theta, 1e-3 * theta);
        let devs = [
            rel(e.u, m.cv * theta + r.f - theta * r.ft),
            rel(e.cv, m.cv - theta * ftt(theta, n)),
            (e.dcv - fd_dcv).abs() / fd_dcv.abs().max(1e-3),
        ];
        for (w, d) in worst.iter_mut().zip(devs) {
            *w = w.max(d);
        }
        assert!((e.eta - LennardJones::packing_fraction(theta, n)).abs() < 1e-15, "eta at ({theta}, {n})");
    }
    eprintln!("worst relative deviation of u, C_V from the full jet, dC_V/dtheta from FD: {:.2e} {:.2e} {:.2e}", worst[0], worst[1], worst[2]);
    assert!(worst[0] < 1e-14 && worst[1] < 1e-14 && worst[2] < 1e-8, "{worst:?}");
}

/// Evaluations of one [`LjAt::solve`], replayed through its state machine.
fn evaluations(at: &LjAt, u: f64, guess: f64) -> usize {
    let Ok(mut s) = Newton::new(at, u, guess) else { return 0 };
    let mut count = 1;
    while s.take(at.eval(s.x)).is_none() {
        count += 1;
    }
    count
}

/// theta, C_V and 1/tau after the stop on the predicted error, against Newton run until
/// its step is below 1e-16 relative, over refreshes like the sweep's: u moved from a
/// state at theta by up to 3 % of C_V theta, from the old theta and from the sweep's
/// first-order guess ([`AtDensity::guess_after`]).
#[test]
fn predicted_stop_agrees_with_the_converged_solve() {
    let mut worst = [0.0f64; 3];
    let mut evals = [0usize; 2];
    let mut solves = 0;
    for cv in [1.5, 60.0] {
        let m = LennardJones::new(cv);
        for (theta, n) in grid() {
            let at = m.at_density(n);
            let inv_tau = |t: f64, c: f64| (1.0 - 1.0 / c) / t;
            let tau0 = inv_tau(theta, m.cv(theta, n));
            for k in 0..=16 {
                let du = 0.03 * cv * theta * (if k % 2 == 0 { 1.0 } else { -1.0 }) * 10f64.powi(-(k / 2));
                let u = m.u(theta, n) + du;
                let guesses = [theta, at.guess_after(theta, tau0, du)];
                for (e, guess) in evals.iter_mut().zip(guesses) {
                    *e += evaluations(&at, u, guess);
                }
                solves += 1;
                let (mut x, mut cx) = (theta, 0.0);
                for _ in 0..20 {
                    let Eval { u: ux, cv: cvx, .. } = at.eval(x);
                    let step = (ux - u) / cvx;
                    (x, cx) = (x - step, cvx);
                    if step.abs() <= 1e-16 * x {
                        break;
                    }
                }
                for guess in guesses {
                    let (t, c) = at.solve(u, guess);
                    for (w, e) in worst.iter_mut().zip([rel(t, x), rel(c, cx), rel(inv_tau(t, c), inv_tau(x, cx))]) {
                        *w = w.max(e);
                    }
                }
            }
        }
    }
    let per = evals.map(|e| e as f64 / solves as f64);
    eprintln!("evaluations per solve from the old theta {:.3}, from the first-order guess {:.3}", per[0], per[1]);
    eprintln!("worst relative deviation of theta, C_V, 1/tau from the converged solve: {:.2e} {:.2e} {:.2e}", worst[0], worst[1], worst[2]);
    // theta to round-off; C_V (so 1/tau) carried along dC_V/dtheta, whose error is
    // ~ C_V'' step^2 / 2
    assert!(worst[0] < 1e-14 && worst[1] < 1e-13 && worst[2] < 1e-13, "{worst:?}");
    assert!(per[1] < per[0], "{per:?}");
}

/// The interleaved solves of two particles give the bits of two single solves, over
/// sweep-like refreshes paired with each other (solves of different lengths), without a
/// guess, and with input no solve accepts.
#[test]
fn paired_solves_are_the_single_solves() {
    let m = LennardJones::new(60.0);
    let mut cases = Vec::new();
    for (theta, n) in grid() {
        for k in 0..=8 {
            let du = 0.03 * m.cv * theta * (if k % 2 == 0 { 1.0 } else { -1.0 }) * 10f64.powi(-(k / 2));
            let guess = if k == 8 { f64::NAN } else { theta };
            cases.push((m.at_density(n), m.u(theta, n) + du, guess));
        }
    }
    cases.push((m.at_density(0.5), f64::NAN, 1.0));
    cases.push((m.at_density(0.5), -1e9, 1.0));
    cases.push((m.at_density(0.5), 1e9, 1.0));
    cases.push((m.at_density(7.0), 1.0, 1.0));
    let bits = |r: [(f64, f64); 2]| r.map(|(t, c)| (t.to_bits(), c.to_bits()));
    for (a, b) in cases.iter().zip(cases.iter().rev().chain(cases.iter().skip(7))) {
        let single = [a.0.solve(a.1, a.2), b.0.solve(b.1, b.2)];
        let paired = LjAt::solve_pair([&a.0, &b.0], [a.1, b.1], [a.2, b.2]);
        assert_eq!(bits(paired), bits(single), "u {} and {}", a.1, b.1);
        let (x, y) = (a.0.theta_inv_tau(a.1, a.2), b.0.theta_inv_tau(b.1, b.2));
        let pair = a.0.theta_inv_tau_pair(&b.0, [a.1, b.1], [a.2, b.2]);
        assert_eq!(bits(pair), bits([x, y]));
    }
}

/// Central five-point first derivative, error O(h^4).
fn d1(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    (8.0 * (f(x + h) - f(x - h)) - (f(x + 2.0 * h) - f(x - 2.0 * h))) / (12.0 * h)
}

#[test]
fn derivatives_match_finite_differences() {
    let m = LennardJones::new(1.5);
    let close = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * b.abs().max(1.0);
    let mut worst = [0.0f64; 4];
    for (theta, n) in grid() {
        let r = LennardJones::eval(theta, n);
        assert_eq!(r.f, m.f_res(theta, n));
        let (ht, hn) = (1e-3 * theta, 3e-4);
        let fd_t = d1(|t| m.f_res(t, n), theta, ht);
        let fd_tt = d1(|t| LennardJones::eval(t, n).ft, theta, ht);
        let fd_n = d1(|x| m.f_res(theta, x), n, hn);
        let fd_cv = d1(|t| m.u(t, n), theta, ht);
        let fd_s = -d1(|t| m.f_res(t, n) - m.cv * t * (t.ln() - 1.0), theta, ht);
        for (w, (a, b)) in worst.iter_mut().zip([
            (r.ft, fd_t),
            (ftt(theta, n), fd_tt),
            (r.fn_, fd_n),
            (m.cv(theta, n), fd_cv),
        ]) {
            *w = w.max((a - b).abs() / b.abs().max(1.0));
        }
        assert!(close(r.ft, fd_t, 1e-9), "f_t at ({theta}, {n}): {} vs {fd_t}", r.ft);
        assert!(close(ftt(theta, n), fd_tt, 1e-9), "f_tt at ({theta}, {n}): {} vs {fd_tt}", ftt(theta, n));
        assert!(close(r.fn_, fd_n, 1e-9), "f_n at ({theta}, {n}): {} vs {fd_n}", r.fn_);
        assert_eq!(m.pn2(theta, n), r.fn_);
        assert!(close(m.cv(theta, n), fd_cv, 1e-9), "cv at ({theta}, {n})");
        assert!(close(m.pressure(theta, n), n * theta + n * n * fd_n, 1e-9));
        assert!(close(m.u_res(theta, n), r.f - theta * fd_t, 1e-9));
        // entropy s = -df/dtheta of the full particle free energy
        let s = m.entropy(m.u(theta, n), n).unwrap();
        assert!(close(s, fd_s, 1e-9), "s at ({theta}, {n}): {s} vs {fd_s}");
    }
    eprintln!("worst relative FD deviation of f_t, f_tt, f_n, C_V: {worst:?}");
}

#[test]
fn theta_inverts_u_from_any_guess() {
    for cv in [1.5, 60.0] {
        let m = LennardJones::new(cv);
        for (theta, n) in grid() {
            let u = m.u(theta, n);
            for guess in [theta, 1.0, 0.0, -1.0, f64::NAN, f64::INFINITY, 1e3, 1e-9] {
                let t = m.theta(u, n, guess);
                assert!(rel(t, theta) < 1e-12, "cv {cv} ({theta}, {n}) guess {guess}: {t}");
            }
            let st = m.state(u, n, theta).unwrap();
            assert!(rel(st.theta, theta) < 1e-12);
            assert_eq!(st.pn2, m.pn2(st.theta, n));
            assert!(st.cv > 1.0);
        }
    }
}

#[test]
fn theta_solve_covers_the_domain() {
    let m = LennardJones::new(1.5);
    for &n in &[0.0, 1e-6, 0.01, 0.3, 0.8, 1.2, 1.5] {
        for k in 0..=60 {
            let theta = 1e-3 * (10.0f64).powf(k as f64 / 10.0);
            if !LennardJones::in_domain(theta, n) {
                continue;
            }
            let u = m.u(theta, n);
            assert!(m.cv(theta, n) > 0.0, "C_V <= 0 at ({theta}, {n})");
            for guess in [f64::NAN, 1.0, 1e3, 1e-3] {
                let t = m.theta(u, n, guess);
                assert!(rel(t, theta) < 1e-12, "({theta}, {n}) guess {guess}: {t}");
            }
        }
    }
}

/// u(s, n) at fixed s: solve C_V ln theta - f_res,theta(theta, n) = s for theta.
fn u_at_entropy(m: &LennardJones, s: f64, n: f64, mut theta: f64) -> f64 {
    for _ in 0..100 {
        let r = LennardJones::eval(theta, n);
        let g = m.cv * theta.ln() - r.ft - s;
        let step = g / (m.cv / theta - ftt(theta, n)); // ds/dtheta = C_V(theta, n)/theta
        theta -= step;
        if step.abs() < 1e-15 * theta {
            break;
        }
    }
    m.u(theta, n)
}

#[test]
fn particle_pressure_is_du_dn_at_fixed_entropy() {
    let m = LennardJones::new(1.5);
    for (theta, n) in grid() {
        let u = m.u(theta, n);
        let s = m.entropy(u, n).unwrap();
        assert!((u_at_entropy(&m, s, n, theta) - u).abs() < 1e-12 * u.abs().max(1.0));
        let h = 1e-5;
        let fd =
            (u_at_entropy(&m, s, n + h, theta) - u_at_entropy(&m, s, n - h, theta)) / (2.0 * h);
        let pn2 = m.pn2(theta, n);
        assert!((fd - pn2).abs() < 1e-7 * pn2.abs().max(1.0), "({theta}, {n}): {fd} vs {pn2}");
        // theta = du/ds at fixed n (eq 6)
        let hs = 1e-5;
        let ts = (u_at_entropy(&m, s + hs, n, theta) - u_at_entropy(&m, s - hs, n, theta))
            / (2.0 * hs);
        assert!(rel(ts, theta) < 1e-7, "({theta}, {n}): du/ds {ts}");
    }
}

#[test]
fn states_outside_the_domain_are_errors() {
    let m = LennardJones::new(1.5);
    let n = 0.5;
    // below the ground state (u at the floor of the domain)
    for u in [-1e12, -1e300, f64::MIN] {
        let e = m.state(u, n, 1.0);
        assert!(matches!(e, Err(EosError::NonPositiveTheta { .. })), "{e:?}");
        assert_eq!(m.theta(u, n, 1.0), 0.0);
        assert!(m.entropy(u, n).is_none());
    }
    // hotter than THETA_MAX, NaN, or denser than the domain at any theta
    assert!(m.state(1e9, n, 1.0).is_err());
    assert_eq!(m.theta(1e9, n, 1.0), f64::INFINITY);
    assert!(m.state(f64::NAN, n, 1.0).is_err());
    assert!(m.state(f64::INFINITY, n, 1.0).is_err());
    assert!(m.state(10.0, f64::NAN, 1.0).is_err());
    assert!(m.state(10.0, 10.0, 1.0).is_err());
    assert!(m.theta(10.0, -1.0, 1.0).is_nan());
    // just inside and just outside the edges
    let lo = LennardJones::THETA_MIN;
    let u_lo = m.u(lo, 1e-6);
    assert!(u_lo < 0.0);
    let above = m.state(u_lo + 1e-9 * u_lo.abs(), 1e-6, 1.0).unwrap();
    assert!(above.theta >= lo && above.theta < lo * (1.0 + 1e-6));
    assert_eq!(m.theta(u_lo - 1e-6 * u_lo.abs(), 1e-6, 1.0), 0.0);
    assert!(m.theta(10.0, 10.0, 1.0).is_nan());
}

#[test]
fn isolated_particles_feel_no_pressure() {
    let m = LennardJones::new(60.0);
    let st = m.state(90.0, 0.0, 1.5).unwrap();
    assert_eq!(st.pn2, 0.0);
    assert!(rel(st.theta, 1.5) < 1e-6);
    assert!(rel(m.u(st.theta, ISOLATED), 90.0) < 1e-14);
    assert!(m.density_dependent());
    assert_eq!(m.kb(), 1.0);
}

use super::super::ISOLATED_DENSITY as ISOLATED;
