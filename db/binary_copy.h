// COPY ... FROM STDIN (FORMAT binary): rows streamed as PostgreSQL's binary
// field values, so the server parses no text. Each field is a big-endian
// int32 length (-1 for NULL) and the type's binary form: big-endian integers
// and float8, raw bytes for text and bytea, EWKB for a PostGIS geometry,
// version byte 1 and the text for jsonb, four float8 for a box.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "db/big_endian.h"
#include "db/connection.h"

namespace lineloc::db {

class BinaryCopyIn {
 public:
  // `target` is what follows COPY: "table (column, ...)".
  BinaryCopyIn(Connection& connection, const std::string& target);

  // Starts a row of `fields` values, which the calls below then append in order.
  void beginRow(int16_t fields);

  template <BigEndianValue T>
  void value(T number) {
    appendBigEndian<int32_t>(copy_.buffer(), sizeof(T));
    appendBigEndian(copy_.buffer(), number);
  }
  void bytes(std::string_view bytes);
  void null();
  // A field whose bytes `write(std::string& out)` appends.
  template <typename Write>
  void field(Write&& write) {
    std::string& out = copy_.buffer();
    const size_t length_at = out.size();
    out.append(sizeof(int32_t), '\0');
    write(out);
    std::string length;
    appendBigEndian(length, static_cast<int32_t>(out.size() - length_at - sizeof(int32_t)));
    out.replace(length_at, length.size(), length);
  }

  // Ends the copy; throws DatabaseError with the server's verdict.
  void finish();

 private:
  CopyIn copy_;
};

}  // namespace lineloc::db
