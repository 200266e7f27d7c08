# Fails when a module includes one it must not depend on: the backbone and the
# robot share only idl/ and common/; common/ depends on no module of lineloc;
# no library includes apps/ (docs/architecture.md).
# Usage: cmake -DSOURCE_DIR=<repository> -P check_layering.cmake
set(forbidden
  "backbone:robot/" "robot:backbone/"
  "common:robot/" "common:backbone/" "common:db/" "common:sim/"
  "robot:apps/" "backbone:apps/" "db:apps/" "sim:apps/" "common:apps/")
set(violations "")
foreach(rule ${forbidden})
  string(REPLACE ":" ";" parts ${rule})
  list(GET parts 0 module)
  list(GET parts 1 included)
  file(GLOB_RECURSE sources ${SOURCE_DIR}/${module}/*.h ${SOURCE_DIR}/${module}/*.cpp)
  foreach(source ${sources})
    file(STRINGS ${source} lines REGEX "^#include \"${included}")
    foreach(line ${lines})
      file(RELATIVE_PATH relative ${SOURCE_DIR} ${source})
      string(APPEND violations "  ${relative}: ${line}\n")
    endforeach()
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "includes across module boundaries:\n${violations}")
endif()
