# Helpers shared by every module's CMakeLists.txt.

# lineloc_add_executable(NAME SOURCES... LIBS ...): a thin main into build/bin.
function(lineloc_add_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
endfunction()

# lineloc_add_unit_test(NAME SOURCES... LIBS ... [POSTGIS]): a GoogleTest
# binary registered with CTest under the label "unit" (the sanitizer build runs
# every test it builds; it builds no integration tests or benchmarks).
# POSTGIS: its tests need the private PostGIS cluster (the CTest fixture
# "postgis" starts it; tests/support/test_database.h gives each test a fresh
# migrated database) and are labelled "postgis" instead.
function(lineloc_add_unit_test name)
  cmake_parse_arguments(ARG "POSTGIS" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} lineloc_test_support GTest::gtest
                        GTest::gtest_main)
  target_precompile_headers(${name} REUSE_FROM lineloc_test_pch)
  target_compile_definitions(${name} PRIVATE
    LINELOC_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    LINELOC_SHARED_DATA_DIR="${LINELOC_SHARED_DATA_DIR}")
  if(ARG_POSTGIS)
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS postgis
                         FIXTURES_REQUIRED postgis
                         ENVIRONMENT "LINELOC_TEST_PG_PORT=${LINELOC_TEST_PG_PORT}")
  else()
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS unit)
  endif()
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
    LINELOC_SHARED_DATA_DIR="${LINELOC_SHARED_DATA_DIR}"
    LINELOC_BIN_DIR="${CMAKE_RUNTIME_OUTPUT_DIRECTORY}")
endfunction()

# lineloc_add_module_directories(): add_subdirectory() for every immediate
# subfolder that has a CMakeLists.txt, so a new module is one new folder.
function(lineloc_add_module_directories)
  file(GLOB children LIST_DIRECTORIES true CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*)
  foreach(child ${children})
    if(IS_DIRECTORY ${child} AND EXISTS ${child}/CMakeLists.txt)
      add_subdirectory(${child})
    endif()
  endforeach()
endfunction()

# lineloc_add_fuzz_target(NAME SOURCES... LIBS ... [CORPUS dir]): a fuzz target
# defining LLVMFuzzerTestOneInput. With clang and LINELOC_FUZZ=ON it is a
# libFuzzer binary; otherwise it links tests/fuzz/fuzz_replay_main.cpp, which
# replays the seed corpus plus a fixed number of deterministic mutations of it,
# and is registered as a CTest test (label "fuzz") so every build exercises it.
option(LINELOC_FUZZ "Build fuzz targets as libFuzzer binaries (needs clang)" OFF)
function(lineloc_add_fuzz_target name)
  cmake_parse_arguments(ARG "" "CORPUS" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  if(LINELOC_FUZZ)
    target_compile_options(${name} PRIVATE -fsanitize=fuzzer)
    target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  else()
    target_sources(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/fuzz/fuzz_replay_main.cpp)
    add_test(NAME ${name} COMMAND ${name} ${ARG_CORPUS})
    set_tests_properties(${name} PROPERTIES LABELS fuzz)
  endif()
endfunction()

# lineloc_add_integration_test(NAME [REAL_TIME] SOURCES... LIBS ... DEPENDS programs...):
# a GoogleTest binary that starts the project's real programs (from
# LINELOC_BIN_DIR) against the private PostGIS cluster and DDS on loopback;
# labelled "integration". REAL_TIME tests replay sensors in real time and check
# what the robot achieved in that time: they run alone (RUN_SERIAL), so other
# tests do not take the cores the real robot and backbone would have.
function(lineloc_add_integration_test name)
  cmake_parse_arguments(ARG "REAL_TIME" "" "SOURCES;LIBS;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} lineloc_test_support GTest::gtest
                        GTest::gtest_main)
  target_precompile_headers(${name} REUSE_FROM lineloc_test_pch)
  target_compile_definitions(${name} PRIVATE
    LINELOC_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    LINELOC_SHARED_DATA_DIR="${LINELOC_SHARED_DATA_DIR}"
    LINELOC_BIN_DIR="${CMAKE_RUNTIME_OUTPUT_DIRECTORY}")
  if(ARG_DEPENDS)
    add_dependencies(${name} ${ARG_DEPENDS})
  endif()
  set(run_serial FALSE)
  if(ARG_REAL_TIME)
    set(run_serial TRUE)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS integration
                       FIXTURES_REQUIRED postgis RUN_SERIAL ${run_serial}
                       ENVIRONMENT "LINELOC_TEST_PG_PORT=${LINELOC_TEST_PG_PORT}")
endfunction()
