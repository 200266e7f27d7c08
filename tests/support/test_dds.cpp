#include "tests/support/test_dds.h"

#include <unistd.h>

namespace lineloc::test {

std::string testDdsConfig() {
  return std::string(LINELOC_SOURCE_DIR) + "/deploy/cyclonedds.xml";
}

uint32_t testDomainId() {
  return 10 + static_cast<uint32_t>(getpid()) % 200;
}

}  // namespace lineloc::test
