# vesper_embed_migrations(<target> <migrations dir> <C++ variable> <header>):
# embeds <dir>/NNNN_*.sql into <target> as a generated header
# (${CMAKE_CURRENT_BINARY_DIR}/generated/<header>, included as <header>)
# defining `inline constexpr Migration <variable>[]` (jobs/migrations.h).
# Migrations are reviewed as SQL and embedded at build time as raw string
# literals; the header is regenerated whenever a .sql file changes (a new
# file re-runs the configure step). Used by the job store and the
# regression history.
function(vesper_embed_migrations target dir variable header)
  file(GLOB sql_files CONFIGURE_DEPENDS ${dir}/*.sql)
  set(generated ${CMAKE_CURRENT_BINARY_DIR}/generated)
  add_custom_command(
    OUTPUT ${generated}/${header}
    COMMAND ${CMAKE_COMMAND} -DMIGRATIONS_DIR=${dir} -DOUTPUT=${generated}/${header}
            -DVARIABLE=${variable} -P ${PROJECT_SOURCE_DIR}/jobs/embed_migrations.cmake
    DEPENDS ${sql_files} ${PROJECT_SOURCE_DIR}/jobs/embed_migrations.cmake
    COMMENT "Embedding ${dir}/*.sql"
    VERBATIM)
  target_sources(${target} PRIVATE ${generated}/${header})
  target_include_directories(${target} PRIVATE ${generated})
endfunction()
