# ctest script (cmake -P): installs the build tree into a temporary prefix,
# then configures, builds and runs tests/consumer against it.
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
if(PYTHON)
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYTHON_DIR} ${PYTHON} ${SOURCE_DIR}/tests/consumer/check_python.py
      ${prefix})
endif()
