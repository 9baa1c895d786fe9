#pragma once
// The job store's schema migrations: jobs/migrations/NNNN_*.sql, embedded at
// build time (jobs/embed_migrations.cmake). Migration n leads to schema
// version n; a database's `schema_version` counts the migrations applied.
#include <span>
#include <string>

namespace vesper {

namespace sql {
class Db;
}

struct Migration {
  int version;       // the schema version after this migration (1, 2, ...)
  const char* file;  // e.g. "0002_job_assets.sql"
  const char* sql;   // the file's text, run as one script
};

// Every migration, in version order.
std::span<const Migration> schema_migrations();

// Creates the schema_version table if needed and applies the migrations the
// database lacks, in order, in the caller's transaction. Throws StoreError
// for a database newer than this build (`file` names it in the message).
void migrate_schema(sql::Db& db, const std::string& file);

// The same for another database with its own migrations (embedded the same
// way, embed_migrations.cmake -DVARIABLE=...); `what` names it in errors.
void migrate_schema(sql::Db& db, const std::string& file, std::span<const Migration> migrations,
                    const std::string& what);

}  // namespace vesper
