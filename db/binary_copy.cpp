#include "db/binary_copy.h"

namespace lineloc::db {
namespace {

// Signature, flags (no OIDs), header extension length.
constexpr std::string_view kHeader("PGCOPY\n\377\r\n\0\0\0\0\0\0\0\0\0", 19);

}  // namespace

BinaryCopyIn::BinaryCopyIn(Connection& connection, const std::string& target)
    : copy_(connection, "COPY " + target + " FROM STDIN (FORMAT binary)") {
  copy_.buffer().append(kHeader);
}

void BinaryCopyIn::beginRow(int16_t fields) {
  copy_.flushIfFull();
  appendBigEndian(copy_.buffer(), fields);
}

void BinaryCopyIn::bytes(std::string_view bytes) {
  appendBigEndian(copy_.buffer(), static_cast<int32_t>(bytes.size()));
  copy_.buffer().append(bytes);
}

void BinaryCopyIn::null() {
  appendBigEndian<int32_t>(copy_.buffer(), -1);
}

void BinaryCopyIn::finish() {
  appendBigEndian<int16_t>(copy_.buffer(), -1);
  copy_.finish();
}

}  // namespace lineloc::db
