# twinrender_library(NAME DEPS...): one library per folder. Sources are the folder's *.cpp
# files except the *_test.cpp ones, which form the folder's test binary NAME_tests.
# Tests whose file name ends in _gl_test.cpp need an OpenGL context: they go into a separate
# binary NAME_gl_tests with the CTest label "gl".
function(twinrender_library name)
  cmake_parse_arguments(ARG "" "" "DEPS;TEST_DEPS" ${ARGN})
  file(GLOB _all CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*.cpp")
  set(_src)
  set(_tests)
  set(_gl_tests)
  foreach(_f IN LISTS _all)
    if(_f MATCHES "_gl_test\\.cpp$")
      list(APPEND _gl_tests "${_f}")
    elseif(_f MATCHES "_test\\.cpp$")
      list(APPEND _tests "${_f}")
    else()
      list(APPEND _src "${_f}")
    endif()
  endforeach()
  add_library(${name} STATIC ${_src})
  target_include_directories(${name} PUBLIC "${TWINRENDER_SOURCE_DIR}")
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  if(TWINRENDER_BUILD_TESTS AND _tests)
    add_executable(${name}_tests ${_tests})
    target_link_libraries(${name}_tests PRIVATE ${name} ${ARG_TEST_DEPS} GTest::gtest GTest::gtest_main)
    gtest_discover_tests(${name}_tests DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "unit")
  endif()
  if(TWINRENDER_BUILD_TESTS AND _gl_tests)
    add_executable(${name}_gl_tests ${_gl_tests})
    target_link_libraries(${name}_gl_tests PRIVATE ${name} ${ARG_TEST_DEPS} GTest::gtest GTest::gtest_main)
    # The GL tests run in poison mode (realtime/gl/poison.h): memory nobody wrote is not zero.
    gtest_discover_tests(${name}_gl_tests DISCOVERY_TIMEOUT 60
                         PROPERTIES LABELS "gl" ENVIRONMENT "TWINRENDER_GL_POISON=1")
  endif()
endfunction()

# twinrender_embed_files(TARGET NAMESPACE ns FUNCTION f ORIGIN dir FILES...): compiles FILES
# into TARGET as `std::span<const core::EmbeddedFile> ns::f()` (cmake/embed_files.cmake),
# regenerated when a file changes.
function(twinrender_embed_files target)
  cmake_parse_arguments(ARG "" "NAMESPACE;FUNCTION;ORIGIN" "FILES" ${ARGN})
  set(_script "${TWINRENDER_SOURCE_DIR}/cmake/embed_files.cmake")
  set(_out "${CMAKE_CURRENT_BINARY_DIR}/embedded_${ARG_FUNCTION}.cpp")
  add_custom_command(
    OUTPUT "${_out}"
    COMMAND "${CMAKE_COMMAND}" "-DOUTPUT=${_out}" "-DFILES=${ARG_FILES}"
            "-DNAMESPACE=${ARG_NAMESPACE}" "-DFUNCTION=${ARG_FUNCTION}" "-DORIGIN=${ARG_ORIGIN}"
            -P "${_script}"
    DEPENDS ${ARG_FILES} "${_script}"
    COMMENT "Embedding ${ARG_ORIGIN}"
    VERBATIM)
  target_sources(${target} PRIVATE "${_out}")
endfunction()
