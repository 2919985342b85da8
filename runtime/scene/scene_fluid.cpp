// Fluid entries of scene files (see scene_fluid.h and docs/scene_format.md).
#include "scene/scene_fluid.h"

#include <cmath>

namespace vp {
namespace {

using nlohmann::json;

Status parseRegion(const JsonObject& obj, FluidShape* out) {
  VP_TRY(obj.checkKeys({"type", "centre", "halfExtents", "radius"}));
  int type = 0;
  VP_TRY(parseEnum(obj, "type", {"box", "sphere"}, &type));
  out->type = static_cast<FluidShape::Type>(type);
  VP_TRY(obj.vec3("centre", &out->centre));
  VP_TRY(obj.vec3("halfExtents", &out->halfExtents));
  VP_TRY(obj.number("radius", &out->radius));
  return Status::Ok;
}

template <class Parse>
Status parseList(const JsonObject& obj, const char* key, const Parse& parse) {
  if (!obj.has(key)) return Status::Ok;
  const json& list = obj.at(key);
  if (!list.is_array()) return fail(Status::ParseError, "%s: expected an array", obj.pathOf(key).c_str());
  for (size_t i = 0; i < list.size(); ++i) VP_TRY(parse(JsonObject(list[i], obj.pathOf(key) + "[" + std::to_string(i) + "]")));
  return Status::Ok;
}

Status parseResolution(const JsonObject& obj, MacGridSpec* grid) {
  if (!obj.has("resolution")) return Status::Ok;
  Vec3 r;
  VP_TRY(obj.vec3("resolution", &r));
  for (int a = 0; a < 3; ++a)
    if (r[a] != std::floor(r[a]) || r[a] < 2 || r[a] > kMaxFluidCellsPerAxis)
      return fail(Status::ParseError, "%s: expected 3 integers in [2, %d]", obj.pathOf("resolution").c_str(),
                  kMaxFluidCellsPerAxis);
  grid->nx = int(r[0]), grid->ny = int(r[1]), grid->nz = int(r[2]);
  return Status::Ok;
}

Status parseSides(const JsonObject& obj, std::array<DomainSide, 6>* sides) {
  std::optional<JsonObject> s;
  VP_TRY(obj.object("sides", &s, false));
  if (!s) return Status::Ok;
  static const char* const names[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};
  VP_TRY(s->checkKeys({"-x", "+x", "-y", "+y", "-z", "+z"}));
  for (int i = 0; i < 6; ++i) {
    int side = static_cast<int>((*sides)[i]);
    VP_TRY(parseEnum(*s, names[i], {"wall", "open"}, &side));
    (*sides)[i] = static_cast<DomainSide>(side);
  }
  return Status::Ok;
}

Status parseEmitter(const JsonObject& e, FluidEmitter* emitter) {
  VP_TRY(e.checkKeys({"region", "velocity", "densityRate", "temperature"}));
  std::optional<JsonObject> region;
  VP_TRY(e.object("region", &region, true));
  VP_TRY(parseRegion(*region, &emitter->shape));
  VP_TRY(e.vec3("velocity", &emitter->velocity));
  VP_TRY(e.number("densityRate", &emitter->densityRate));
  VP_TRY(e.number("temperature", &emitter->temperature));
  return Status::Ok;
}

}  // namespace

Status parseFluid(const JsonObject& obj, FluidDesc* d) {
  VP_TRY(obj.checkKeys({"name", "kind", "origin", "resolution", "cellSize", "sides", "density", "kinematicViscosity", "advection",
                        "cflNumber", "maxSubsteps", "pressureTolerance", "pressureMaxIterations", "smoke",
                        "initialLiquid", "emitters", "drains", "twoWayCoupling", "priority",
                        "collisionFilter"}));
  VP_TRY(obj.string("name", &d->name));
  int kind = 0;
  VP_TRY(parseEnum(obj, "kind", {"smoke", "liquid"}, &kind));
  d->kind = static_cast<FluidKind>(kind);
  // A scene that names no size gets the C ABI's defaults: 32^3 cells of 1/32 m.
  d->grid.nx = d->grid.ny = d->grid.nz = 32;
  d->grid.h = 1.0 / 32.0;
  VP_TRY(obj.vec3("origin", &d->grid.origin));
  VP_TRY(parseResolution(obj, &d->grid));
  VP_TRY(obj.number("cellSize", &d->grid.h));
  VP_TRY(parseSides(obj, &d->sides));
  VP_TRY(obj.number("density", &d->density));
  VP_TRY(obj.number("kinematicViscosity", &d->kinematicViscosity));
  int advection = static_cast<int>(d->solver.advection);
  VP_TRY(parseEnum(obj, "advection", {"semiLagrangian", "macCormack"}, &advection));
  d->solver.advection = static_cast<AdvectionScheme>(advection);
  VP_TRY(obj.number("cflNumber", &d->solver.cflNumber));
  VP_TRY(obj.integer("maxSubsteps", &d->solver.maxSubsteps));
  VP_TRY(obj.number("pressureTolerance", &d->solver.pressureTolerance));
  VP_TRY(obj.integer("pressureMaxIterations", &d->solver.pressureMaxIterations));
  std::optional<JsonObject> smoke;
  VP_TRY(obj.object("smoke", &smoke, false));
  if (smoke) {
    SmokeParameters& p = d->smoke;
    VP_TRY(smoke->checkKeys({"ambientTemperature", "densityBuoyancy", "thermalBuoyancy", "vorticityConfinement",
                             "densityDissipation", "temperatureDissipation"}));
    VP_TRY(smoke->number("ambientTemperature", &p.ambientTemperature));
    VP_TRY(smoke->number("densityBuoyancy", &p.densityBuoyancy));
    VP_TRY(smoke->number("thermalBuoyancy", &p.thermalBuoyancy));
    VP_TRY(smoke->number("vorticityConfinement", &p.vorticityConfinement));
    VP_TRY(smoke->number("densityDissipation", &p.densityDissipation));
    VP_TRY(smoke->number("temperatureDissipation", &p.temperatureDissipation));
  }
  VP_TRY(parseList(obj, "initialLiquid", [&](const JsonObject& r) {
    d->initialLiquid.emplace_back();
    return parseRegion(r, &d->initialLiquid.back());
  }));
  VP_TRY(parseList(obj, "drains", [&](const JsonObject& r) {
    d->drains.emplace_back();
    return parseRegion(r, &d->drains.back());
  }));
  VP_TRY(parseList(obj, "emitters", [&](const JsonObject& e) {
    d->emitters.emplace_back();
    return parseEmitter(e, &d->emitters.back());
  }));
  VP_TRY(obj.boolean("twoWayCoupling", &d->twoWayCoupling));
  VP_TRY(obj.integer("priority", &d->priority));
  VP_TRY(parseCollisionFilter(obj, &d->filter));
  const Status s = validateFluidDesc(*d);
  if (!ok(s)) return addErrorContext(s, obj.path());
  return Status::Ok;
}

}  // namespace vp
