//! Time per theta solve of the analytic LJ EOS on sweep-like refreshes: single and paired
//! (the sweep's refresh of i and j in lockstep) from the old theta, and paired from the
//! sweep's first-order guess ([`AtDensity::guess_after`]); the minimum over repetitions,
//! so a loaded machine still gives the unloaded cost (docs/PERFORMANCE.md, parts 3 and 4):
//! `cargo run --release -p gendpde-potentials --example lj_solve_timing`.

use gendpde_potentials::{AtDensity, Eos, FixedDensity, LennardJones};
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let m = LennardJones::new(60.0);
    let mut cases = Vec::new();
    for i in 0..=9 {
        let theta = 0.5 * 10f64.powf(i as f64 / 9.0);
        for k in 0..=11 {
            let n = 0.05 + 0.05 * k as f64;
            for e in 0..4 {
                let du = 0.003 * m.cv * theta * if e % 2 == 0 { 1.0 } else { -1.0 } * 10f64.powi(-e);
                let at = m.at_density(n);
                let guess = at.guess_after(theta, (1.0 - 1.0 / m.cv(theta, n)) / theta, du);
                cases.push((at, m.u(theta, n) + du, theta, guess));
            }
        }
    }
    let time = |f: &dyn Fn() -> f64| {
        let best = (0..30)
            .map(|_| {
                let start = Instant::now();
                black_box(f());
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min);
        1e9 * best / cases.len() as f64
    };
    let single = || cases.iter().map(|c| c.0.theta_inv_tau(black_box(c.1), c.2).0).sum::<f64>();
    let paired = |first_order: bool| {
        let g = |c: &(_, f64, f64, f64)| if first_order { c.3 } else { c.2 };
        cases.chunks_exact(2).map(|c| c[0].0.theta_inv_tau_pair(&c[1].0, black_box([c[0].1, c[1].1]), [g(&c[0]), g(&c[1])])).map(|[x, y]| x.0 + y.0).sum::<f64>()
    };
    for _ in 0..3 {
        println!(
            "ns per solve: single {:.1}, paired {:.1}, paired from the first-order guess {:.1}",
            time(&single),
            time(&|| paired(false)),
            time(&|| paired(true))
        );
    }
}
