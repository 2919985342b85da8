#include "contact_events.h"

#include <algorithm>
#include <tuple>

#include "deform/deformable_body.h"

namespace vp {

bool ContactEventTracker::Pair::operator<(const Pair& o) const {
  return std::tie(deformableIndex1, deformableGeneration, colliderIndex1, colliderGeneration) <
         std::tie(o.deformableIndex1, o.deformableGeneration, o.colliderIndex1, o.colliderGeneration);
}

bool ContactEventTracker::Pair::operator==(const Pair& o) const { return !(*this < o) && !(o < *this); }

void ContactEventTracker::update(uint32_t index1, uint32_t generation, const DeformableBody& body) {
  // The colliders touched now, with the sums for their Begin events.
  std::vector<ContactEvent> now;
  const Array<double>& x = body.positions();
  auto touching = [&](const NodeContact& c) {
    auto it = std::find_if(now.begin(), now.end(), [&](const ContactEvent& e) {
      return e.colliderIndex1 == c.colliderIndex1 && e.colliderGeneration == c.colliderGeneration;
    });
    if (it == now.end()) {
      ContactEvent e;
      e.deformableIndex1 = index1;
      e.deformableGeneration = generation;
      e.colliderIndex1 = c.colliderIndex1;
      e.colliderGeneration = c.colliderGeneration;
      now.push_back(e);
      it = now.end() - 1;
    }
    it->nodeCount++;
    it->point += Vec3(x[3 * c.node], x[3 * c.node + 1], x[3 * c.node + 2]);
    it->normal += c.normal;
  };
  for (const NodeContact& c : body.contacts()) touching(c);
  for (const NodeContact& c : body.rigidContacts()) touching(c);
  for (ContactEvent& e : now) {
    e.point /= e.nodeCount;
    if (e.normal.norm() > 0.0) e.normal.normalize();
  }
  auto first = std::lower_bound(touching_.begin(), touching_.end(), Pair{index1, generation, 0, 0});
  auto last = first;
  while (last != touching_.end() && last->deformableIndex1 == index1 && last->deformableGeneration == generation)
    ++last;
  for (auto p = first; p != last; ++p) {
    const bool stillTouching = std::any_of(now.begin(), now.end(), [&](const ContactEvent& e) {
      return e.colliderIndex1 == p->colliderIndex1 && e.colliderGeneration == p->colliderGeneration;
    });
    if (stillTouching) continue;
    ContactEvent end;
    end.type = ContactEvent::Type::End;
    end.deformableIndex1 = index1;
    end.deformableGeneration = generation;
    end.colliderIndex1 = p->colliderIndex1;
    end.colliderGeneration = p->colliderGeneration;
    events_.push_back(end);
  }
  std::vector<Pair> before(first, last);
  touching_.erase(first, last);
  for (const ContactEvent& e : now) {
    const Pair pair{index1, generation, e.colliderIndex1, e.colliderGeneration};
    if (std::find(before.begin(), before.end(), pair) == before.end()) events_.push_back(e);
    touching_.insert(std::upper_bound(touching_.begin(), touching_.end(), pair), pair);
  }
}

void ContactEventTracker::forget(uint32_t index1, uint32_t generation) {
  touching_.erase(std::remove_if(touching_.begin(), touching_.end(),
                                 [&](const Pair& p) {
                                   return p.deformableIndex1 == index1 && p.deformableGeneration == generation;
                                 }),
                  touching_.end());
}

std::vector<uint32_t> ContactEventTracker::saveState() const {
  std::vector<uint32_t> out;
  for (const Pair& p : touching_)
    out.insert(out.end(), {p.deformableIndex1, p.deformableGeneration, p.colliderIndex1, p.colliderGeneration});
  return out;
}

void ContactEventTracker::restoreState(const std::vector<uint32_t>& pairs) {
  touching_.clear();
  for (size_t i = 0; i + 3 < pairs.size(); i += 4) touching_.push_back(Pair{pairs[i], pairs[i + 1], pairs[i + 2], pairs[i + 3]});
  std::sort(touching_.begin(), touching_.end());
  touching_.erase(std::unique(touching_.begin(), touching_.end()), touching_.end());
  events_.clear();
}

}  // namespace vp
