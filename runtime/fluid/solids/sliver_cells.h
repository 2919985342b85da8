// Sliver cells: cut cells whose open part is too small to hold a pressure of their own are
// closed, so they become part of the solid.
//
// Why. A cut cell's pressure balances the flux through its open faces against what the
// colliders' covered parts move (cut_cell_poisson.h). Where a collider covers all but a sliver
// of the cell, any mismatch in the covered parts' flux (a deforming surface has one velocity
// per face; a deformable against a rigid collider counts the two coverages as disjoint) has
// to pass through the sliver's tiny open faces. Beside a deformable floating in a liquid that
// gave such cells pressures of megapascals and their faces speeds of hundreds of metres per
// second, which advection spread into the liquid and the sub-step rule counted
// (docs/choices.md, "Deformables in fluids").
//
// What. A cell whose open weight (the mean of its six faces' open fractions, colliders only,
// as cellOpenFractions in liquid_volume.h) is above zero but below kSliverCellWeight gets all
// six faces closed: its neighbours see the solid's velocity there, and it has no pressure
// row. Closing faces lowers the neighbours' weights, so the pass repeats over its region
// until no cell of it changes; cells outside the region are left as they are.
#pragma once

#include <cstdint>

#include "collide/face_coverage.h"
#include "core/slab_passes.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {

// A cell that a collider's side cuts parallel to the grid is open through one whole face, so
// its weight is at least 1/6 however deep the cut: such a cell carries real flow and stays.
// Below half that, less than half a face is open in all.
constexpr double kSliverCellWeight = 1.0 / 12.0;

// Closes the sliver cells among those around `box` (the cells with a face that a fraction
// update for `box` recomputes, cell_box.h); returns how many it closed. Serial.
int64_t closeSliverCells(const Aabb& box, FaceFractionField* field);

// The same as one serial pass of bounded slices (core/slab_passes.h), run after the passes
// that recompute the box's faces.
void addSliverCellPasses(SlabPasses& passes, const Aabb& box, FaceFractionField* field);

}  // namespace vp
