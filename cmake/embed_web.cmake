# Writes OUT, a header holding web/index.html and web/app.js as raw string
# literals (namespace intrinsic::app::web), so `intrinsic serve` needs no
# files beside the mesh. Run as: cmake -DWEB_DIR=... -DOUT=... -P embed_web.cmake
set(_delim "INTRINSIC_WEB")
set(_text "// Generated from web/ by cmake/embed_web.cmake: do not edit.\n#pragma once\n\nnamespace intrinsic::app::web {\n")
foreach(_pair "index.html;index_html" "app.js;app_js")
  list(GET _pair 0 _file)
  list(GET _pair 1 _name)
  file(READ ${WEB_DIR}/${_file} _content)
  string(FIND "${_content}" ")${_delim}\"" _clash)
  if(NOT _clash EQUAL -1)
    message(FATAL_ERROR "${_file} contains the raw string delimiter )${_delim}\"")
  endif()
  string(APPEND _text "inline const char* const ${_name} = R\"${_delim}(${_content})${_delim}\";\n")
endforeach()
string(APPEND _text "}  // namespace intrinsic::app::web\n")
file(WRITE ${OUT} "${_text}")
