//! The Shardlow sweep (eq 82): every pair within the cutoff in colour order, theta
//! (and 1/tau) of i and j refreshed from the EOS after each pair; then the reservoir.
//!
//! Between colours the ghosts written in the colour return their values to their
//! owners, and the particles the colour touched forward their new values to their ghosts
//! (docs/models/sweep.md).
//!
//! theta -> 0: a pair update that would leave a particle temperature non-positive (or
//! non-finite) is undone and redone as two half steps whose noises split the step's
//! Wiener increments by a Brownian bridge (dW_1,2 = dW/2 +- sqrt(dt)/2 eta, eta a fresh
//! counter-based normal), recursively up to `Dissipation::substeps` levels. Each split
//! conserves momentum and energy like a full update. A pair that still fails stops the
//! run, or with `Dissipation::reject` is left unchanged for this step (counted; like a
//! Metropolis rejection of a move outside the domain, it keeps p and K + u exact but
//! biases the dynamics at the rare states it touches).

use crate::error::{lowest, StepError};
use crate::passes::heat::{HeatFlow, Temps};
use crate::passes::noise::Noise;
use crate::passes::pair_update::{pair_update, PairDrive, PairState};
use crate::rng::{normal_pair, stream, Normals, LANES};
use crate::passes::dissipation::{Dissipation, Reservoir};
use crate::passes::species::Species;
use crate::simd::avx2_fn;
use crate::system::System;
use crate::passes::many_body::density_of;
use gendpde_engine::{exact_sums, Fields, Particles, Vec3};
use gendpde_potentials::{AtDensity, Before, Eos, EosError, FixedDensity, ISOLATED_DENSITY};

/// Fields the sweep writes, exchanged between colours.
pub const SWEPT: Fields = Fields::MOMENTUM.union(Fields::ENERGY).union(Fields::THETA).union(Fields::INV_TAU);

avx2_fn! {
    /// One full sweep over all pairs of all colours. A pair update that fails is undone:
    /// left out under `reject`, else reported after the sweep (the failure of lowest tag:
    /// the pairs after it see the same states on any rank count). Built for AVX2 where
    /// the processor has it ([`avx2_fn`]: 3-operand instructions, fewer register copies).
    pub fn sweep<E: FixedDensity, H: HeatFlow, N: Noise>(eos: &Species<E>, d: &Dissipation, sys: &mut System, dt: f64) -> Result<(), StepError> {
        let kb = eos.kb();
        let rc = d.cutoff();
        let (inv_rcd, inv_rch) = (1.0 / d.rc_friction, 1.0 / d.rc_heat);
        let gamma = d.gamma * d.noise.scale();
        let (step, key, normals) = (sys.clock.step, sys.noise_step(sys.clock.step), Normals::get());
        sys.take_inverse_masses();
        let inv_m = &sys.scratch.inv_mass;
        // each particle's EOS at its density, which the sweep does not change
        let at: Vec<E::At<'_>> = (0..sys.store.mass.len()).map(|i| at_density(eos, &sys.store, i)).collect();
        let mut outcome = Ok(());
        let mut failures = Vec::new();
        let keys = Keys { seed: d.seed, key, kb };
        for colour in 0..sys.sweep.colours() {
            let (pairs, displacement) = sys.sweep.within_displaced(colour, &sys.store, rc);
            let mut v = Swept::new::<H, N>(&mut sys.store, &at, inv_m);
            // the pairs' noises a block of LANES ahead, their Philox blocks side by side: the
            // keys (step, tags) do not change during the sweep
            for (block, displaced) in pairs.chunks(LANES).zip(displacement.chunks(LANES)) {
                let last = block.len() - 1;
                let ends: [(Idx, Idx); LANES] = std::array::from_fn(|l| v.pair(block[l.min(last)]));
                let tags = ends.map(|(i, j)| (v.tag(i), v.tag(j)));
                let noises = normals.pairs(d.seed, key, tags, stream::PAIR);
                for ((&(i, j), &(xi, xibar)), &[dx, dy, dz, r2]) in ends.iter().zip(&noises).zip(displaced) {
                    let r = r2.sqrt();
                    let wd = (1.0 - r * inv_rcd).max(0.0);
                    let wh = (1.0 - r * inv_rch).max(0.0);
                    let inv_r = 1.0 / r;
                    let pair = Pair {
                        i,
                        j,
                        e: [dx * inv_r, dy * inv_r, dz * inv_r],
                        inv_m: (v.inv_m(i), v.inv_m(j)),
                        gamma: gamma * wd * wd,
                        kappa: d.kappa * wh * wh,
                    };
                    if let Err(failed) = pair_step::<_, H, N>(&mut v, &keys, pair, xi, xibar, dt, 0, d.substeps, &mut sys.control.substeps) {
                        sys.control.rejected += d.reject as u64;
                        if !d.reject {
                            failures.push(failed);
                        }
                    }
                }
            }
            for failed in failures.drain(..) {
                outcome = lowest(outcome, Err(failed.error(eos, &sys.store, step)));
            }
            sys.comm.after_colour(&mut sys.store, &sys.sweep, colour, SWEPT);
        }
        outcome
    }
}

/// The EOS of particle `i` at its density (raised to the isolated floor).
#[inline]
fn at_density<'a, E: FixedDensity>(eos: &'a Species<E>, s: &Particles, i: usize) -> E::At<'a> {
    eos.of(s.kind[i]).at_state(density_of(s, i).max(ISOLATED_DENSITY), s.theta[i])
}

/// Heat exchange of the owned particles of the reservoir's group with the bath (2019
/// eq 72; the Fourier form after 2021 eq 62), then a forward exchange of the new values.
/// The energy put in, summed exactly over all particles (the same on every rank count),
/// is added to the reservoir's tally.
pub fn reservoir<E: FixedDensity, H: HeatFlow, N: Noise>(eos: &Species<E>, res: &Reservoir, sys: &mut System, dt: f64) -> Result<(), StepError> {
    let kb = eos.kb();
    let sqrt_dt = dt.sqrt();
    let (step, key) = (sys.clock.step, sys.noise_step(sys.clock.step));
    let s = &mut sys.store;
    let mut outcome = Ok(());
    let mut added = Vec::new();
    for i in 0..s.nlocal {
        if !s.in_group(i, res.mask) {
            continue;
        }
        let (q, alpha) = H::reservoir(kb, res.kappa, temps::<H, N>(s, i), res.temperature);
        let xi = normal_pair(res.seed, key, s.tag[i], 0, stream::RESERVOIR).0;
        let du = dt * q + sqrt_dt * alpha * xi;
        s.u[i] += du;
        added.push([du]);
        match refresh::<_, H, N>(&at_density(eos, s, i), i, s.p[i], s.u[i], s.theta[i]) {
            Ok(end) => {
                s.theta[i] = end.theta;
                if H::NEEDS_INV_TAU || N::NEEDS_INV_TAU {
                    s.inv_tau[i] = end.inv_tau;
                }
            }
            Err(failed) => outcome = lowest(outcome, Err(failed.error(eos, s, step))),
        }
    }
    let [total] = exact_sums(sys.comm.transport(), added.iter().copied());
    *sys.fixes.reservoir_tally(&res.id) += total;
    sys.comm.forward(&mut sys.store, SWEPT);
    outcome
}

/// What stays fixed while one pair is updated, over any split of its step.
#[derive(Clone, Copy)]
struct Pair {
    i: Idx,
    j: Idx,
    e: [f64; 3],
    /// 1/m_i, 1/m_j.
    inv_m: (f64, f64),
    gamma: f64,
    kappa: f64,
}

/// What stays fixed during the sweep.
struct Keys {
    seed: u64,
    /// The noise step ([`System::noise_step`]).
    key: u64,
    kb: f64,
}

/// An index below the length shared by all [`Swept`] of one sweep, made only by
/// [`Swept::pair`] after its range check.
#[derive(Clone, Copy)]
struct Idx(usize);

/// The fields a pair update reads and writes, owned and ghost particles, as slices of one
/// length `len`, the length of the sweep's `at` (`inv_tau` empty where the heat law does
/// not read it). Every [`Idx`] is checked against that length once, by [`Swept::pair`],
/// so the accessors read and write without further checks.
struct Swept<'a, A> {
    len: usize,
    tag: &'a [u64],
    inv_m: &'a [f64],
    at: &'a [A],
    p: &'a mut [Vec3],
    u: &'a mut [f64],
    theta: &'a mut [f64],
    inv_tau: &'a mut [f64],
}

/// The element `i` of a slice of [`Swept`].
macro_rules! at {
    ($slice:expr, $i:expr) => {
        // SAFETY: every slice of a `Swept` has the length `len` the `Idx` was checked
        // against (`Swept::new` cuts them all to `at.len()`, the same for every `Swept`
        // of the sweep); `inv_tau` is read only under the same condition that gave it
        // that length.
        unsafe { $slice.get_unchecked($i.0) }
    };
}

/// As [`at!`], for writing.
macro_rules! at_mut {
    ($slice:expr, $i:expr) => {
        // SAFETY: as in `at!`.
        unsafe { $slice.get_unchecked_mut($i.0) }
    };
}

impl<'a, A: AtDensity> Swept<'a, A> {
    #[inline(always)]
    fn new<H: HeatFlow, N: Noise>(s: &'a mut Particles, at: &'a [A], inv_m: &'a [f64]) -> Self {
        let len = at.len();
        Self {
            len,
            tag: &s.tag[..len],
            inv_m: &inv_m[..len],
            at,
            p: &mut s.p[..len],
            u: &mut s.u[..len],
            theta: &mut s.theta[..len],
            inv_tau: if H::NEEDS_INV_TAU || N::NEEDS_INV_TAU { &mut s.inv_tau[..len] } else { &mut [] },
        }
    }

    /// The checked indices of a pair of the sweep's list (a list entry outside the store
    /// is a bug of the list build: a panic, never a silent read).
    #[inline(always)]
    fn pair(&self, [i, j]: [u32; 2]) -> (Idx, Idx) {
        let (i, j) = (i as usize, j as usize);
        assert!(i < self.len && j < self.len, "sweep pair outside the store");
        (Idx(i), Idx(j))
    }

    #[inline(always)]
    fn tag(&self, i: Idx) -> u64 {
        *at!(self.tag, i)
    }

    #[inline(always)]
    fn inv_m(&self, i: Idx) -> f64 {
        *at!(self.inv_m, i)
    }

    #[inline(always)]
    fn at(&self, i: Idx) -> &A {
        at!(self.at, i)
    }

    #[inline(always)]
    fn load<H: HeatFlow, N: Noise>(&self, i: Idx) -> End {
        let inv_tau = if H::NEEDS_INV_TAU || N::NEEDS_INV_TAU { *at!(self.inv_tau, i) } else { 0.0 };
        End { p: *at!(self.p, i), u: *at!(self.u, i), theta: *at!(self.theta, i), inv_tau }
    }

    #[inline(always)]
    fn store<H: HeatFlow, N: Noise>(&mut self, i: Idx, e: End) {
        *at_mut!(self.p, i) = e.p;
        *at_mut!(self.u, i) = e.u;
        *at_mut!(self.theta, i) = e.theta;
        if H::NEEDS_INV_TAU || N::NEEDS_INV_TAU {
            *at_mut!(self.inv_tau, i) = e.inv_tau;
        }
    }
}

/// One particle's swept state.
#[derive(Clone, Copy)]
struct End {
    p: Vec3,
    u: f64,
    theta: f64,
    inv_tau: f64,
}

impl End {
    #[inline(always)]
    fn temps(&self) -> Temps {
        Temps { theta: self.theta, inv_tau: self.inv_tau }
    }

    #[inline(always)]
    fn before(&self) -> Before {
        Before { theta: self.theta, inv_tau: self.inv_tau, u: self.u }
    }
}

/// A refresh that gave no valid temperature: particle `k`, its new u and the theta found.
#[derive(Clone, Copy, Debug)]
struct Failed {
    k: usize,
    u: f64,
    theta: f64,
}

impl Failed {
    #[cold]
    fn error<E: Eos>(self, eos: &Species<E>, s: &Particles, step: u64) -> StepError {
        let n = density_of(s, self.k).max(ISOLATED_DENSITY);
        let e = EosError::at(eos.of(s.kind[self.k]), self.u, n, self.theta);
        StepError::eos(s, self.k, step, e)
    }
}

/// Updates one pair over `dt` with Wiener increments `xi sqrt(dt)`, `xibar sqrt(dt)`, and
/// stores the new states only when both temperatures are valid (else nothing is written);
/// splits the step by a Brownian bridge when a temperature fails (`node` numbers the
/// halves of the binary tree, `levels` how many splits remain).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn pair_step<A: AtDensity, H: HeatFlow, N: Noise>(
    v: &mut Swept<'_, A>,
    k: &Keys,
    p: Pair,
    xi: f64,
    xibar: f64,
    dt: f64,
    node: u32,
    levels: u32,
    splits: &mut u64,
) -> Result<(), Failed> {
    let (i, j) = (p.i, p.j);
    let (a, b) = (v.load::<H, N>(i), v.load::<H, N>(j));
    let drive = PairDrive { e: p.e, gamma: p.gamma, kappa: p.kappa, ti: a.temps(), tj: b.temps(), xi, xibar };
    let (mut p_i, mut p_j, mut u_i, mut u_j) = (a.p, b.p, a.u, b.u);
    let state = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i: p.inv_m.0, inv_m_j: p.inv_m.1 };
    pair_update::<H, N>(state, &drive, k.kb, dt, dt.sqrt());
    let refreshed = refresh_pair::<A, H, N>([v.at(i), v.at(j)], [i.0, j.0], [p_i, p_j], [u_i, u_j], [a.before(), b.before()]);
    match refreshed {
        Ok((a, b)) => {
            v.store::<H, N>(i, a);
            v.store::<H, N>(j, b);
            Ok(())
        }
        Err(failed) if levels == 0 => Err(failed),
        Err(_) => split::<A, H, N>(v, k, p, (xi, xibar, dt, node, levels), splits),
    }
}

/// Does a failed pair update as two half steps; restores the pair when they fail too.
#[cold]
fn split<A: AtDensity, H: HeatFlow, N: Noise>(
    v: &mut Swept<'_, A>,
    k: &Keys,
    p: Pair,
    (xi, xibar, dt, node, levels): (f64, f64, f64, u32, u32),
    splits: &mut u64,
) -> Result<(), Failed> {
    let (i, j) = (p.i, p.j);
    let saved = (v.load::<H, N>(i), v.load::<H, N>(j));
    *splits += 1;
    let (eta, etabar) = normal_pair(k.seed, k.key, v.tag(i), v.tag(j), stream::SUBSTEP + node);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let first = ((xi + eta) * h, (xibar + etabar) * h);
    let second = ((xi - eta) * h, (xibar - etabar) * h);
    let halves = pair_step::<A, H, N>(v, k, p, first.0, first.1, 0.5 * dt, 2 * node + 1, levels - 1, splits)
        .and_then(|_| pair_step::<A, H, N>(v, k, p, second.0, second.1, 0.5 * dt, 2 * node + 2, levels - 1, splits));
    if halves.is_err() {
        v.store::<H, N>(i, saved.0);
        v.store::<H, N>(j, saved.1);
    }
    halves
}

#[inline(always)]
pub(crate) fn temps<H: HeatFlow, N: Noise>(s: &Particles, i: usize) -> Temps {
    Temps { theta: s.theta[i], inv_tau: if H::NEEDS_INV_TAU || N::NEEDS_INV_TAU { s.inv_tau[i] } else { 0.0 } }
}

/// theta(u) at the particle's fixed density after a pair update, and 1/tau where the heat
/// or noise law reads it: the particle's new state, or why it has none.
#[inline(always)]
fn refresh<A: AtDensity, H: HeatFlow, N: Noise>(at: &A, k: usize, p: Vec3, u: f64, guess: f64) -> Result<End, Failed> {
    let found = if H::NEEDS_INV_TAU || N::NEEDS_INV_TAU { at.theta_inv_tau(u, guess) } else { (at.theta(u, guess), 0.0) };
    end(k, p, u, found)
}

/// [`refresh`] of the two particles of a pair after a pair update moved their energies
/// from the states `before` ([`AtDensity::after_pair`]); a failure of the first reported
/// first.
#[inline(always)]
fn refresh_pair<A: AtDensity, H: HeatFlow, N: Noise>(at: [&A; 2], k: [usize; 2], p: [Vec3; 2], u: [f64; 2], before: [Before; 2]) -> Result<(End, End), Failed> {
    let found = at[0].after_pair(at[1], before, u, H::NEEDS_INV_TAU || N::NEEDS_INV_TAU);
    Ok((end(k[0], p[0], u[0], found[0])?, end(k[1], p[1], u[1], found[1])?))
}

/// Particle `k`'s new state from the (theta, 1/tau) found, or why it has none.
#[inline(always)]
#[allow(clippy::eq_op)] // theta - theta on purpose (below)
fn end(k: usize, p: Vec3, u: f64, (theta, inv_tau): (f64, f64)) -> Result<End, Failed> {
    // theta > 0 and finite (theta - theta is 0 only when finite): three floating-point
    // instructions, where `is_finite` compiles to integer bit tests
    if !(theta > 0.0 && theta - theta == 0.0) {
        return Err(Failed { k, u, theta });
    }
    Ok(End { p, u, theta, inv_tau })
}
