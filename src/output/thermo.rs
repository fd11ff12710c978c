//! Thermodynamic output: keywords, their values and LAMMPS's line format.
//!
//! temp = sum p^2/m / (3N - 3) k_B; tint = mean theta; press = the virial pressure of
//! the conservative force (eq 52; dissipative and random forces are not included; for
//! Voronoi cells (sum 3 p V + sum P^2/M) / 3 V_T, integrators/src/models/voronoi/), in
//! LAMMPS's pressure unit (bar in metal, atm in real); density = mass / volume (g/cm^3 in
//! metal and real); tpcpu, spcpu = simulated time and steps per CPU second since the
//! previous thermo line of the run;
//! nmean = mean local density n_i (the density the EOS reads);
//! pe = sum u for GenDPDE (the internal energy holds the EOS's configurational energy),
//! the pair energy for LAMMPS's pairwise styles (whose u = uCond + uMech is reported by
//! compute dpd, c_ID[1..5]);
//! ke = sum p^2/2m; etotal = pe + ke; edrift = (E - E0)/|E0| since the first setup;
//! pxtot, pytot, pztot = total momentum. Sums are decomposition-independent (exact_sums).
//! With `thermo_modify norm yes` (the lj default) pe, ke and etotal are per particle.
//! With `thermo_modify temp ID` (a compute temp of a group), temp, ke, etotal and the
//! kinetic part of the pressure are those of the group, as in LAMMPS.

use crate::model::sim::Sim;
use crate::output::schedule::{Frame, RunOutput, Span};
pub use crate::output::thermo_settings::ThermoConfig;
use crate::output::thermo_settings::Mark;
use crate::model::{group_functions, per_atom};
use crate::styles::compute::{self, Temperature};
use crate::styles::fix::FixStyle;
use gendpde_engine::exact_sums;
use gendpde_integrators::{FixRecord, NphState, System};
use gendpde_io::{format_printf, Variables};

impl RunOutput for ThermoConfig {
    /// At the setup, every `every` steps and at the last step of the run.
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        if step == run.first {
            return Some(step);
        }
        let periodic = if self.every > 0 { step.next_multiple_of(self.every) } else { run.last };
        (step <= run.last).then_some(periodic.min(run.last))
    }

    /// One value line on the screen and in the log.
    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let step = f.sys.clock.step;
        if step == f.run.first {
            self.builds_at_setup = [f.sys.lists.count, f.sys.lists.dangerous];
        }
        self.steps_left = f.run.last.saturating_sub(step);
        let values = values(self, f)?;
        f.out.line(&value_line(&self.keywords, &values, self.float_format.as_deref()));
        self.last = Some(Mark { step: f.sys.clock.step, time: f.sys.clock.time, cpu: f.cpu });
        if self.flush {
            f.out.sync();
        }
        Ok(())
    }
}

/// The values of thermo `keywords` at the frame's step (collective: every rank calls).
pub fn values(config: &ThermoConfig, f: &Frame) -> Result<Vec<f64>, String> {
    let ctx = ThermoContext::new(f.sim, f.sys, config, f.vars, f.sys.clock.step - f.run.first, f.cpu);
    let resolve = |name: &str| ctx.keyword(name);
    let mut values = Vec::with_capacity(config.keywords.len());
    for k in &config.keywords {
        let published = compute::reference(k).filter(|r| r.0 == 'f').and_then(|r| f.sim.fix_values.get(r.1).map(|v| (r.1, v.freq)));
        if let Some((id, freq)) = published.filter(|(_, freq)| *freq > 0 && f.sys.clock.step % freq != 0) {
            return Err(format!("thermo keyword {k}: Thermo fix {id} not computed at compatible time (its values change every {freq} steps)"));
        }
        let v = match ctx.keyword(k) {
            Some(v) => v,
            None => gendpde_io::evaluate(k, f.vars, &resolve).map_err(|e| format!("thermo keyword {k}: {e}"))?,
        };
        values.push(v);
    }
    Ok(values)
}

/// Global sums a thermo line reads.
#[derive(Clone, Copy, Debug)]
pub struct Observables {
    pub atoms: f64,
    pub ke: f64,
    pub u: f64,
    pub theta: f64,
    pub mv2: f64,
    /// Diagonal of sum p p^T / m and of the virial (the traces are `mv2` and the scalar
    /// virial).
    pub mv2_diag: [f64; 3],
    pub virial_diag: [f64; 3],
    pub mass: f64,
    pub volume: f64,
    /// Total momentum.
    pub momentum: [f64; 3],
    /// Pair energy of pairwise styles.
    pub epair: f64,
    /// sum uCond (classic DPDE) and sum 1/theta.
    pub u_cond: f64,
    pub inv_theta: f64,
    /// sum of the local densities n_i the EOS reads (zero for pairwise styles).
    pub n: f64,
}

impl Observables {
    /// Sums over all particles of all ranks, independent of the decomposition.
    pub fn measure(sys: &System) -> Self {
        let s = &sys.store;
        let opt = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(0.0);
        let rows = (0..s.nlocal).map(|i| {
            let (p, m) = (s.p[i], s.mass[i]);
            let (u_cond, epair) = (opt(&s.u_cond, i), opt(&s.epair, i));
            let w = s.virial.get(i).copied().unwrap_or_default();
            let q = [p[0] * p[0] / m, p[1] * p[1] / m, p[2] * p[2] / m];
            [1.0, q[0], q[1], q[2], s.u[i], s.theta[i], m, w[0], w[1], w[2], p[0], p[1], p[2], epair, u_cond, 1.0 / s.theta[i], opt(&s.n, i)]
        });
        let sums = exact_sums(sys.comm.transport(), rows);
        Self {
            atoms: sums[0],
            ke: 0.5 * (sums[1] + sums[2] + sums[3]),
            u: sums[4],
            theta: sums[5],
            mv2: sums[1] + sums[2] + sums[3],
            mv2_diag: [sums[1], sums[2], sums[3]],
            virial_diag: [sums[7], sums[8], sums[9]],
            mass: sums[6],
            volume: sys.domain.volume(),
            momentum: [sums[10], sums[11], sums[12]],
            epair: sums[13],
            u_cond: sums[14],
            inv_theta: sums[15],
            n: sums[16],
        }
    }

    /// Total energy: K + sum u + pair energy (the last is zero for GenDPDE).
    pub fn energy(&self) -> f64 {
        self.ke + self.u + self.epair
    }

    /// The kinetic sums of all particles, LAMMPS's thermo_temp: dof = 3N - 3 (the
    /// off-diagonal terms are not measured).
    pub fn kinetic(&self) -> Temperature {
        let [xx, yy, zz] = self.mv2_diag;
        Temperature { dof: 3.0 * self.atoms - 3.0, tensor: [xx, yy, zz, 0.0, 0.0, 0.0] }
    }

    /// LAMMPS's temperature of group all: dof = 3N - 3.
    pub fn temperature(&self, kb: f64) -> f64 {
        self.kinetic().value(kb)
    }

    pub fn pressure(&self) -> f64 {
        self.pressure_with(&self.kinetic())
    }

    /// The pressure with the kinetic part of `k` (LAMMPS: that of the thermo temperature).
    pub fn pressure_with(&self, k: &Temperature) -> f64 {
        (k.mv2() + self.virial_diag.iter().sum::<f64>()) / (3.0 * self.volume)
    }

    /// Diagonal component `a` of the pressure tensor (LAMMPS's pxx, pyy, pzz).
    pub fn pressure_component(&self, k: &Temperature, a: usize) -> f64 {
        (k.tensor[a] + self.virial_diag[a]) / self.volume
    }
}

/// Context for one evaluation of thermo keywords.
pub struct ThermoContext<'a> {
    sim: &'a Sim,
    sys: &'a System,
    /// The script's variables (atom-style inputs of compute reduce).
    vars: &'a Variables,
    obs: Observables,
    /// Kinetic sums of the thermo temperature (thermo_modify temp).
    kinetic: Temperature,
    norm: bool,
    /// The previous thermo line of this run (None at its first).
    last: Option<Mark>,
    elapsed: u64,
    cpu: f64,
    /// Builds and dangerous builds since the run's set-up; steps of the run left.
    builds: [u64; 2],
    steps_left: u64,
}

impl<'a> ThermoContext<'a> {
    /// Measures `sys` of `sim` (collective) for the thermo settings `config`; `elapsed`
    /// steps and `cpu` seconds of the run.
    pub fn new(sim: &'a Sim, sys: &'a System, config: &ThermoConfig, vars: &'a Variables, elapsed: u64, cpu: f64) -> Self {
        let obs = Observables::measure(sys);
        let temp = config.temp.as_deref().and_then(|id| compute::find(&sim.computes, id));
        let kinetic = temp.and_then(|c| per_atom::evaluate(sim, sys, vars, &|_| None, |e| c.temperature(e))).unwrap_or_else(|| obs.kinetic());
        let last = config.last.filter(|_| elapsed > 0);
        let (b, lists) = (config.builds_at_setup, &sys.lists);
        let builds = [lists.count.saturating_sub(b[0]), lists.dangerous.saturating_sub(b[1])];
        Self { sim, sys, vars, obs, kinetic, norm: config.norm, last, elapsed, cpu, builds, steps_left: config.steps_left }
    }

    /// Value of a built-in keyword; None if the name is not one.
    pub fn keyword(&self, name: &str) -> Option<f64> {
        let o = &self.obs;
        let per = |x: f64| if self.norm && o.atoms > 0.0 { x / o.atoms } else { x };
        let (d, units) = (&self.sys.domain, &self.sim.units);
        let l = d.len();
        let press = o.pressure_with(&self.kinetic);
        let etotal = self.potential() + 0.5 * self.kinetic.mv2();
        if let Some(setting) = name.strip_prefix(gendpde_io::functions::SETTING) {
            return self.setting(setting);
        }
        Some(match name {
            "step" => self.sys.clock.step as f64,
            "elapsed" => self.elapsed as f64,
            "elaplong" => self.sys.clock.step.saturating_sub(self.sys.clock.run[0]) as f64,
            "time" => self.sys.clock.time,
            "dt" => self.sim.dt,
            "cpu" => self.cpu,
            "tpcpu" => self.rate(|m| self.sys.clock.time - m.time),
            "spcpu" => self.rate(|m| (self.sys.clock.step - m.step) as f64),
            "atoms" => o.atoms,
            "temp" => self.kinetic.value(self.sim.units.kb),
            "tint" => if o.atoms > 0.0 { o.theta / o.atoms } else { 0.0 },
            "nmean" => if o.atoms > 0.0 { o.n / o.atoms } else { 0.0 },
            "press" => press * units.nktv2p,
            "pxx" => o.pressure_component(&self.kinetic, 0) * units.nktv2p,
            "pyy" => o.pressure_component(&self.kinetic, 1) * units.nktv2p,
            "pzz" => o.pressure_component(&self.kinetic, 2) * units.nktv2p,
            "pe" => per(self.potential()),
            "evdwl" | "epair" => per(self.potential()),
            "ecoul" | "elong" | "emol" | "ebond" | "eangle" | "edihed" | "eimp" => 0.0,
            "nbuild" => self.builds[0] as f64,
            "ndanger" => self.builds[1] as f64,
            "cpuremain" if self.elapsed > 0 => self.cpu * self.steps_left as f64 / self.elapsed as f64,
            "cpuremain" => 0.0,
            "ke" => per(0.5 * self.kinetic.mv2()),
            "etotal" => per(etotal),
            "enthalpy" => per(etotal + press * o.volume),
            "ecouple" => self.sys.fixes.any_barostat().map_or(0.0, |st| self.barostat_energy(st)),
            "econserve" => per(etotal) + self.sys.fixes.any_barostat().map_or(0.0, |st| self.barostat_energy(st)),
            "edrift" => match self.sim.energy0 {
                Some(e0) if e0 != 0.0 => (o.energy() - e0) / e0.abs(),
                _ => 0.0,
            },
            "vol" => o.volume,
            "density" => o.mass / units.mvv2e * units.mv2d / o.volume,
            "lx" | "cella" => l[0],
            "ly" | "cellb" => l[1],
            "lz" | "cellc" => l[2],
            "xlo" => d.lo[0],
            "xhi" => d.hi[0],
            "ylo" => d.lo[1],
            "yhi" => d.hi[1],
            "zlo" => d.lo[2],
            "zhi" => d.hi[2],
            // LAMMPS zeroes beginstep and endstep after a run
            gendpde_io::functions::RUN_BEGIN => if self.sim.running { self.sys.clock.run[0] as f64 } else { 0.0 },
            gendpde_io::functions::RUN_END => if self.sim.running { self.sys.clock.run[1] as f64 } else { 0.0 },
            gendpde_io::functions::RUN_ACTIVE => f64::from(u8::from(self.sim.running)),
            "pxtot" => o.momentum[0],
            "pytot" => o.momentum[1],
            "pztot" => o.momentum[2],
            _ if name.ends_with(')') => return group_functions::value(self.sim, name),
            _ => return self.compute(name),
        })
    }

    /// The `extract_setting()` values of the system.
    fn setting(&self, name: &str) -> Option<f64> {
        Some(match name {
            "box_exist" => 1.0,
            "world_size" => self.sys.comm.size() as f64,
            "world_rank" => self.sys.comm.rank() as f64,
            "ntypes" => self.sim.ntypes as f64,
            "nlocal" => self.sys.store.nlocal as f64,
            _ => return None,
        })
    }

    /// `diff` of the previous thermo line of the run per CPU second since it (0 at the
    /// first line of a run, as LAMMPS).
    fn rate(&self, diff: impl Fn(&Mark) -> f64) -> f64 {
        let Some(m) = &self.last else { return 0.0 };
        let (d, cpu) = (diff(m), self.cpu - m.cpu);
        if d > 0.0 && cpu > 0.0 { d / cpu } else { 0.0 }
    }

    /// `pe`: the pair energy for LAMMPS's pairwise styles, sum u for GenDPDE.
    fn potential(&self) -> f64 {
        if self.sim.pe_is_pair() { self.obs.epair } else { self.obs.u }
    }

    /// `c_ID` or `c_ID[k]` of a compute (`styles::compute`), `f_ID` or `f_ID[k]` of an
    /// output fix (`output::fix`), `f_ID` of a `fix heat/reservoir` or `fix nph`.
    fn compute(&self, name: &str) -> Option<f64> {
        if let Some(('f', id, index)) = compute::reference(name) {
            if let Some(values) = self.sim.fix_values.get(id) {
                let (v, extensive) = match index {
                    None => values.scalar?,
                    Some(k) => *values.vector.get(k.checked_sub(1)?)?,
                };
                return Some(if extensive && self.norm && self.obs.atoms > 0.0 { v / self.obs.atoms } else { v });
            }
        }
        if let Some(id) = name.strip_prefix("f_") {
            if let Some(st) = self.sys.fixes.barostat(id) {
                let e = self.barostat_energy(st);
                return Some(if self.norm && self.obs.atoms > 0.0 { e / self.obs.atoms } else { e });
            }
            return self.reservoir_heat(id);
        }
        let (sim, sys) = (self.sim, self.sys);
        let (v, extensive) = per_atom::evaluate(sim, sys, self.vars, &|n| self.keyword(n), |e| compute::global(&sim.computes, e, name))?.ok()?;
        Some(if extensive && self.norm && self.obs.atoms > 0.0 { v / self.obs.atoms } else { v })
    }

    /// The energy of the `fix nph` barostat in state `st` (LAMMPS's `ecouple`: never per
    /// particle).
    fn barostat_energy(&self, st: &NphState) -> f64 {
        let nph = self.sim.fixes.iter().find_map(|f| match &f.style {
            FixStyle::Nph { nph, .. } if nph.id == st.id => Some(nph),
            _ => None,
        });
        nph.map_or(0.0, |b| b.energy(self.sys, st))
    }

    /// Energy reservoir `id` has put into the particles since it was defined (extensive:
    /// per particle with `thermo_modify norm yes`, as LAMMPS's fix energies).
    fn reservoir_heat(&self, id: &str) -> Option<f64> {
        let Some(&FixRecord::Reservoir(total)) = self.sys.fixes.get(id) else { return None };
        Some(if self.norm && self.obs.atoms > 0.0 { total / self.obs.atoms } else { total })
    }
}

/// Whether a keyword prints as an integer.
pub fn is_integer(name: &str) -> bool {
    matches!(name, "step" | "elapsed" | "elaplong" | "atoms" | "nbuild" | "ndanger")
}

/// Column heading of a keyword, as LAMMPS names it.
pub fn heading(name: &str) -> String {
    match name {
        "step" => "Step".into(),
        "elapsed" => "Elapsed".into(),
        "elaplong" => "Elaplong".into(),
        "time" => "Time".into(),
        "dt" => "Dt".into(),
        "cpu" => "CPU".into(),
        "tpcpu" => "T/CPU".into(),
        "spcpu" => "S/CPU".into(),
        "enthalpy" => "Enthalpy".into(),
        "ecouple" => "Ecouple".into(),
        "econserve" => "Econserve".into(),
        "xlo" => "Xlo".into(),
        "xhi" => "Xhi".into(),
        "ylo" => "Ylo".into(),
        "yhi" => "Yhi".into(),
        "zlo" => "Zlo".into(),
        "zhi" => "Zhi".into(),
        "cella" => "Cella".into(),
        "cellb" => "Cellb".into(),
        "cellc" => "Cellc".into(),
        "atoms" => "Atoms".into(),
        "temp" => "Temp".into(),
        "tint" => "Tint".into(),
        "nmean" => "Nmean".into(),
        "press" => "Press".into(),
        "pxx" => "Pxx".into(),
        "pyy" => "Pyy".into(),
        "pzz" => "Pzz".into(),
        "pe" => "PotEng".into(),
        "evdwl" => "E_vdwl".into(),
        "ecoul" => "E_coul".into(),
        "epair" => "E_pair".into(),
        "elong" => "E_long".into(),
        "emol" => "E_mol".into(),
        "ebond" => "E_bond".into(),
        "eangle" => "E_angle".into(),
        "edihed" => "E_dihed".into(),
        "eimp" => "E_impro".into(),
        "nbuild" => "Nbuild".into(),
        "ndanger" => "Ndanger".into(),
        "cpuremain" => "CPULeft".into(),
        "ke" => "KinEng".into(),
        "etotal" => "TotEng".into(),
        "edrift" => "Edrift".into(),
        "vol" => "Volume".into(),
        "density" => "Density".into(),
        "lx" => "Lx".into(),
        "ly" => "Ly".into(),
        "lz" => "Lz".into(),
        "pxtot" => "Pxtot".into(),
        "pytot" => "Pytot".into(),
        "pztot" => "Pztot".into(),
        other => other.into(),
    }
}

/// The heading line: integers centred in 11 columns, floats in 14, one space apart.
pub fn header_line(keys: &[String]) -> String {
    let cols: Vec<String> = keys
        .iter()
        .map(|k| if is_integer(k) { format!("{:^11}", heading(k)) } else { format!("{:^14}", heading(k)) })
        .collect();
    cols.join(" ")
}

/// One value line: integers as "%10d ", floats as %.8g with a sign column, left in 14.
pub fn value_line(keys: &[String], values: &[f64], float_format: Option<&str>) -> String {
    let cols: Vec<String> = keys
        .iter()
        .zip(values)
        .map(|(k, &v)| {
            if is_integer(k) {
                format!("{:10} ", v as i64)
            } else if let Some(f) = float_format {
                format_printf(f, v).unwrap_or_else(|_| format!("{v}"))
            } else {
                let g = gendpde_io::format_g(v, 8);
                let signed = if g.starts_with('-') { g } else { format!(" {g}") };
                format!("{signed:<14}")
            }
        })
        .collect();
    cols.join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Columns of a LAMMPS 22 Jul 2025 log (thermo_style custom step time temp pe ke
    /// etotal press atoms vol), reproduced character for character.
    #[test]
    fn lines_match_lammps_layout() {
        let keys: Vec<String> = ["step", "time", "temp", "pe", "ke", "etotal", "press", "atoms", "vol"].map(String::from).to_vec();
        assert_eq!(
            header_line(&keys),
            "   Step          Time           Temp          PotEng         KinEng         TotEng         Press         Atoms        Volume    "
        );
        let v = [0.0, 0.0, 3.0, -6.7733681, 4.4824219, -2.2909462, -3.7126102, 256.0, 303.24568];
        assert_eq!(
            value_line(&keys, &v, None),
            "         0   0              3             -6.7733681      4.4824219     -2.2909462     -3.7126102            256   303.24568    "
        );
    }
}
