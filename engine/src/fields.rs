//! Named per-particle fields, as a bit set for the communication layer.

/// A set of per-particle fields to exchange between owners and ghosts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Fields(u32);

impl Fields {
    /// The empty set.
    pub const NONE: Self = Self(0);
    pub const POSITION: Self = Self(1);
    pub const MOMENTUM: Self = Self(2);
    pub const ENERGY: Self = Self(4);
    pub const THETA: Self = Self(8);
    pub const DENSITY: Self = Self(16);
    pub const PRESSURE: Self = Self(32);
    pub const INV_TAU: Self = Self(64);
    /// The conductive part of u (LAMMPS atom_style dpd's uCond).
    pub const U_COND: Self = Self(128);
    /// Per-particle pair energy of pairwise styles (not exchanged).
    pub const PAIR_ENERGY: Self = Self(256);
    /// The MDPD density of pairwise many-body styles, as LAMMPS's mdpd/rhosum sums it.
    pub const RHO: Self = Self(512);
    /// The rates duCond/dt and duMech/dt of velocity-Verlet DPDE (LAMMPS's pair
    /// dpd/fdt/energy without fix shardlow; not exchanged).
    pub const DU: Self = Self(1024);
    /// eDPD's particle temperature (atom_style edpd; allocates heat capacity and flux too).
    pub const EDPD: Self = Self(2048);
    /// The stress increment of one SDPD step (pair sdpd/generic), owners to ghosts.
    pub const SDPD_STRESS: Self = Self(4096);
    /// The heat-flux increment of one SDPD step (pair sdpd/generic), owners to ghosts.
    pub const SDPD_FLUX: Self = Self(8192);
    /// The SPH density rate drho/dt of atom_style sph (pair sdpd/taitwater/isothermal;
    /// not exchanged). The density itself is [`Fields::RHO`].
    pub const SPH: Self = Self(16384);
    /// The entropy of a Voronoi cell (pair voronoi/fv).
    pub const ENTROPY: Self = Self(32768);

    pub const fn union(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// The fields of `self` that are not in `other`.
    pub const fn without(self, other: Self) -> Self {
        Self(self.0 & !other.0)
    }

    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether the sets share a field.
    pub const fn intersects(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }

    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The raw bits (restart files store the enabled set).
    pub const fn bits(self) -> u32 {
        self.0
    }

    pub const fn from_bits(bits: u32) -> Self {
        Self(bits)
    }
}

impl std::ops::BitOr for Fields {
    type Output = Self;
    fn bitor(self, rhs: Self) -> Self {
        self.union(rhs)
    }
}
