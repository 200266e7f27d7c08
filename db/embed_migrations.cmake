# Writes OUTPUT, a C++ source holding every migration in MIGRATIONS_DIR (files
# named NNNN_name.sql, applied in that order) as a raw string, so the programs
# that migrate a database need no files beside them.
file(GLOB migration_files "${MIGRATIONS_DIR}/*.sql")
list(SORT migration_files)
set(entries "")
foreach(path ${migration_files})
  get_filename_component(file_name ${path} NAME_WE)
  string(REGEX MATCH "^([0-9]+)_(.+)$" matched ${file_name})
  if(NOT matched)
    message(FATAL_ERROR "migration ${path}: name must be NNNN_name.sql")
  endif()
  math(EXPR version "${CMAKE_MATCH_1}")
  file(READ ${path} sql)
  string(APPEND entries "    {${version}, \"${CMAKE_MATCH_2}\", R\"lineloc_sql(${sql})lineloc_sql\"},\n")
endforeach()
file(WRITE ${OUTPUT}.tmp "// Generated from db/migrations/*.sql at build time; do not edit.\n"
  "#include \"db/migrations.h\"\n\nnamespace lineloc::db {\n\n"
  "const std::vector<Migration>& embeddedMigrations() {\n"
  "  static const std::vector<Migration> migrations = {\n${entries}  };\n"
  "  return migrations;\n}\n\n}  // namespace lineloc::db\n")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
