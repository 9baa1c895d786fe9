#pragma once
// A thin RAII layer over the SQLite C API (statements, transactions) — the
// Debian-packaged C++ wrappers are not in TOOLCHAIN.md, and this is all the
// store needs.
#include <sqlite3.h>

#include <cstdint>
#include <optional>
#include <string>

#include "jobs/job_store.h"

namespace vesper::sql {

// SQLite virtual-machine steps of the statements finished on this thread so
// far: a deterministic count of a query's work, so a test can check that a
// lease costs the same in a job of 20 tasks and of 20 000 without timing.
uint64_t vm_steps_on_this_thread();

class Db {
 public:
  // `what` names the database in errors ("job store", "regression history").
  explicit Db(const std::string& path, std::string what = "job store");
  ~Db();
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;
  sqlite3* get() const { return db_; }
  void exec(const std::string& sql);
  [[noreturn]] void fail(const std::string& what) const;

 private:
  sqlite3* db_ = nullptr;
  std::string path_, what_;
};

class Stmt {
 public:
  Stmt(const Db& db, const char* sql);
  ~Stmt();
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;
  Stmt& bind(int i, int64_t v);
  Stmt& bind(int i, double v);
  Stmt& bind(int i, const std::string& v);
  Stmt& bind_null(int i);
  // An unset optional binds NULL.
  template <class T>
  Stmt& bind(int i, const std::optional<T>& v) {
    return v ? bind(i, *v) : bind_null(i);
  }
  bool step();  // true: a row is available
  void run() {
    while (step()) {
    }
  }
  int64_t i64(int col) const { return sqlite3_column_int64(s_, col); }
  double f64(int col) const { return sqlite3_column_double(s_, col); }
  bool is_null(int col) const { return sqlite3_column_type(s_, col) == SQLITE_NULL; }
  std::optional<double> optional_f64(int col) const {
    return is_null(col) ? std::nullopt : std::optional<double>(f64(col));
  }
  std::optional<int64_t> optional_i64(int col) const {
    return is_null(col) ? std::nullopt : std::optional<int64_t>(i64(col));
  }
  std::string text(int col) const {
    const auto* t = sqlite3_column_text(s_, col);
    return t ? reinterpret_cast<const char*>(t) : "";
  }

 private:
  const Db& db_;
  sqlite3_stmt* s_ = nullptr;
};

// BEGIN IMMEDIATE ... COMMIT, rolled back if not committed.
class Transaction {
 public:
  explicit Transaction(Db& db) : db_(db) { db_.exec("BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!done_) sqlite3_exec(db_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit() {
    db_.exec("COMMIT");
    done_ = true;
  }

 private:
  Db& db_;
  bool done_ = false;
};

}  // namespace vesper::sql
