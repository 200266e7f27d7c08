#include "tests/support/foxglove_cdr.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tests/support/child_process.h"

namespace lineloc::test {
namespace {

namespace fs = std::filesystem;

// A folder of its own for one call, removed with it.
class CallFolder {
 public:
  CallFolder() {
    static std::atomic<int> calls{0};
    path_ = fs::temp_directory_path() / fmt::format("foxglove_cdr_{}_{}", getpid(), calls++);
    fs::create_directories(path_);
  }
  ~CallFolder() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Runs ros2_cdr.js with `args`; returns its output, throwing it when it fails.
std::string runScript(const std::vector<std::string>& args, const fs::path& output) {
  std::vector<std::string> all = {LINELOC_ROS2_CDR_SCRIPT};
  all.insert(all.end(), args.begin(), args.end());
  ChildProcess node("/usr/bin/node", all, output.string(),
                    {std::string("NODE_PATH=") + LINELOC_ROS2_CDR_MODULES});
  const std::optional<int> exit_code = node.wait(30'000);
  const std::string text = readAll(output);
  if (exit_code != 0) {
    throw std::runtime_error("ros2_cdr.js: " + text);
  }
  return text;
}

}  // namespace

nlohmann::json decodedByFoxglove(const std::string& type, const std::vector<uint8_t>& bytes) {
  const CallFolder folder;
  std::ofstream(folder.path() / "sample.cdr", std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return nlohmann::json::parse(runScript({"decode", type, (folder.path() / "sample.cdr").string()},
                                         folder.path() / "decoded.json"));
}

std::vector<uint8_t> encodedByFoxglove(const std::string& type, const nlohmann::json& message) {
  const CallFolder folder;
  std::ofstream(folder.path() / "message.json") << message.dump();
  runScript({"encode", type, (folder.path() / "message.json").string(),
             (folder.path() / "sample.cdr").string()},
            folder.path() / "node.log");
  const std::string bytes = readAll(folder.path() / "sample.cdr");
  return {bytes.begin(), bytes.end()};
}

}  // namespace lineloc::test
