//! How the blocks of an averaging fix combine: LAMMPS's `ave one` (each block alone),
//! `ave running` (all blocks so far) and `ave window M` (the last M blocks), shared by fix
//! ave/time, ave/chunk and ave/histo.

use crate::base::args::Args;
use gendpde_io::ScriptError;
use std::collections::VecDeque;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Ave {
    One,
    Running,
    Window(usize),
}

#[derive(Debug)]
pub struct Blocks {
    ave: Ave,
    /// Sum of the blocks so far (ave running) or of the last M (ave window).
    total: Vec<f64>,
    /// The last M blocks (ave window).
    window: VecDeque<Vec<f64>>,
    /// Blocks so far (ave running).
    running: u64,
}

impl Default for Blocks {
    fn default() -> Self {
        Self { ave: Ave::One, total: Vec::new(), window: VecDeque::new(), running: 0 }
    }
}

impl Blocks {
    /// The words after the keyword `ave`: one, running or window M.
    pub fn parse(a: &mut Args) -> Result<Self, ScriptError> {
        let ave = match a.word("one, running or window")? {
            "one" => Ave::One,
            "running" => Ave::Running,
            "window" => match a.u64("the number of blocks M")? {
                0 => return Err(a.err("ave window M: M must be positive")),
                m => Ave::Window(usize::try_from(m).map_err(|_| a.err(format!("ave window {m}: too many blocks")))?),
            },
            m => return Err(a.err(format!("expected ave one, running or window, got '{m}'"))),
        };
        Ok(Self { ave, ..Self::default() })
    }

    /// How many of the last blocks a combination holds (all: `usize::MAX`).
    pub fn span(&self) -> usize {
        match self.ave {
            Ave::One => 1,
            Ave::Running => usize::MAX,
            Ave::Window(m) => m,
        }
    }

    /// Combines a block with the earlier ones: the sum and the number of blocks in it.
    pub fn combine(&mut self, block: Vec<f64>) -> (Vec<f64>, f64) {
        if self.ave == Ave::One {
            return (block, 1.0);
        }
        if self.total.len() != block.len() {
            (self.total, self.running) = (vec![0.0; block.len()], 0);
            self.window.clear();
        }
        self.total.iter_mut().zip(&block).for_each(|(t, x)| *t += x);
        self.running += 1;
        if let Ave::Window(m) = self.ave {
            self.window.push_back(block);
            if self.window.len() > m {
                let oldest = self.window.pop_front().expect("longer than m > 0");
                self.total.iter_mut().zip(&oldest).for_each(|(t, x)| *t -= x);
            }
            return (self.total.clone(), self.window.len() as f64);
        }
        (self.total.clone(), self.running as f64)
    }
}
