# Embeds the GLSL files of realtime/shaders/ into a generated C++ file as byte arrays, so the
# binary needs no shader files at run time and no GLSL is written in C++ string literals.
# Usage: cmake -DOUTPUT=file.cpp -DSHADERS="a.vert;b.frag;..." -P embed_shaders.cmake
set(body "")
set(table "")
foreach(path IN LISTS SHADERS)
  get_filename_component(name "${path}" NAME)
  string(MAKE_C_IDENTIFIER "${name}" id)
  file(READ "${path}" hex HEX)
  string(LENGTH "${hex}" hexLength)
  math(EXPR size "${hexLength} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(APPEND body "const unsigned char ${id}[] = {${bytes}0x00};\n")
  string(APPEND table "    {\"${name}\", {reinterpret_cast<const char*>(${id}), ${size}}},\n")
endforeach()
set(content "// Generated from realtime/shaders/ by realtime/embed_shaders.cmake; do not edit.
#include \"realtime/shader_library.h\"

namespace twinrender::realtime {
namespace {
${body}
const EmbeddedFile FILES[] = {
${table}};
}  // namespace

std::span<const EmbeddedFile> embeddedShaderFiles() { return FILES; }

}  // namespace twinrender::realtime
")
# Rewrite only on change, so an unchanged shader set does not recompile.
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL content)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${content}")
