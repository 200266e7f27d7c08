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
  int32_t binaryInt4(int row, int column) const;
  // The raw bytes of a binary-format value (e.g. a geometry's EWKB).
  const char* bytes(int row, int column) const { return PQgetvalue(result_.get(), row, column); }
  int length(int row, int column) const { return PQgetlength(result_.get(), row, column); }
  PGresult* get() const { return result_.get(); }

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
  // Prepares `sql` as `name` unless this session has a statement of that name
  // (so several query objects can share one connection).
  void prepareOnce(const std::string& name, const std::string& sql);
  // Runs a prepared statement with text parameters; results binary when asked.
  Result execPrepared(const std::string& name, const std::vector<std::string>& params,
                      bool binary_results);

  PGconn* get() const { return connection_.get(); }

  // Throws DatabaseError with `what` and the server's message unless the
  // connection's last operation succeeded.
  void throwUnlessOk(int libpq_status, const std::string& what) const;

 private:
  Result check(PGresult* result, const std::string& what) const;

  std::unique_ptr<PGconn, decltype(&PQfinish)> connection_;
};

// COPY ... FROM STDIN in text format, streamed: rows are buffered and sent in
// chunks of about a megabyte. finish() ends the copy and reports the server's
// verdict; an unfinished copy is abandoned (and its transaction fails).
class CopyIn {
 public:
  CopyIn(Connection& connection, const std::string& copy_sql);
  ~CopyIn();
  CopyIn(const CopyIn&) = delete;
  CopyIn& operator=(const CopyIn&) = delete;

  // Appends to the current row's text; rows end with '\n'.
  std::string& buffer() { return buffer_; }
  // Sends the buffer when it has grown past the chunk size.
  void flushIfFull();
  void finish();

 private:
  void send();

  Connection& connection_;
  std::string buffer_;
  bool finished_ = false;
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
