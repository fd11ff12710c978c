//! Pair styles, fixes and models as physics: one module per style or model (eDPD, SDPD,
//! Tait water, tables, multi/lucy, DPD thermostats, fix nph, the alternative integrators,
//! Voronoi cells, heat flow, the papers' scenes and the LTh parameters).

mod dpd_thermostats;
mod edpd;
mod energy_conservation;
mod heat_flow;
mod heat_only;
mod integrators_alt;
mod lth;
mod multi_lucy;
mod noise_forms;
mod nph;
mod scenes;
mod sdpd;
mod sdpd_taitwater;
mod table_parity;
mod vdw_equilibrium;
mod voronoi;
