# ctest script (cmake -P): installs the build tree into a temporary prefix,
# then configures, builds and runs tests/consumer against it, and builds
# examples/ against it: examples/atlas_file on a generated torus must write
# the same OBJ bytes as `intrinsic atlas` and the same report apart from
# timings.
# When the Python module is built, also imports the installed package with
# PYTHONPATH=PREFIX/PYTHON_DIR and parameterizes a small disk.
# Variables: BUILD_DIR, SOURCE_DIR, WORK_DIR, CONFIG, PYTHON (may be empty), PYTHON_DIR.
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f lib/cmake/intrinsic/intrinsicConfig.cmake lib/cmake/intrinsic/intrinsicConfigVersion.cmake
          include/intrinsic/parameterize.h bin/intrinsic)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)

run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${WORK_DIR}/examples -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/examples)
set(cli ${prefix}/bin/intrinsic)
run(${cli} generate torus --rings 12 -o ${WORK_DIR}/torus.obj)
run(${cli} atlas ${WORK_DIR}/torus.obj -o ${WORK_DIR}/cli.obj --report ${WORK_DIR}/cli.json -q)
run(${WORK_DIR}/examples/atlas_file ${WORK_DIR}/torus.obj ${WORK_DIR}/example.obj ${WORK_DIR}/example.json)
file(READ ${WORK_DIR}/cli.obj cli_obj)
file(READ ${WORK_DIR}/example.obj example_obj)
if(NOT cli_obj STREQUAL example_obj)
  message(FATAL_ERROR "examples/atlas_file wrote other OBJ bytes than `intrinsic atlas`")
endif()
# The reports without timings and without "output" (the two paths differ).
foreach(which cli example)
  file(READ ${WORK_DIR}/${which}.json text)
  string(JSON text REMOVE "${text}" timings_ms)
  string(JSON text REMOVE "${text}" output)
  set(${which}_report "${text}")
endforeach()
string(JSON same EQUAL "${cli_report}" "${example_report}")
if(NOT same)
  message(FATAL_ERROR "examples/atlas_file's report differs from `intrinsic atlas --report`:\n${cli_report}\n---\n${example_report}")
endif()
message(STATUS "examples/atlas_file: same OBJ bytes and report as `intrinsic atlas`")
if(PYTHON)
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYTHON_DIR} ${PYTHON} ${SOURCE_DIR}/tests/consumer/check_python.py
      ${prefix})
endif()
