# CTest script (cmake -P): proves that a VTK application can
# find_package(HybridOctree) from an installed tree and use the filter.
#   -DBUILD_DIR=<this build> -DSOURCE_DIR=<tests/consumer> -DWORK_DIR=<scratch>
#   -DVTK_DIR=<VTK package dir> [-DBUILD_TYPE=Release]
#   [-DPVPYTHON=<pvpython> -DPYTHON_DESTINATION=<lib/python3.x/site-packages>]
#   [-DPVBATCH=<pvbatch> -DPLUGIN_SUBDIR=<lib/paraview-5.11/plugins>]
foreach (var IN ITEMS BUILD_DIR SOURCE_DIR WORK_DIR VTK_DIR)
  if (NOT DEFINED ${var})
    message(FATAL_ERROR "${var} is required")
  endif ()
endforeach ()
if (NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif ()

function (run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif ()
  message(STATUS "${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction ()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run_step("install into ${prefix}"
  "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}" --config "${BUILD_TYPE}")
if (NOT EXISTS "${prefix}/lib/cmake/HybridOctree/HybridOctreeConfig.cmake")
  message(FATAL_ERROR "the install has no lib/cmake/HybridOctree/HybridOctreeConfig.cmake")
endif ()
run_step("configure the consumer"
  "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build"
  "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
  "-DCMAKE_PREFIX_PATH=${prefix}"
  "-DVTK_DIR=${VTK_DIR}")
run_step("build the consumer"
  "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" --config "${BUILD_TYPE}")
find_program(consumer hybrid_octree_consumer
  PATHS "${WORK_DIR}/build" "${WORK_DIR}/build/${BUILD_TYPE}" NO_DEFAULT_PATH)
run_step("run the consumer" "${consumer}")
message(STATUS "${step_output}")
find_program(volume hybrid_octree_volume
  PATHS "${WORK_DIR}/build" "${WORK_DIR}/build/${BUILD_TYPE}" NO_DEFAULT_PATH)
run_step("run the volume application" "${volume}")
message(STATUS "${step_output}")

# The installed Python package, from the prefix (not the build tree).
if (PVPYTHON AND PYTHON_DESTINATION)
  set(site "${prefix}/${PYTHON_DESTINATION}")
  run_step("import the installed Python package"
    "${CMAKE_COMMAND}" -E env "PYTHONPATH=${site}"
    "${PVPYTHON}" -c
    "import hybrid_octree as h; assert h.__file__.startswith('${site}'), h.__file__; m = h.vtkHybridOctreeVolumeMapper(); m.SetBudgetMB(3); assert m.GetBudgetMB() == 3; h.vtkHybridOctreeFilter(); print('python OK:', h.__file__)")
  message(STATUS "${step_output}")
endif ()

# The installed ParaView plugin, auto-loaded from the prefix both ways the
# README gives: PV_PLUGIN_PATH (the plugin's folder) and PV_PLUGIN_CONFIG_FILE
# (the plugins XML installed beside it).
if (PVBATCH AND PLUGIN_SUBDIR)
  set(plugins "${prefix}/${PLUGIN_SUBDIR}")
  if (NOT EXISTS "${plugins}/HybridOctree/HybridOctree.so" OR NOT EXISTS "${plugins}/HybridOctree.plugins.xml")
    message(FATAL_ERROR "the install has no ${PLUGIN_SUBDIR}/HybridOctree/HybridOctree.so and HybridOctree.plugins.xml")
  endif ()
  run_step("pvbatch with PV_PLUGIN_PATH=${plugins}/HybridOctree"
    "${CMAKE_COMMAND}" -E env "PV_PLUGIN_PATH=${plugins}/HybridOctree"
    "${PVBATCH}" "${SOURCE_DIR}/plugin_check.py")
  message(STATUS "${step_output}")
  run_step("pvbatch with PV_PLUGIN_CONFIG_FILE=${plugins}/HybridOctree.plugins.xml"
    "${CMAKE_COMMAND}" -E env "PV_PLUGIN_CONFIG_FILE=${plugins}/HybridOctree.plugins.xml"
    "${PVBATCH}" "${SOURCE_DIR}/plugin_check.py")
  message(STATUS "${step_output}")
endif ()
