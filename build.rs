//! Generates the C++ side of `src/ffi/mod.rs` (header and glue) with cxx-build.
//! The header lands in `$CARGO_TARGET_DIR/cxxbridge/hybrid-octree/src/ffi/mod.rs.h`.
fn main() {
    cxx_build::bridge("src/ffi/mod.rs").std("c++17").compile("hybrid_octree_cxxbridge");
    println!("cargo:rerun-if-changed=src/ffi/mod.rs");
    println!("cargo:rerun-if-changed=cpp/Filters/vtkHybridOctreeBuildProgress.h");
    println!("cargo:rerun-if-changed=cpp/Filters/vtkHybridOctreeBridgeEnums.h");
}
