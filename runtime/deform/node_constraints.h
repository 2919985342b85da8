// What a deformable's implicit solve holds at each node: nothing, the node's whole velocity
// (pinned, attached, or a sticking contact: kFixed), or its velocity along a contact normal
// (a sliding contact: kContact). CG's filter and the multigrids' smoothers project with this
// one rule.
#pragma once

#include <cstdint>

#include "core/allocator.h"
#include "core/task_system.h"
#include "gpu_kernels/constraint_kernels.h"

namespace vp {

struct NodeConstraints {
  // kernels::NodeConstraintKind's values (gpu_kernels/constraint_kernels.h), whose projection
  // filter() runs.
  enum Kind : uint8_t {
    kFree = kernels::kNodeFree,
    kFixed = kernels::kNodeFixed,
    kContact = kernels::kNodeContact,
  };

  Array<uint8_t> kind;   // per node
  Array<double> normal;  // 3 per node, read where kind == kContact

  void resize(int32_t nodeCount);
  void clear();  // every node free
  // Removes from `vec` (3 per node) the components the constraints prescribe.
  void filter(TaskSystem& tasks, double* vec) const;
  // The same projection as a 3x3 row-major matrix per node (9 per node), for the multigrids.
  void projectors(TaskSystem& tasks, double* out) const;
};

}  // namespace vp
