//! The clock of a simulation: step, time, the current run's span and the noise key.

/// Step and time, advanced after every step by [`crate::Physics::advance`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Clock {
    pub step: u64,
    pub time: f64,
    /// The first and last step of the current run (LAMMPS's beginstep, endstep), over
    /// which the thermostat pair styles ramp their temperature.
    pub run: [u64; 2],
    /// What `reset_timestep` moved the step by, summed (wrapping): the counter-based noise
    /// is keyed by [`Clock::noise_step`], which a reset leaves running on, so no stretch of
    /// noise repeats (kept in restart files).
    pub noise_shift: u64,
}

impl Clock {
    /// The step the noise of step `step` is keyed by: the step count as if no
    /// `reset_timestep` had moved the clock.
    pub fn noise_step(&self, step: u64) -> u64 {
        step.wrapping_add(self.noise_shift)
    }

    /// One step of `dt` done.
    pub fn advance(&mut self, dt: f64) {
        self.step += 1;
        self.time += dt;
    }
}
