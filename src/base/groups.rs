//! Group masks: a particle carries its groups as a bit mask (bit k for the k-th name of
//! the group list), so membership travels with it between ranks.

use crate::base::args::Args;
use gendpde_io::ScriptError;

/// Most groups besides `all` (LAMMPS allows 32 including all).
pub const MAX_GROUPS: usize = 31;

/// The bit mask of group `name` among the group names by bit (all bits for `all`).
pub fn mask(groups: &[String], name: &str, a: &Args) -> Result<u32, ScriptError> {
    if name == "all" {
        return Ok(u32::MAX);
    }
    let k = groups.iter().position(|g| g == name).ok_or_else(|| a.err(format!("no group '{name}' (define it with the group command)")))?;
    Ok(1 << k)
}
