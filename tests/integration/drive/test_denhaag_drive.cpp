// Den Haag's centre (../shared/data), a real LoD2 tile with terrain and a
// street network the drives turn through (city_drive.h): a 30 s drive from a
// standing start, and one whose robot is already moving when its software
// starts (the navigator's start in motion, the backbone's first search from
// a moving robot's prior). The robot must be found within kMaxFirstFixS of
// first moving, answered with a pose on nearly every frame from then on, and
// its attitude within the bound. Its fixes must be as consistent as their
// covariances say: no more of them beyond chi2_6(0.9973) than the 0.27 % a
// consistent estimator gives (one in 370), where Delft's drives have none.
// Its position RMSE and the states it reported beyond three sigma are
// printed, not asserted. Through Den Haag's turns these do not yet hold
// Delft's bounds (5 cm; no fix or state beyond) on every run: a view there
// now and then leaves a fix just beyond.
#include "tests/integration/drive/city_drive.h"

namespace lineloc {
namespace {

using namespace lineloc::test;

constexpr double kMaxFirstFixS = 5.0;

class DenHaagDrive : public CityDrive {
 protected:
  DenHaagDrive()
      : CityDrive({"denhaag",
                   fs::path(LINELOC_SHARED_DATA_DIR) / "citymodels" / "denhaag_01.city.json",
                   {"78650", "457950", "0"},
                   1.5,
                   "2026-04-14T09:30:00Z"}) {}

  // The drive of `seed` (lineloc-sim's `options` besides), localised, and
  // checked as above.
  void driveAndCheck(int seed, const std::vector<std::string>& options) {
    simulateDrive(seed, "dataset", options);
    const auto backbone = startBackbone("backbone.log");
    const auto robot = startRobot();
    waitForRobot(*robot);
    backbone->signal(SIGTERM);
    backbone->wait(10'000);
    EXPECT_LE(expectFoundAndAnswered("drive", "dataset", kConsistentShareBeyond).attitude_rmse_deg,
              kMaxAttitudeRmseDeg);
    const std::string report = consistencyReport("drive", "dataset");
    EXPECT_LE(firstFixAfterMovingS(report), kMaxFirstFixS) << report;
    fmt::print("states beyond three sigma: {}\n", statesBeyondThreeSigma(report));
  }
};

TEST_F(DenHaagDrive, TheRobotIsFoundAndFixedWithoutAWrongPoseAfterAStandingStart) {
  driveAndCheck(1, {});
}

TEST_F(DenHaagDrive, TheRobotIsFoundAndFixedWithoutAWrongPoseAfterAStartInMotion) {
  driveAndCheck(2, {"--initial-still-s", "0", "--initial-speed-m-s", "1.2"});
}

}  // namespace
}  // namespace lineloc
