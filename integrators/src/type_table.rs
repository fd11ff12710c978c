//! Per type-pair coefficients for the inner loops: one flat ntypes x ntypes table (both
//! orders of a pair hold the same value), read by the particles' types without a branch
//! or an allocation.

/// A value for every ordered pair of types 1..=n.
#[derive(Clone, Debug, PartialEq)]
pub struct TypeTable<T> {
    n: usize,
    values: Vec<T>,
}

impl<T> TypeTable<T> {
    /// The table from its `n * n` values, row `i - 1` holding the pairs (i, 1..=n); None
    /// if the count is not a positive square of `n`.
    pub fn new(n: usize, values: Vec<T>) -> Option<Self> {
        (n > 0 && values.len() == n * n).then_some(Self { n, values })
    }

    /// The value of types `ti`, `tj` (1-based, as the particles' `kind`).
    #[inline(always)]
    pub fn get(&self, ti: u32, tj: u32) -> &T {
        &self.values[(ti as usize - 1) * self.n + tj as usize - 1]
    }

    /// The number of types.
    pub fn ntypes(&self) -> usize {
        self.n
    }

    /// Every value (each unordered pair of distinct types twice).
    pub fn iter(&self) -> impl Iterator<Item = &T> {
        self.values.iter()
    }

    /// The largest of `f` over all pairs.
    pub fn max_of(&self, f: impl Fn(&T) -> f64) -> f64 {
        self.values.iter().map(f).fold(0.0, f64::max)
    }
}
