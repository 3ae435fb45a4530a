//! Generates the C++ side of `src/ffi.rs` (header and glue) with cxx-build.
//! The header lands in `$CARGO_TARGET_DIR/cxxbridge/hybrid-octree/src/ffi.rs.h`.
fn main() {
    cxx_build::bridge("src/ffi.rs").std("c++17").compile("hybrid_octree_cxxbridge");
    println!("cargo:rerun-if-changed=src/ffi.rs");
    println!("cargo:rerun-if-changed=cpp/Filters/vtkHybridOctreeBuildProgress.h");
}
