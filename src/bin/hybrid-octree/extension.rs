//! Output file names: each writer writes one format, so a file named for
//! another one (`--output x.jpg` for a PNG) is refused before any work.

use hybrid_octree::{Error, Result};
use std::path::Path;

/// Refuses `path` (given with `flag`) unless it ends in one of `allowed`
/// (lowercase, with the dot; matched in any case). `what` names the format.
pub fn require_extension(path: &Path, flag: &str, allowed: &[&str], what: &str) -> Result<()> {
    let name = path.to_string_lossy().to_ascii_lowercase();
    if allowed.iter().any(|ext| name.ends_with(ext) && name.len() > ext.len()) {
        return Ok(());
    }
    Err(Error::InvalidArgument(format!(
        "{flag} '{}': this command writes {what} only; name the file with {}",
        hybrid_octree::limits::excerpt(&path.display().to_string()),
        allowed.join(" or ")
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_are_matched_in_any_case() {
        require_extension(Path::new("a/b.PNG"), "--output", &[".png"], "PNG").unwrap();
        let e = require_extension(Path::new("b.jpg"), "--output", &[".png"], "PNG pictures").unwrap_err();
        assert!(e.to_string().contains("--output 'b.jpg'") && e.to_string().contains(".png"), "{e}");
        assert!(require_extension(Path::new(".png"), "--plot", &[".png"], "PNG").is_err());
    }
}
