//! Running work inside a rayon pool of a chosen size.

use hybrid_octree::{Error, Result};

/// The most worker threads a command accepts: beyond this a pool only costs
/// stacks and start-up time (and a huge count never finishes starting).
pub const MAX_THREADS: usize = 1024;

/// Checks a `--threads` value: `1 ..= MAX_THREADS`.
pub fn check_threads(n: usize) -> Result<()> {
    if n == 0 {
        return Err(Error::InvalidArgument("--threads must be at least 1".into()));
    }
    if n > MAX_THREADS {
        let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
        return Err(Error::InvalidArgument(format!(
            "--threads {n} is too many: use at most {MAX_THREADS} (this machine has {cores} cores)"
        )));
    }
    Ok(())
}

/// Checks every value of a `--threads` list (see [`check_threads`]).
pub fn check_thread_list(list: &[usize]) -> Result<()> {
    list.iter().try_for_each(|&n| check_threads(n))
}

/// Runs `f` in a rayon pool of `threads` threads (`None`: all cores).
pub fn with_threads<R: Send>(threads: Option<usize>, f: impl FnOnce() -> Result<R> + Send) -> Result<R> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        check_threads(n)?;
        builder = builder.num_threads(n);
    }
    let pool = builder
        .build()
        .map_err(|e| Error::InvalidArgument(format!("cannot start a pool of {threads:?} threads: {e}")))?;
    pool.install(f)
}
