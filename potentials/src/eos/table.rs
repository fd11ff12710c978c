//! Tabulated EOS: any [`Eos`] replaced by bicubic Hermite interpolants on a (theta, n)
//! grid, so that theta(u, n), the call of the Shardlow sweep after every pair update, costs
//! a cubic solve instead of the inner model's own (possibly iterative) evaluation.
//!
//! Grid ([`TableGrid`]). Nodes theta_i = theta_min (theta_max/theta_min)^{i/(N_theta - 1)},
//! uniform in ln theta (the cell is found through a bucket table, without a logarithm),
//! and n_j = n_min + j dn, uniform in n. At every node the table holds u, C_V = du/dtheta,
//! du/dn|_theta and d^2u/dtheta dn, and pi/n^2 with its three derivatives d/dtheta, d/dn
//! and d^2/dtheta dn. u, C_V and pi/n^2 come from the inner EOS; the other derivatives from
//! five-point finite differences of the inner EOS with a step of 1/100 of the adjacent node
//! spacing (central inside the grid, one-sided at its edges, so the inner EOS is only
//! evaluated inside the table). Their error enters the interpolants multiplied by a node
//! spacing: about 1e-13 relative.
//!
//! Interpolation. In cell [theta_i, theta_i+1] x [n_j, n_j+1] with local coordinates
//! t = (theta - theta_i)/(theta_i+1 - theta_i) and s = (n - n_j)/dn (t is linear in theta,
//! so a model linear in theta, such as [`super::LinearTheta`], is reproduced exactly in
//! theta), u and pi/n^2 are bicubic Hermite polynomials sum_kl a_kl t^k s^l: C^1 across
//! cells, error O(h^4) for u and pi/n^2 (h the node spacing), and exact for polynomials of
//! degree 3 in theta and in n. [`Eos::cv`] is the exact derivative du/dtheta of the
//! interpolated u (error O(h^3)): the table is its own consistent EOS (C_V = du/dtheta,
//! and the Newton solve of theta(u, n) uses it), and it equals the inner C_V at the nodes.
//! pi/n^2 is interpolated on its own, so the Maxwell relation between u and pi/n^2 holds
//! only to the interpolation error.
//!
//! Monotonicity. [`Tabulated::new`] writes the u-patch of every cell in Bernstein-Bezier
//! form (degree 3 x 3, control net P_kl) and requires P_k+1,l > P_kl for all k, l: then
//! du/dt, a polynomial with Bernstein coefficients 3 (P_k+1,l - P_kl), is positive on the
//! whole closed cell, so the interpolated u increases strictly with theta at every n, the
//! interpolated C_V > 0 everywhere in the table and theta(u, n) is unique. The condition is
//! sufficient, not necessary; a smooth u with C_V > 0 meets it once the grid resolves C_V,
//! otherwise the constructor fails with [`TableError::NotMonotone`] naming the cell.
//!
//! theta(u, n) inverts the interpolated u: the cell holding u at density n is the guess's
//! cell or is found by a galloping search from it (then bisection) over the node values of
//! the interpolated u at this n, then a Newton iteration bracketed in [0, 1] solves the
//! cubic in t, stopping when the error it predicts is below 1e-15 theta (one iteration
//! from the sweep's first-order guess after a pair update). The sweep's model at a
//! particle's density ([`TableAt`]) keeps the cubics of the three cells around the
//! particle's theta, so that most refreshes skip the lookup (the same bits).
//! It is consistent with [`Eos::u`] to round-off: theta(u(t, n), n) = t within a few ulps
//! (tests: 1e-12 relative), so energies round trip exactly through the table.
//!
//! Outside the table. For theta outside [theta_min, theta_max] or n outside [n_min, n_max]
//! (inclusive, NaN included) `u`, `pn2` and `cv` return NaN; `theta` returns NaN for n
//! outside the range or u outside [u(theta_min, n), u(theta_max, n)], so that
//! [`Eos::state`] returns an error. [`Tabulated::check`] and [`Tabulated::theta_checked`]
//! give errors naming the state and the table's range. Isolated particles are evaluated at
//! n = [`ISOLATED_DENSITY`] (see [`Eos::state`]): a table meant for them needs n_min <= 1e-6.
//!
//! Entropy is delegated to the inner EOS, s(u, n) at the same u and n (not integrated from
//! the table), for states inside the table (None outside). `kb`, `density_dependent` and
//! `max_density` are the inner model's.
//!
//! Accuracy is measured with [`Tabulated::max_error`]. Kolafa-Nezbeda LJ fluid, C_V = 60,
//! theta in [0.5, 5], n in [0.05, 0.85] (largest relative errors between the nodes; the
//! worst u, C_V and theta(u) errors sit at theta_min, the worst pi/n^2 near n_max):
//!
//! | nodes     | u       | pi/n^2  | C_V     | theta(u) |
//! |-----------|---------|---------|---------|----------|
//! | 31 x 33   | 2.0e-6  | 9.8e-5  | 5.0e-5  | 1.3e-6   |
//! | 61 x 65   | 1.3e-7  | 7.5e-6  | 6.5e-6  | 8.8e-8   |
//! | 121 x 129 | 8.4e-9  | 5.7e-7  | 8.4e-7  | 5.6e-9   |

use super::{Eos, EosError, EosState, ISOLATED_DENSITY};
use std::fmt;

/// Table grid: (min, max, node count) in theta (nodes uniform in ln theta) and in n
/// (nodes uniform in n). Both counts must be at least 2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableGrid {
    pub theta: (f64, f64, usize),
    pub n: (f64, f64, usize),
}

/// Why a table cannot be built or a state lies outside it.
#[derive(Clone, Debug, PartialEq)]
pub enum TableError {
    /// The grid description is unusable.
    Grid(String),
    /// The inner EOS fails at a node (theta, n) of the grid, or next to it.
    Inner { theta: f64, n: f64, reason: String },
    /// The interpolated u of this cell cannot be shown to increase with theta.
    NotMonotone { theta: (f64, f64), n: (f64, f64) },
    /// The state (theta, n) lies outside the table.
    OutOfRange { theta: f64, n: f64, theta_range: (f64, f64), n_range: (f64, f64) },
    /// The energy u at density n lies outside the table: `u_range` is (u(theta_min, n),
    /// u(theta_max, n)) of the table, None when n itself is outside `n_range`.
    EnergyOutOfRange { u: f64, n: f64, u_range: Option<(f64, f64)>, n_range: (f64, f64) },
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Grid(msg) => write!(f, "invalid EOS table grid: {msg}"),
            Self::Inner { theta, n, reason } => write!(
                f,
                "cannot tabulate the EOS at the node theta = {theta:e}, n = {n:e}: {reason}"
            ),
            Self::NotMonotone { theta, n } => write!(
                f,
                "the tabulated u may not increase with theta in the cell theta in [{:e}, {:e}], \
                 n in [{:e}, {:e}]: refine the theta grid there, or check that C_V > 0",
                theta.0, theta.1, n.0, n.1
            ),
            Self::OutOfRange { theta, n, theta_range, n_range } => write!(
                f,
                "state theta = {theta:e}, n = {n:e} lies outside the EOS table \
                 (theta in [{:e}, {:e}], n in [{:e}, {:e}])",
                theta_range.0, theta_range.1, n_range.0, n_range.1
            ),
            Self::EnergyOutOfRange { u, n, u_range: Some(r), .. } => write!(
                f,
                "state u = {u:e}, n = {n:e} lies outside the EOS table: at this density the \
                 table covers u in [{:e}, {:e}] (its theta range)",
                r.0, r.1
            ),
            Self::EnergyOutOfRange { u, n, u_range: None, n_range } => write!(
                f,
                "state u = {u:e}, n = {n:e} lies outside the EOS table (n in [{:e}, {:e}])",
                n_range.0, n_range.1
            ),
        }
    }
}

impl std::error::Error for TableError {}

/// Largest error of one quantity and the state (theta, n) where it occurs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ErrorAt {
    /// |table - inner| / max(|inner|, floor), floor = 1e-3 max |inner| over the nodes
    /// (so that the zero crossings of pi/n^2 do not dominate). For theta(u): the relative
    /// error of the table's theta at the inner model's u(theta, n).
    pub rel: f64,
    pub theta: f64,
    pub n: f64,
}

/// Result of [`Tabulated::max_error`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TableErrors {
    pub u: ErrorAt,
    pub pn2: ErrorAt,
    pub cv: ErrorAt,
    pub theta: ErrorAt,
    /// Number of sampled states.
    pub samples: usize,
}

impl fmt::Display for TableErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let rows =
            [("u", &self.u), ("pi/n^2", &self.pn2), ("C_V", &self.cv), ("theta(u)", &self.theta)];
        write!(f, "max relative error over {} states:", self.samples)?;
        for (name, e) in rows {
            write!(f, " {name} {:.2e} at ({:.4}, {:.4});", e.rel, e.theta, e.n)?;
        }
        Ok(())
    }
}

/// Bicubic coefficients a_kl (index 4k + l) of sum_kl a_kl t^k s^l over one cell.
type Patch = [f64; 16];

/// Node data of one function: value, d/dtheta, d/dn, d^2/dtheta dn.
#[derive(Clone, Copy, Default)]
struct Node {
    f: f64,
    ft: f64,
    fn_: f64,
    ftn: f64,
}

/// Cell and local coordinates of a state.
#[derive(Clone, Copy)]
struct Loc {
    i: usize,
    j: usize,
    t: f64,
    s: f64,
}

/// An [`Eos`] evaluated through bicubic Hermite tables (see the module documentation).
///
/// ```
/// use gendpde_potentials::{Eos, LennardJones, TableGrid, Tabulated};
/// let grid = TableGrid { theta: (0.5, 5.0, 61), n: (0.05, 0.85, 65) };
/// let table = Tabulated::new(LennardJones::new(60.0), grid)?;
/// let err = table.max_error(4); // against the analytic model, between the nodes
/// assert!(err.u.rel < 1e-6 && err.theta.rel < 1e-6, "{err}");
/// let u = table.u(1.3, 0.4);
/// assert!((table.theta(u, 0.4, 1.0) - 1.3).abs() < 1e-14); // exact round trip
/// assert!(table.theta(u, 0.9, 1.0).is_nan() && table.check(1.3, 0.9).is_err());
/// # Ok::<(), gendpde_potentials::TableError>(())
/// ```
#[derive(Clone, PartialEq)]
pub struct Tabulated<E: Eos> {
    inner: E,
    grid: TableGrid,
    nt: usize,
    nn: usize,
    /// theta nodes (exactly theta_min and theta_max at the ends).
    thetas: Vec<f64>,
    /// 1 / (theta_i+1 - theta_i).
    inv_h: Vec<f64>,
    /// Cell lookup without a logarithm: bucket k covers theta_min + [k, k + 1) / inv_w
    /// and holds the cell of its left edge; buckets are at most as wide as the narrowest
    /// (first) cell unless their number is capped, so theta lies in that cell or the next.
    bucket: Vec<u32>,
    inv_w: f64,
    dn: f64,
    inv_dn: f64,
    /// 1/k_B of the inner model (the sweep's step 1/C_V = (1 - theta/tau)/k_B).
    inv_kb: f64,
    /// u patches, cell (i, j) at j (nt - 1) + i.
    pu: Vec<Patch>,
    /// pi/n^2 patches.
    pp: Vec<Patch>,
    /// Largest |u|, |pi/n^2|, |C_V| over the nodes (floors of [`ErrorAt::rel`]).
    scale: [f64; 3],
}

impl<E: Eos + fmt::Debug> fmt::Debug for Tabulated<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Tabulated").field("inner", &self.inner).field("grid", &self.grid).finish()
    }
}

/// Finite-difference step as a fraction of the adjacent node spacing.
const FD_STEP: f64 = 1e-2;
/// Largest number of nodes of a table.
const MAX_NODES: usize = 1 << 22;
/// Largest number of theta lookup buckets (more only for wide theta ranges).
const MAX_BUCKETS: f64 = (1 << 14) as f64;
/// Tolerance of the inner model's own round trip theta(u(theta, n), n) at the nodes.
const INNER_TOL: f64 = 1e-6;
/// Relative error of theta below which the Newton solve stops (that of the analytic LJ
/// solve, a few ulps).
const NEWTON_TOL: f64 = 1e-15;
/// Smallest tolerance of the Newton solve in t (in [0, 1]), 1/10 ulp of 1.
const NEWTON_TOL_T: f64 = 1e-17;
const MAX_ITER: usize = 100;

/// Hermite-to-power basis: p(t) = sum_k t^k (M [f(0), f(1), f'(0), f'(1)])_k.
const M: [[f64; 4]; 4] =
    [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [-3.0, 3.0, -2.0, -1.0], [2.0, -2.0, 1.0, 1.0]];
/// Hermite-to-Bernstein basis: Bezier control points of the same cubic.
const B: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [1.0, 0.0, 1.0 / 3.0, 0.0],
    [0.0, 1.0, 0.0, -1.0 / 3.0],
    [0.0, 1.0, 0.0, 0.0],
];

/// X F X^T for 4x4 matrices.
fn sandwich(x: &[[f64; 4]; 4], f: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut out = [[0.0; 4]; 4];
    for (k, row) in out.iter_mut().enumerate() {
        for (l, o) in row.iter_mut().enumerate() {
            let mut acc = 0.0;
            for a in 0..4 {
                for b in 0..4 {
                    acc += x[k][a] * f[a][b] * x[l][b];
                }
            }
            *o = acc;
        }
    }
    out
}

/// df/dx at nodes[k]: five-point stencil with step FD_STEP times the adjacent spacing,
/// central inside, one-sided at the first and last node (never leaves the node range).
fn fd(f: &dyn Fn(f64) -> f64, nodes: &[f64], k: usize) -> f64 {
    let last = nodes.len() - 1;
    let x = nodes[k];
    if k == 0 || k == last {
        let h = if k == 0 {
            FD_STEP * (nodes[1] - nodes[0])
        } else {
            -FD_STEP * (nodes[last] - nodes[last - 1])
        };
        (-25.0 * f(x) + 48.0 * f(x + h) - 36.0 * f(x + 2.0 * h) + 16.0 * f(x + 3.0 * h)
            - 3.0 * f(x + 4.0 * h))
            / (12.0 * h)
    } else {
        let h = FD_STEP * (nodes[k] - nodes[k - 1]).min(nodes[k + 1] - nodes[k]);
        (f(x - 2.0 * h) - 8.0 * (f(x - h) - f(x + h)) - f(x + 2.0 * h)) / (12.0 * h)
    }
}

/// a_k0 + a_k1 s + a_k2 s^2 + a_k3 s^3 for row k of a patch.
#[inline(always)]
fn row(a: &Patch, k: usize, s: f64) -> f64 {
    ((a[4 * k + 3] * s + a[4 * k + 2]) * s + a[4 * k + 1]) * s + a[4 * k]
}

/// The patch restricted to density s: cubic coefficients in t.
#[inline(always)]
fn cubic(a: &Patch, s: f64) -> [f64; 4] {
    [row(a, 0, s), row(a, 1, s), row(a, 2, s), row(a, 3, s)]
}

#[inline(always)]
fn value(c: &[f64; 4], t: f64) -> f64 {
    ((c[3] * t + c[2]) * t + c[1]) * t + c[0]
}

#[inline(always)]
fn slope(c: &[f64; 4], t: f64) -> f64 {
    (3.0 * c[3] * t + 2.0 * c[2]) * t + c[1]
}

fn check_range(
    name: &str,
    (lo, hi, count): (f64, f64, usize),
    lo_min: f64,
) -> Result<(), TableError> {
    if !(lo.is_finite() && hi.is_finite() && lo >= lo_min && hi > lo && count >= 2) {
        let need = if lo_min > 0.0 { "0 < min < max" } else { "0 <= min < max" };
        return Err(TableError::Grid(format!(
            "{name} = (min {lo:e}, max {hi:e}, count {count}): need finite {need} and count >= 2"
        )));
    }
    Ok(())
}

impl<E: Eos> Tabulated<E> {
    /// Tabulates `inner` on `grid`. Fails on an invalid grid, when the inner EOS gives a
    /// non-finite value, C_V <= 0 or no theta(u(theta, n), n) = theta at a node (outside
    /// its domain), or when a cell's interpolated u cannot be shown monotone in theta.
    pub fn new(inner: E, grid: TableGrid) -> Result<Self, TableError> {
        check_range("theta", grid.theta, f64::MIN_POSITIVE)?;
        check_range("n", grid.n, 0.0)?;
        let (tmin, tmax, nt) = grid.theta;
        let (nmin, nmax, nn) = grid.n;
        if !matches!(nt.checked_mul(nn), Some(c) if c <= MAX_NODES) {
            return Err(TableError::Grid(format!(
                "{nt} x {nn} nodes: at most {MAX_NODES} nodes are supported"
            )));
        }
        let dx = (tmax / tmin).ln() / (nt - 1) as f64;
        let mut thetas: Vec<f64> = (0..nt).map(|i| tmin * (dx * i as f64).exp()).collect();
        thetas[0] = tmin;
        thetas[nt - 1] = tmax;
        let dn = (nmax - nmin) / (nn - 1) as f64;
        let mut ns: Vec<f64> = (0..nn).map(|j| nmin + dn * j as f64).collect();
        ns[nn - 1] = nmax;
        if thetas.windows(2).any(|w| w[1] <= w[0]) || ns.windows(2).any(|w| w[1] <= w[0]) {
            return Err(TableError::Grid(format!(
                "theta ({tmin:e}, {tmax:e}, {nt}), n ({nmin:e}, {nmax:e}, {nn}): node spacing \
                 below the floating-point resolution"
            )));
        }

        let mut nu = vec![Node::default(); nt * nn];
        let mut np = vec![Node::default(); nt * nn];
        let mut scale = [0.0f64; 3];
        for (j, &n) in ns.iter().enumerate() {
            for (i, &theta) in thetas.iter().enumerate() {
                let fail = |reason: String| TableError::Inner { theta, n, reason };
                let u = inner.u(theta, n);
                let cv = inner.cv(theta, n);
                let p = inner.pn2(theta, n);
                for (name, v) in [("u", u), ("C_V", cv), ("pi/n^2", p)] {
                    if !v.is_finite() {
                        return Err(fail(format!("{name} = {v}")));
                    }
                }
                if cv <= 0.0 {
                    return Err(fail(format!("C_V = {cv:e} is not positive")));
                }
                let back = inner.theta(u, n, theta);
                let recovered = (back - theta).abs() <= INNER_TOL * theta; // false for NaN
                if !recovered {
                    return Err(fail(format!(
                        "the EOS gives theta(u = {u:e}, n) = {back:e}: the node lies outside \
                         its domain"
                    )));
                }
                let un = fd(&|y| inner.u(theta, y), &ns, j);
                let cvn = fd(&|y| inner.cv(theta, y), &ns, j);
                let pt = fd(&|x| inner.pn2(x, n), &thetas, i);
                let pn = fd(&|y| inner.pn2(theta, y), &ns, j);
                let ptn = fd(&|y| fd(&|x| inner.pn2(x, y), &thetas, i), &ns, j);
                if ![un, cvn, pt, pn, ptn].iter().all(|d| d.is_finite()) {
                    return Err(fail(
                        "a finite-difference derivative next to the node is not finite".into(),
                    ));
                }
                nu[j * nt + i] = Node { f: u, ft: cv, fn_: un, ftn: cvn };
                np[j * nt + i] = Node { f: p, ft: pt, fn_: pn, ftn: ptn };
                scale = [scale[0].max(u.abs()), scale[1].max(p.abs()), scale[2].max(cv)];
            }
        }

        let m = nt - 1;
        let mut pu = Vec::with_capacity(m * (nn - 1));
        let mut pp = Vec::with_capacity(m * (nn - 1));
        for j in 0..nn - 1 {
            for i in 0..m {
                let ht = thetas[i + 1] - thetas[i];
                // Hermite data: rows t-data (f(0), f(1), f_t(0), f_t(1)), columns s-data
                let herm = |d: &[Node]| {
                    let c = [j * nt + i, j * nt + i + 1, (j + 1) * nt + i, (j + 1) * nt + i + 1];
                    let [a, b, c_, d_] = c.map(|k| d[k]);
                    [
                        [a.f, c_.f, dn * a.fn_, dn * c_.fn_],
                        [b.f, d_.f, dn * b.fn_, dn * d_.fn_],
                        [ht * a.ft, ht * c_.ft, ht * dn * a.ftn, ht * dn * c_.ftn],
                        [ht * b.ft, ht * d_.ft, ht * dn * b.ftn, ht * dn * d_.ftn],
                    ]
                };
                let fu = herm(&nu);
                let bez = sandwich(&B, &fu);
                let rising = |k: usize, l: usize| bez[k + 1][l] > bez[k][l];
                if !(0..3).all(|k| (0..4).all(|l| rising(k, l))) {
                    return Err(TableError::NotMonotone {
                        theta: (thetas[i], thetas[i + 1]),
                        n: (ns[j], ns[j + 1]),
                    });
                }
                let flat = |a: [[f64; 4]; 4]| -> Patch {
                    let mut p = [0.0; 16];
                    for k in 0..4 {
                        p[4 * k..4 * k + 4].copy_from_slice(&a[k]);
                    }
                    p
                };
                pu.push(flat(sandwich(&M, &fu)));
                pp.push(flat(sandwich(&M, &herm(&np))));
            }
        }
        let inv_h = thetas.windows(2).map(|w| 1.0 / (w[1] - w[0])).collect();
        let count = ((tmax - tmin) / (thetas[1] - thetas[0])).ceil().min(MAX_BUCKETS) as usize;
        let inv_w = count as f64 / (tmax - tmin);
        let mut cell = 0;
        let bucket = (0..=count)
            .map(|k| {
                let edge = tmin + k as f64 / inv_w;
                while cell + 1 < m && thetas[cell + 1] <= edge {
                    cell += 1;
                }
                cell as u32
            })
            .collect();
        Ok(Self {
            inv_kb: 1.0 / inner.kb(),
            inner,
            grid,
            nt,
            nn,
            thetas,
            inv_h,
            bucket,
            inv_w,
            dn,
            inv_dn: 1.0 / dn,
            pu,
            pp,
            scale,
        })
    }

    /// The tabulated EOS.
    pub fn inner(&self) -> &E {
        &self.inner
    }

    /// The grid of the table.
    pub fn grid(&self) -> &TableGrid {
        &self.grid
    }

    fn theta_range(&self) -> (f64, f64) {
        (self.grid.theta.0, self.grid.theta.1)
    }

    fn n_range(&self) -> (f64, f64) {
        (self.grid.n.0, self.grid.n.1)
    }

    /// Ok when (theta, n) lies inside the table, else an error naming the state and the
    /// table's range.
    pub fn check(&self, theta: f64, n: f64) -> Result<(), TableError> {
        match self.locate(theta, n) {
            Some(_) => Ok(()),
            None => Err(TableError::OutOfRange {
                theta,
                n,
                theta_range: self.theta_range(),
                n_range: self.n_range(),
            }),
        }
    }

    /// [`Eos::theta`] with an error naming the state and the range of u the table covers
    /// at this density when (u, n) lies outside the table.
    pub fn theta_checked(&self, u: f64, n: f64, guess: f64) -> Result<f64, TableError> {
        if let Some((l, _)) = self.solve(u, n, guess) {
            return Ok(self.theta_at(l.i, l.t));
        }
        let u_range =
            self.cell_n(n).map(|(j, s)| (self.node_u(0, j, s), self.node_u(self.nt - 1, j, s)));
        Err(TableError::EnergyOutOfRange { u, n, u_range, n_range: self.n_range() })
    }

    /// Largest errors of the interpolated u, pi/n^2, C_V and of theta(u) against the inner
    /// EOS, sampled at `samples_per_cell`^2 states inside every cell (at the centres of a
    /// regular subdivision of the cell in (theta, n), so never on a node).
    pub fn max_error(&self, samples_per_cell: usize) -> TableErrors {
        let k = samples_per_cell.max(1);
        let floors = self.scale.map(|s| 1e-3 * s);
        let mut out = TableErrors::default();
        let update = |e: &mut ErrorAt, rel: f64, theta: f64, n: f64| {
            let rel = if rel.is_nan() { f64::INFINITY } else { rel };
            if rel > e.rel || e.theta == 0.0 {
                *e = ErrorAt { rel, theta, n };
            }
        };
        for j in 0..self.nn - 1 {
            for i in 0..self.nt - 1 {
                let h = self.thetas[i + 1] - self.thetas[i];
                for a in 0..k {
                    for b in 0..k {
                        let theta = self.thetas[i] + h * (a as f64 + 0.5) / k as f64;
                        let n = self.grid.n.0 + self.dn * (j as f64 + (b as f64 + 0.5) / k as f64);
                        let eu = self.inner.u(theta, n);
                        let ep = self.inner.pn2(theta, n);
                        let ec = self.inner.cv(theta, n);
                        let rel = |t: f64, e: f64, floor: f64| (t - e).abs() / e.abs().max(floor);
                        update(&mut out.u, rel(self.u(theta, n), eu, floors[0]), theta, n);
                        update(&mut out.pn2, rel(self.pn2(theta, n), ep, floors[1]), theta, n);
                        update(&mut out.cv, rel(self.cv(theta, n), ec, floors[2]), theta, n);
                        let back = self.theta(eu, n, theta);
                        update(&mut out.theta, (back - theta).abs() / theta, theta, n);
                        out.samples += 1;
                    }
                }
            }
        }
        out
    }

    /// Row j and local s of density n, None outside [n_min, n_max].
    #[inline(always)]
    fn cell_n(&self, n: f64) -> Option<(usize, f64)> {
        if !(n >= self.grid.n.0 && n <= self.grid.n.1) {
            return None;
        }
        let y = (n - self.grid.n.0) * self.inv_dn;
        let j = (y as usize).min(self.nn - 2);
        Some((j, unit(y - j as f64)))
    }

    /// Column i and local t of theta in [theta_min, theta_max].
    #[inline(always)]
    fn cell_theta(&self, theta: f64) -> (usize, f64) {
        let m = self.nt - 1;
        let k = (((theta - self.grid.theta.0) * self.inv_w) as usize).min(self.bucket.len() - 1);
        let mut i = self.bucket[k] as usize;
        // the node array decides (round-off at bucket edges, capped bucket count)
        while theta < self.thetas[i] && i > 0 {
            i -= 1;
        }
        while theta > self.thetas[i + 1] && i + 1 < m {
            i += 1;
        }
        (i, unit((theta - self.thetas[i]) * self.inv_h[i]))
    }

    /// Cell and local coordinates of (theta, n), None outside the table.
    #[inline(always)]
    fn locate(&self, theta: f64, n: f64) -> Option<Loc> {
        if !(theta >= self.grid.theta.0 && theta <= self.grid.theta.1) {
            return None;
        }
        let (j, s) = self.cell_n(n)?;
        let (i, t) = self.cell_theta(theta);
        Some(Loc { i, j, t, s })
    }

    #[inline(always)]
    fn cell(&self, i: usize, j: usize) -> usize {
        j * (self.nt - 1) + i
    }

    /// Interpolated u at node i of row j and density s (u at theta_i).
    #[inline(always)]
    fn node_u(&self, i: usize, j: usize, s: f64) -> f64 {
        let m = self.nt - 1;
        if i < m {
            row(&self.pu[self.cell(i, j)], 0, s)
        } else {
            value(&cubic(&self.pu[self.cell(m - 1, j)], s), 1.0)
        }
    }

    /// Tolerance in t of the Newton solve in cell column i: an error of NEWTON_TOL theta,
    /// at least NEWTON_TOL_T.
    #[inline(always)]
    fn newton_tol(&self, i: usize) -> f64 {
        (NEWTON_TOL * self.thetas[i] * self.inv_h[i]).max(NEWTON_TOL_T)
    }

    #[inline(always)]
    fn theta_at(&self, i: usize, t: f64) -> f64 {
        let (a, b) = (self.thetas[i], self.thetas[i + 1]);
        within(a + t * (b - a), a, b)
    }

    /// Cell, local coordinates and the cubic u(t) at this density of the state of energy
    /// u at density n; None outside the table.
    #[inline]
    fn solve(&self, u: f64, n: f64, guess: f64) -> Option<(Loc, [f64; 4])> {
        if !u.is_finite() {
            return None;
        }
        let (j, s) = self.cell_n(n)?;
        let m = self.nt - 1;
        let guess_in = guess >= self.grid.theta.0 && guess <= self.grid.theta.1;
        let i0 = if guess_in { self.cell_theta(guess).0 } else { m / 2 };
        let mut i = i0;
        let mut c = cubic(&self.pu[self.cell(i, j)], s);
        let (ua, ub) = (c[0], value(&c, 1.0));
        if u < ua || u > ub {
            // node bracket lo < hi with u(lo) <= u <= u(hi): gallop from the guess, bisect
            let (mut lo, mut hi);
            if u < ua {
                hi = i0;
                let mut step = 1;
                loop {
                    if hi == 0 {
                        return None; // below u(theta_min, n)
                    }
                    let cand = hi.saturating_sub(step);
                    if self.node_u(cand, j, s) <= u {
                        lo = cand;
                        break;
                    }
                    hi = cand;
                    step *= 2;
                }
            } else {
                lo = i0 + 1;
                let mut step = 1;
                loop {
                    if lo == m {
                        return None; // above u(theta_max, n)
                    }
                    let cand = (lo + step).min(m);
                    if self.node_u(cand, j, s) >= u {
                        hi = cand;
                        break;
                    }
                    lo = cand;
                    step *= 2;
                }
            }
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if self.node_u(mid, j, s) <= u {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            i = lo;
            c = cubic(&self.pu[self.cell(i, j)], s);
        }
        let (p0, p1) = (c[0], value(&c, 1.0));
        let t = if u <= p0 {
            0.0
        } else if u >= p1 {
            1.0
        } else {
            let (a, b) = (self.thetas[i], self.thetas[i + 1]);
            let t0 = if guess >= a && guess <= b {
                (guess - a) * self.inv_h[i]
            } else {
                (u - p0) / (p1 - p0)
            };
            newton(&c, u, unit(t0), self.newton_tol(i))
        };
        Some((Loc { i, j, t, s }, c))
    }
}

/// t limited to [0, 1], for a t that is not NaN: two compare-selects (`f64::clamp` also
/// carries NaN through, at several instructions more in the sweep's refreshes).
#[inline(always)]
fn unit(t: f64) -> f64 {
    within(t, 0.0, 1.0)
}

/// x limited to [a, b] (a < b), for an x that is not NaN.
#[inline(always)]
fn within(x: f64, a: f64, b: f64) -> f64 {
    let x = if x > a { x } else { a };
    if x < b { x } else { b }
}

/// Root in [0, 1] of the increasing cubic c(t) = u with c(0) < u < c(1): Newton,
/// bisection whenever a step leaves the bracket. A Newton step dt is the last one when
/// the error it leaves, c''/(2 c') dt^2 (quadratic convergence), is below `tol`
/// ([`Tabulated::newton_tol`]).
#[inline]
fn newton(c: &[f64; 4], u: f64, mut t: f64, tol: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..MAX_ITER {
        let r = value(c, t) - u;
        if r == 0.0 {
            return t;
        }
        if r < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let d1 = slope(c, t);
        let dt = r / d1;
        let next = t - dt;
        if next >= lo && next <= hi {
            let d2 = 6.0 * c[3] * t + 2.0 * c[2];
            if (d2 * dt * dt).abs() <= 2.0 * tol * d1 {
                return next;
            }
            t = next;
        } else {
            t = 0.5 * (lo + hi);
            if hi - lo <= f64::EPSILON {
                return t;
            }
        }
    }
    t
}

impl<E: Eos> Eos for Tabulated<E> {
    fn kb(&self) -> f64 {
        self.inner.kb()
    }
    fn outside(&self, u: f64, n: f64) -> Option<String> {
        self.theta_checked(u, n, f64::NAN).err().map(|e| e.to_string())
    }
    fn density_dependent(&self) -> bool {
        self.inner.density_dependent()
    }
    /// theta inverting the interpolated u at fixed n; NaN outside the table.
    #[inline]
    fn theta(&self, u: f64, n: f64, guess: f64) -> f64 {
        match self.solve(u, n, guess) {
            Some((l, _)) => self.theta_at(l.i, l.t),
            None => f64::NAN,
        }
    }
    /// One cell lookup for both.
    #[inline]
    fn theta_cv(&self, u: f64, n: f64, guess: f64) -> (f64, f64) {
        match self.solve(u, n, guess) {
            Some((l, c)) => (self.theta_at(l.i, l.t), slope(&c, l.t) * self.inv_h[l.i]),
            None => (f64::NAN, f64::NAN),
        }
    }
    /// Interpolated u; NaN outside the table.
    #[inline]
    fn u(&self, theta: f64, n: f64) -> f64 {
        match self.locate(theta, n) {
            Some(l) => value(&cubic(&self.pu[self.cell(l.i, l.j)], l.s), l.t),
            None => f64::NAN,
        }
    }
    /// Interpolated pi/n^2; NaN outside the table.
    #[inline]
    fn pn2(&self, theta: f64, n: f64) -> f64 {
        match self.locate(theta, n) {
            Some(l) => value(&cubic(&self.pp[self.cell(l.i, l.j)], l.s), l.t),
            None => f64::NAN,
        }
    }
    /// du/dtheta of the interpolated u; NaN outside the table.
    #[inline]
    fn cv(&self, theta: f64, n: f64) -> f64 {
        match self.locate(theta, n) {
            Some(l) => slope(&cubic(&self.pu[self.cell(l.i, l.j)], l.s), l.t) * self.inv_h[l.i],
            None => f64::NAN,
        }
    }
    /// The inner model's s(u, n) for states inside the table, None outside.
    fn entropy(&self, u: f64, n: f64) -> Option<f64> {
        self.solve(u, n, f64::NAN)?;
        self.inner.entropy(u, n)
    }
    fn max_density(&self) -> Option<f64> {
        self.inner.max_density()
    }

    /// As the provided method (isolated-particle rule included), with theta, pi/n^2 and
    /// C_V taken from one cell lookup (equal to `theta`, `pn2`, `cv` up to round-off).
    #[inline]
    fn state(&self, u: f64, n: f64, guess: f64) -> Result<EosState, EosError> {
        let isolated = n < ISOLATED_DENSITY;
        let n = if isolated { ISOLATED_DENSITY } else { n };
        let Some((l, c)) = self.solve(u, n, guess) else {
            return Err(EosError::NonPositiveTheta { u, n, theta: f64::NAN });
        };
        let theta = self.theta_at(l.i, l.t);
        let pn2 =
            if isolated { 0.0 } else { value(&cubic(&self.pp[self.cell(l.i, l.j)], l.s), l.t) };
        Ok(EosState { theta, pn2, cv: slope(&c, l.t) * self.inv_h[l.i] })
    }
}

mod at_density;
pub use at_density::TableAt;

#[cfg(test)]
mod tests;
