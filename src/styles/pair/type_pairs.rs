//! The app's per type-pair table: what `pair_coeff` lines set, with LAMMPS's `setflag`
//! (a pair no line set is None until a run refuses it).

/// One value per unordered pair of types 1..=n (LAMMPS's `setflag` with its
/// coefficient arrays), `None` where no `pair_coeff` set it.
#[derive(Clone, Debug, PartialEq)]
pub struct TypePairs<T> {
    n: usize,
    set: Vec<Option<T>>,
}

impl<T> Default for TypePairs<T> {
    fn default() -> Self {
        Self { n: 0, set: Vec::new() }
    }
}

impl<T: Clone> TypePairs<T> {
    /// The number of types the table holds (0 before the first `pair_coeff`).
    pub fn ntypes(&self) -> usize {
        self.n
    }

    /// The value of types `i`, `j` (1-based, either order).
    pub fn get(&self, i: usize, j: usize) -> Option<&T> {
        let (i, j) = (i.min(j), i.max(j));
        if i == 0 || j > self.n {
            return None;
        }
        self.set[(i - 1) * self.n + j - 1].as_ref()
    }

    /// Every set value.
    pub fn values(&self) -> impl Iterator<Item = &T> {
        self.set.iter().flatten()
    }

    /// The table for `n` types, or the first pair (i <= j) left unset.
    pub fn complete(&self, n: usize) -> Result<Vec<T>, (usize, usize)> {
        let mut flat = Vec::with_capacity(n * n);
        for i in 1..=n {
            for j in 1..=n {
                flat.push(self.get(i, j).cloned().ok_or((i.min(j), i.max(j)))?);
            }
        }
        Ok(flat)
    }

    /// Applies `f` to every set value.
    pub fn for_each_set(&mut self, f: impl FnMut(&mut T)) {
        self.set.iter_mut().flatten().for_each(f);
    }

    /// Sets the value of types `i`, `j` (1-based, `i <= j`) in a table of `n` types (a
    /// new `n` starts the table afresh).
    pub fn put(&mut self, n: usize, i: usize, j: usize, v: T) {
        if self.n != n {
            *self = Self { n, set: vec![None; n * n] };
        }
        self.set[(i - 1) * n + j - 1] = Some(v);
    }
}
