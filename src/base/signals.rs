//! SIGTERM, SIGINT and SIGUSR1 (what batch systems send before the wall time): the
//! handlers (signal-hook) record the signal's number, a run stops after the step all ranks
//! agree on (`System::settle`), saves its state, closes its outputs and gendpde exits
//! with 128 + the number, as a killed process would. The same signal again exits at once.

use std::sync::atomic::{AtomicBool, AtomicUsize};
use std::sync::{Arc, OnceLock};

use signal_hook::consts::{SIGINT, SIGTERM, SIGUSR1};

/// The number of SIGPIPE, recorded when the screen's reader went away (gendpde ignores
/// the signal itself, as Rust programs do, and sees the broken pipe as a write error).
pub const SIGPIPE: usize = signal_hook::consts::SIGPIPE as usize;

/// The number of the signal received (0: none).
pub fn received() -> Arc<AtomicUsize> {
    static RECEIVED: OnceLock<Arc<AtomicUsize>> = OnceLock::new();
    Arc::clone(RECEIVED.get_or_init(Arc::default))
}

/// Installs the handlers.
pub fn install() -> std::io::Result<()> {
    let again = Arc::new(AtomicBool::new(false));
    for sig in [SIGTERM, SIGINT, SIGUSR1] {
        // registered first, so it sees the flag set by an earlier signal
        signal_hook::flag::register_conditional_shutdown(sig, 128 + sig, Arc::clone(&again))?;
        signal_hook::flag::register(sig, Arc::clone(&again))?;
        signal_hook::flag::register_usize(sig, received(), sig as usize)?;
    }
    Ok(())
}

/// The name of a signal number.
pub fn name(sig: usize) -> String {
    match sig as i32 {
        SIGTERM => "SIGTERM".into(),
        SIGINT => "SIGINT".into(),
        SIGUSR1 => "SIGUSR1".into(),
        signal_hook::consts::SIGPIPE => "SIGPIPE (the screen's reader went away)".into(),
        n => format!("signal {n}"),
    }
}
