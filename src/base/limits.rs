//! Limits checked before allocating: the memory a request would take against
//! the memory this process may still use, and excerpts of user text fit to
//! print.
//!
//! # Memory
//!
//! A reader, a generator or a renderer that is about to allocate a buffer whose
//! size comes from a file header or an argument calls [`check_memory`] first.
//! The memory this process may use is the least of
//!
//! - `MemAvailable` of `/proc/meminfo` (what the kernel can give without
//!   swapping),
//! - the cgroup limit (`/sys/fs/cgroup/memory.max`, cgroup v2) minus what the
//!   cgroup already uses,
//! - the address-space limit (`ulimit -v`, `RLIMIT_AS`) minus what this process
//!   has mapped,
//! - `HYBRID_OCTREE_MAX_MEMORY` (bytes, or with a `K`, `M`, `G` or `T` suffix)
//!   when it is set: a user's (or a test's) own cap.
//!
//! A request above it is refused with the size it would need, never attempted.
//! A request of at most [`SMALL_REQUEST_BYTES`] is checked against the user's
//! cap alone: the system's bounds are five small file reads, which cost more
//! than reading a brick of a store, and so many bytes cannot be what exhausts
//! a machine that runs ParaView.

use crate::base::error::{Error, Result};

/// The environment variable a user sets to cap what one request may allocate.
pub const MAX_MEMORY_VAR: &str = "HYBRID_OCTREE_MAX_MEMORY";

/// Bytes as a short human figure: `512 B`, `3.2 MiB`, `6.0 GiB`.
pub fn human_bytes(bytes: u128) -> String {
    const UNITS: [&str; 6] = ["B", "KiB", "MiB", "GiB", "TiB", "PiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else if value >= 1e6 {
        format!("{value:.3e} {}", UNITS[unit])
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

/// Parses `123`, `64K`, `512M`, `8G`, `1T` (binary units; a trailing `B` or
/// `iB` is allowed).
pub fn parse_bytes(text: &str) -> Option<u128> {
    let t = text.trim().to_ascii_uppercase();
    let t = t.trim_end_matches("IB").trim_end_matches('B');
    let (digits, shift) = match t.chars().last()? {
        'K' => (&t[..t.len() - 1], 10),
        'M' => (&t[..t.len() - 1], 20),
        'G' => (&t[..t.len() - 1], 30),
        'T' => (&t[..t.len() - 1], 40),
        _ => (t, 0),
    };
    let value: u128 = digits.trim().parse().ok()?;
    value.checked_mul(1u128 << shift)
}

fn meminfo_field(text: &str, field: &str) -> Option<u128> {
    let line = text.lines().find(|l| l.starts_with(field))?;
    let kib: u128 = line[field.len()..].trim().trim_end_matches("kB").trim().parse().ok()?;
    Some(kib * 1024)
}

fn read_small(path: &str) -> Option<String> {
    use std::io::Read;
    let mut text = String::new();
    std::fs::File::open(path).ok()?.take(1 << 16).read_to_string(&mut text).ok()?;
    Some(text)
}

/// Requests up to this many bytes (16 MiB) are checked against
/// `HYBRID_OCTREE_MAX_MEMORY` only (see the module documentation).
pub const SMALL_REQUEST_BYTES: u128 = 16 << 20;

/// The bytes this process may still allocate, by the rules of the module
/// documentation; `None` when nothing bounds it (no `/proc`, no limit set).
pub fn available_memory() -> Option<u128> {
    [user_cap(), system_available()].into_iter().flatten().min()
}

/// `HYBRID_OCTREE_MAX_MEMORY`, when it is set and parses.
fn user_cap() -> Option<u128> {
    std::env::var(MAX_MEMORY_VAR).ok().and_then(|cap| parse_bytes(&cap))
}

/// The least of the system's bounds: `MemAvailable`, the cgroup's room and
/// the address-space limit's.
fn system_available() -> Option<u128> {
    let mut bounds: Vec<u128> = Vec::new();
    if let Some(text) = read_small("/proc/meminfo") {
        if let Some(b) = meminfo_field(&text, "MemAvailable:") {
            bounds.push(b);
        }
    }
    if let (Some(max), Some(current)) =
        (read_small("/sys/fs/cgroup/memory.max"), read_small("/sys/fs/cgroup/memory.current"))
    {
        if let (Ok(max), Ok(current)) = (max.trim().parse::<u128>(), current.trim().parse::<u128>()) {
            bounds.push(max.saturating_sub(current));
        }
    }
    if let Some(limits) = read_small("/proc/self/limits") {
        let line = limits.lines().find(|l| l.starts_with("Max address space"));
        let soft = line.and_then(|l| l.split_whitespace().nth(3)).and_then(|v| v.parse::<u128>().ok());
        if let Some(soft) = soft {
            let mapped = read_small("/proc/self/status").and_then(|s| meminfo_field(&s, "VmSize:")).unwrap_or(0);
            bounds.push(soft.saturating_sub(mapped));
        }
    }
    bounds.into_iter().min()
}

/// Refuses a request of `bytes` that is more than this process may still
/// allocate. `what` names the request in the error ("the 3000^3 f32
/// shepp-logan volume"); `advice` says what to do instead.
pub fn check_memory(bytes: u128, what: &str, advice: &str) -> Result<()> {
    match bound_for(bytes, user_cap(), system_available) {
        Some(available) if bytes > available => Err(Error::InvalidArgument(format!(
            "{what} needs {} of memory but only {} is available{}; {advice}",
            human_bytes(bytes),
            human_bytes(available),
            if std::env::var_os(MAX_MEMORY_VAR).is_some() {
                format!(" (capped by {MAX_MEMORY_VAR})")
            } else {
                String::new()
            }
        ))),
        _ => Ok(()),
    }
}

/// The bound a request of `bytes` is checked against: the least of `cap` and,
/// above [`SMALL_REQUEST_BYTES`] only, `system()`.
fn bound_for(bytes: u128, cap: Option<u128>, system: impl FnOnce() -> Option<u128>) -> Option<u128> {
    let system = if bytes > SMALL_REQUEST_BYTES { system() } else { None };
    [cap, system].into_iter().flatten().min()
}

/// At most this many characters of user text appear in a message.
pub const EXCERPT_CHARS: usize = 64;

/// User text (a header field, an attribute, an argument) fit to print: control
/// characters and escapes shown as `\n`, `\x1b`, `\u{..}`, and cut to
/// [`EXCERPT_CHARS`] characters with `...` and the full length after a cut.
pub fn excerpt(text: &str) -> String {
    let total = text.chars().count();
    let mut out = escape_controls(&text.chars().take(EXCERPT_CHARS).collect::<String>());
    if total > EXCERPT_CHARS {
        out.push_str(&format!("... ({total} characters)"));
    }
    out
}

/// `text` with control characters (DEL and the C0 and C1 ranges) shown as
/// `\n`, `\u{1b}`, and the rest kept whole.
pub fn escape_controls(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// [`excerpt`] of bytes that may not be UTF-8.
pub fn excerpt_bytes(bytes: &[u8]) -> String {
    let head = &bytes[..bytes.len().min(EXCERPT_CHARS * 4)];
    let mut text = excerpt(&String::from_utf8_lossy(head));
    if bytes.len() > head.len() && !text.ends_with(')') {
        text.push_str(&format!("... ({} bytes)", bytes.len()));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_byte_sizes() {
        assert_eq!(parse_bytes("123"), Some(123));
        assert_eq!(parse_bytes("64K"), Some(64 << 10));
        assert_eq!(parse_bytes("512MiB"), Some(512 << 20));
        assert_eq!(parse_bytes("8g"), Some(8 << 30));
        assert_eq!(parse_bytes("lots"), None);
        assert_eq!(parse_bytes(""), None);
    }

    #[test]
    fn refuses_more_than_available() {
        // The machine has some finite bound (MemAvailable at least on Linux).
        let available = available_memory().expect("a Linux machine reports MemAvailable");
        let e = check_memory(available + (1 << 30), "the test buffer", "ask for less").unwrap_err();
        let text = e.to_string();
        assert!(text.contains("the test buffer needs") && text.contains("ask for less"), "{text}");
        check_memory(1024, "a small buffer", "-").unwrap();
    }

    #[test]
    fn a_small_request_reads_no_system_bound_but_meets_the_cap() {
        let never = || -> Option<u128> { panic!("the system's bounds read for a small request") };
        assert_eq!(bound_for(SMALL_REQUEST_BYTES, None, never), None);
        assert_eq!(bound_for(1024, Some(512), never), Some(512), "the user's cap holds at any size");
        assert_eq!(bound_for(SMALL_REQUEST_BYTES + 1, Some(1 << 40), || Some(1 << 30)), Some(1 << 30));
        assert_eq!(bound_for(SMALL_REQUEST_BYTES + 1, Some(1 << 20), || Some(1 << 30)), Some(1 << 20));
        assert_eq!(bound_for(SMALL_REQUEST_BYTES + 1, None, || None), None);
    }

    #[test]
    fn excerpts_escape_and_cut() {
        assert_eq!(excerpt("1 1 1"), "1 1 1");
        assert_eq!(excerpt("\u{1b}[31mred"), "\\u{1b}[31mred");
        let long = "9".repeat(1 << 20);
        let e = excerpt(&long);
        assert!(e.len() < 100 && e.ends_with("(1048576 characters)"), "{e}");
        assert_eq!(excerpt_bytes(b"a\nb"), "a\\nb");
    }

    #[test]
    fn human_sizes() {
        assert_eq!(human_bytes(512), "512 B");
        assert_eq!(human_bytes(3 << 30), "3.0 GiB");
    }
}
