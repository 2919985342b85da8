// What the pair contacts (deform/pair_contacts.h) put into one body's implicit step. At each
// node of the body on a contact, the contact's impulse over the step is P = c − D v', with v'
// the node's new velocity: D (symmetric, positive semi-definite) goes on the node's diagonal
// block, c on the right-hand side. Uncoupled, the node side takes the spring with the
// triangle's point at its frame-start velocity; each triangle node i takes −w_i times the
// spring with the node at its frame-start velocity and the other triangle nodes at theirs.
// Coupled (both sides in one solve), the other nodes' velocities are unknowns of the same
// system and their blocks are applied by addPairCouplingProduct; so are a rigid body's six
// velocities, whose rows a contact group's solve holds (addRigidContactTerms). A sticking contact's
// springs act in every direction; a sliding one's only along the normal, with kinetic friction
// mu J_n (the last normal impulse) against the slip.
#pragma once

#include <cstdint>
#include <vector>

#include "core/allocator.h"
#include "deform/pair_contacts.h"
#include "linalg/block_sparse_matrix.h"

namespace vp {

// The contacts' D on the diagonal blocks of body `body`'s matrix (after its assembly).
void addPairContactStiffness(const std::vector<PairContact>& pairs, int32_t body, double h,
                             BlockSparseMatrix<double>* matrix);
// Their c on its right-hand side (3 per node).
void addPairContactRhs(const std::vector<PairContact>& pairs, int32_t body, double h, Array<double>* rhs);
// The solved velocities of each pair contacts' body (3 per node) that a coupled contact reads;
// null for a body outside the solve.
using PairVelocities = std::vector<const Array<double>*>;

// The work Σ P·v' the contacts did on the body's nodes over the step (the energy guard's).
double pairContactWork(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext,
                       const PairVelocities& solved);
// What the two sides of contact p applied in total (zero for an exact coupling): the node side
// over a step of nodeH with the node's body's new velocities, the triangle side over triangleH
// with its body's (a side whose body did not step has h = 0 and applied nothing). Each side
// saw the other at the frame's start, so the sum is not zero; the world hands it back, half
// to each side, as impulses in their next steps, and the momentum is conserved.
Vec3 pairContactMismatch(const PairContact& p, double nodeH, const Array<double>& nodeV, double triangleH,
                         const Array<double>& triangleV);
// After the solve, the body's nodes' friction states for the next step, and those of the rigid
// corners on its triangles: a sticking spring stretched beyond mu J_n slides, a slide that
// stopped or reversed sticks again; a node or corner with no contact, or one whose spring
// pulled, starts afresh (a corner's state is then dropped).
void updatePairFriction(const std::vector<PairContact>& pairs, int32_t body, double h, const Array<double>& vNext,
                        const PairVelocities& solved, Array<PairFriction>* friction,
                        Array<CornerFriction>* cornerFriction);
// A rigid body's six velocities in a solve: linear, then angular about its centre of mass.
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// The impulse coupled contact p applied to its node at the solved velocities.
Vec3 coupledNodeImpulse(const PairContact& p, double h, const PairVelocities& solved);
// What the coupled contacts with rigid pair body `body` put into its rows of a contact group's
// solve: their J^T D J on its 6×6 diagonal block, J^T c on its right-hand side.
void addRigidContactTerms(const std::vector<PairContact>& pairs, int32_t body, double h, Mat6* block, Vec6* rhs);
// y += the coupled contacts' spring terms between different nodes, over the vector of a
// contact group's solve, in which pair body b's nodes start at offsets[b] (scalars; −1 or past
// the end: not in the group, and its contacts are left out).
void addPairCouplingProduct(const std::vector<PairContact>& pairs, const std::vector<int64_t>& offsets,
                            const double* x, double* y);

}  // namespace vp
