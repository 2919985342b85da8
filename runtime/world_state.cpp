// World::saveState and World::restoreState: what a saved state holds, in its order.
//   world        step index, the deformable-collider pairs touching (contact events)
//   colliders    count; per collider in slot order: id, body type, its state
//   contacts     Bullet's manifolds with points (CollisionWorld::SavedManifold)
//   deformables  count; per deformable in slot order: id, its state
//   fluids       count; per fluid in slot order: id, kind, its state
// The ids, kinds and sizes are what makes a buffer this world's; snapshot/actor_state_io.cpp
// writes and checks each actor's part.
#include <new>

#include "snapshot/actor_state_io.h"
#include "world.h"

namespace vp {

namespace {

template <class Handle>
void writeId(StateWriter& out, Handle h) {
  out.value(h.index1);
  out.value(h.generation);
}

template <class Handle>
void expectId(StateReader& in, const char* what, Handle h) {
  const uint32_t index1 = in.value<uint32_t>(), generation = in.value<uint32_t>();
  in.expect(what, (uint64_t(index1) << 32) | generation, (uint64_t(h.index1) << 32) | h.generation);
}

// A state read in full, applied only once all of it checked out.
struct StagedWorld {
  uint64_t stepIndex = 0;
  std::vector<uint32_t> touching;
  std::vector<ColliderState> colliders;
  std::vector<CollisionWorld::SavedManifold> contacts;
  std::vector<DeformableState> deformables;
  std::vector<FluidState> fluids;
};

}  // namespace

std::vector<Collider*> World::collidersInSlotOrder() const {
  std::vector<Collider*> out;
  for (ColliderHandle h : colliderHandles()) out.push_back(collider(h));
  return out;
}

Status World::completeFluidSteps() {
  for (FluidHandle h : fluidHandles()) {
    FluidActor& f = *fluid(h);
    if (!f.stepInProgress()) continue;
    const Deadline timer(config_.clock, 0.0);
    ActorStats stats;
    try {
      while (!f.advance(FluidStepInput{}, SliceBudget{}, &stats)) {
      }
    } catch (const std::bad_alloc&) {
      f.abandonStep();
      return fail(Status::OutOfMemory, "out of memory completing fluid (%u, %u)'s step in progress; it was "
                  "dropped (the fluid is its last completed step) and nothing was saved", h.index1, h.generation);
    }
    f.schedule().stepMs += timer.elapsedMs();
    noteFluidStepCompleted(f.schedule());
  }
  return Status::Ok;
}

Status World::saveState(std::vector<uint8_t>* out) {
  VP_TRY(completeFluidSteps());
  StateWriter w;
  w.value(stats_.stepIndex);
  w.array(contactEvents_.saveState());
  const std::vector<ColliderHandle> colliderIds = colliderHandles();
  const std::vector<Collider*> colliders = collidersInSlotOrder();
  std::vector<ColliderState> colliderStates;
  w.value(static_cast<uint64_t>(colliders.size()));
  for (size_t i = 0; i < colliders.size(); ++i) {
    writeId(w, colliderIds[i]);
    w.value(static_cast<int32_t>(colliders[i]->bodyType()));
    colliderStates.push_back(colliders[i]->saveState());
    writeColliderState(w, colliderStates.back());
  }
  const std::vector<CollisionWorld::SavedManifold> contacts = collision_.saveContacts(colliders);
  w.array(contacts);
  const std::vector<DeformableHandle> deformableIds = deformableHandles();
  w.value(static_cast<uint64_t>(deformableIds.size()));
  for (DeformableHandle h : deformableIds) {
    writeId(w, h);
    writeDeformableState(w, deformable(h)->saveState());
  }
  const std::vector<FluidHandle> fluidIds = fluidHandles();
  w.value(static_cast<uint64_t>(fluidIds.size()));
  for (FluidHandle h : fluidIds) {
    writeId(w, h);
    w.value(static_cast<int32_t>(fluid(h)->desc().kind));
    writeFluidState(w, fluid(h)->saveState());
  }
  *out = w.finish();
  // From here the saved world goes on exactly as a restored one will.
  collision_.rebuild(colliders, colliderStates, contacts);
  for (FluidHandle h : fluidIds) fluid(h)->invalidateDerived();
  return Status::Ok;
}

Status World::restoreState(const uint8_t* data, size_t size) {
  StateReader in(data, size);
  StagedWorld staged;
  staged.stepIndex = in.value<uint64_t>();
  // Each touching pair is four ids; there are at most as many as deformable-collider pairs.
  in.arrayUpTo(&staged.touching, 4 * uint64_t(deformableCount()) * colliderCount(), "touching pair ids");
  if (in.ok() && staged.touching.size() % 4 != 0) in.outOfRange("the touching pair id count");

  const std::vector<ColliderHandle> colliderIds = colliderHandles();
  const std::vector<Collider*> colliders = collidersInSlotOrder();
  in.expect("collider count", in.value<uint64_t>(), colliders.size());
  staged.colliders.resize(in.ok() ? colliders.size() : 0);
  for (size_t i = 0; i < staged.colliders.size() && in.ok(); ++i) {
    expectId(in, "collider id (index, generation)", colliderIds[i]);
    in.expect("collider body type", static_cast<uint32_t>(in.value<int32_t>()),
              static_cast<uint32_t>(colliders[i]->bodyType()));
    readColliderState(in, colliders[i]->geometry() != nullptr, &staged.colliders[i]);
  }
  // Bullet's manifolds are between pairs of bodies, at most MANIFOLD_CACHE_SIZE points each.
  in.arrayUpTo(&staged.contacts, uint64_t(colliders.size()) * colliders.size(), "contact manifold count");
  for (const CollisionWorld::SavedManifold& m : staged.contacts) {
    if (!in.ok()) break;
    if (m.body0 >= m.body1 || m.body1 >= colliders.size() || m.pointCount < 1 ||
        m.pointCount > CollisionWorld::kMaxManifoldPoints)
      in.outOfRange("a contact manifold's bodies or point count");
    for (int p = 0; p < m.pointCount && in.ok(); ++p)
      in.requireFinite("a contact point", &m.points[p].localA[0], offsetof(CollisionWorld::SavedContactPoint, partId0) / sizeof(double));
  }

  const std::vector<DeformableHandle> deformableIds = deformableHandles();
  in.expect("deformable count", in.value<uint64_t>(), deformableIds.size());
  staged.deformables.resize(in.ok() ? deformableIds.size() : 0);
  for (size_t i = 0; i < staged.deformables.size() && in.ok(); ++i) {
    expectId(in, "deformable id (index, generation)", deformableIds[i]);
    readDeformableState(in, *deformable(deformableIds[i]), &staged.deformables[i]);
  }

  const std::vector<FluidHandle> fluidIds = fluidHandles();
  in.expect("fluid count", in.value<uint64_t>(), fluidIds.size());
  staged.fluids.resize(in.ok() ? fluidIds.size() : 0);
  for (size_t i = 0; i < staged.fluids.size() && in.ok(); ++i) {
    expectId(in, "fluid id (index, generation)", fluidIds[i]);
    in.expect("fluid kind", static_cast<uint32_t>(in.value<int32_t>()),
              static_cast<uint32_t>(fluid(fluidIds[i])->desc().kind));
    if (in.ok()) readFluidState(in, *fluid(fluidIds[i]), &staged.fluids[i]);
  }
  VP_TRY(in.finish());

  // All of it checked out: nothing below can fail but for memory.
  for (size_t i = 0; i < fluidIds.size(); ++i) fluid(fluidIds[i])->restoreState(std::move(staged.fluids[i]));
  for (size_t i = 0; i < deformableIds.size(); ++i)
    deformable(deformableIds[i])->restoreState(std::move(staged.deformables[i]));
  collision_.rebuild(colliders, staged.colliders, staged.contacts);
  contactEvents_.restoreState(staged.touching);
  stats_ = StepStats{};
  stats_.stepIndex = staged.stepIndex;
  return Status::Ok;
}

}  // namespace vp
