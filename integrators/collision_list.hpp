#pragma once
// The tutorial's collision list, which the game loops notify gameplay from: a pair detected in a
// step is listed with `persistence` frames left; after each step, in one batch, newly listed pairs
// get Begin, every listed pair loses a frame, and a pair whose frames run out gets End and leaves
// the list. Unlike the tutorial (whose std::set::insert keeps an existing entry's counter), a pair
// detected again has its frames refilled, so a long contact is one Begin and one End, not a
// flicker. The batch goes to the run's record and to the caller's callback, if any, only after
// the step: never in the middle of the physics.
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/integrators/run_result.hpp"

#include <cstddef>
#include <functional>
#include <vector>

namespace contact {

class CollisionList {
 public:
  using Callback = std::function<void(const std::vector<CollisionEvent>&)>;
  CollisionList(std::size_t contacts, int persistence, Callback callback)
      : persistence_(persistence),
        frames_left_(contacts, -1),
        fresh_(contacts, false),
        callback_(std::move(callback)) {}

  // Contact i is detected in the step under way.
  void detected(std::size_t i) {
    if (frames_left_[i] < 0) fresh_[i] = true;
    frames_left_[i] = persistence_;
  }

  // Step n, ending at t, is over: its batch to the record and the callback.
  void end_step(long n, double t, RunRecorder& rec) {
    batch_.clear();
    for (std::size_t i = 0; i < frames_left_.size(); ++i) {
      if (frames_left_[i] < 0) continue;
      if (fresh_[i]) batch_.push_back({CollisionEvent::Kind::Begin, i, n, t});
      fresh_[i] = false;
      if (--frames_left_[i] < 0) batch_.push_back({CollisionEvent::Kind::End, i, n, t});
    }
    if (batch_.empty()) return;
    rec.notify(batch_);
    if (callback_) callback_(batch_);
  }

 private:
  int persistence_;
  std::vector<int> frames_left_;  // per contact; -1 when not listed
  std::vector<bool> fresh_;       // listed during the step under way
  Callback callback_;
  std::vector<CollisionEvent> batch_;
};

}  // namespace contact
