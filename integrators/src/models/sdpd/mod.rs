//! Smoothed dissipative particle dynamics: Serrano and Espanol's thermal SDPD
//! ([`generic`], `pair sdpd/generic`) and DPD-SMOOTH's isothermal Tait water
//! ([`taitwater`], `pair sdpd/taitwater/isothermal`).

pub mod generic;
pub mod taitwater;
