# Install rules: the static library, the public headers, the `intrinsic` CLI
# and the CMake package (intrinsicConfig.cmake + version file) so that another
# project does find_package(intrinsic REQUIRED) and links intrinsic::intrinsic.
# SuiteSparse, OpenBLAS, METIS and the OpenMP runtime are linked by path (no
# CMake config on Debian 12); Eigen3, ZLIB, PNG, Threads and assimp are found again
# by the config (find_dependency). The Python package's rules are in
# python/CMakeLists.txt.
include(CMakePackageConfigHelpers)

set(INTRINSIC_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/intrinsic)
install(TARGETS intrinsic_lib EXPORT intrinsicTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/intrinsic DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS intrinsic RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT intrinsicTargets NAMESPACE intrinsic:: DESTINATION ${INTRINSIC_CMAKE_DIR})

configure_package_config_file(cmake/intrinsicConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/intrinsicConfig.cmake INSTALL_DESTINATION ${INTRINSIC_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/intrinsicConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/intrinsicConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/intrinsicConfigVersion.cmake
        DESTINATION ${INTRINSIC_CMAKE_DIR})

# The consumer project of tests/consumer, built against a fresh install in
# the build tree (not with the sanitizers: the consumer is not instrumented).
if(INTRINSIC_BUILD_TESTS AND NOT INTRINSIC_SANITIZE)
  add_test(NAME install_consumer
           COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${CMAKE_BINARY_DIR} -DSOURCE_DIR=${CMAKE_SOURCE_DIR}
                   -DWORK_DIR=${CMAKE_BINARY_DIR}/consumer-test -DCONFIG=$<CONFIG>
                   -DPYTHON=$<$<BOOL:${INTRINSIC_BUILD_PYTHON}>:${Python3_EXECUTABLE}>
                   -DPYTHON_DIR=${INTRINSIC_PYTHON_INSTALL_DIR}
                   -P ${CMAKE_SOURCE_DIR}/tests/consumer/run_consumer_test.cmake)
  set_tests_properties(install_consumer PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)
endif()
