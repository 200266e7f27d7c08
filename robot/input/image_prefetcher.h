// Frames of an image sequence decoded ahead of their use on a thread of
// their own, the way a camera driver hands over frames already in memory: a
// replayed frame then costs the robot no file reading or decoding at its
// exposure time, and the latency it measures from exposure is the latency a
// live camera would see.
//
// Frames are decoded in order, at most `depth` ahead of the last one taken.
// take(i) blocks until frame i is decoded (decoding it at once when it is not
// the next one due, e.g. after a skip) and rethrows its decoding error
// (readGreyImage's, naming the file).
//
// A live camera's driver hands over frames without the CPU decoding them; a
// replay does not. So decoding ahead pauses at every take() until resume():
// the caller resumes it once its latency-critical work on the frame is done,
// and the replay's decoding does not compete with the frame in flight.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <map>
#include <mutex>
#include <opencv2/core.hpp>
#include <thread>
#include <vector>

#include "robot/input/image_sequence.h"

namespace lineloc {

class ImagePrefetcher {
 public:
  ImagePrefetcher(std::vector<FrameRef> frames, size_t depth = 2);
  ~ImagePrefetcher();
  ImagePrefetcher(const ImagePrefetcher&) = delete;
  ImagePrefetcher& operator=(const ImagePrefetcher&) = delete;

  // Frame `index` as 8-bit grey; frames before it are dropped. Decoding
  // ahead pauses until resume().
  cv::Mat take(size_t index);

  // Lets decoding ahead go on.
  void resume();

 private:
  struct Decoded {
    cv::Mat image;
    std::exception_ptr error;
  };
  // The frame decoded, or the error that stopped it.
  static Decoded decode(const FrameRef& frame);
  static cv::Mat imageOf(Decoded decoded);
  void decodeAhead();

  const std::vector<FrameRef> frames_;
  const size_t depth_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<size_t, Decoded> ready_;
  size_t next_to_decode_ = 0;
  // Frames before this one are no longer wanted.
  size_t first_wanted_ = 0;
  bool paused_ = false;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace lineloc
