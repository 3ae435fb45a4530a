//! Shared by the fuzz targets: the memory cap and the verdict on a read.

use hybrid_octree::volume::Volume;
use hybrid_octree::{Error, Result};

/// Caps what one read may allocate (64 MiB), once per process.
pub fn cap_memory() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| std::env::set_var(hybrid_octree::limits::MAX_MEMORY_VAR, "64M"));
}

/// A read must give a volume whose length matches its dims, or a `Format` or
/// `InvalidArgument` error.
pub fn check(result: Result<Volume>) {
    match result {
        Ok(v) => assert_eq!(v.samples.len(), v.shape.point_count() * v.components, "inconsistent volume"),
        Err(Error::Format { .. } | Error::InvalidArgument(_)) => {}
        Err(e) => panic!("unexpected error kind {e:?}"),
    }
}
