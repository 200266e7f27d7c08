# Helpers shared by every module's CMakeLists.txt.

# lineloc_add_executable(NAME SOURCES... LIBS ...): a thin main into build/bin.
function(lineloc_add_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
endfunction()

# lineloc_add_unit_test(NAME SOURCES... LIBS ... [POSTGIS] [SHARED_DATA]): a GoogleTest
# binary registered with CTest under the label "unit" (the sanitizer build runs
# every test it builds; it builds no integration tests or benchmarks).
# POSTGIS: its tests need the private PostGIS cluster (the CTest fixture
# "postgis" starts it; tests/support/test_database.h gives each test a fresh
# migrated database) and are labelled "postgis" instead. SHARED_DATA: its tests
# read the real data of ../shared/data (lineloc_shared_data_properties).
function(lineloc_add_unit_test name)
  cmake_parse_arguments(ARG "POSTGIS;SHARED_DATA" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} lineloc_test_support GTest::gtest
                        GTest::gtest_main)
  target_precompile_headers(${name} REUSE_FROM lineloc_test_pch)
  target_compile_definitions(${name} PRIVATE
    LINELOC_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    LINELOC_SHARED_DATA_DIR="${LINELOC_SHARED_DATA_DIR}")
  set(label unit)
  if(ARG_POSTGIS)
    set(label postgis)
  endif()
  lineloc_shared_data_properties(${name} ${ARG_SHARED_DATA} label shared_data)
  if(ARG_POSTGIS)
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${label}"
                         FIXTURES_REQUIRED postgis
                         ENVIRONMENT "LINELOC_TEST_PG_PORT=${LINELOC_TEST_PG_PORT}"
                         ${shared_data})
  else()
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${label}"
                         ${shared_data})
  endif()
endfunction()

# lineloc_shared_data_properties(NAME READS_SHARED_DATA LABEL_VAR PROPERTIES_VAR):
# for a test binary that reads ../shared/data, the label "shared-data" in
# place of its own and, where that folder is missing (a fresh clone on its
# own), the property DISABLED, so CTest lists its tests as not run rather than
# failed; the configure step says which binaries it disabled.
function(lineloc_shared_data_properties name reads_shared_data label_var properties_var)
  set(properties "")
  if(reads_shared_data)
    # One label: gtest_discover_tests takes a list value for more properties.
    set(${label_var} shared-data PARENT_SCOPE)
    if(NOT EXISTS "${LINELOC_SHARED_DATA_DIR}/citymodels")
      message(STATUS "${name}: disabled, its real data is missing (${LINELOC_SHARED_DATA_DIR})")
      set(properties DISABLED TRUE)
    endif()
  endif()
  set(${properties_var} ${properties} PARENT_SCOPE)
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
# libFuzzer binary, registered as a CTest test (label "fuzz") that fuzzes for
# LINELOC_FUZZ_SECONDS from the seed corpus, keeping what it finds under the
# build's fuzz-corpus/ and any crashing input under fuzz-findings/
# (deploy/fuzz.sh); otherwise it links tests/fuzz/fuzz_replay_main.cpp, which
# replays the seed corpus plus a fixed number of deterministic mutations of it,
# and is registered as a CTest test (label "fuzz") so every build exercises it.
option(LINELOC_FUZZ "Build fuzz targets as libFuzzer binaries (needs clang)" OFF)
set(LINELOC_FUZZ_SECONDS 600 CACHE STRING "How long each libFuzzer test fuzzes (LINELOC_FUZZ)")
function(lineloc_add_fuzz_target name)
  cmake_parse_arguments(ARG "" "CORPUS" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  if(LINELOC_FUZZ)
    target_compile_options(${name} PRIVATE -fsanitize=fuzzer)
    target_link_options(${name} PRIVATE -fsanitize=fuzzer)
    set(found ${CMAKE_BINARY_DIR}/fuzz-corpus/${name})
    file(MAKE_DIRECTORY ${found} ${CMAKE_BINARY_DIR}/fuzz-findings)
    add_test(NAME ${name}
             COMMAND ${name} -max_total_time=${LINELOC_FUZZ_SECONDS}
                     -artifact_prefix=${CMAKE_BINARY_DIR}/fuzz-findings/${name}- ${found}
                     ${ARG_CORPUS})
    set_tests_properties(${name} PROPERTIES LABELS fuzz TIMEOUT 0)
  else()
    target_sources(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/fuzz/fuzz_replay_main.cpp)
    add_test(NAME ${name} COMMAND ${name} ${ARG_CORPUS})
    set_tests_properties(${name} PROPERTIES LABELS fuzz)
  endif()
endfunction()

# lineloc_add_integration_test(NAME [REAL_TIME] [SHARED_DATA] SOURCES... LIBS ... DEPENDS programs...):
# a GoogleTest binary that starts the project's real programs (from
# LINELOC_BIN_DIR) against the private PostGIS cluster and DDS on loopback;
# labelled "integration". REAL_TIME tests replay sensors in real time and check
# what the robot achieved in that time: they run alone (RUN_SERIAL), so other
# tests do not take the cores the real robot and backbone would have.
function(lineloc_add_integration_test name)
  cmake_parse_arguments(ARG "REAL_TIME;SHARED_DATA" "" "SOURCES;LIBS;DEPENDS" ${ARGN})
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
  set(label integration)
  lineloc_shared_data_properties(${name} ${ARG_SHARED_DATA} label shared_data)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${label}"
                       FIXTURES_REQUIRED postgis RUN_SERIAL ${run_serial}
                       ENVIRONMENT "LINELOC_TEST_PG_PORT=${LINELOC_TEST_PG_PORT}"
                       ${shared_data})
endfunction()
