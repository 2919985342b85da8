// How often the world steps its fluids when the frame budget cannot hold all of them every
// frame.
//
// The iterative solvers stop at the budget, but most of a fluid step is not iterative
// (advection, face fractions, level-set upkeep) and cannot be cut short without leaving the
// grid half updated. What a game does with such work is simulate it at a lower rate: here
// each fluid steps every `interval` frames with the time it skipped (dt * interval), and the
// fluids are staggered so that each frame carries about 1/interval of the fluid work. Semi-Lagrangian advection is
// stable at any step, and the CFL sub-steps grow with the longer step where the flow is fast.
//
// The interval comes from the measured cost of the fluid steps (each fluid's own step time,
// smoothed over its steps by the world) and of everything else in the frame:
//   interval = smallest k with sum of the fluids' step ms / k <= kFill * (budget - otherMs),
// raised at once when a frame needs it (protecting the budget), lowered only after
// kCalmFrames consecutive frames would have fitted at the lower interval with room to spare
// (kRelaxFill), so it does not flip every frame. Capped at kMaxInterval: beyond that the
// fluid would visibly stutter, and the frame overruns instead. Budget 0 (unlimited) is
// interval 1.
#pragma once

#include <cstdint>

namespace vp {

class FluidPacing {
 public:
  static constexpr int kMaxInterval = 4;
  static constexpr double kFill = 0.85;       // of the time the fluids can have
  static constexpr double kRelaxFill = 0.7;   // what a lower interval must fit to be taken
  static constexpr int kCalmFrames = 30;
  static constexpr double kSmoothing = 0.2;   // weight of the newest frame in the averages
  // The world holds back this multiple of a due fluid's smoothed step cost from the
  // deformables: a fluid step varies from frame to frame (the default scene's two fluids on
  // a busy machine: standard deviation 15% and 23% of the mean), and the frame's end is what
  // must hold.
  static constexpr double kReserveMargin = 1.25;

  int interval() const { return interval_; }
  // The running average the policy keeps of a measured cost (average < 0: none yet).
  static double smoothed(double average, double sample) {
    return average < 0.0 ? sample : average + kSmoothing * (sample - average);
  }
  // Whether the fluid at position `ordinal` of `fluidCount` in the world's slot order steps on
  // `frame`, having waited `waitedFrames` frames since its last step. The fluids' offsets are
  // spread over the interval (two fluids at interval 4 step on frames 0 and 2 mod 4, not 0 and
  // 1), and a fluid never waits kMaxInterval frames or more, even while the interval changes.
  bool due(uint64_t frame, int ordinal, int fluidCount, int waitedFrames) const {
    const uint64_t offset = static_cast<uint64_t>(ordinal) * interval_ / static_cast<uint64_t>(fluidCount);
    return waitedFrames + 1 >= kMaxInterval || (frame + offset) % static_cast<uint64_t>(interval_) == 0;
  }
  // After a frame: the budget it ran under, the ms spent outside fluid steps that the budget
  // cannot shrink (the world leaves out the deformables' iterative solves; smoothed here), and
  // what one step of every fluid costs (the sum of their smoothed step times; 0 while none
  // has stepped).
  void observe(double budgetMs, double otherMs, double fluidMs);

 private:
  int interval_ = 1;
  int calmFrames_ = 0;
  double otherMs_ = -1.0;  // < 0: no frame seen yet
};

}  // namespace vp
