#include "robot/input/image_prefetcher.h"

#include <algorithm>
#include <utility>

#include "common/parallel/thread_priority.h"

namespace lineloc {
namespace {

// Decoding ahead yields to the robot's loop and DDS, not to a search.
constexpr int kDecodeNice = 5;

}  // namespace

ImagePrefetcher::Decoded ImagePrefetcher::decode(const FrameRef& frame) {
  try {
    return {readGreyImage(frame.path), nullptr};
  } catch (...) {
    return {cv::Mat(), std::current_exception()};
  }
}

cv::Mat ImagePrefetcher::imageOf(Decoded decoded) {
  if (decoded.error) {
    std::rethrow_exception(decoded.error);
  }
  return decoded.image;
}

ImagePrefetcher::ImagePrefetcher(std::vector<FrameRef> frames, size_t depth)
    : frames_(std::move(frames)), depth_(std::max<size_t>(1, depth)) {
  worker_ = std::thread([this] { decodeAhead(); });
}

ImagePrefetcher::~ImagePrefetcher() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  worker_.join();
}

void ImagePrefetcher::decodeAhead() {
  lowerThreadPriority(kDecodeNice);
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] {
      return stopping_ || (!paused_ && next_to_decode_ < frames_.size() &&
                           next_to_decode_ < first_wanted_ + depth_);
    });
    if (stopping_) {
      return;
    }
    const size_t index = next_to_decode_++;
    lock.unlock();
    Decoded decoded = decode(frames_[index]);
    lock.lock();
    if (index >= first_wanted_) {
      ready_.emplace(index, std::move(decoded));
    }
    changed_.notify_all();
  }
}

cv::Mat ImagePrefetcher::take(size_t index) {
  std::unique_lock<std::mutex> lock(mutex_);
  paused_ = true;
  ready_.erase(ready_.begin(), ready_.lower_bound(index));
  if (next_to_decode_ <= index) {
    // Not the next one due: move the worker past it and decode it here.
    next_to_decode_ = index + 1;
    first_wanted_ = index + 1;
    changed_.notify_all();
    lock.unlock();
    return imageOf(decode(frames_.at(index)));
  }
  first_wanted_ = index;
  changed_.wait(lock, [this, index] { return ready_.count(index) > 0; });
  Decoded decoded = std::move(ready_.at(index));
  ready_.erase(index);
  first_wanted_ = index + 1;
  changed_.notify_all();
  return imageOf(std::move(decoded));
}

void ImagePrefetcher::resume() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    paused_ = false;
  }
  changed_.notify_all();
}

}  // namespace lineloc
