//! The 3D grid of ranks: its shape, this rank's place in it and its neighbours.

/// Ranks arranged as dims[0] x dims[1] x dims[2], x fastest.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProcGrid {
    pub dims: [usize; 3],
    pub coords: [usize; 3],
}

impl ProcGrid {
    pub fn new(dims: [usize; 3], rank: usize) -> Self {
        let coords = [rank % dims[0], (rank / dims[0]) % dims[1], rank / (dims[0] * dims[1])];
        Self { dims, coords }
    }

    fn rank_at(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }

    /// (rank one step along `dir` in `dim`, rank one step against it), periodic.
    pub fn neighbours(&self, dim: usize, dir: i32) -> (usize, usize) {
        let step = |s: i32| {
            let mut c = self.coords;
            c[dim] = (c[dim] as i64 + s as i64).rem_euclid(self.dims[dim] as i64) as usize;
            self.rank_at(c)
        };
        (step(dir), step(-dir))
    }

    /// The grid for `nprocs` ranks that minimises the sub-domain surface of a box of
    /// `lengths`, honouring the fixed counts in `fixed` (LAMMPS `processors`).
    pub fn choose(nprocs: usize, lengths: [f64; 3], fixed: [Option<usize>; 3]) -> Result<[usize; 3], String> {
        let mut best: Option<([usize; 3], f64)> = None;
        // larger counts first along x, then y: ties split x first
        for px in (1..=nprocs).rev() {
            if nprocs % px != 0 || fixed[0].is_some_and(|f| f != px) {
                continue;
            }
            for py in (1..=nprocs / px).rev() {
                if (nprocs / px) % py != 0 || fixed[1].is_some_and(|f| f != py) {
                    continue;
                }
                let pz = nprocs / px / py;
                if fixed[2].is_some_and(|f| f != pz) {
                    continue;
                }
                let (a, b, c) = (lengths[0] / px as f64, lengths[1] / py as f64, lengths[2] / pz as f64);
                let surface = a * b + b * c + a * c;
                if best.as_ref().is_none_or(|(_, s)| surface < *s - 1e-12 * s.abs()) {
                    best = Some(([px, py, pz], surface));
                }
            }
        }
        best.map(|(d, _)| d).ok_or_else(|| {
            format!("no processor grid with {nprocs} ranks matches processors {:?}", fixed.map(|f| f.map_or("*".to_string(), |v| v.to_string())))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbours_wrap() {
        let g = ProcGrid::new([2, 3, 1], 5);
        assert_eq!(g.coords, [1, 2, 0]);
        assert_eq!(g.neighbours(0, 1), (4, 4));
        assert_eq!(g.neighbours(1, 1), (1, 3));
        assert_eq!(g.neighbours(2, -1), (5, 5));
    }

    #[test]
    fn grid_minimises_surface() {
        assert_eq!(ProcGrid::choose(8, [10.0; 3], [None; 3]).unwrap(), [2, 2, 2]);
        assert_eq!(ProcGrid::choose(4, [40.0, 10.0, 10.0], [None; 3]).unwrap(), [4, 1, 1]);
        assert_eq!(ProcGrid::choose(3, [10.0; 3], [None; 3]).unwrap(), [3, 1, 1]);
        assert_eq!(ProcGrid::choose(4, [10.0; 3], [None, Some(4), None]).unwrap(), [1, 4, 1]);
        assert!(ProcGrid::choose(4, [10.0; 3], [Some(3), None, None]).is_err());
    }
}
