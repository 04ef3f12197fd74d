# The library's layers (docs/layout.md draws them). Each is an object library
# built from its folders; a layer may include its own headers and those of
# the layers it uses, directly or through them, and nothing above. Every
# public header (include/intrinsic/) belongs to one layer. The rule is
# checked when the layer builds (cmake/check_layer_includes.cmake): a
# wrong-way include stops the build naming the file, the line and the layer.
#
#   intrinsic_layer(NAME FOLDERS dir... HEADERS header... USES layer...)
#
# The static library intrinsic (intrinsic::intrinsic) is every layer's objects.

set(INTRINSIC_LAYERS "")

# Usage requirements every layer compiles with (include folders, the
# optional solvers' definitions, third-party headers).
add_library(intrinsic_layer_settings INTERFACE)
target_include_directories(intrinsic_layer_settings INTERFACE ${CMAKE_SOURCE_DIR}/include ${CMAKE_SOURCE_DIR}/src
                           ${TINYGLTF_INCLUDE_DIR})
target_link_libraries(intrinsic_layer_settings INTERFACE Eigen3::Eigen nlohmann_json::nlohmann_json ZLIB::ZLIB
                      PNG::PNG JPEG::JPEG Threads::Threads assimp::assimp draco::draco)
target_compile_options(intrinsic_layer_settings INTERFACE -Wall -Wextra)

function(intrinsic_layer name)
  cmake_parse_arguments(L "" "" "FOLDERS;HEADERS;USES" ${ARGN})
  set(sources "")
  set(files "")
  foreach(folder ${L_FOLDERS})
    file(GLOB_RECURSE cpp CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/${folder}/*.cpp)
    file(GLOB_RECURSE h CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/${folder}/*.h)
    list(APPEND sources ${cpp})
    list(APPEND files ${cpp} ${h})
  endforeach()
  foreach(header ${L_HEADERS})
    list(APPEND files ${CMAKE_SOURCE_DIR}/include/intrinsic/${header}.h)
  endforeach()
  # What this layer may include: itself and every layer below it that it uses.
  set(allowed ${name})
  foreach(used ${L_USES})
    if(NOT used IN_LIST INTRINSIC_LAYERS)
      message(FATAL_ERROR "layer ${name} uses ${used}, which is not a layer below it")
    endif()
    list(APPEND allowed ${INTRINSIC_LAYER_${used}_ALLOWED})
  endforeach()
  list(REMOVE_DUPLICATES allowed)
  set(INTRINSIC_LAYER_${name}_ALLOWED ${allowed} PARENT_SCOPE)
  set(INTRINSIC_LAYER_${name}_FOLDERS ${L_FOLDERS} PARENT_SCOPE)
  set(INTRINSIC_LAYER_${name}_HEADERS ${L_HEADERS} PARENT_SCOPE)
  set(INTRINSIC_LAYERS ${INTRINSIC_LAYERS} ${name} PARENT_SCOPE)

  add_library(intrinsic_${name} OBJECT ${sources})
  set_target_properties(intrinsic_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON
                        UNITY_BUILD ${INTRINSIC_UNITY_BUILD} UNITY_BUILD_BATCH_SIZE ${INTRINSIC_UNITY_BATCH})
  target_link_libraries(intrinsic_${name} PRIVATE intrinsic_layer_settings)
  foreach(used ${L_USES})
    add_dependencies(intrinsic_${name} intrinsic_${used})
  endforeach()
  set(stamp ${CMAKE_BINARY_DIR}/layers/${name}.checked)
  add_custom_command(OUTPUT ${stamp}
    COMMAND ${CMAKE_COMMAND} -DLAYER=${name} -DTABLE=${CMAKE_BINARY_DIR}/layers/table.cmake
            -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DSTAMP=${stamp} -P ${CMAKE_SOURCE_DIR}/cmake/check_layer_includes.cmake
    DEPENDS ${files} ${CMAKE_SOURCE_DIR}/cmake/check_layer_includes.cmake ${CMAKE_BINARY_DIR}/layers/table.cmake
    COMMENT "Checking the includes of layer ${name}")
  add_custom_target(intrinsic_${name}_layer_check DEPENDS ${stamp})
  add_dependencies(intrinsic_${name} intrinsic_${name}_layer_check)
endfunction()

# Bottom up.
intrinsic_layer(util FOLDERS src/util HEADERS error choice option_table mesh_data)
intrinsic_layer(mesh FOLDERS src/mesh src/boundary src/constraints HEADERS mesh topology boundary constraints
                USES util)
intrinsic_layer(io FOLDERS src/io HEADERS io gltf image mesh_document USES mesh)
intrinsic_layer(solve FOLDERS src/weights src/solve HEADERS weights solver_kind USES mesh)
intrinsic_layer(metrics FOLDERS src/metrics HEADERS metrics uv_mesh USES mesh)
intrinsic_layer(core FOLDERS src/core HEADERS parameterize parameterizer charts boundary_editor
                USES solve metrics)
intrinsic_layer(optimize FOLDERS src/optimize HEADERS boundary_optimization optimal_lambda USES core)
intrinsic_layer(atlas FOLDERS src/atlas HEADERS atlas atlas_files USES optimize io)
intrinsic_layer(texture FOLDERS src/texture HEADERS texture texture_transfer USES atlas)
intrinsic_layer(generate FOLDERS src/generate HEADERS generate USES io)
intrinsic_layer(render FOLDERS src/render HEADERS render pictures USES metrics io)
intrinsic_layer(report FOLDERS src/report HEADERS report USES texture)
intrinsic_layer(pipeline FOLDERS src/pipeline HEADERS pipeline atlas_option_table param_option_table edit_session intrinsic
                USES texture generate render report)

# The table the check reads: each layer's folders, headers and what it may include.
set(_table "")
foreach(layer ${INTRINSIC_LAYERS})
  string(APPEND _table "set(LAYER_${layer}_FOLDERS \"${INTRINSIC_LAYER_${layer}_FOLDERS}\")\n"
                       "set(LAYER_${layer}_HEADERS \"${INTRINSIC_LAYER_${layer}_HEADERS}\")\n"
                       "set(LAYER_${layer}_ALLOWED \"${INTRINSIC_LAYER_${layer}_ALLOWED}\")\n")
endforeach()
string(APPEND _table "set(LAYERS \"${INTRINSIC_LAYERS}\")\n")
file(CONFIGURE OUTPUT ${CMAKE_BINARY_DIR}/layers/table.cmake CONTENT "${_table}")

set(_objects "")
foreach(layer ${INTRINSIC_LAYERS})
  list(APPEND _objects $<TARGET_OBJECTS:intrinsic_${layer}>)
endforeach()
add_library(intrinsic_lib STATIC ${_objects})
