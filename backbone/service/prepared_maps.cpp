#include "backbone/service/prepared_maps.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

#include "backbone/service/map_geometry.h"
#include "common/time/clock.h"

namespace lineloc {
namespace {

// The one key the worker runs its preparations under: one at a time.
constexpr char kPreparation[] = "map";

}  // namespace

PreparedMap::PreparedMap(std::shared_ptr<const MapView> map_view, const Eigen::Vector3d& centre)
    : view(std::move(map_view)),
      centre_world(centre),
      segments(modelSegments(view->lines, view->learnt_lines)),
      scene(occlusionScene(view->faces)),
      ground_level(*view) {}

PreparedMaps::PreparedMaps(MapTileCache& tiles, double query_radius_m, double reuse_distance_m,
                           ForegroundGate* gate)
    : tiles_(tiles),
      query_radius_m_(query_radius_m),
      reuse_distance_m_(reuse_distance_m),
      worker_(gate) {}

std::shared_ptr<const PreparedMap> PreparedMaps::around(const Eigen::Vector3d& position_world) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (failure_) {
      std::rethrow_exception(std::exchange(failure_, nullptr));
    }
  }
  if (std::shared_ptr<const PreparedMap> own = ownPrepared(position_world)) {
    return own;
  }
  worker_.submit(kPreparation, [this, position_world] { prepare(position_world); });
  const std::lock_guard<std::mutex> lock(mutex_);
  return nearestPrepared(position_world);
}

std::shared_ptr<const PreparedMap> PreparedMaps::preparedAround(
    const Eigen::Vector3d& position_world) {
  if (std::shared_ptr<const PreparedMap> own = ownPrepared(position_world)) {
    return own;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  return nearestPrepared(position_world);
}

std::shared_ptr<const PreparedMap> PreparedMaps::ownPrepared(
    const Eigen::Vector3d& position_world) {
  const std::shared_ptr<const MapView> view =
      tiles_.aroundIfLoaded(position_world, query_radius_m_);
  if (!view) {
    return nullptr;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  return findPrepared(view);
}

void PreparedMaps::waitUntilIdle() {
  worker_.waitUntilIdle();
}

void PreparedMaps::prepare(const Eigen::Vector3d& position_world) {
  try {
    const int64_t start_ns = steadyClockNs();
    const std::shared_ptr<const MapView> view = tiles_.around(position_world, query_radius_m_);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (findPrepared(view)) {
        return;
      }
    }
    const int64_t loaded_ns = steadyClockNs();
    auto prepared = std::make_shared<const PreparedMap>(view, position_world);
    spdlog::info(
        "prepared the map around ({:.1f}, {:.1f}) m: {} model lines, {} faces; tiles {:.1f} ms, "
        "preparation {:.1f} ms",
        position_world.x(), position_world.y(), view->lines.size(), view->faces.size(),
        toMilliseconds(static_cast<double>(loaded_ns - start_ns)),
        toMilliseconds(static_cast<double>(steadyClockNs() - loaded_ns)));
    const std::lock_guard<std::mutex> lock(mutex_);
    prepared_.push_front(std::move(prepared));
    if (prepared_.size() > kPreparedMaps) {
      prepared_.pop_back();
    }
  } catch (...) {
    const std::lock_guard<std::mutex> lock(mutex_);
    failure_ = std::current_exception();
  }
}

std::shared_ptr<const PreparedMap> PreparedMaps::findPrepared(
    const std::shared_ptr<const MapView>& view) {
  const auto found = std::find_if(prepared_.begin(), prepared_.end(),
                                  [&view](const auto& prepared) { return prepared->view == view; });
  if (found == prepared_.end()) {
    return nullptr;
  }
  prepared_.splice(prepared_.begin(), prepared_, found);
  return prepared_.front();
}

std::shared_ptr<const PreparedMap> PreparedMaps::nearestPrepared(
    const Eigen::Vector3d& position_world) const {
  const auto near = std::find_if(
      prepared_.begin(), prepared_.end(), [&](const std::shared_ptr<const PreparedMap>& prepared) {
        return (prepared->centre_world - position_world).head<2>().norm() <= reuse_distance_m_;
      });
  return near != prepared_.end() ? *near : nullptr;
}

}  // namespace lineloc
