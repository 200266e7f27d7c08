# Helpers shared by every module's CMakeLists.txt.

# lineloc_add_executable(NAME SOURCES... LIBS ...): a thin main into build/bin.
function(lineloc_add_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
endfunction()

# lineloc_add_unit_test(NAME SOURCES... LIBS ... [LABELS ...]): a GoogleTest
# binary registered with CTest under the "unit" label (the sanitizer build runs
# exactly these).
function(lineloc_add_unit_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    LINELOC_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    LINELOC_SHARED_DATA_DIR="${LINELOC_SHARED_DATA_DIR}")
  gtest_discover_tests(${name}
    PROPERTIES LABELS "unit;${ARG_LABELS}"
    DISCOVERY_TIMEOUT 60)
endfunction()

# lineloc_add_benchmark(NAME SOURCES... LIBS ...): a Google Benchmark binary.
function(lineloc_add_benchmark name)
  if(NOT LINELOC_BUILD_BENCH)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} benchmark::benchmark)
  target_compile_definitions(${name} PRIVATE
    LINELOC_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    LINELOC_SHARED_DATA_DIR="${LINELOC_SHARED_DATA_DIR}")
endfunction()
