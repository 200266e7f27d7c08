// The backbone's in-memory map: square tiles of model lines, faces and terrain, read
// from the database once and kept (least recently used first out), and loaded
// ahead of the robots along their motion so that steady-state frames never wait
// for the database (paper §3.1: latency-sensitive queries).
//
// One worker thread owns all database access (a libpq connection is not
// thread-safe): tiles a frame needs now jump the queue, prefetches wait behind
// them. A view merged from the same tiles as one of the last few is that view
// again (the same object), so that what a caller builds from a view (a
// ray-casting scene) can be kept for as long as the view does not change. A tile that failed to
// load is not cached; the frame that needed it gets the error, the next one retries.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "db/tiles/map_tile_query.h"

namespace lineloc {

using MapTile = db::TileContents;

// Everything near a position: each line, face and terrain triangle once, even
// when it spans tiles.
using MapView = MapTile;

// Loads the lines and faces whose 2D bounding box meets `bounds_world`.
using TileFetcher = std::function<MapTile(const Eigen::AlignedBox2d& bounds_world)>;

struct MapCacheStats {
  uint64_t hits = 0;
  uint64_t misses = 0;
  uint64_t prefetched = 0;
  uint64_t evicted = 0;
  uint64_t failures = 0;
};

class MapTileCache {
 public:
  // `make_fetcher` is called on the worker thread, so that whatever the
  // fetcher holds (a database connection) lives on the thread that uses it;
  // it is called again after any failure, to start afresh (reconnect).
  MapTileCache(std::function<TileFetcher()> make_fetcher, double tile_size_m, size_t max_tiles);
  ~MapTileCache();
  MapTileCache(const MapTileCache&) = delete;
  MapTileCache& operator=(const MapTileCache&) = delete;

  // The lines and faces of every tile meeting the square of half-side
  // `radius_m` around `position_world`; blocks while missing tiles load.
  // Rethrows the loader's error when a needed tile failed.
  std::shared_ptr<const MapView> around(const Eigen::Vector3d& position_world, double radius_m);

  // The same view when every one of its tiles is in memory; else nullptr,
  // with the missing tiles queued ahead of prefetches. Never waits for the
  // database.
  std::shared_ptr<const MapView> aroundIfLoaded(const Eigen::Vector3d& position_world,
                                                double radius_m);

  // Queues the tiles around a future position for background loading.
  void prefetch(const Eigen::Vector3d& position_world, double radius_m);

  MapCacheStats stats() const;

 private:
  struct TileKey {
    int64_t ix;
    int64_t iy;
    auto operator<=>(const TileKey&) const = default;
  };
  struct Entry {
    std::shared_ptr<const MapTile> tile;
    std::list<TileKey>::iterator recency;
  };
  // A merged view and the tiles it was merged from.
  struct MergedView {
    std::vector<std::shared_ptr<const MapTile>> tiles;
    std::shared_ptr<const MapView> view;
  };
  static constexpr size_t kRecentViews = 16;

  std::shared_ptr<const MapView> merged(const std::vector<TileKey>& keys,
                                        std::vector<std::shared_ptr<const MapTile>> tiles);

  // Under mutex_: counts each key a hit or a miss and queues the missing
  // ones ahead of prefetches, a failed one again.
  void request(const std::vector<TileKey>& keys);
  std::vector<TileKey> keysAround(const Eigen::Vector3d& position_world, double radius_m) const;
  Eigen::AlignedBox2d bounds(const TileKey& key) const;
  void enqueue(const TileKey& key, bool urgent);
  void touch(Entry& entry, const TileKey& key);
  void insert(const TileKey& key, std::shared_ptr<const MapTile> tile);
  std::shared_ptr<const MapTile> waitForTile(const TileKey& key,
                                             std::unique_lock<std::mutex>& lock);
  void work(const std::function<TileFetcher()>& make_fetcher);

  const double tile_size_m_;
  const size_t max_tiles_;
  mutable std::mutex mutex_;
  std::condition_variable work_ready_;
  std::condition_variable tile_done_;
  std::map<TileKey, Entry> tiles_;
  std::list<TileKey> recency_;  // most recently used first
  std::deque<TileKey> queue_;
  std::map<TileKey, bool> pending_;  // queued or loading; value: someone waits for it
  std::map<TileKey, std::exception_ptr> failed_;
  MapCacheStats stats_;
  // Most recent first.
  std::list<std::pair<std::vector<TileKey>, MergedView>> recent_views_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lineloc
