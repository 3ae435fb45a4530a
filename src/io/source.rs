//! Opening an input file safely: only regular files (symlinks followed) are
//! read, never more bytes than the file had when it was opened, and only when
//! the process has the memory for them. A named pipe would block forever and
//! a device such as `/dev/zero` never ends, so both are refused up front.

use super::format_error;
use crate::base::error::Result;
use crate::base::limits::{check_memory, escape_controls, human_bytes};
use std::io::Read;
use std::path::Path;

/// `path` fit to print: control characters escaped (a file name may hold a
/// terminal escape sequence), otherwise whole.
pub fn display_path(path: &Path) -> String {
    escape_controls(&path.display().to_string())
}

/// The size of the regular file at `path`, or an error saying what it is
/// instead (missing, a directory, a pipe, a device, a socket). `label` names
/// the file in errors.
pub fn regular_file_len(path: &Path, label: &str) -> Result<u64> {
    let meta = match std::fs::metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(format_error(label, "the file does not exist; check the path"))
        }
        Err(e) => return Err(format_error(label, format!("cannot access the file: {e}"))),
        Ok(m) => m,
    };
    if meta.is_file() {
        return Ok(meta.len());
    }
    Err(format_error(label, format!("this is {}, not a regular file; give a volume file", kind_name(&meta))))
}

/// What a non-regular file is, for messages.
fn kind_name(meta: &std::fs::Metadata) -> &'static str {
    let kind = meta.file_type();
    if kind.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a named pipe (FIFO)";
        }
        if kind.is_char_device() || kind.is_block_device() {
            return "a device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    "a special file"
}

/// The whole regular file at `path`, which had `len` bytes when it was
/// checked: at most `len` bytes are read (a file that grows meanwhile is cut,
/// one that shrinks gives what is there), after [`check_memory`] allowed them.
pub fn read_regular_file(path: &Path, label: &str, len: u64) -> Result<Vec<u8>> {
    check_memory(
        u128::from(len),
        &format!("reading '{label}' ({})", human_bytes(u128::from(len))),
        "free memory or raise HYBRID_OCTREE_MAX_MEMORY",
    )?;
    let file = open_regular_file(path, label)?;
    let capacity = usize::try_from(len).map_err(|_| format_error(label, "the file is too large to read"))?;
    let mut bytes = Vec::with_capacity(capacity);
    file.take(len).read_to_end(&mut bytes).map_err(|e| format_error(label, format!("cannot read the file: {e}")))?;
    Ok(bytes)
}

/// Opens the regular file at `path` (checked again once open: it may have
/// been replaced since it was looked at).
pub fn open_regular_file(path: &Path, label: &str) -> Result<std::fs::File> {
    let file = std::fs::File::open(path).map_err(|e| format_error(label, format!("cannot open the file: {e}")))?;
    let opened = file.metadata().map_err(|e| format_error(label, format!("cannot access the file: {e}")))?;
    if !opened.is_file() {
        return Err(format_error(label, "the file was replaced by something that is not a regular file; try again"));
    }
    Ok(file)
}
