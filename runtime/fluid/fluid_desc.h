// Everything needed to create a fluid actor: its box domain, what it is (smoke or liquid),
// the physical parameters, and its sources. The C ABI and scene files both fill this in.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/collision_filter.h"
#include "core/math_types.h"
#include "core/status.h"
#include "fluid/mac_grid.h"

namespace vp {

enum class FluidKind : int { Smoke = 0, Liquid = 1 };

// MacCormack (Selle et al. 2008) with the min/max clamp is the default: it keeps vortices
// and thin smoke features that plain semi-Lagrangian smears out, for twice the sampling.
enum class AdvectionScheme : int { SemiLagrangian = 0, MacCormack = 1 };

// A region in world coordinates: a box (centre, halfExtents, axis-aligned) or a sphere.
struct FluidShape {
  enum class Type : int { Box = 0, Sphere = 1 } type = Type::Box;
  Vec3 centre = Vec3::Zero();
  Vec3 halfExtents = Vec3::Constant(0.1);
  double radius = 0.1;

  // Negative inside, exact for the sphere and outside the box, the box's inside distance
  // is the distance to its nearest face.
  double signedDistance(const Vec3& x) const;
};

// Smoke: every step, cells inside add `densityRate` * dt of smoke and take the emitter's
// temperature; faces inside take its velocity. Liquid: the shape is kept full of liquid
// moving with `velocity` (densityRate and temperature are ignored).
struct FluidEmitter {
  FluidShape shape;
  Vec3 velocity = Vec3::Zero();
  double densityRate = 1.0;  // smoke density units per second
  double temperature = 1.0;  // above ambient
  bool enabled = true;       // a host may switch an emitter off and on (vpFluidSetEmitter)
};

struct SmokeParameters {
  double ambientTemperature = 0.0;
  double densityBuoyancy = 0.05;    // alpha: m/s^2 per unit smoke density, pulls smoke down
  double thermalBuoyancy = 1.0;     // beta: m/s^2 per unit temperature above ambient, lifts it
  double vorticityConfinement = 0.2; // epsilon (Fedkiw et al. 2001), dimensionless
  double densityDissipation = 0.0;  // 1/s, exponential decay
  double temperatureDissipation = 0.0;
};

// A liquid's level set is advected semi-Lagrangian whatever FluidSolverSettings::advection
// says. It is redistanced and volume-corrected every sub-step, so MacCormack's sharper
// transport buys it little, and with MacCormack a closed inviscid dam break gained energy
// step after step and never settled (docs/choices.md, FluidLiquidEnergy.*).
constexpr AdvectionScheme kLevelSetAdvection = AdvectionScheme::SemiLagrangian;

struct FluidSolverSettings {
  // The velocity's scheme, and smoke's density and temperature's (kLevelSetAdvection above).
  AdvectionScheme advection = AdvectionScheme::MacCormack;
  double cflNumber = 2.0;    // largest displacement per sub-step, in cells
  int maxSubsteps = 4;       // more are not taken; the scheme stays stable, only less accurate
  double pressureTolerance = 1e-4;  // relative residual of the pressure solve
  int pressureMaxIterations = 200;
  // Samples one slice of a grid pass covers at most (fluid_actor.h; under a budget the slabs
  // grow toward it only while slices stay well under the target slice length,
  // core/slice_sizer.h): large enough that the per-slice dispatch and the workers' wait at
  // each slab's end are negligible in an unbudgeted step of a large grid (docs/benchmarks.md: fluid steps).
  // Not in the C ABI; tests lower it to split small grids.
  int64_t samplesPerSlice = int64_t(1) << 17;
};

struct FluidDesc {
  std::string name;
  FluidKind kind = FluidKind::Smoke;
  MacGridSpec grid;  // origin = the domain's low corner
  std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                  DomainSide::Wall, DomainSide::Wall, DomainSide::Wall};
  double density = 1000.0;  // kg/m^3 of the fluid (water 1000, air 1.2): scales pressure forces
  // m^2/s; 0 is inviscid and skips the viscosity solve entirely (viscosity.h).
  double kinematicViscosity = 0.0;
  SmokeParameters smoke;
  std::vector<FluidShape> initialLiquid;  // liquid: union of regions filled at creation
  std::vector<FluidEmitter> emitters;
  std::vector<FluidShape> drains;         // liquid: removed where these are
  FluidSolverSettings solver;
  bool twoWayCoupling = true;  // pressure forces act on dynamic colliders
  int priority = 0;  // higher is served first when the frame budget is short (actor_priority.h)
  CollisionFilter filter;  // which colliders its face fractions see
  void* userData = nullptr;
};

// Cells per axis and in total that a fluid may have (memory and time guard: 512^3 doubles of
// several fields is already gigabytes).
constexpr int kMaxFluidCellsPerAxis = 1024;
constexpr int64_t kMaxFluidCells = int64_t(1) << 27;
// m^2/s: a thousand times honey's. Past it the implicit solve's condition number (about
// 1 + 12 nu dt / h^2) makes its CG iterations, not the physics, the limit at game steps.
constexpr double kMaxKinematicViscosity = 10.0;

// Field names in messages follow vpFluidDef.
Status validateFluidDesc(const FluidDesc& desc);

// What a host may change on a fluid after creation: the forces on the smoke, the viscosity,
// its emitters (on/off, rate, velocity, temperature; not their shapes) and the domain's side
// types.
struct FluidControls {
  SmokeParameters smoke;
  double kinematicViscosity = 0.0;
  std::vector<FluidEmitter> emitters;
  std::array<DomainSide, 6> sides{DomainSide::Wall, DomainSide::Wall, DomainSide::Wall,
                                  DomainSide::Wall, DomainSide::Wall, DomainSide::Wall};
};
// The one check of these fields, for creation and for changes (messages as for vpFluidDef).
Status validateFluidControls(const FluidControls& controls);

}  // namespace vp
