//! Refusing work that would not fit in memory, before allocating it.

/// Bytes of memory the system can still give (MemAvailable), where the OS tells.
pub fn available() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Bytes per particle of the store: primary and derived fields of an owned particle and
/// its share of ghosts (measured layout, rounded up).
pub const STORE_BYTES_PER_PARTICLE: f64 = 640.0;

/// Bytes per neighbour-list entry (index, F_ij and g_ij) and per sweep pair (two indices).
pub const NEIGHBOUR_ENTRY_BYTES: f64 = 20.0;
pub const SWEEP_PAIR_BYTES: f64 = 8.0;

/// Err with a message when `bytes` exceed the memory available to this rank.
pub fn check(bytes: f64, what: &str) -> Result<(), String> {
    match available() {
        Some(avail) if bytes > avail as f64 => Err(format!(
            "{what} needs about {:.1} GiB of memory, but only {:.1} GiB are available",
            bytes / 1073741824.0,
            avail as f64 / 1073741824.0
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_huge_request_is_refused_and_a_small_one_passes() {
        if available().is_some() {
            let e = check(1e18, "this test").unwrap_err();
            assert!(e.contains("this test needs about") && e.contains("GiB"), "{e}");
        }
        assert!(check(1.0, "one byte").is_ok());
    }
}
