#include "backbone/map/map_tile_cache.h"

#include <cmath>
#include <set>

namespace lineloc {

MapTileCache::MapTileCache(std::function<TileFetcher()> make_fetcher, double tile_size_m,
                           size_t max_tiles)
    : tile_size_m_(tile_size_m),
      max_tiles_(max_tiles),
      worker_([this, make_fetcher = std::move(make_fetcher)] { work(make_fetcher); }) {}

MapTileCache::~MapTileCache() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  worker_.join();
}

std::vector<MapTileCache::TileKey> MapTileCache::keysAround(const Eigen::Vector3d& position_world,
                                                            double radius_m) const {
  const auto index = [this](double coordinate) {
    return static_cast<int64_t>(std::floor(coordinate / tile_size_m_));
  };
  std::vector<TileKey> keys;
  for (int64_t ix = index(position_world.x() - radius_m);
       ix <= index(position_world.x() + radius_m); ++ix) {
    for (int64_t iy = index(position_world.y() - radius_m);
         iy <= index(position_world.y() + radius_m); ++iy) {
      keys.push_back({ix, iy});
    }
  }
  return keys;
}

Eigen::AlignedBox2d MapTileCache::bounds(const TileKey& key) const {
  const Eigen::Vector2d corner(key.ix * tile_size_m_, key.iy * tile_size_m_);
  return {corner, corner + Eigen::Vector2d::Constant(tile_size_m_)};
}

void MapTileCache::enqueue(const TileKey& key, bool urgent) {
  const auto pending = pending_.find(key);
  if (pending != pending_.end()) {
    if (urgent && !pending->second) {
      pending->second = true;
      // Still queued, it goes first; already being loaded, it is not queued again.
      if (const auto queued = std::ranges::find(queue_, key); queued != queue_.end()) {
        queue_.erase(queued);
        queue_.push_front(key);
      }
    }
    return;
  }
  pending_[key] = urgent;
  urgent ? queue_.push_front(key) : queue_.push_back(key);
  work_ready_.notify_one();
}

void MapTileCache::touch(Entry& entry, const TileKey& key) {
  recency_.erase(entry.recency);
  recency_.push_front(key);
  entry.recency = recency_.begin();
}

void MapTileCache::insert(const TileKey& key, std::shared_ptr<const MapTile> tile) {
  recency_.push_front(key);
  tiles_[key] = {std::move(tile), recency_.begin()};
  while (tiles_.size() > max_tiles_) {
    tiles_.erase(recency_.back());
    recency_.pop_back();
    ++stats_.evicted;
  }
}

std::shared_ptr<const MapTile> MapTileCache::waitForTile(const TileKey& key,
                                                         std::unique_lock<std::mutex>& lock) {
  for (;;) {
    if (const auto entry = tiles_.find(key); entry != tiles_.end()) {
      touch(entry->second, key);
      return entry->second.tile;
    }
    if (const auto failure = failed_.find(key); failure != failed_.end()) {
      std::rethrow_exception(failure->second);
    }
    if (pending_.count(key) == 0) {
      enqueue(key, true);  // evicted again before this caller got to it
    }
    tile_done_.wait(lock);
  }
}

std::shared_ptr<const MapView> MapTileCache::merged(
    const std::vector<TileKey>& keys, std::vector<std::shared_ptr<const MapTile>> tiles) {
  for (auto recent = recent_views_.begin(); recent != recent_views_.end(); ++recent) {
    if (recent->first == keys && recent->second.tiles == tiles) {
      recent_views_.splice(recent_views_.begin(), recent_views_, recent);
      return recent->second.view;
    }
  }
  auto view = std::make_shared<MapView>();
  std::set<int64_t> line_ids;
  std::set<int64_t> face_ids;
  std::set<int64_t> terrain_ids;
  std::set<int64_t> learnt_ids;
  for (const auto& tile : tiles) {
    for (const db::ModelLine& line : tile->lines) {
      if (line_ids.insert(line.id).second)
        view->lines.push_back(line);
    }
    for (const db::ModelFaceRecord& face : tile->faces) {
      if (face_ids.insert(face.id).second)
        view->faces.push_back(face);
    }
    for (const db::TerrainTriangleRecord& triangle : tile->terrain) {
      if (terrain_ids.insert(triangle.id).second)
        view->terrain.push_back(triangle);
    }
    for (const db::LearntLineRecord& line : tile->learnt_lines) {
      if (learnt_ids.insert(line.id).second)
        view->learnt_lines.push_back(line);
    }
  }
  recent_views_.push_front({keys, {std::move(tiles), view}});
  if (recent_views_.size() > kRecentViews) {
    recent_views_.pop_back();
  }
  return view;
}

void MapTileCache::request(const std::vector<TileKey>& keys) {
  for (const TileKey& key : keys) {
    failed_.erase(key);
    if (tiles_.count(key) > 0) {
      ++stats_.hits;
    } else {
      ++stats_.misses;
      enqueue(key, true);
    }
  }
}

std::shared_ptr<const MapView> MapTileCache::aroundIfLoaded(const Eigen::Vector3d& position_world,
                                                            double radius_m) {
  const std::vector<TileKey> keys = keysAround(position_world, radius_m);
  std::vector<std::shared_ptr<const MapTile>> found;
  const std::lock_guard lock(mutex_);
  request(keys);
  for (const TileKey& key : keys) {
    const auto entry = tiles_.find(key);
    if (entry == tiles_.end()) {
      return nullptr;
    }
    touch(entry->second, key);
    found.push_back(entry->second.tile);
  }
  return merged(keys, std::move(found));
}

std::shared_ptr<const MapView> MapTileCache::around(const Eigen::Vector3d& position_world,
                                                    double radius_m) {
  const std::vector<TileKey> keys = keysAround(position_world, radius_m);
  std::vector<std::shared_ptr<const MapTile>> found;
  std::unique_lock lock(mutex_);
  request(keys);
  for (const TileKey& key : keys) {
    found.push_back(waitForTile(key, lock));
  }
  return merged(keys, std::move(found));
}

void MapTileCache::prefetch(const Eigen::Vector3d& position_world, double radius_m) {
  std::lock_guard lock(mutex_);
  for (const TileKey& key : keysAround(position_world, radius_m)) {
    if (tiles_.count(key) == 0) {
      enqueue(key, false);
    }
  }
}

MapCacheStats MapTileCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void MapTileCache::work(const std::function<TileFetcher()>& make_fetcher) {
  TileFetcher fetch;
  std::unique_lock lock(mutex_);
  for (;;) {
    work_ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_) {
      return;
    }
    const TileKey key = queue_.front();
    queue_.pop_front();
    const bool urgent = pending_.at(key);
    lock.unlock();
    std::shared_ptr<const MapTile> tile;
    std::exception_ptr error;
    try {
      if (!fetch) {
        fetch = make_fetcher();
      }
      tile = std::make_shared<const MapTile>(fetch(bounds(key)));
    } catch (...) {
      error = std::current_exception();
      fetch = nullptr;  // whatever it held may be broken: make a new one next time
    }
    lock.lock();
    pending_.erase(key);
    if (error) {
      ++stats_.failures;
      failed_[key] = error;
    } else {
      stats_.prefetched += urgent ? 0 : 1;
      insert(key, std::move(tile));
    }
    tile_done_.notify_all();
  }
}

}  // namespace lineloc
