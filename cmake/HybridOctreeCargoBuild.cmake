# Build step of the hybrid_octree_cargo target (cmake -P):
#   -DCARGO=<cargo> -DMANIFEST=<Cargo.toml> -DTARGET_DIR=<CARGO_TARGET_DIR>
#   -DLINK_FILE=<response file> [-DEXTRA_FLAGS=<list>]
#
# Runs cargo twice in the same target folder: first
# `cargo build --release --locked --bin hybrid-octree` (the command line tool,
# with the crate's default `cli` feature), then
# `cargo build --release --locked --lib --no-default-features` (the static
# library without the tool's crates: the plots' fonts would bring fontconfig
# and freetype). The library comes last so that the archive cargo leaves in
# release/ is the one built without `cli`.
#
# Writes to LINK_FILE the system libraries the library's build scripts link
# dynamically (for example -llzma from lzma-sys): a Rust static library does
# not bundle them, so whatever links the archive must name them. The list
# comes from the library build's build-script-executed messages, which cargo
# emits for fresh build scripts too. LINK_FILE is a GNU ld response file,
# rewritten only when its content changes (no spurious relinks).
foreach (var IN ITEMS CARGO MANIFEST TARGET_DIR LINK_FILE)
  if (NOT DEFINED ${var})
    message(FATAL_ERROR "${var} is required")
  endif ()
endforeach ()

set(ENV{CARGO_TARGET_DIR} "${TARGET_DIR}")
execute_process(
  COMMAND "${CARGO}" build --release --locked --manifest-path "${MANIFEST}"
          --bin hybrid-octree ${EXTRA_FLAGS}
  RESULT_VARIABLE rc)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "cargo build --release --locked --bin hybrid-octree failed (exit ${rc})")
endif ()
execute_process(
  COMMAND "${CARGO}" build --release --locked --manifest-path "${MANIFEST}"
          --lib --no-default-features
          --message-format=json-render-diagnostics ${EXTRA_FLAGS}
  OUTPUT_VARIABLE messages
  RESULT_VARIABLE rc)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "cargo build --release --locked --lib --no-default-features failed (exit ${rc})")
endif ()

set(flags "")
string(REPLACE "\n" ";" lines "${messages}")
foreach (line IN LISTS lines)
  if (NOT line MATCHES "\"reason\":\"build-script-executed\"")
    continue ()
  endif ()
  string(JSON nlibs LENGTH "${line}" linked_libs)
  set(dynamic_libs "")
  if (nlibs GREATER 0)
    math(EXPR last "${nlibs} - 1")
    foreach (i RANGE ${last})
      string(JSON lib GET "${line}" linked_libs ${i})
      # static= libraries are bundled into the Rust archive; C++'s runtime
      # comes with the C++ linker.
      if (lib MATCHES "^static(:[^=]*)?=" OR lib MATCHES "^(dylib=)?(stdc\\+\\+|c\\+\\+)$")
        continue ()
      endif ()
      string(REGEX REPLACE "^dylib(:[^=]*)?=" "" lib "${lib}")
      list(APPEND dynamic_libs "-l${lib}")
    endforeach ()
  endif ()
  if (NOT dynamic_libs)
    continue ()
  endif ()
  string(JSON npaths LENGTH "${line}" linked_paths)
  if (npaths GREATER 0)
    math(EXPR last "${npaths} - 1")
    foreach (i RANGE ${last})
      string(JSON path GET "${line}" linked_paths ${i})
      string(REGEX REPLACE "^(native|all|dependency)=" "" path "${path}")
      list(APPEND flags "-L${path}")
    endforeach ()
  endif ()
  list(APPEND flags ${dynamic_libs})
endforeach ()
list(REMOVE_DUPLICATES flags)
string(REPLACE ";" "\n" content "${flags}")
file(CONFIGURE OUTPUT "${LINK_FILE}" CONTENT "${content}\n" @ONLY)
