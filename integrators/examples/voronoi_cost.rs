//! Cost per cell-step of the Voronoi fluid models against N, with the tessellation's share
//! (docs/PERFORMANCE.md "Voronoi fluid particles: cost per cell-step"; run through
//! scripts/bench/voronoi_cost.sh):
//! `cargo run --release -p gendpde-integrators --example voronoi_cost -- N...`.
//!
//! The scene is examples/voronoi-vdw's (vdW cells of V~ = 20 at n~ = 1, T~ = 1.5, eta =
//! zeta = kappa = 1, k_B = 1, dt = 0.05) on a simple-cubic lattice perturbed by +-0.1
//! spacing (the exact lattice is the tessellation's slow degenerate case). A step is what
//! `fix nve/voronoi` does: the model's Heun step from the previous step's end frame plus
//! the end-of-step frame, so two tessellations. Times are this thread's CPU time
//! (/proc/thread-self/schedstat), so a loaded machine inflates them less than wall time.
//! Prints one line per N and model: `N model steps step_s frame_s`, the CPU seconds per
//! step and per end-of-step frame (the tessellation and the cell states; the predictor's
//! frame costs the same, so the tessellation's share is about 2 frame_s / step_s).

use gendpde_integrators::models::voronoi::{Cells, CellDissipation, FiniteVolume, CellFrame, Tessellation, CellTransport};
use gendpde_potentials::cell_energy::{vdw_entropy, WATER_C};
use gendpde_potentials::VdwCell;

/// CPU seconds this thread has run.
fn cpu() -> f64 {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").unwrap_or_default();
    text.split_whitespace().next().and_then(|ns| ns.parse::<f64>().ok()).map_or(f64::NAN, |ns| 1e-9 * ns)
}

/// Uniform numbers in [0, 1) (a 64-bit LCG: the scene only needs to be reproducible).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

const VOLUME: f64 = 20.0;
const MASS: f64 = 20.0;
const T: f64 = 1.5;

/// k^3 cells of the perturbed lattice with random velocities of temperature T.
fn scene(k: usize) -> (Cells, [f64; 3]) {
    let a = VOLUME.cbrt();
    let len = [k as f64 * a; 3];
    let mut g = Lcg(4928);
    let mut c = Cells::default();
    let vmax = (3.0 * T / MASS).sqrt();
    for (t, idx) in (0..k * k * k).enumerate() {
        let ijk = [idx % k, idx / k % k, idx / (k * k)];
        c.tag.push(t as u64 + 1);
        c.r.push(std::array::from_fn(|x| (ijk[x] as f64 + 0.5 + 0.2 * (g.next() - 0.5)) * a));
        c.p.push(std::array::from_fn(|_| MASS * vmax * (2.0 * g.next() - 1.0)));
        c.m.push(MASS);
    }
    let tess = Tessellation::build(&c.r, [0.0; 3], len).unwrap_or_else(|e| panic!("{e}"));
    c.s = tess.volumes.iter().map(|&v| vdw_entropy(WATER_C, MASS, v, T)).collect();
    (c, len)
}

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).map(|a| a.parse().unwrap_or_else(|_| panic!("not a cell count: {a}"))).collect();
    let energy = VdwCell { c: WATER_C };
    let transport = CellTransport { eta: 1.0, zeta: 1.0, kappa: 1.0, kb: 1.0 };
    let (lo, dt) = ([0.0; 3], 0.05);
    for n in sizes {
        let k = (n as f64).cbrt().round() as usize;
        let (start, len) = scene(k);
        for (name, dissipation) in [("fv", CellDissipation::Hydrodynamic), ("dpd", CellDissipation::Dpd { gamma: 1.0 })] {
            let model = FiniteVolume { energy, transport, dissipation, seed: 4928 };
            let mut cells = start.clone();
            let mut frame = CellFrame::new(&cells, &energy, lo, len).unwrap_or_else(|e| panic!("{e}"));
            let steps = (60_000 / cells.len()).clamp(2, 50) as u64;
            let (mut total, mut end) = (0.0, 0.0);
            for step in 0..steps {
                let t0 = cpu();
                model.step(&mut cells, &frame, lo, len, dt, step).unwrap_or_else(|e| panic!("{e}"));
                let t1 = cpu();
                frame = CellFrame::new(&cells, &energy, lo, len).unwrap_or_else(|e| panic!("{e}"));
                let t2 = cpu();
                (total, end) = (total + t2 - t0, end + t2 - t1);
            }
            let (per_step, per_frame) = (total / steps as f64, end / steps as f64);
            println!("{} {name} {steps} {per_step:.6e} {per_frame:.6e}", cells.len());
        }
    }
}
