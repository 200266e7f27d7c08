// Fuzz target: YAML configuration files applied to program options.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/config/program_options.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string robot_id = "robot1";
  double rate_hz = 10.0;
  int domain_id = 0;
  std::vector<double> pose;
  lineloc::ProgramOptions options("fuzz", "fuzz");
  options.add("robot_id", robot_id, "");
  options.add("rate_hz", rate_hz, "");
  options.add("domain_id", domain_id, "");
  options.add("pose", pose, "");
  try {
    options.applyConfig(std::string(reinterpret_cast<const char*>(data), size), "fuzz.yml");
  } catch (const std::runtime_error&) {
  }
  return 0;
}
