// The schema migrations embedded from jobs/migrations/NNNN_*.sql: numbered
// without gaps, and a database left at any older version by an older vesper
// reaches exactly the schema of a fresh one, keeping its jobs.
#include "jobs/migrations.h"

#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "jobs/job_store.h"
#include "jobs/sqlite_db.h"
#include "tests/common/temp_dir.h"

namespace vesper {
namespace {

// Every table, index and trigger with its CREATE statement (as ALTERed).
std::string schema_of(const std::filesystem::path& file) {
  sql::Db db(file.string());
  sql::Stmt s(db, "SELECT type, name, tbl_name, sql FROM sqlite_master ORDER BY type, name");
  std::string out;
  while (s.step())
    out += s.text(0) + " " + s.text(1) + " on " + s.text(2) + ": " + s.text(3) + "\n";
  return out;
}

// A database as a vesper of schema version `version` left it, with one job
// of two queued tasks when the version has jobs.
void write_database_at(const std::filesystem::path& file, int version) {
  sql::Db db(file.string());
  db.exec("CREATE TABLE schema_version(version INTEGER NOT NULL)");
  db.exec("INSERT INTO schema_version(version) VALUES(" + std::to_string(version) + ")");
  for (int v = 0; v < version; ++v) db.exec(schema_migrations()[size_t(v)].sql);
  if (version == 0) return;
  db.exec(
      "INSERT INTO jobs(id, name, scene, spp, priority, max_attempts, state, created) "
      "VALUES(1, 'old', 'scene-sha', 8, 50, 3, 'active', 0)");
  db.exec(
      "INSERT INTO tasks(job_id, frame, sample_begin, sample_end, state) "
      "VALUES(1, 1, 0, 8, 'queued'), (1, 2, 0, 8, 'queued')");
}

TEST(Migrations, AreNumberedFilesWithoutGaps) {
  const auto migrations = schema_migrations();
  ASSERT_FALSE(migrations.empty());
  const std::regex name("[0-9]{4}_[a-z0-9_]+\\.sql");
  for (size_t i = 0; i < migrations.size(); ++i) {
    EXPECT_EQ(migrations[i].version, int(i + 1));
    EXPECT_TRUE(std::regex_match(migrations[i].file, name)) << migrations[i].file;
    EXPECT_EQ(std::stoi(migrations[i].file), int(i + 1)) << migrations[i].file;
    EXPECT_NE(std::string(migrations[i].sql).find(';'), std::string::npos) << migrations[i].file;
  }
}

TEST(Migrations, EveryOlderVersionReachesTheSchemaOfAFreshDatabase) {
  const test::TempDir dir("migrations");
  const int latest = int(schema_migrations().size());
  { JobStore fresh(dir / "fresh.sqlite"); }
  const std::string expected = schema_of(dir / "fresh.sqlite");
  EXPECT_NE(expected.find("table tasks"), std::string::npos) << expected;
  for (int version = 0; version <= latest; ++version) {
    SCOPED_TRACE("from version " + std::to_string(version));
    const auto file = dir / ("v" + std::to_string(version) + ".sqlite");
    write_database_at(file, version);
    {
      JobStore s(file);
      EXPECT_EQ(s.schema_version(), latest);
      if (version > 0) {  // its job survived and its tasks are still leased out
        EXPECT_EQ(s.job(1)->name, "old");
        EXPECT_EQ(s.job(1)->queued, 2);
        const auto lease = s.lease("w", 1);
        ASSERT_TRUE(lease);
        EXPECT_EQ(lease->task.frame, 1);
        EXPECT_EQ(lease->scene, "scene-sha");
        EXPECT_EQ(lease->spp, 8);
      }
    }
    EXPECT_EQ(schema_of(file), expected);
    { JobStore again(file); }  // opening a current database changes nothing
    EXPECT_EQ(schema_of(file), expected);
  }
}

}  // namespace
}  // namespace vesper
