//! Running work inside a rayon pool of a chosen size.

use hybrid_octree::{Error, Result};

/// Runs `f` in a rayon pool of `threads` threads (`None`: all cores).
pub fn with_threads<R: Send>(threads: Option<usize>, f: impl FnOnce() -> Result<R> + Send) -> Result<R> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        if n == 0 {
            return Err(Error::InvalidArgument("--threads must be at least 1".into()));
        }
        builder = builder.num_threads(n);
    }
    let pool = builder
        .build()
        .map_err(|e| Error::InvalidArgument(format!("cannot start a pool of {threads:?} threads: {e}")))?;
    pool.install(f)
}
