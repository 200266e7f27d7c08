// DDS settings for tests: the project's loopback configuration and a domain id
// of this test process's own, so tests running in parallel never hear each other.
#pragma once

#include <cstdint>
#include <string>

namespace lineloc::test {

// deploy/cyclonedds.xml of this source tree.
std::string testDdsConfig();

// A domain id in [10, 210) derived from the process id.
uint32_t testDomainId();

}  // namespace lineloc::test
