#include "backbone/service/frame_workers.h"

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <utility>

#include "common/time/clock.h"

namespace lineloc {

FrameWorkers::FrameWorkers(int threads, Answers answers, std::function<void()> start_thread)
    : answers_(std::move(answers)), queue_(threads) {
  if (!answers_.answer || !answers_.busy || !answers_.publish) {
    throw std::invalid_argument("FrameWorkers: answer, busy and publish must all be given");
  }
  threads_.reserve(static_cast<size_t>(threads));
  for (int t = 0; t < threads; ++t) {
    threads_.emplace_back([this, start_thread] {
      if (start_thread) {
        start_thread();
      }
      work();
    });
  }
}

FrameWorkers::~FrameWorkers() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  threads_.clear();
}

void FrameWorkers::take(LineSetData line_set, int64_t taken_ns) {
  FairFrameQueue::Pushed pushed;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    pushed = queue_.push(std::move(line_set), taken_ns);
  }
  changed_.notify_one();
  if (pushed.superseded) {
    answers_.publish(answers_.busy(*pushed.superseded, taken_ns, FrameRefusal::kSuperseded));
  }
  if (pushed.late) {
    answers_.publish(answers_.busy(*pushed.late, taken_ns, FrameRefusal::kLate));
  }
}

void FrameWorkers::waitUntilIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return queue_.idle(); });
}

void FrameWorkers::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    std::optional<FairFrameQueue::Taken> taken;
    changed_.wait(lock, [&] {
      taken = stopping_ ? std::nullopt : queue_.pop(steadyClockNs());
      return stopping_ || taken.has_value();
    });
    if (stopping_) {
      return;
    }
    lock.unlock();
    const int64_t start_ns = steadyClockNs();
    try {
      answers_.publish(answers_.answer(taken->line_set, taken->taken_ns));
    } catch (const std::exception& error) {
      spdlog::error("LineSet of {} #{} not answered: {}", taken->line_set.robot_id,
                    taken->line_set.sequence_number, error.what());
    }
    const int64_t end_ns = steadyClockNs();
    lock.lock();
    queue_.done(taken->line_set.robot_id, end_ns - start_ns, end_ns);
    changed_.notify_all();
  }
}

}  // namespace lineloc
