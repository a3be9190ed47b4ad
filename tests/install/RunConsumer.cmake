# Installs the build tree into a scratch prefix, then configures, builds and
# runs a separate consumer project against it with find_package(vtkrt); then
# the same against the build tree itself (vtkrt_DIR naming the build).
foreach (var IN ITEMS BUILD_DIR WORK_DIR SOURCE_DIR GENERATOR)
  if (NOT DEFINED ${var})
    message(FATAL_ERROR "RunConsumer.cmake needs -D${var}=...")
  endif ()
endforeach ()
set(prefix "${WORK_DIR}/prefix")
file(REMOVE_RECURSE "${WORK_DIR}")

function (run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}")
  endif ()
endfunction ()

run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")
if (NOT EXISTS "${prefix}/lib/cmake/vtkrt/vtkrtConfig.cmake")
  message(FATAL_ERROR "the install has no lib/cmake/vtkrt/vtkrtConfig.cmake")
endif ()
run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" -G "${GENERATOR}"
  "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/vtkrtConsumer")

# The build tree itself, as the README's C++ quick start says: vtkrt_DIR
# names the build.
run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build-tree" -G "${GENERATOR}"
  "-Dvtkrt_DIR=${BUILD_DIR}" -DCMAKE_BUILD_TYPE=Release)
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/build-tree")
run("${WORK_DIR}/build-tree/vtkrtConsumer")
