#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>

#include "common/config/program_options.h"

namespace lineloc {
namespace {

struct Options {
  std::string robot_id = "robot1";
  double rate_hz = 10.0;
  int domain_id = 0;
  std::vector<double> pose = {0, 0, 0};
  std::vector<double> origin;
  std::vector<std::string> files;
};

class ProgramOptionsTest : public ::testing::Test {
 protected:
  ProgramOptionsTest() : options_("test", "test program") {
    options_.add("robot_id", values_.robot_id, "id");
    options_.add("rate_hz", values_.rate_hz, "rate");
    options_.add("domain_id", values_.domain_id, "domain");
    options_.add("pose", values_.pose, "pose");
    options_.addFixedSize("origin", values_.origin, 3, "origin x y z");
    options_.addPositional("files", values_.files, "input files");
  }

  std::string writeConfig(const std::string& text) {
    const auto path =
        std::filesystem::temp_directory_path() / ("options_" + std::to_string(getpid()) + ".yml");
    std::ofstream(path) << text;
    return path.string();
  }

  std::optional<int> parse(std::vector<const char*> args) {
    args.insert(args.begin(), "test");
    return options_.parse(static_cast<int>(args.size()), args.data());
  }

  Options values_;
  ProgramOptions options_;
};

TEST_F(ProgramOptionsTest, DefaultsStandWithoutConfig) {
  EXPECT_EQ(parse({}), std::nullopt);
  EXPECT_EQ(values_.robot_id, "robot1");
  EXPECT_DOUBLE_EQ(values_.rate_hz, 10.0);
}

TEST_F(ProgramOptionsTest, YamlSetsAndFlagsOverride) {
  const std::string config =
      writeConfig("robot_id: rover\nrate_hz: 30\ndomain_id: 5\npose: [1, 2, 3]\n");
  EXPECT_EQ(parse({"--config", config.c_str(), "--rate-hz", "15"}), std::nullopt);
  EXPECT_EQ(values_.robot_id, "rover");
  EXPECT_DOUBLE_EQ(values_.rate_hz, 15.0);
  EXPECT_EQ(values_.domain_id, 5);
  EXPECT_EQ(values_.pose, (std::vector<double>{1, 2, 3}));
}

TEST_F(ProgramOptionsTest, UnknownKeyIsAnErrorNamingIt) {
  EXPECT_THROW(options_.applyConfig("rate_hz: 1\nrobot_idd: x\n", "c.yml"), std::runtime_error);
  try {
    options_.applyConfig("robot_idd: x\n", "c.yml");
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("c.yml:1: unknown key 'robot_idd'"), std::string::npos)
        << error.what();
  }
}

TEST_F(ProgramOptionsTest, BadValuesAreErrors) {
  EXPECT_THROW(options_.applyConfig("rate_hz: fast\n", "c.yml"), std::runtime_error);
  EXPECT_THROW(options_.applyConfig("domain_id: [1, 2]\n", "c.yml"), std::runtime_error);
  EXPECT_THROW(options_.applyConfig("- a\n- b\n", "c.yml"), std::runtime_error);
}

TEST_F(ProgramOptionsTest, ConfigNestedTooDeeplyIsAnErrorNamingIt) {
  try {
    options_.applyConfig("pose: " + std::string(70000, '[') + std::string(70000, ']') + "\n",
                         "deep.yml");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("deep.yml: not valid YAML: nested too deeply"),
              std::string::npos)
        << error.what();
  }
}

TEST_F(ProgramOptionsTest, MissingOrBrokenFileExitsNonZero) {
  EXPECT_EQ(parse({"--config", "/nonexistent/lineloc.yml"}), 2);
  const std::string broken = writeConfig("rate_hz: [1,\n");
  EXPECT_EQ(parse({"--config", broken.c_str()}), 2);
}

TEST_F(ProgramOptionsTest, PrintedConfigReadsBackToTheSameValues) {
  testing::internal::CaptureStdout();
  EXPECT_EQ(parse({"--print-config", "--robot-id", "rover-9", "--pose", "4", "5", "6"}), 0);
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_NE(printed.find("# id\nrobot_id: rover-9"), std::string::npos) << printed;

  Options reread;
  ProgramOptions options("test", "test program");
  options.add("robot_id", reread.robot_id, "id");
  options.add("rate_hz", reread.rate_hz, "rate");
  options.add("domain_id", reread.domain_id, "domain");
  options.add("pose", reread.pose, "pose");
  options.addFixedSize("origin", reread.origin, 3, "origin x y z");
  options.applyConfig(printed, "printed.yml");
  EXPECT_EQ(reread.robot_id, "rover-9");
  EXPECT_EQ(reread.pose, (std::vector<double>{4, 5, 6}));
  EXPECT_DOUBLE_EQ(reread.rate_hz, 10.0);
}

TEST_F(ProgramOptionsTest, FixedSizeVectorLeavesThePositionalsAfterIt) {
  EXPECT_EQ(parse({"--origin", "84900", "447600", "0", "city.json"}), std::nullopt);
  EXPECT_EQ(values_.origin, (std::vector<double>{84900.0, 447600.0, 0.0}));
  EXPECT_EQ(values_.files, (std::vector<std::string>{"city.json"}));
}

TEST_F(ProgramOptionsTest, FixedSizeVectorRefusesTooFewValues) {
  EXPECT_NE(parse({"--origin", "84900", "447600"}).value_or(0), 0);
  EXPECT_TRUE(values_.origin.empty());
}

TEST_F(ProgramOptionsTest, UnknownFlagExitsNonZero) {
  EXPECT_NE(parse({"--no-such-flag"}).value_or(0), 0);
}

TEST_F(ProgramOptionsTest, VersionPrintsTheProgramAndLinelocVersionsThenExits) {
  ::testing::internal::CaptureStdout();
  EXPECT_EQ(parse({"--version"}), 0);
  const std::string printed = ::testing::internal::GetCapturedStdout();
  EXPECT_NE(printed.find("test (lineloc "), std::string::npos) << printed;
}

TEST_F(ProgramOptionsTest, LogLevelSetsTheLogsLevel) {
  EXPECT_EQ(parse({"--log-level", "warn"}), std::nullopt);
  EXPECT_EQ(spdlog::get_level(), spdlog::level::warn);
  spdlog::set_level(spdlog::level::info);
}

TEST_F(ProgramOptionsTest, AnUnknownLogLevelIsAnError) {
  EXPECT_NE(parse({"--log-level", "loud"}).value_or(0), 0);
}

}  // namespace
}  // namespace lineloc
