#include "tests/support/test_dds.h"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace lineloc::test {

std::string testDdsConfig() {
  return std::string(LINELOC_SOURCE_DIR) + "/deploy/cyclonedds.xml";
}

namespace {

// Runs deploy/dds-security.sh with `arguments` on `folder`; returns its output's last line.
std::string runDdsSecurity(const std::string& folder, const std::string& arguments) {
  const std::string command = "LINELOC_DDS_SECURITY_DIR='" + folder + "' '" +
                              std::string(LINELOC_SOURCE_DIR) + "/deploy/dds-security.sh' " +
                              arguments;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    throw std::runtime_error("cannot run " + command);
  }
  std::string output;
  std::array<char, 512> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) {
    output = buffer.data();
  }
  if (pclose(pipe) != 0) {
    throw std::runtime_error("failed: " + command);
  }
  while (!output.empty() && output.back() == '\n') {
    output.pop_back();
  }
  return output;
}

}  // namespace

std::string issueDdsIdentity(const std::string& folder, const std::string& kind,
                             const std::string& name) {
  return runDdsSecurity(folder, "issue " + kind + " '" + name + "'");
}

void revokeDdsIdentity(const std::string& folder, const std::string& kind,
                       const std::string& name) {
  runDdsSecurity(folder, "revoke '" + kind + "-" + name + "'");
}

uint32_t testDomainId() {
  return 10 + static_cast<uint32_t>(getpid()) % 200;
}

std::vector<std::string> networkJitterEnvironment(int jitter_ms) {
  // AddressSanitizer wants its runtime loaded first; preloading comes before it.
  const char* asan_options = std::getenv("ASAN_OPTIONS");
  return {std::string("LD_PRELOAD=") + LINELOC_NETWORK_JITTER_LIBRARY,
          "LINELOC_TEST_SEND_JITTER_MS=" + std::to_string(jitter_ms),
          std::string("ASAN_OPTIONS=") + (asan_options != nullptr ? asan_options : "") +
              ":verify_asan_link_order=0"};
}

}  // namespace lineloc::test
