# Embeds files into a generated C++ file as byte arrays, so the binary needs none of them at
# run time and no file's text is written in C++ string literals. The generated file defines
#   std::span<const twinrender::core::EmbeddedFile> NAMESPACE::FUNCTION();
# Usage (through twinrender_embed_files in twinrender_library.cmake):
#   cmake -DOUTPUT=file.cpp -DFILES="a;b;..." -DNAMESPACE=ns -DFUNCTION=f -DORIGIN=dir
#         -P embed_files.cmake
set(body "")
set(table "")
foreach(path IN LISTS FILES)
  get_filename_component(name "${path}" NAME)
  string(MAKE_C_IDENTIFIER "${name}" id)
  file(READ "${path}" hex HEX)
  string(LENGTH "${hex}" hexLength)
  math(EXPR size "${hexLength} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(APPEND body "const unsigned char ${id}[] = {${bytes}0x00};\n")
  string(APPEND table "    {\"${name}\", {reinterpret_cast<const char*>(${id}), ${size}}},\n")
endforeach()
set(content "// Generated from ${ORIGIN} by cmake/embed_files.cmake; do not edit.
#include <span>

#include \"core/embedded_file.h\"

namespace ${NAMESPACE} {
namespace {
${body}
const core::EmbeddedFile FILES[] = {
${table}};
}  // namespace

std::span<const core::EmbeddedFile> ${FUNCTION}() { return FILES; }

}  // namespace ${NAMESPACE}
")
# Rewrite only on change, so an unchanged file set does not recompile.
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL content)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${content}")
