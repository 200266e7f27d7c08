#include "db/connection.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>

namespace lineloc::db {
namespace {

uint64_t readBigEndian64(const char* bytes) {
  uint64_t value;
  std::memcpy(&value, bytes, sizeof(value));
  return std::endian::native == std::endian::little ? __builtin_bswap64(value) : value;
}

uint16_t readBigEndian16(const char* bytes) {
  uint16_t value;
  std::memcpy(&value, bytes, sizeof(value));
  return std::endian::native == std::endian::little ? __builtin_bswap16(value) : value;
}

std::vector<const char*> pointersTo(const std::vector<std::string>& params) {
  std::vector<const char*> pointers;
  pointers.reserve(params.size());
  for (const std::string& param : params) {
    pointers.push_back(param.c_str());
  }
  return pointers;
}

}  // namespace

double Result::binaryFloat8(int row, int column) const {
  return std::bit_cast<double>(readBigEndian64(PQgetvalue(result_.get(), row, column)));
}

int64_t Result::binaryInt8(int row, int column) const {
  return static_cast<int64_t>(readBigEndian64(PQgetvalue(result_.get(), row, column)));
}

int32_t Result::binaryInt4(int row, int column) const {
  uint32_t value;
  std::memcpy(&value, PQgetvalue(result_.get(), row, column), sizeof(value));
  return static_cast<int32_t>(std::endian::native == std::endian::little ? __builtin_bswap32(value)
                                                                         : value);
}

int16_t Result::binaryInt2(int row, int column) const {
  return static_cast<int16_t>(readBigEndian16(PQgetvalue(result_.get(), row, column)));
}

Connection::Connection(const std::string& conninfo)
    : connection_(PQconnectdb(conninfo.c_str()), &PQfinish) {
  if (PQstatus(connection_.get()) != CONNECTION_OK) {
    throw DatabaseError(fmt::format("cannot connect to PostgreSQL ({}): {}", conninfo,
                                    PQerrorMessage(connection_.get())));
  }
  PQclear(PQexec(connection_.get(), "SET client_min_messages = warning"));
}

Result Connection::check(PGresult* raw, const std::string& what) const {
  Result result(raw);
  const ExecStatusType status = PQresultStatus(raw);
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
    throw DatabaseError(fmt::format("{} failed: {}", what, PQerrorMessage(connection_.get())));
  }
  return result;
}

Result Connection::exec(const std::string& sql) {
  return check(PQexec(connection_.get(), sql.c_str()), fmt::format("SQL '{:.60}'", sql));
}

Result Connection::execParams(const std::string& sql, const std::vector<std::string>& params) {
  const std::vector<const char*> values = pointersTo(params);
  return check(PQexecParams(connection_.get(), sql.c_str(), static_cast<int>(values.size()),
                            nullptr, values.data(), nullptr, nullptr, 0),
               fmt::format("SQL '{:.60}'", sql));
}

void Connection::prepare(const std::string& name, const std::string& sql) {
  check(PQprepare(connection_.get(), name.c_str(), sql.c_str(), 0, nullptr),
        fmt::format("prepare '{}'", name));
}

void Connection::prepareOnce(const std::string& name, const std::string& sql) {
  if (execParams("SELECT 1 FROM pg_prepared_statements WHERE name = $1", {name}).rows() == 0) {
    prepare(name, sql);
  }
}

Result Connection::execPrepared(const std::string& name, const std::vector<std::string>& params,
                                bool binary_results) {
  const std::vector<const char*> values = pointersTo(params);
  return check(PQexecPrepared(connection_.get(), name.c_str(), static_cast<int>(values.size()),
                              values.data(), nullptr, nullptr, binary_results ? 1 : 0),
               fmt::format("statement '{}'", name));
}

void Connection::throwUnlessOk(int libpq_status, const std::string& what) const {
  if (libpq_status != 1) {
    throw DatabaseError(fmt::format("{} failed: {}", what, PQerrorMessage(connection_.get())));
  }
}

namespace {
constexpr size_t kCopyChunkBytes = 1 << 20;
}  // namespace

CopyIn::CopyIn(Connection& connection, const std::string& copy_sql) : connection_(connection) {
  Result result(PQexec(connection.get(), copy_sql.c_str()));
  if (PQresultStatus(result.get()) != PGRES_COPY_IN) {
    throw DatabaseError(
        fmt::format("SQL '{:.60}' failed: {}", copy_sql, PQerrorMessage(connection.get())));
  }
  buffer_.reserve(2 * kCopyChunkBytes);
}

CopyIn::~CopyIn() {
  if (!finished_) {
    PQputCopyEnd(connection_.get(), "abandoned");
    while (PGresult* result = PQgetResult(connection_.get())) {
      PQclear(result);
    }
  }
}

void CopyIn::send() {
  if (!buffer_.empty()) {
    connection_.throwUnlessOk(
        PQputCopyData(connection_.get(), buffer_.data(), static_cast<int>(buffer_.size())),
        "COPY data");
    buffer_.clear();
  }
}

void CopyIn::flushIfFull() {
  if (buffer_.size() >= kCopyChunkBytes) {
    send();
  }
}

void CopyIn::finish() {
  send();
  finished_ = true;
  connection_.throwUnlessOk(PQputCopyEnd(connection_.get(), nullptr), "COPY end");
  std::string error;
  while (PGresult* raw = PQgetResult(connection_.get())) {
    Result result(raw);
    if (PQresultStatus(raw) != PGRES_COMMAND_OK && error.empty()) {
      error = PQresultErrorMessage(raw);
    }
  }
  if (!error.empty()) {
    throw DatabaseError("COPY failed: " + error);
  }
}

}  // namespace lineloc::db
