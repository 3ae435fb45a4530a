//! The process's memory as a measured figure, like time.

/// The process's peak resident set size in bytes: `VmHWM` of
/// `/proc/self/status` (Linux); `None` where that file is absent or has no
/// such line.
pub fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.trim_start_matches("VmHWM:").trim().trim_end_matches("kB").trim().parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    #[test]
    fn peak_rss_covers_a_touched_buffer() {
        let buffer = vec![1u8; 64 << 20];
        let touched: u64 = buffer.iter().step_by(4096).map(|&b| b as u64).sum();
        assert!(touched > 0);
        if let Some(peak) = super::peak_rss_bytes() {
            assert!(peak >= 64 << 20, "peak RSS {peak} bytes below the 64 MiB just touched");
        }
    }
}
