// Fuzz target: decoding a building's line pack as a query reads it from the
// database; malformed packs must be refused with DatabaseError, never read
// out of bounds.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "db/line_pack.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<lineloc::db::ModelLine> lines;
  try {
    lineloc::db::decodeLinePack(std::string_view(reinterpret_cast<const char*>(data), size), 1,
                                Eigen::Vector3d(85000.0, 447000.0, 0.0), lines);
  } catch (const lineloc::db::DatabaseError&) {
  }
  return 0;
}
