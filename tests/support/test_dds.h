// DDS settings for tests: the project's loopback configuration and a domain id
// of this test process's own, so tests running in parallel never hear each other.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lineloc::test {

// deploy/cyclonedds.xml of this source tree.
std::string testDdsConfig();

// A domain id in [10, 210) derived from the process id.
uint32_t testDomainId();

// Issues a DDS Security identity with deploy/dds-security.sh into `folder`
// (its CA made there first): `kind` "robot" or "backbone", `name` the robot's
// id or the backbone's name. Returns the Cyclone DDS overlay that secures a
// participant with it, to add to testDdsConfig() after a comma.
std::string issueDdsIdentity(const std::string& folder, const std::string& kind,
                             const std::string& name);

// Revokes "<kind>-<name>" issued in `folder`: participants started after it
// refuse that identity.
void revokeDdsIdentity(const std::string& folder, const std::string& kind, const std::string& name);

// The environment ("NAME=value") under which a child process's UDP datagrams
// each leave up to `jitter_ms` late (tests/support/network_jitter), for
// ChildProcess.
std::vector<std::string> networkJitterEnvironment(int jitter_ms);

}  // namespace lineloc::test
