# Embeds the files of compare/report_assets/ (the report's CSS and JavaScript, inlined into
# every page so the report works offline) into a generated C++ file as byte arrays.
# Usage: cmake -DOUTPUT=file.cpp -DASSETS="a.css;b.js;..." -P embed_report_assets.cmake
set(body "")
set(table "")
foreach(path IN LISTS ASSETS)
  get_filename_component(name "${path}" NAME)
  string(MAKE_C_IDENTIFIER "${name}" id)
  file(READ "${path}" hex HEX)
  string(LENGTH "${hex}" hexLength)
  math(EXPR size "${hexLength} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(APPEND body "const unsigned char ${id}[] = {${bytes}0x00};\n")
  string(APPEND table "    {\"${name}\", {reinterpret_cast<const char*>(${id}), ${size}}},\n")
endforeach()
set(content "// Generated from compare/report_assets/ by compare/embed_report_assets.cmake; do not edit.
#include \"compare/report_assets.h\"

namespace twinrender::compare {
namespace {
struct Asset {
    std::string_view name;
    std::string_view text;
};
${body}
const Asset ASSETS[] = {
${table}};
}  // namespace

std::optional<std::string_view> findReportAsset(std::string_view name) {
    for (const Asset& a : ASSETS)
        if (a.name == name) return a.text;
    return std::nullopt;
}

}  // namespace twinrender::compare
")
# Rewrite only on change, so an unchanged asset set does not recompile.
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL content)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${content}")
