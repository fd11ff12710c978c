//! Property tests (proptest, default 256 cases or fewer per property):
//!
//! * EOS inversion: theta(u(theta, n), n, guess) == theta to 1e-10 relative for the
//!   linear-in-theta models (van der Waals excess and full, ideal gas), the
//!   Kolafa-Nezbeda Lennard-Jones fluid and a bicubic table of it, from several guesses;
//!   `state()` never panics and either errors or returns finite values with theta > 0.
//! * Pair update (eSSA, eq 87): total momentum and K + u_i + u_j are conserved to 1e-12
//!   relative to their scales over extreme states, for both heat laws; a state that
//!   overflows must show it (non-finite totals) rather than come back finite and wrong.
//!
//! Run with `cargo test --release --test it properties::`.
#![allow(clippy::approx_constant)] // 1.4142 is the vdW b of the 2019 paper, not sqrt 2

use std::sync::OnceLock;

use gendpde_engine::Vec3;
use gendpde_integrators::passes::heat::{Fourier, HeatFlow, Original, Temps};
use gendpde_integrators::passes::noise::{Arithmetic, Harmonic, Noise};
use gendpde_integrators::passes::pair_update::{pair_update, PairDrive, PairState};
use gendpde_potentials::{Eos, LennardJones, LinearTheta, TableGrid, Tabulated, ISOLATED_DENSITY};
use proptest::prelude::*;
use proptest::strategy::ValueTree;

// ---------------------------------------------------------------------------------------
// EOS inversion
// ---------------------------------------------------------------------------------------

/// vdW parameters of the 2019 paper's examples.
const A_VDW: f64 = 2.4682;
const B_VDW: f64 = 1.4142;

/// Relative tolerance of theta(u(theta, n), n, guess) == theta.
const INVERSION_TOL: f64 = 1e-10;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Asserts theta(u(theta, n), n, guess) == theta for the true guess, 1.0, a far one and
/// guesses no solver should trust (0, negative, NaN, infinite).
fn check_inversion(eos: &dyn Eos, theta: f64, n: f64, far: f64) -> Result<(), TestCaseError> {
    let u = eos.u(theta, n);
    prop_assert!(u.is_finite(), "u({theta}, {n}) = {u}");
    for guess in [theta, 1.0, far, 0.0, -1.0, f64::NAN, f64::INFINITY] {
        let back = eos.theta(u, n, guess);
        prop_assert!(
            rel(back, theta) <= INVERSION_TOL,
            "theta(u({theta:e}, {n:e}) = {u:e}, guess {guess:e}) = {back:e}, rel error {:e}",
            rel(back, theta)
        );
    }
    // The state at the same point recovers theta too, with finite pi/n^2 and C_V > 0
    // (below ISOLATED_DENSITY it is evaluated at that density instead, by design).
    if n < ISOLATED_DENSITY {
        return Ok(());
    }
    let st = eos.state(u, n, theta).map_err(|e| TestCaseError::fail(e.to_string()))?;
    prop_assert!(rel(st.theta, theta) <= INVERSION_TOL, "state theta {} vs {theta}", st.theta);
    prop_assert!(st.pn2.is_finite() && st.cv.is_finite() && st.cv > 0.0, "{st:?}");
    Ok(())
}

/// `state()` must not panic; an `Ok` must hold finite values with theta > 0.
fn check_state_sane(eos: &dyn Eos, u: f64, n: f64, guess: f64) -> Result<(), TestCaseError> {
    if let Ok(st) = eos.state(u, n, guess) {
        prop_assert!(
            st.theta > 0.0 && st.theta.is_finite() && st.pn2.is_finite() && st.cv.is_finite(),
            "state({u:e}, {n:e}, {guess:e}) = {st:?}"
        );
    }
    Ok(())
}

/// `state()` must not panic whatever its input; an `Ok` holds a finite theta > 0.
/// (pi/n^2 may come back inf or NaN at absurd states, n = 1e215 or n = NaN, for the
/// linear models: see `eos_state_pn2_overflows_at_absurd_density` and
/// `eos_state_accepts_nan_density`.)
fn check_state_no_panic(eos: &dyn Eos, u: f64, n: f64, guess: f64) -> Result<(), TestCaseError> {
    if let Ok(st) = eos.state(u, n, guess) {
        prop_assert!(
            st.theta > 0.0 && st.theta.is_finite(),
            "state({u:e}, {n:e}, {guess:e}) = {st:?}"
        );
    }
    Ok(())
}

/// Any f64 a corrupt state could hold: ordinary magnitudes of both signs, huge and tiny
/// ones, zeros and non-finite values.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -1e3..1e3f64,
        2 => (-300.0..300.0f64, any::<bool>()).prop_map(|(e, neg)| {
            let x = 10f64.powf(e);
            if neg { -x } else { x }
        }),
        1 => prop::sample::select(vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ]),
    ]
}

/// The LJ table of the property tests: theta in [0.5, 5], n in [0.05, 0.85].
const TABLE_GRID: TableGrid = TableGrid { theta: (0.5, 5.0, 31), n: (0.05, 0.85, 33) };

fn lj_table() -> &'static Tabulated<LennardJones> {
    static TABLE: OnceLock<Tabulated<LennardJones>> = OnceLock::new();
    TABLE.get_or_init(|| {
        Tabulated::new(LennardJones::new(60.0), TABLE_GRID).expect("LJ table over the test grid")
    })
}

/// Densities for vdW: the exact range and past the cap 0.95/b, up to 1.2/b.
fn vdw_density() -> impl Strategy<Value = f64> {
    prop_oneof![0.0..0.65f64, (0.95 / B_VDW)..(1.2 / B_VDW)]
}

proptest! {
    #[test]
    fn eos_vdw_excess_inverts(cv in 1.5..1000.0f64, theta in 0.05..20.0f64, n in vdw_density()) {
        check_inversion(&LinearTheta::vdw_excess(cv, A_VDW, B_VDW), theta, n, 1e4)?;
    }

    #[test]
    fn eos_vdw_full_inverts(cv in 1.5..1000.0f64, theta in 0.05..20.0f64, n in vdw_density()) {
        check_inversion(&LinearTheta::vdw_full(cv, A_VDW, B_VDW), theta, n, 1e4)?;
    }

    #[test]
    fn eos_ideal_inverts(cv in 1.5..1000.0f64, theta in 0.05..20.0f64, n in 0.0..0.65f64) {
        check_inversion(&LinearTheta::ideal(cv), theta, n, 1e4)?;
    }

    #[test]
    fn eos_lennard_jones_inverts(cv in 1.5..1000.0f64, theta in 0.5..10.0f64, n in 0.01..1.2f64) {
        let lj = LennardJones::new(cv);
        prop_assert!(LennardJones::in_domain(theta, n));
        check_inversion(&lj, theta, n, LennardJones::THETA_MAX)?;
        check_inversion(&lj, theta, n, LennardJones::THETA_MIN)?;
    }

    #[test]
    fn eos_lj_table_inverts(theta in 0.5..5.0f64, n in 0.05..0.85f64) {
        let table = lj_table();
        check_inversion(table, theta, n, 1e3)?;
        // the grid's end points exactly
        for t in [TABLE_GRID.theta.0, TABLE_GRID.theta.1] {
            check_inversion(table, t, n, 1e3)?;
        }
    }

    #[test]
    fn eos_state_never_panics(
        cv in 1.5..1000.0f64,
        u in wild(),
        n in wild(),
        guess in wild(),
    ) {
        check_state_no_panic(&LinearTheta::vdw_excess(cv, A_VDW, B_VDW), u, n, guess)?;
        check_state_no_panic(&LinearTheta::vdw_full(cv, A_VDW, B_VDW), u, n, guess)?;
        check_state_no_panic(&LinearTheta::ideal(cv), u, n, guess)?;
        check_state_no_panic(&LennardJones::new(cv), u, n, guess)?;
        check_state_no_panic(lj_table(), u, n, guess)?;
        // Inside the models' domains (any u, n in [0, 1.2/b]) every Ok is finite.
        if (0.0..=1.2 / B_VDW).contains(&n) && u.abs() <= 1e100 {
            check_state_sane(&LinearTheta::vdw_excess(cv, A_VDW, B_VDW), u, n, guess)?;
            check_state_sane(&LinearTheta::vdw_full(cv, A_VDW, B_VDW), u, n, guess)?;
            check_state_sane(&LinearTheta::ideal(cv), u, n, guess)?;
        }
        check_state_sane(&LennardJones::new(cv), u, n, guess)?;
        check_state_sane(lj_table(), u, n, guess)?;
    }

    /// States near the physical ones, where an error is the exception.
    #[test]
    fn eos_state_sane_near_physical_states(
        cv in 1.5..1000.0f64,
        theta in 0.05..20.0f64,
        n in 0.0..1.5f64,
        du in -10.0..10.0f64,
        guess in 0.0..30.0f64,
    ) {
        let vdw = LinearTheta::vdw_excess(cv, A_VDW, B_VDW);
        check_state_sane(&vdw, vdw.u(theta, n) + du, n, guess)?;
        let full = LinearTheta::vdw_full(cv, A_VDW, B_VDW);
        check_state_sane(&full, full.u(theta, n) + du, n, guess)?;
        let lj = LennardJones::new(cv);
        let t = theta.clamp(0.5, 10.0);
        check_state_sane(&lj, lj.u(t, n) + du, n, guess)?;
        let table = lj_table();
        let (t, m) = (theta.clamp(0.5, 5.0), n.clamp(0.05, 0.85));
        check_state_sane(table, table.u(t, m) + du, n, guess)?;
    }
}

/// Finding (potentials/src/eos/linear.rs, fixed in `Eos::state`): at an absurd density far past
/// the cap the Taylor continuation times theta overflows and `state()` returns `Ok` with
/// pi/n^2 = inf instead of an error. Minimal case found by `eos_state_never_panics`.
#[test]
fn eos_state_pn2_overflows_at_absurd_density() {
    let vdw = LinearTheta::vdw_excess(1.5, A_VDW, B_VDW);
    let st = vdw.state(0.0, 1.4140151202674355e215, 0.0);
    assert!(st.is_err() || st.as_ref().is_ok_and(|s| s.pn2.is_finite()), "{st:?}");
}

/// Finding (potentials/src/eos/mod.rs, `Eos::state`, fixed): a NaN density is
/// not rejected (`NaN < ISOLATED_DENSITY` is false) and the ideal gas, whose theta does
/// not read n, returns `Ok` with pi/n^2 = NaN. Minimal case of `eos_state_never_panics`.
#[test]
fn eos_state_accepts_nan_density() {
    let st = LinearTheta::ideal(1.5).state(919.7892251464189, f64::NAN, 0.0);
    assert!(st.is_err() || st.as_ref().is_ok_and(|s| s.pn2.is_finite()), "{st:?}");
}

// ---------------------------------------------------------------------------------------
// Pair update conservation
// ---------------------------------------------------------------------------------------

/// Relative tolerance of momentum and energy conservation.
const CONSERVATION_TOL: f64 = 1e-12;

/// A value of magnitude 10^[lo, hi] with a random sign.
fn signed_log(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi, any::<bool>()).prop_map(|(e, neg)| {
        let x = 10f64.powf(e);
        if neg {
            -x
        } else {
            x
        }
    })
}

fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.log10()..hi.log10()).prop_map(|e| 10f64.powf(e))
}

/// A momentum with components of magnitude 10^[lo, hi] (or exactly zero).
fn momentum(lo: f64, hi: f64) -> impl Strategy<Value = Vec3> {
    let c = prop_oneof![9 => signed_log(lo, hi), 1 => Just(0.0)];
    [c.clone(), c.clone(), c]
}

/// A unit vector (the pair direction e_ij).
fn unit() -> impl Strategy<Value = Vec3> {
    [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64]
        .prop_filter("direction too short to normalise", |v| dot(*v, *v) > 1e-6)
        .prop_map(|v| {
            let n = dot(v, v).sqrt();
            [v[0] / n, v[1] / n, v[2] / n]
        })
}

/// Particle temperatures: theta and 1/tau = (1 - k_B/C_V)/theta (eqs 19, 23).
fn temps() -> impl Strategy<Value = Temps> {
    (log_uniform(1e-4, 1e4), 1.5..1000.0f64)
        .prop_map(|(theta, cv)| Temps { theta, inv_tau: (1.0 - 1.0 / cv) / theta })
}

/// gamma and kappa: zero (the kernel cut-off) or up to 1e4.
fn coefficient() -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 3 => 0.0..1e4f64, 3 => log_uniform(1e-6, 1e4)]
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

#[derive(Clone, Debug)]
struct Case {
    p_i: Vec3,
    p_j: Vec3,
    u_i: f64,
    u_j: f64,
    m_i: f64,
    m_j: f64,
    drive: PairDrive,
    dt: f64,
}

fn case(p_lo: f64, p_hi: f64) -> impl Strategy<Value = Case> {
    let drive = (unit(), coefficient(), coefficient(), temps(), temps(), -8.0..8.0f64, -8.0..8.0f64)
        .prop_map(|(e, gamma, kappa, ti, tj, xi, xibar)| PairDrive { e, gamma, kappa, ti, tj, xi, xibar });
    (
        momentum(p_lo, p_hi),
        momentum(p_lo, p_hi),
        signed_log(-3.0, 6.0),
        signed_log(-3.0, 6.0),
        log_uniform(1e-3, 1e3),
        log_uniform(1e-3, 1e3),
        drive,
        log_uniform(1e-5, 1.0),
    )
        .prop_map(|(p_i, p_j, u_i, u_j, m_i, m_j, drive, dt)| Case { p_i, p_j, u_i, u_j, m_i, m_j, drive, dt })
}

/// |a| of the first kick of eq 87 (explicit half step plus noise), from the inputs.
fn explicit_impulse(c: &Case) -> f64 {
    let d = &c.drive;
    if d.gamma <= 0.0 {
        return 0.0;
    }
    let v: Vec3 = std::array::from_fn(|k| c.p_i[k] / c.m_i - c.p_j[k] / c.m_j);
    let sigma = (d.gamma * (d.ti.theta + d.tj.theta)).sqrt();
    0.5 * c.dt * d.gamma * dot(v, d.e).abs() + 0.5 * c.dt.sqrt() * sigma * d.xi.abs()
}

/// Outcome of one checked update.
#[derive(Debug, PartialEq)]
enum Outcome {
    Conserved,
    NonFinite,
}

/// Runs one pair update and checks conservation (see the module doc).
fn check_pair_update<H: HeatFlow, N: Noise>(c: &Case) -> Result<Outcome, TestCaseError> {
    let (mut p_i, mut p_j, mut u_i, mut u_j) = (c.p_i, c.p_j, c.u_i, c.u_j);
    let (inv_m_i, inv_m_j) = (1.0 / c.m_i, 1.0 / c.m_j);
    let kinetic = |p_i: Vec3, p_j: Vec3| 0.5 * (dot(p_i, p_i) * inv_m_i + dot(p_j, p_j) * inv_m_j);
    let k_before = kinetic(p_i, p_j);
    let s = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i, inv_m_j };
    let deltas = pair_update::<H, N>(s, &c.drive, 1.0, c.dt, c.dt.sqrt());
    let k_after = kinetic(p_i, p_j);

    let total_p = |a: Vec3, b: Vec3| [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
    let (p_before, p_after) = (total_p(c.p_i, c.p_j), total_p(p_i, p_j));
    let e_before = k_before + c.u_i + c.u_j;
    let e_after = k_after + u_i + u_j;

    let outputs_finite =
        p_i.iter().chain(&p_j).all(|x| x.is_finite()) && u_i.is_finite() && u_j.is_finite();
    if !outputs_finite || !k_after.is_finite() {
        // An overflow must be visible in the conserved totals, not hidden by a
        // finite-looking state.
        let totals_finite = p_after.iter().all(|x| x.is_finite()) && e_after.is_finite();
        prop_assert!(
            !totals_finite || !k_after.is_finite(),
            "non-finite state with finite totals: p_i {p_i:?} p_j {p_j:?} u {u_i:e} {u_j:e}"
        );
        return Ok(Outcome::NonFinite);
    }
    prop_assert!(deltas.heat.is_finite() && deltas.half_dk.is_finite(), "{deltas:?}");

    // The momentum scale: the momenta before and after and, as the update moves momentum
    // through two opposite kicks, the impulse of its explicit (velocity-Verlet) half step,
    // 0.5 dt gamma |v_ij . e| + the noise half-kick. In the stiff corner
    // (0.5 gamma dt (1/m_i + 1/m_j) >> 1) that impulse is far larger than the momenta and
    // sets the round-off: see `pair_update_stiff_momentum_strict`.
    let p_scale = norm(c.p_i) + norm(c.p_j) + norm(p_i) + norm(p_j) + explicit_impulse(c);
    for k in 0..3 {
        let err = (p_after[k] - p_before[k]).abs();
        prop_assert!(
            err <= CONSERVATION_TOL * p_scale,
            "momentum[{k}] {:e} -> {:e}: error {err:e} vs scale {p_scale:e}",
            p_before[k],
            p_after[k]
        );
    }
    let e_scale = k_before
        + k_after
        + c.u_i.abs()
        + c.u_j.abs()
        + u_i.abs()
        + u_j.abs()
        + 2.0 * deltas.heat.abs();
    let err = (e_after - e_before).abs();
    prop_assert!(
        err <= CONSERVATION_TOL * e_scale,
        "K + u {e_before:e} -> {e_after:e}: error {err:e} vs scale {e_scale:e} ({deltas:?})"
    );
    Ok(Outcome::Conserved)
}

proptest! {
    #[test]
    fn pair_update_conserves_original(c in case(-6.0, 6.0)) {
        check_pair_update::<Original, Arithmetic>(&c)?;
    }

    #[test]
    fn pair_update_conserves_fourier(c in case(-6.0, 6.0)) {
        check_pair_update::<Fourier, Arithmetic>(&c)?;
    }

    /// The harmonic noise form (fix shardlow noise harmonic) with either heat law.
    #[test]
    fn pair_update_conserves_harmonic_noise(c in case(-6.0, 6.0)) {
        check_pair_update::<Original, Harmonic>(&c)?;
        check_pair_update::<Fourier, Harmonic>(&c)?;
    }

    /// Momenta far beyond any simulation (up to 1e200, so K overflows): the update either
    /// conserves or its result is visibly non-finite.
    #[test]
    fn pair_update_overflow_is_visible(c in case(-6.0, 200.0)) {
        check_pair_update::<Original, Arithmetic>(&c)?;
        check_pair_update::<Fourier, Arithmetic>(&c)?;
    }
}

/// Within the brief's ranges nothing overflows: every update conserves exactly.
#[test]
fn pair_update_in_range_states_stay_finite() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = case(-6.0, 6.0);
    for _ in 0..256 {
        let c = strategy.new_tree(&mut runner).unwrap().current();
        assert_eq!(check_pair_update::<Original, Arithmetic>(&c).unwrap(), Outcome::Conserved, "{c:?}");
        assert_eq!(check_pair_update::<Fourier, Arithmetic>(&c).unwrap(), Outcome::Conserved, "{c:?}");
    }
}

/// Finding (integrators/src/pair_update.rs, fixed by folding the two kicks): with 0.5 gamma dt (1/m_i +
/// 1/m_j) >> 1 the explicit half step kicks the pair by ~1e6 and the implicit one kicks
/// it back, so total momentum is conserved only to round-off of that intermediate kick,
/// 7e-12 relative to the momenta here (minimal case of `pair_update_conserves_original`).
/// Applying the two kicks as one (a + b, with the velocity after the first kick computed
/// as v + (1/m_i + 1/m_j) a) would conserve it to round-off of the momenta.
#[test]
fn pair_update_stiff_momentum_strict() {
    let t = Temps { theta: 1.0, inv_tau: 1.0 / 3.0 };
    let (mut p_i, mut p_j) = ([1.255865066831282e-4, 2.5583378740279114e-5, 5.12814983936212e-3], [9.45010378026018e-3, 1.0, -1.0]);
    let (before_i, before_j) = (p_i, p_j);
    let (mut u_i, mut u_j) = (1.0, 1.0);
    let drive = PairDrive { e: [0.0, 0.0, -1.0], gamma: 8892.599973432598, kappa: 0.0, ti: t, tj: t, xi: 0.0, xibar: 0.0 };
    let s = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i: 1.0, inv_m_j: 1.0 / 0.004051844860422516 };
    pair_update::<Original, Arithmetic>(s, &drive, 1.0, 1.0, 1.0);
    let scale = norm(before_i) + norm(before_j) + norm(p_i) + norm(p_j);
    for k in 0..3 {
        let err = ((p_i[k] + p_j[k]) - (before_i[k] + before_j[k])).abs();
        assert!(err <= CONSERVATION_TOL * scale, "momentum[{k}]: error {err:e}, scale {scale:e}");
    }
}

/// A momentum whose kinetic energy overflows is reported as non-finite.
#[test]
fn pair_update_overflow_example() {
    let e = [1.0, 0.0, 0.0];
    let t = Temps { theta: 1.0, inv_tau: 0.5 };
    let c = Case {
        p_i: [1e200, 0.0, 0.0],
        p_j: [-1e200, 0.0, 0.0],
        u_i: 1.0,
        u_j: 1.0,
        m_i: 1.0,
        m_j: 1.0,
        drive: PairDrive { e, gamma: 10.0, kappa: 1.0, ti: t, tj: t, xi: 1.0, xibar: 1.0 },
        dt: 0.01,
    };
    assert_eq!(check_pair_update::<Original, Arithmetic>(&c).unwrap(), Outcome::NonFinite);
}
