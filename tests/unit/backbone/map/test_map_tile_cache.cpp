// The tile cache's bookkeeping, with a tile loader that synthesises one line
// per tile (plus one line shared by all tiles) and counts its calls.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "backbone/map/map_tile_cache.h"

namespace lineloc {
namespace {

constexpr double kTileSize = 100.0;

struct CountingLoader {
  std::atomic<int> calls{0};
  std::atomic<int> failures_left{0};

  TileFetcher fetcher() {
    return [this](const Eigen::AlignedBox2d& bounds) {
      ++calls;
      if (failures_left > 0) {
        --failures_left;
        throw std::runtime_error("database unreachable");
      }
      MapTile tile;
      const Eigen::Vector2d centre = bounds.center();
      db::ModelLine own;
      own.id = static_cast<int64_t>(std::floor(centre.x() / kTileSize)) * 1000 +
               static_cast<int64_t>(std::floor(centre.y() / kTileSize));
      own.start_world = Eigen::Vector3d(centre.x(), centre.y(), 0);
      own.end_world = own.start_world + Eigen::Vector3d(0, 0, 10);
      db::ModelLine shared;  // spans every tile: must come back once
      shared.id = -1000000;
      tile.lines = {own, shared};
      tile.faces = {{-7, 1, 1, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}}};
      return tile;
    };
  }
};

template <typename Predicate>
bool eventually(Predicate&& predicate) {
  for (int i = 0; i < 500 && !predicate(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return predicate();
}

TEST(MapTileCache, LoadsOnceAndReturnsEachLineAndFaceOnce) {
  CountingLoader loader;
  MapTileCache cache([&] { return loader.fetcher(); }, kTileSize, 64);
  // 150 m around (50, 50) spans -100..200 in x and y: tiles -1..2, 16 of them.
  const MapView view = *cache.around({50, 50, 1.5}, 150.0);
  EXPECT_EQ(loader.calls, 16);
  EXPECT_EQ(view.lines.size(), 17u);
  EXPECT_EQ(view.faces.size(), 1u);
  cache.around({60, 70, 1.5}, 150.0);
  EXPECT_EQ(loader.calls, 16) << "the second frame must be served from memory";
  EXPECT_EQ(cache.stats().hits, 16u);
  EXPECT_EQ(cache.stats().misses, 16u);
}

TEST(MapTileCache, TheSameTilesGiveTheSameViewUntilOneIsReloaded) {
  CountingLoader loader;
  MapTileCache cache([&] { return loader.fetcher(); }, kTileSize, 4);
  const auto first = cache.around({50, 50, 0}, 10.0);  // tile (0, 0) alone
  EXPECT_EQ(cache.around({60, 40, 0}, 10.0), first);
  cache.around({550, 50, 0}, 10.0);  // four other tiles evict (0, 0)
  cache.around({50, 550, 0}, 10.0);
  cache.around({950, 950, 0}, 10.0);
  cache.around({1550, 50, 0}, 10.0);
  const auto reloaded = cache.around({50, 50, 0}, 10.0);
  EXPECT_NE(reloaded, first);
  EXPECT_EQ(reloaded->lines.size(), first->lines.size());
}

TEST(MapTileCache, PrefetchedTilesAreHitsLater) {
  CountingLoader loader;
  MapTileCache cache([&] { return loader.fetcher(); }, kTileSize, 64);
  cache.prefetch({1050, 50, 0}, 50.0);  // tiles 10..10 x 0..0 and neighbours met: 4 tiles
  ASSERT_TRUE(eventually([&] { return cache.stats().prefetched == 4; }));
  cache.around({1050, 50, 0}, 50.0);
  EXPECT_EQ(cache.stats().misses, 0u);
  EXPECT_EQ(loader.calls, 4);
}

TEST(MapTileCache, AroundIfLoadedNeverWaitsButQueuesWhatIsMissing) {
  CountingLoader loader;
  MapTileCache cache([&] { return loader.fetcher(); }, kTileSize, 64);
  EXPECT_EQ(cache.aroundIfLoaded({50, 50, 0}, 10.0), nullptr);
  ASSERT_TRUE(eventually([&] { return cache.aroundIfLoaded({50, 50, 0}, 10.0) != nullptr; }));
  const auto view = cache.aroundIfLoaded({50, 50, 0}, 10.0);
  EXPECT_EQ(view->lines.size(), 2u);
  EXPECT_EQ(cache.around({50, 50, 0}, 10.0), view);
  EXPECT_EQ(loader.calls, 1);
}

TEST(MapTileCache, AFailedLoadIsReportedThenRetried) {
  CountingLoader loader;
  loader.failures_left = 1;
  MapTileCache cache([&] { return loader.fetcher(); }, kTileSize, 64);
  EXPECT_THROW(cache.around({50, 50, 0}, 10.0), std::runtime_error);
  EXPECT_EQ(cache.around({50, 50, 0}, 10.0)->lines.size(), 2u);
  EXPECT_EQ(cache.stats().failures, 1u);
}

TEST(MapTileCache, EvictsLeastRecentlyUsedAndStillAnswersCorrectly) {
  CountingLoader loader;
  MapTileCache cache([&] { return loader.fetcher(); }, kTileSize, 4);
  for (int step = 0; step < 10; ++step) {
    EXPECT_EQ(cache.around({50.0 + 100 * step, 50, 0}, 10.0)->lines.size(), 2u);
  }
  EXPECT_EQ(cache.stats().evicted, 6u);
  // A query needing more tiles than the cache holds still gets them all.
  EXPECT_EQ(cache.around({50, 50, 0}, 150.0)->lines.size(), 17u);
}

// A tile asked for while its prefetch is being loaded is loaded once, and
// the loader goes on serving after it.
TEST(MapTileCache, ATileAskedForWhileItsPrefetchLoadsIsLoadedOnce) {
  CountingLoader loader;
  std::atomic<bool> release{false};
  std::atomic<int> started{0};
  MapTileCache cache(
      [&] {
        return [&, fetch = loader.fetcher()](const Eigen::AlignedBox2d& bounds) {
          ++started;
          while (!release) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
          }
          return fetch(bounds);
        };
      },
      kTileSize, 64);
  cache.prefetch({50, 50, 1.5}, 1.0);
  ASSERT_TRUE(eventually([&] { return started == 1; }));
  std::thread asking([&] { cache.around({50, 50, 1.5}, 1.0); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  release = true;
  asking.join();
  EXPECT_EQ(loader.calls, 1);
  EXPECT_EQ(cache.around({250, 50, 1.5}, 1.0)->lines.size(), 2u) << "the loader still serves";
  EXPECT_EQ(loader.calls, 2);
}

TEST(MapTileCache, ServesConcurrentCallers) {
  CountingLoader loader;
  MapTileCache cache([&] { return loader.fetcher(); }, kTileSize, 256);
  std::vector<std::thread> callers;
  std::atomic<int> wrong{0};
  for (int t = 0; t < 4; ++t) {
    callers.emplace_back([&, t] {
      for (int step = 0; step < 20; ++step) {
        const auto view = cache.around({25.0 * (step + t), 50, 0}, 120.0);
        wrong += view->lines.empty() ? 1 : 0;
      }
    });
  }
  for (auto& caller : callers)
    caller.join();
  EXPECT_EQ(wrong, 0);
  // x from -120 to 670 meets tiles -2..6, y from -70 to 170 tiles -1..1: each
  // of the 27 loaded exactly once however many callers wanted it at once.
  EXPECT_EQ(loader.calls, 27);
}

}  // namespace
}  // namespace lineloc
