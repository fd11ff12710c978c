//! The periodic Voronoi tessellation of the particle positions (Serrano & Español, Secs III
//! and X): per cell its volume, per face the two cells, the area A, the unit normal, the
//! distance R between the generators and the centroid offset c (eqs 22, 127, 128).
//!
//! Built by the `meshless_voronoi` crate (exact predicates on degenerate input; the measured
//! choice is in docs/models/voronoi.md). Each face is kept once, so a pair term
//! added to one cell and subtracted from the other conserves exactly.

use glam::DVec3;
use meshless_voronoi::{Dimensionality, Voronoi};
use std::fmt;

/// One face between cells `i` and `j`, seen from `i` (j's generator taken at its periodic
/// image nearest through this face).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Face {
    pub i: usize,
    pub j: usize,
    /// A_ij.
    pub area: f64,
    /// Unit normal from R_i towards R_j (the image): -e_ij of the paper.
    pub normal: [f64; 3],
    /// R_ij = |R_j - R_i|.
    pub dist: f64,
    /// c_ij: face centroid minus (R_i + R_j)/2 (eq 22, 128), the same seen from j.
    pub offset: [f64; 3],
    /// The periodic image of j across this face, in box lengths (-1, 0 or 1 each): two
    /// cells of a small box can share faces through several images.
    pub image: [i8; 3],
}

impl Face {
    /// e_ij = (R_i - R_j)/R_ij as seen from `cell` (i or j), and the sign of that view.
    #[inline]
    pub fn e_from(&self, cell: usize) -> ([f64; 3], f64) {
        let s = if cell == self.i { -1.0 } else { 1.0 };
        ([s * self.normal[0], s * self.normal[1], s * self.normal[2]], s)
    }
}

/// Why a tessellation could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum TessellationError {
    /// A box length is not positive and finite.
    BadBox([f64; 3]),
    /// A position is not finite.
    BadPosition(usize),
    /// A cell came out empty or not finite (coincident generators).
    EmptyCell(usize),
    /// A cell touches its own periodic image: too few particles for the box.
    SelfImage(usize),
}

impl fmt::Display for TessellationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadBox(l) => write!(f, "Voronoi tessellation needs positive box lengths, got {l:?}"),
            Self::BadPosition(i) => write!(f, "Voronoi tessellation: position of particle {i} is not finite"),
            Self::EmptyCell(i) => write!(f, "Voronoi cell of particle {i} is empty (coincident particles?)"),
            Self::SelfImage(i) => write!(f, "Voronoi cell of particle {i} touches its own periodic image (too few particles)"),
        }
    }
}

impl std::error::Error for TessellationError {}

/// Volumes and faces of every cell of a fully periodic box.
#[derive(Clone, Debug, Default)]
pub struct Tessellation {
    pub volumes: Vec<f64>,
    pub faces: Vec<Face>,
    /// Cell k's faces are `face_index[face_start[k]..face_start[k + 1]]`, in face order.
    face_start: Vec<usize>,
    face_index: Vec<usize>,
}

impl Tessellation {
    /// Tessellates `positions` (wrapped into the box [lo, lo + len) first) periodically.
    pub fn build(positions: &[[f64; 3]], lo: [f64; 3], len: [f64; 3]) -> Result<Self, TessellationError> {
        if len.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(TessellationError::BadBox(len));
        }
        let width = DVec3::from(len);
        let mut gens = Vec::with_capacity(positions.len());
        for (k, p) in positions.iter().enumerate() {
            if p.iter().any(|x| !x.is_finite()) {
                return Err(TessellationError::BadPosition(k));
            }
            let mut r = (DVec3::from(*p) - DVec3::from(lo)).rem_euclid(width);
            // rem_euclid can round up to the width itself.
            r = DVec3::select(r.cmplt(width), r, DVec3::ZERO);
            gens.push(r);
        }
        let vor = Voronoi::build(&gens, DVec3::ZERO, width, Dimensionality::ThreeD, true);
        let mut volumes = Vec::with_capacity(gens.len());
        for (k, c) in vor.cells().iter().enumerate() {
            let v = c.volume();
            if !(v.is_finite() && v > 0.0) {
                return Err(TessellationError::EmptyCell(k));
            }
            volumes.push(v);
        }
        let mut faces = Vec::with_capacity(vor.faces().len() / 2 + 1);
        for f in vor.faces() {
            let (i, Some(j)) = (f.left(), f.right()) else { continue };
            let shift = f.shift().unwrap_or(DVec3::ZERO);
            if i == j && f.area() > 0.0 {
                return Err(TessellationError::SelfImage(i));
            }
            // Faces through the periodic boundary come once from each side: keep one.
            if (f.shift().is_some() && i > j) || f.area() <= 0.0 {
                continue;
            }
            let (ri, rj) = (gens[i], gens[j] + shift);
            let d = rj - ri;
            let dist = d.length();
            let offset = f.centroid() - 0.5 * (ri + rj);
            let image = std::array::from_fn(|a| (shift[a] / width[a]).round() as i8);
            faces.push(Face { i, j, area: f.area(), normal: (d / dist).into(), dist, offset: offset.into(), image });
        }
        let n = gens.len();
        let mut face_start = vec![0usize; n + 1];
        for f in &faces {
            face_start[f.i + 1] += 1;
            face_start[f.j + 1] += 1;
        }
        for k in 0..n {
            face_start[k + 1] += face_start[k];
        }
        let mut fill = face_start.clone();
        let mut face_index = vec![0usize; face_start[n]];
        for (k, f) in faces.iter().enumerate() {
            for c in [f.i, f.j] {
                face_index[fill[c]] = k;
                fill[c] += 1;
            }
        }
        Ok(Self { volumes, faces, face_start, face_index })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.volumes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.volumes.is_empty()
    }

    /// The faces of cell `k`.
    pub fn faces_of(&self, k: usize) -> impl Iterator<Item = &Face> + '_ {
        self.face_index[self.face_start[k]..self.face_start[k + 1]].iter().map(move |&f| &self.faces[f])
    }

    /// The neighbours of cell `k`, one per face.
    pub fn neighbours(&self, k: usize) -> impl Iterator<Item = usize> + '_ {
        self.faces_of(k).map(move |f| if f.i == k { f.j } else { f.i })
    }

    /// dV_mu/dR_nu for the face's two cells (eq 129): the derivative of cell `i`'s volume
    /// with respect to R_j is -A (c/R + e_ij/2); that of j with respect to R_i is
    /// -A (c/R + e_ji/2). Returns (dV_i/dR_j, dV_j/dR_i).
    pub fn volume_gradients(f: &Face) -> ([f64; 3], [f64; 3]) {
        let mut gij = [0.0; 3];
        let mut gji = [0.0; 3];
        for a in 0..3 {
            let c = f.offset[a] / f.dist;
            gij[a] = -f.area * (c - 0.5 * f.normal[a]);
            gji[a] = -f.area * (c + 0.5 * f.normal[a]);
        }
        (gij, gji)
    }
}
