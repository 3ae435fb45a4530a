#[==[.md
# HybridOctreeCargo

Builds the Rust crate into the CMake build tree and exposes its static
library to CMake: the library with `cargo build --release --locked --lib
--no-default-features` (without the command line tool's crates), the
`hybrid-octree` tool with its `cli` feature (see HybridOctreeCargoBuild.cmake).

Defines:

  * `hybrid_octree_cargo`: a custom target that runs cargo on every build
    (cargo is incremental, so an unchanged crate costs a second): the
    `hybrid-octree` command line tool, then the library.
  * `HybridOctree::rust`: an IMPORTED STATIC library for
    `<cargo target>/release/libhybrid_octree.a`, carrying the cxx include
    folder `<cargo target>/cxxbridge` (headers `hybrid-octree/src/ffi/mod.rs.h`
    and `rust/cxx.h`), the system libraries Rust's std needs, and a linker
    response file listing the system libraries the crate's build scripts
    link dynamically (see HybridOctreeCargoBuild.cmake).
  * `HYBRID_OCTREE_CARGO_TARGET_DIR`: the cargo target folder.
  * `HYBRID_OCTREE_CLI`: path of the `hybrid-octree` executable.

Link `HybridOctree::rust` PRIVATE, with `LINKER:--exclude-libs,ALL`, so the
Rust symbols stay inside the library that embeds them.
#]==]

find_program(CARGO_EXECUTABLE cargo
  HINTS "$ENV{CARGO_HOME}/bin" "$ENV{HOME}/.cargo/bin"
  DOC "cargo, the Rust build tool")
if (NOT CARGO_EXECUTABLE)
  message(FATAL_ERROR
    "cargo was not found: install Rust (https://rustup.rs) or set CARGO_EXECUTABLE.")
endif ()

set(HYBRID_OCTREE_CARGO_TARGET_DIR "${CMAKE_BINARY_DIR}/cargo"
  CACHE PATH "CARGO_TARGET_DIR used for the Rust crate")
set(HYBRID_OCTREE_CARGO_FLAGS "" CACHE STRING
  "Extra arguments for `cargo build` (for example --offline)")
mark_as_advanced(HYBRID_OCTREE_CARGO_TARGET_DIR HYBRID_OCTREE_CARGO_FLAGS)

set(_hybrid_octree_cargo_manifest "${PROJECT_SOURCE_DIR}/Cargo.toml")
set(_hybrid_octree_rust_lib
  "${HYBRID_OCTREE_CARGO_TARGET_DIR}/release/${CMAKE_STATIC_LIBRARY_PREFIX}hybrid_octree${CMAKE_STATIC_LIBRARY_SUFFIX}")
set(HYBRID_OCTREE_CLI
  "${HYBRID_OCTREE_CARGO_TARGET_DIR}/release/hybrid-octree${CMAKE_EXECUTABLE_SUFFIX}")
set(_hybrid_octree_cxxbridge_dir "${HYBRID_OCTREE_CARGO_TARGET_DIR}/cxxbridge")

# CMake refuses an INTERFACE_INCLUDE_DIRECTORIES entry that does not exist yet;
# cxx-build fills the folder during the first cargo run.
file(MAKE_DIRECTORY "${_hybrid_octree_cxxbridge_dir}")

# System libraries the crate's build scripts link dynamically (-llzma, ...),
# collected by HybridOctreeCargoBuild.cmake after every cargo run; empty until
# the first build.
set(HYBRID_OCTREE_RUST_LINK_FILE "${HYBRID_OCTREE_CARGO_TARGET_DIR}/native-libs.rsp")
if (NOT EXISTS "${HYBRID_OCTREE_RUST_LINK_FILE}")
  file(WRITE "${HYBRID_OCTREE_RUST_LINK_FILE}" "\n")
endif ()

separate_arguments(_hybrid_octree_cargo_flags UNIX_COMMAND "${HYBRID_OCTREE_CARGO_FLAGS}")
add_custom_target(hybrid_octree_cargo ALL
  COMMAND "${CMAKE_COMMAND}"
          "-DCARGO=${CARGO_EXECUTABLE}"
          "-DMANIFEST=${_hybrid_octree_cargo_manifest}"
          "-DTARGET_DIR=${HYBRID_OCTREE_CARGO_TARGET_DIR}"
          "-DLINK_FILE=${HYBRID_OCTREE_RUST_LINK_FILE}"
          "-DEXTRA_FLAGS=${_hybrid_octree_cargo_flags}"
          -P "${CMAKE_CURRENT_LIST_DIR}/HybridOctreeCargoBuild.cmake"
  BYPRODUCTS "${_hybrid_octree_rust_lib}" "${HYBRID_OCTREE_CLI}" "${HYBRID_OCTREE_RUST_LINK_FILE}"
  WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
  USES_TERMINAL
  COMMENT "cargo build --release --locked (hybrid-octree tool, then the library without cli)")

# The bridge header includes the crate's own C++ headers as
# "hybrid-octree/cpp/<path>" (cxx's crate-relative include!): a copy of each
# under <build>/cxx-crate/hybrid-octree/cpp makes that path resolve.
set(_hybrid_octree_crate_include_dir "${CMAKE_BINARY_DIR}/cxx-crate")
foreach (_header IN ITEMS Filters/vtkHybridOctreeBuildProgress.h Filters/vtkHybridOctreeBridgeEnums.h)
  configure_file("${PROJECT_SOURCE_DIR}/cpp/${_header}"
    "${_hybrid_octree_crate_include_dir}/hybrid-octree/cpp/${_header}" COPYONLY)
endforeach ()

find_package(Threads REQUIRED)
add_library(HybridOctree::rust STATIC IMPORTED GLOBAL)
set_target_properties(HybridOctree::rust PROPERTIES
  IMPORTED_LOCATION "${_hybrid_octree_rust_lib}"
  INTERFACE_INCLUDE_DIRECTORIES "${_hybrid_octree_cxxbridge_dir};${_hybrid_octree_crate_include_dir}"
  INTERFACE_LINK_LIBRARIES
    "-Wl,@${HYBRID_OCTREE_RUST_LINK_FILE};Threads::Threads;${CMAKE_DL_LIBS};m")
add_dependencies(HybridOctree::rust hybrid_octree_cargo)
