//! Time per theta solve of the analytic LJ EOS, single against paired (the sweep's refresh
//! of i and j in lockstep), on sweep-like refreshes; the minimum over repetitions, so a
//! loaded machine still gives the unloaded cost (docs/PERFORMANCE.md, part 3):
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
                cases.push((m.at_density(n), m.u(theta, n) + du, theta));
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
    let paired = || cases.chunks_exact(2).map(|c| c[0].0.theta_inv_tau_pair(&c[1].0, black_box([c[0].1, c[1].1]), [c[0].2, c[1].2])).map(|[x, y]| x.0 + y.0).sum::<f64>();
    for _ in 0..3 {
        println!("ns per solve: single {:.1}, paired {:.1}", time(&single), time(&paired));
    }
}
