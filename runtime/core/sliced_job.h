// Work done in slices: bounded pieces between which the work may stop and later resume
// exactly where it stopped. A slice returns true when its work is done, false to be run again
// (an iterative solve runs one iteration per call). A slice may queue further slices behind
// the queue (a stage that decides how many sub-steps follow), so the job reads as the list of
// stages it runs.
//
// The job knows nothing of time: whoever runs it decides between two slices whether the next
// one still fits (frame_plan.h), from the slices' measured costs, which the job keeps per
// kind (smoothed), so the decision can be made before a slice starts.
#pragma once

#include <deque>
#include <functional>
#include <vector>

#include "core/budget_clock.h"

namespace vp {

class SlicedJob {
 public:
  using Work = std::function<bool()>;  // true when done; false: run me again

  explicit SlicedJob(int kindCount) : costMs_(static_cast<size_t>(kindCount), -1.0) {}

  // Queues a slice behind everything queued so far.
  void then(int kind, Work work) { queue_.push_back(Slice{kind, std::move(work)}); }
  // Queues a slice that always finishes in one call.
  void thenOnce(int kind, std::function<void()> work) {
    then(kind, [w = std::move(work)] {
      w();
      return true;
    });
  }

  bool done() const { return queue_.empty(); }
  int nextKind() const { return queue_.front().kind; }
  // Smoothed cost of the next slice (0 while its kind has never run).
  double expectedNextMs() const;
  // Runs the next slice and measures it on `clock`; returns its ms.
  double runNext(const Clock& clock);
  // Slices run since the last reset(); the queue's length now.
  int slicesRun() const { return slicesRun_; }
  int slicesQueued() const { return static_cast<int>(queue_.size()); }
  // The smoothed costs per kind (what a saved world state keeps); restoreCosts takes a list
  // of kindCount values (a negative one: never measured).
  const std::vector<double>& costs() const { return costMs_; }
  void restoreCosts(const std::vector<double>& costs) { costMs_ = costs; }
  // Empties the queue for a new piece of work (costs are kept).
  void reset() {
    queue_.clear();
    slicesRun_ = 0;
  }

 private:
  struct Slice {
    int kind;
    Work work;
  };
  std::deque<Slice> queue_;
  std::vector<double> costMs_;  // per kind; < 0: never measured
  int slicesRun_ = 0;
};

}  // namespace vp
