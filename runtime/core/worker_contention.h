// Whether the pool's workers help or hurt this frame. On a machine with a core free for every
// pool thread, items spread over the workers finish sooner. When another process keeps cores
// busy, a worker is preempted while it holds a block of items or runs an actor beside the
// caller, and the caller waits a scheduler time slice for it: a frame that spreads its work
// then ends later than one that runs it all on the caller (which has a core to itself as long
// as the workers sleep). The signal is the time the frame's threads spent runnable but
// waiting for a CPU (core/run_delay.h).
//
// Policy: a frame that used the workers and saw more run delay than kContendedFraction of its
// length (and at least kMinDelayMs, against scheduler noise) turns them off. They come back
// after a hold of kFirstHoldFrames frames for a probe; a probe frame that finds the cores
// still busy doubles the hold (up to kMaxHoldFrames), so a steadily busy machine pays for one
// probe every few seconds; kCalmFrames clean frames with the workers on reset it. Results
// never depend on the choice (task_system.h).
#pragma once

namespace vp {

class WorkerContention {
 public:
  static constexpr double kContendedFraction = 0.25;
  static constexpr double kMinDelayMs = 0.5;
  static constexpr int kFirstHoldFrames = 60;
  static constexpr int kMaxHoldFrames = 960;
  static constexpr int kCalmFrames = 120;

  // After a frame of frameMs in which the pool's threads waited runDelayMs (< 0: unknown)
  // for a CPU, with the workers on or off. Returns whether they are on for the next frame.
  bool noteFrame(double frameMs, double runDelayMs, bool workersUsed);
  bool workersEnabled() const { return holdLeft_ == 0; }

 private:
  int hold_ = kFirstHoldFrames;  // frames off after the next contended frame
  int holdLeft_ = 0;             // frames still off; 0: on
  int calm_ = 0;                 // clean frames in a row with the workers on
};

}  // namespace vp
