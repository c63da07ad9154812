# Fails when a C++ source of the project deviates from .clang-format. Run as
#   cmake -DCLANG_FORMAT=<path> -DSOURCE_DIR=<root> -P cmake/check_format.cmake
# The sources are listed when the test runs, so a new file is checked without re-configuring.
if(NOT CLANG_FORMAT)
  message(FATAL_ERROR "clang-format was not found when configuring; install the Debian package "
                      "clang-format (scripts/setup does) and re-run cmake")
endif()
set(dirs app bench compare core fuzz raymarch realtime report tests)
set(files)
foreach(dir IN LISTS dirs)
  file(GLOB_RECURSE found "${SOURCE_DIR}/${dir}/*.cpp" "${SOURCE_DIR}/${dir}/*.h")
  list(APPEND files ${found})
endforeach()
list(SORT files)
list(LENGTH files count)
execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror --style=file ${files}
                WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE result ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  string(REGEX MATCHALL "[^\n]*: error:[^\n]*" lines "${errors}")
  set(named)
  foreach(line IN LISTS lines)
    string(REGEX REPLACE ":[0-9]+:[0-9]+: error:.*" "" file "${line}")
    list(APPEND named "${file}")
  endforeach()
  list(REMOVE_DUPLICATES named)
  list(JOIN named "\n  " listing)
  message(FATAL_ERROR "these files are not formatted as .clang-format says; run\n"
                      "  clang-format -i FILE\non each:\n  ${listing}")
endif()
message(STATUS "${count} C++ sources formatted as .clang-format says")
