// A libpq connection with RAII results and errors that carry the server's message.
#pragma once

#include <libpq-fe.h>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace lineloc::db {

class DatabaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Owns one PGresult.
class Result {
 public:
  explicit Result(PGresult* result) : result_(result, &PQclear) {}
  int rows() const { return PQntuples(result_.get()); }
  bool isNull(int row, int column) const { return PQgetisnull(result_.get(), row, column); }
  std::string text(int row, int column) const { return PQgetvalue(result_.get(), row, column); }
  // Binary-format column values (network byte order), as sent by PostgreSQL.
  double binaryFloat8(int row, int column) const;
  int64_t binaryInt8(int row, int column) const;
  int16_t binaryInt2(int row, int column) const;

 private:
  std::unique_ptr<PGresult, decltype(&PQclear)> result_;
};

class Connection {
 public:
  // `conninfo` is a libpq connection string ("host=... port=... dbname=...").
  explicit Connection(const std::string& conninfo);

  // Runs one or more statements; throws DatabaseError with the server's message.
  Result exec(const std::string& sql);
  // Runs a statement with text parameters $1, $2, ...
  Result execParams(const std::string& sql, const std::vector<std::string>& params);
  void prepare(const std::string& name, const std::string& sql);
  // Runs a prepared statement with text parameters; results binary when asked.
  Result execPrepared(const std::string& name, const std::vector<std::string>& params,
                      bool binary_results);

  PGconn* get() const { return connection_.get(); }

 private:
  Result check(PGresult* result, const std::string& what) const;

  std::unique_ptr<PGconn, decltype(&PQfinish)> connection_;
};

// Runs `body` inside BEGIN/COMMIT; rolls back and rethrows when it throws.
template <typename Body>
void inTransaction(Connection& connection, Body&& body) {
  connection.exec("BEGIN");
  try {
    body();
  } catch (...) {
    PQclear(PQexec(connection.get(), "ROLLBACK"));
    throw;
  }
  connection.exec("COMMIT");
}

}  // namespace lineloc::db
