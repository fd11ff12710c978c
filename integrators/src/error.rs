//! A step that cannot continue, naming the particle and the state that failed. `step`
//! is the last completed step: the failure happened while advancing from it.
//!
//! Which failure is reported does not depend on the rank count: every pass over the
//! particles keeps the failure of lowest tag ([`lowest`]), and [`crate::System::settle`]
//! agrees on the lowest over the ranks and hands its error to every rank.

use gendpde_engine::{Particles, Transport};
use gendpde_potentials::EosError;
use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub struct StepError {
    pub tag: u64,
    pub step: u64,
    pub u: f64,
    pub n: f64,
    pub theta: f64,
    pub what: String,
}

/// Of two outcomes, the failure of the particle of lower tag (`a` on a tie).
pub fn lowest(a: Result<(), StepError>, b: Result<(), StepError>) -> Result<(), StepError> {
    match (a, b) {
        (Err(a), Err(b)) if b.tag < a.tag => Err(b),
        (Err(a), _) => Err(a),
        (Ok(()), b) => b,
    }
}

impl StepError {
    /// An EOS failure of particle `i`.
    pub fn eos(s: &Particles, i: usize, step: u64, e: EosError) -> Self {
        let (u, n, theta, what) = match e {
            EosError::NonPositiveTheta { u, n, theta } => {
                let what = if theta.is_finite() && u.is_finite() { "particle temperature is not positive" } else { "particle state is not finite" };
                (u, n, theta, what.to_string())
            }
            EosError::Outside { u, n, why } => (u, n, f64::NAN, why),
        };
        Self { tag: s.tag[i], step, u, n, theta, what }
    }

    /// Particle `i` reached a state the dynamics cannot continue from.
    pub fn state(s: &Particles, i: usize, step: u64, what: &str) -> Self {
        let n = s.n.get(i).copied().unwrap_or(f64::NAN);
        Self { tag: s.tag[i], step, u: s.u[i], n, theta: s.theta[i], what: what.into() }
    }

    /// A failure of the whole system (no particle; tag 0), the same on every rank.
    pub fn global(step: u64, what: &str) -> Self {
        Self { tag: 0, step, u: f64::NAN, n: f64::NAN, theta: f64::NAN, what: what.into() }
    }

    /// The error of the first rank that passes `Some`, on every rank (at least one must).
    pub fn agree(t: &dyn Transport, mine: Option<StepError>) -> StepError {
        let words = mine.map(|e| e.to_words()).unwrap_or_default();
        let lens = t.all_gather(&[words.len() as u64]);
        let width = lens.iter().copied().max().unwrap_or(0) as usize;
        let from = lens.iter().position(|&l| l > 0).expect("a rank holds the error");
        let mut padded = words;
        padded.resize(width, 0);
        let all = t.all_gather(&padded);
        Self::from_words(&all[from * width..(from + 1) * width])
    }

    /// tag, step, u, n, theta, the length of `what` and its bytes, 8 to a word.
    fn to_words(&self) -> Vec<u64> {
        let mut w = vec![self.tag, self.step, self.u.to_bits(), self.n.to_bits(), self.theta.to_bits(), self.what.len() as u64];
        w.extend(self.what.as_bytes().chunks(8).map(|c| {
            let mut b = [0u8; 8];
            b[..c.len()].copy_from_slice(c);
            u64::from_le_bytes(b)
        }));
        w
    }

    fn from_words(w: &[u64]) -> Self {
        let bytes: Vec<u8> = w[6..].iter().flat_map(|x| x.to_le_bytes()).take(w[5] as usize).collect();
        let f = f64::from_bits;
        Self { tag: w[0], step: w[1], u: f(w[2]), n: f(w[3]), theta: f(w[4]), what: String::from_utf8_lossy(&bytes).into_owned() }
    }

    /// "particle TAG WHEN: what (u, n, theta); advice".
    pub(crate) fn describe(&self, f: &mut fmt::Formatter<'_>, when: fmt::Arguments) -> fmt::Result {
        if self.tag == 0 {
            return write!(f, "{when}: {}", self.what);
        }
        write!(
            f,
            "particle {} {when}: {} (u = {:.9e}, n = {:.9e}, theta = {:.9e}); \
             a smaller timestep, a larger C_V or weaker noise may help",
            self.tag, self.what, self.u, self.n, self.theta
        )
    }
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.describe(f, format_args!("during step {}", self.step + 1))
    }
}

impl std::error::Error for StepError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_error_travels_through_words_unchanged() {
        let e = StepError { tag: 110, step: 5, u: -1.5, n: f64::NAN, theta: -0.25, what: "particle temperature is not positive".into() };
        let back = StepError::from_words(&e.to_words());
        assert_eq!((back.tag, back.step, back.u, back.theta, &back.what), (110, 5, -1.5, -0.25, &e.what));
        assert!(back.n.is_nan());
    }

    #[test]
    fn the_lower_tag_wins_whatever_the_order() {
        let e = |tag| Err(StepError { tag, step: 0, u: 0.0, n: 0.0, theta: 0.0, what: String::new() });
        assert_eq!(lowest(e(110), e(1)).unwrap_err().tag, 1);
        assert_eq!(lowest(e(1), e(110)).unwrap_err().tag, 1);
        assert_eq!(lowest(Ok(()), e(7)).unwrap_err().tag, 7);
        assert!(lowest(Ok(()), Ok(())).is_ok());
    }
}
