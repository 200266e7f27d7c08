// What localization needs of the model near a robot (paper §3.1:
// latency-sensitive queries): a map view's model segments, the ray-casting
// scene of its faces and its ground level (ground_level.h), built once per view on a thread
// of its own, so that no frame waits for the database or for a scene to be
// built. The tile cache hands out the same view object while its tiles stay
// the same (map_tile_cache.h), so steady frames find theirs prepared. A frame
// whose view is not prepared yet is localized in the most recently prepared
// one built around a point within reuse_distance_m of it (the tiles the robot
// moves into while its next view is built), and answered without a pose when
// there is none: a robot's first frame, which would otherwise wait for a map
// to load and be prepared, and the frames behind it with it.
#pragma once

#include <Eigen/Core>
#include <exception>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "backbone/map/ground_level.h"
#include "backbone/map/map_tile_cache.h"
#include "backbone/service/search_worker.h"
#include "backbone/visibility/occlusion_scene.h"
#include "backbone/visibility/visible_lines.h"

namespace lineloc {

struct PreparedMap {
  PreparedMap(std::shared_ptr<const MapView> map_view, const Eigen::Vector3d& centre_world);

  std::shared_ptr<const MapView> view;
  // Where the view was asked for: it holds the model query_radius_m around it.
  Eigen::Vector3d centre_world;
  std::vector<ModelSegment> segments;
  OcclusionScene scene;
  GroundLevel ground_level;
};

class PreparedMaps {
 public:
  // Views are prepared as background work of `gate` (may be null), which
  // must outlive this.
  PreparedMaps(MapTileCache& tiles, double query_radius_m, double reuse_distance_m,
               ForegroundGate* gate);

  // The prepared map to localize a frame at `position_world` in (see above);
  // nullptr while none is ready. Starts preparing the frame's own view when
  // it is not. Rethrows, once, the error that ended the last preparation.
  std::shared_ptr<const PreparedMap> around(const Eigen::Vector3d& position_world);
  // The map around() would return now, without starting a preparation or
  // taking its error: for work ahead of a frame, which must leave both to the
  // frame itself.
  std::shared_ptr<const PreparedMap> preparedAround(const Eigen::Vector3d& position_world);

  // Blocks until the view being prepared is.
  void waitUntilIdle();

 private:
  static constexpr size_t kPreparedMaps = 8;

  // Runs on the worker: loads the view around `position_world` (waiting for
  // the database) and prepares it.
  void prepare(const Eigen::Vector3d& position_world);
  // The map prepared from the loaded view around `position_world`, if any.
  std::shared_ptr<const PreparedMap> ownPrepared(const Eigen::Vector3d& position_world);
  // Under mutex_: the map prepared from `view`, moved to the front.
  std::shared_ptr<const PreparedMap> findPrepared(const std::shared_ptr<const MapView>& view);
  // Under mutex_: the most recent map centred within reuse_distance_m.
  std::shared_ptr<const PreparedMap> nearestPrepared(const Eigen::Vector3d& position_world) const;

  MapTileCache& tiles_;
  const double query_radius_m_;
  const double reuse_distance_m_;
  std::mutex mutex_;
  std::list<std::shared_ptr<const PreparedMap>> prepared_;  // most recent first
  std::exception_ptr failure_;
  // Last, so that it is destroyed first: its jobs use the members above.
  SearchWorker worker_;
};

}  // namespace lineloc
