#include "jobs/migrations.h"

#include "jobs/embedded_migrations.h"
#include "jobs/sqlite_db.h"

namespace vesper {

std::span<const Migration> schema_migrations() { return kEmbeddedMigrations; }

void migrate_schema(sql::Db& db, const std::string& file) {
  migrate_schema(db, file, schema_migrations(), "job store");
}

void migrate_schema(sql::Db& db, const std::string& file, std::span<const Migration> migrations,
                    const std::string& what) {
  db.exec("CREATE TABLE IF NOT EXISTS schema_version(version INTEGER NOT NULL)");
  int version = 0;
  {
    sql::Stmt s(db, "SELECT version FROM schema_version");
    if (s.step())
      version = int(s.i64(0));
    else
      db.exec("INSERT INTO schema_version(version) VALUES(0)");
  }
  const int latest = int(migrations.size());
  if (version > latest)
    throw StoreError(what + " " + file + " has schema version " + std::to_string(version) +
                     ", newer than this vesper understands (" + std::to_string(latest) + ")");
  for (; version < latest; ++version) db.exec(migrations[size_t(version)].sql);
  sql::Stmt(db, "UPDATE schema_version SET version = ?1").bind(1, int64_t(latest)).run();
}

}  // namespace vesper
