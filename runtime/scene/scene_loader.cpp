#include "scene/scene_loader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/regular_file.h"
#include "deform/deformable_mesh_source.h"
#include "geometry/box_tet_mesh.h"
#include "scene/json_fields.h"
#include "scene/scene_fluid.h"
#include "world.h"

namespace vp {
namespace {

using nlohmann::json;

struct SceneWorldSettings {
  std::optional<Vec3> gravity;
  std::optional<double> frameBudgetMs;
};

struct SceneAttachment {
  std::string collider;
  std::vector<int32_t> nodes;
};

struct SceneDeformable {
  DeformableDesc desc;
  std::vector<int32_t> pinnedNodes;
  std::vector<SceneAttachment> attachments;
  bool startAtRest = false;  // solved to static equilibrium once the scene is in the world
};

// "startAtRest": a static solve as a host would ask for a pre-roll (deform/static_equilibrium.h).
constexpr int32_t kStartAtRestIterations = 200;
constexpr double kStartAtRestTolerance = 1e-4;

struct Scene {
  SceneWorldSettings world;
  std::vector<ColliderDesc> colliders;
  std::vector<SceneDeformable> deformables;
  std::vector<FluidDesc> fluids;
};

Status parsePointArray(const JsonObject& obj, const char* key, Array<Vec3>* out) {
  if (!obj.has(key)) return Status::Ok;
  const json& arr = obj.at(key);
  if (!arr.is_array()) return fail(Status::ParseError, "%s: expected an array of [x, y, z]", obj.pathOf(key).c_str());
  out->clear();
  for (size_t i = 0; i < arr.size(); ++i) {
    const json& p = arr[i];
    if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
      return fail(Status::ParseError, "%s[%zu]: expected [x, y, z] numbers, got %s", obj.pathOf(key).c_str(), i,
                  p.dump().substr(0, 80).c_str());
    out->emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  }
  return Status::Ok;
}

Status parseTriangles(const JsonObject& obj, const char* key, Array<std::array<int32_t, 3>>* out) {
  if (!obj.has(key)) return Status::Ok;
  const json& arr = obj.at(key);
  if (!arr.is_array()) return fail(Status::ParseError, "%s: expected an array of [a, b, c]", obj.pathOf(key).c_str());
  for (size_t i = 0; i < arr.size(); ++i) {
    const json& t = arr[i];
    if (!t.is_array() || t.size() != 3 || !t[0].is_number_integer() || !t[1].is_number_integer() ||
        !t[2].is_number_integer())
      return fail(Status::ParseError, "%s[%zu]: expected [a, b, c] integers, got %s", obj.pathOf(key).c_str(), i,
                  t.dump().substr(0, 80).c_str());
    out->push_back({t[0].get<int32_t>(), t[1].get<int32_t>(), t[2].get<int32_t>()});
  }
  return Status::Ok;
}

Status parseShape(const JsonObject& obj, const std::string& baseDirectory, ShapeDesc* shape) {
  VP_TRY(obj.checkKeys({"type", "radius", "halfHeight", "halfExtents", "normal", "offset", "points", "triangles",
                        "file", "scale"}));
  if (!obj.has("type")) return fail(Status::ParseError, "%s: missing required key", obj.pathOf("type").c_str());
  int type = 0;
  VP_TRY(parseEnum(obj, "type", {"sphere", "box", "capsule", "cylinder", "plane", "convexHull", "triangleMesh"}, &type));
  shape->type = static_cast<ShapeType>(type);
  VP_TRY(obj.number("radius", &shape->radius));
  VP_TRY(obj.number("halfHeight", &shape->halfHeight));
  VP_TRY(obj.vec3("halfExtents", &shape->halfExtents));
  VP_TRY(obj.vec3("normal", &shape->normal));
  VP_TRY(obj.number("offset", &shape->offset));
  VP_TRY(parsePointArray(obj, "points", &shape->points));
  VP_TRY(parseTriangles(obj, "triangles", &shape->triangles));
  VP_TRY(obj.string("file", &shape->meshFile));
  if (!shape->meshFile.empty() && shape->meshFile[0] != '/') shape->meshFile = baseDirectory + "/" + shape->meshFile;
  VP_TRY(obj.vec3("scale", &shape->meshScale));
  return Status::Ok;
}

Status parsePose(const JsonObject& obj, Pose* pose) {
  VP_TRY(obj.vec3("position", &pose->position));
  if (obj.has("rotation") && obj.has("axisAngle"))
    return fail(Status::ParseError, "%s: give either rotation or axisAngle, not both", obj.path().c_str());
  if (obj.has("rotation")) {
    const json& q = obj.at("rotation");
    if (!q.is_array() || q.size() != 4 || !q[0].is_number() || !q[1].is_number() || !q[2].is_number() ||
        !q[3].is_number())
      return fail(Status::ParseError, "%s: expected a quaternion [x, y, z, w]", obj.pathOf("rotation").c_str());
    pose->rotation = Quat(q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
  }
  if (obj.has("axisAngle")) {
    const json& a = obj.at("axisAngle");
    if (!a.is_array() || a.size() != 4 || !a[0].is_number() || !a[1].is_number() || !a[2].is_number() ||
        !a[3].is_number())
      return fail(Status::ParseError, "%s: expected [axisX, axisY, axisZ, degrees]", obj.pathOf("axisAngle").c_str());
    Vec3 axis(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
    double degrees = a[3].get<double>();
    if (!axis.allFinite() || axis.norm() < 1e-9 || !std::isfinite(degrees))
      return fail(Status::ParseError, "%s: the axis must be finite and non-zero, the angle finite",
                  obj.pathOf("axisAngle").c_str());
    pose->rotation = Quat(Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()));
  }
  return Status::Ok;
}

Status parseCollider(const JsonObject& obj, const std::string& baseDirectory, ColliderDesc* desc) {
  VP_TRY(obj.checkKeys({"name", "bodyType", "shape", "position", "rotation", "axisAngle", "linearVelocity",
                        "angularVelocity", "mass", "friction", "restitution", "linearDamping", "angularDamping",
                        "collisionFilter", "sleeping"}));
  VP_TRY(obj.string("name", &desc->name));
  int body = 0;
  VP_TRY(parseEnum(obj, "bodyType", {"static", "kinematic", "dynamic"}, &body));
  desc->bodyType = static_cast<BodyType>(body);
  std::optional<JsonObject> shape;
  VP_TRY(obj.object("shape", &shape, true));
  VP_TRY(parseShape(*shape, baseDirectory, &desc->shape));
  VP_TRY(parsePose(obj, &desc->pose));
  VP_TRY(obj.vec3("linearVelocity", &desc->linearVelocity));
  VP_TRY(obj.vec3("angularVelocity", &desc->angularVelocity));
  VP_TRY(obj.number("mass", &desc->mass));
  VP_TRY(obj.number("friction", &desc->friction));
  VP_TRY(obj.number("restitution", &desc->restitution));
  VP_TRY(obj.number("linearDamping", &desc->linearDamping));
  VP_TRY(obj.number("angularDamping", &desc->angularDamping));
  VP_TRY(parseCollisionFilter(obj, &desc->filter));
  VP_TRY(obj.boolean("sleeping", &desc->sleeping));
  // Validate now (with the JSON path) so that applying the scene cannot fail half-way.
  Status s = validateColliderDesc(*desc);
  if (!ok(s)) return addErrorContext(s, obj.path());
  return Status::Ok;
}

// Nodes whose world position (rest shape placed by the pose) lies in the box {min, max}.
Status parseNodeBox(const JsonObject& parent, const char* key, const DeformableDesc& desc,
                    std::vector<int32_t>* nodes) {
  std::optional<JsonObject> box;
  VP_TRY(parent.object(key, &box, true));
  VP_TRY(box->checkKeys({"min", "max"}));
  Vec3 lo(NAN, NAN, NAN), hi(NAN, NAN, NAN);
  VP_TRY(box->vec3("min", &lo));
  VP_TRY(box->vec3("max", &hi));
  if (!lo.allFinite() || !hi.allFinite() || (hi - lo).minCoeff() < 0.0)
    return fail(Status::ParseError, "%s: needs finite min and max with min <= max", box->path().c_str());
  for (size_t i = 0; i < desc.mesh.vertices.size(); ++i) {
    const Vec3 x = desc.pose.apply(desc.mesh.vertices[i]);
    if ((x - lo).minCoeff() >= 0.0 && (hi - x).minCoeff() >= 0.0) nodes->push_back(static_cast<int32_t>(i));
  }
  if (nodes->empty()) return fail(Status::ParseError, "%s: selects no node of the mesh", box->path().c_str());
  return Status::Ok;
}

std::string resolvePath(const std::string& path, const std::string& baseDirectory) {
  return path.empty() || path[0] == '/' ? path : baseDirectory + "/" + path;
}

// The keys that say where a deformable's mesh comes from; "ifFileMissing" may replace them.
const std::initializer_list<const char*> kMeshSourceKeys = {
    "box", "tetFile", "surfaceFile", "voxelResolution", "surfaceMesher", "meshGrading", "renderFile", "scale"};

Status parseDeformable(const JsonObject& obj, const std::string& baseDirectory, SceneDeformable* out);

// A scene can name a model that only some machines have (a system package's sample file) and
// say what to use instead: when the tetFile / surfaceFile does not exist, the mesh-source
// keys of "ifFileMissing" replace the deformable's own. *replaced tells whether they did.
Status applyFileFallback(const JsonObject& obj, const std::string& baseDirectory, SceneDeformable* out,
                         bool* replaced) {
  *replaced = false;
  if (!obj.has("ifFileMissing")) return Status::Ok;
  std::optional<JsonObject> fallback;
  VP_TRY(obj.object("ifFileMissing", &fallback, true));
  VP_TRY(fallback->checkKeys(kMeshSourceKeys));
  std::string file;
  VP_TRY(obj.string("surfaceFile", &file));
  if (file.empty()) VP_TRY(obj.string("tetFile", &file));
  if (file.empty())
    return fail(Status::ParseError, "%s: needs a surfaceFile or tetFile whose absence it stands in for",
                obj.pathOf("ifFileMissing").c_str());
  std::error_code ec;
  if (std::filesystem::exists(resolvePath(file, baseDirectory), ec)) return Status::Ok;
  nlohmann::json merged = obj.value();
  for (const char* key : kMeshSourceKeys) merged.erase(key);
  merged.erase("ifFileMissing");
  for (const auto& [key, value] : fallback->value().items()) merged[key] = value;
  *replaced = true;
  return parseDeformable(JsonObject(merged, obj.path()), baseDirectory, out);
}

// Uniform scale of the rest mesh and render mesh in the actor's frame (before the pose).
Status applyScale(const JsonObject& obj, DeformableDesc* desc) {
  if (!obj.has("scale")) return Status::Ok;
  double scale = 1.0;
  VP_TRY(obj.number("scale", &scale));
  if (!(scale > 0.0 && std::isfinite(scale)))
    return fail(Status::ParseError, "%s = %g: must be a positive number", obj.pathOf("scale").c_str(), scale);
  for (Vec3& v : desc->mesh.vertices) v *= scale;
  if (desc->renderMesh)
    for (Vec3& v : desc->renderMesh->vertices) v *= scale;
  return Status::Ok;
}

// "surfaceMesher": "stuffing" | "voxel"; absent: the default (stuffing).
Status parseSurfaceMesher(const JsonObject& obj, SurfaceMesher* out) {
  int position = -1;
  VP_TRY(parseEnum(obj, "surfaceMesher", {"stuffing", "voxel"}, &position));
  if (position >= 0) *out = position == 0 ? SurfaceMesher::Stuffing : SurfaceMesher::Voxel;
  return Status::Ok;
}

// "selfCollision": "auto" | "off" | "on"; absent: auto.
Status parseSelfCollision(const JsonObject& obj, SelfCollision* out) {
  int position = -1;
  VP_TRY(parseEnum(obj, "selfCollision", {"auto", "off", "on"}, &position));
  if (position >= 0) *out = static_cast<SelfCollision>(position);
  return Status::Ok;
}

Status parseDeformable(const JsonObject& obj, const std::string& baseDirectory, SceneDeformable* out) {
  VP_TRY(obj.checkKeys({"name", "degree", "box", "tetFile", "surfaceFile", "voxelResolution", "surfaceMesher",
                        "meshGrading", "renderFile", "scale",
                        "ifFileMissing", "position", "rotation", "axisAngle", "linearVelocity", "youngsModulus",
                        "poissonRatio", "density", "massDamping", "stiffnessDamping", "friction", "solverTolerance",
                        "solverMaxIterations", "targetResidual", "priority", "pinBox", "attach",
                        "collisionFilter", "startAtRest", "selfCollision"}));
  bool replaced = false;
  VP_TRY(applyFileFallback(obj, baseDirectory, out, &replaced));
  if (replaced) return Status::Ok;
  DeformableDesc& desc = out->desc;
  DeformableMeshSource source;
  VP_TRY(obj.string("name", &desc.name));
  VP_TRY(obj.integer("degree", &desc.degree));
  if (obj.has("box")) {
    std::optional<JsonObject> box;
    VP_TRY(obj.object("box", &box, true));
    VP_TRY(box->checkKeys({"cells", "size"}));
    Vec3 cells(4, 4, 4);
    VP_TRY(box->vec3("cells", &cells));
    for (int k = 0; k < 3; ++k)
      if (cells[k] != std::floor(cells[k]) || cells[k] < 1 || cells[k] > kMaxBoxCellsPerAxis)
        return fail(Status::ParseError, "%s.cells: expected 3 integers in [1, %d]", box->path().c_str(),
                    kMaxBoxCellsPerAxis);
    source.boxCells = std::array<int, 3>{int(cells[0]), int(cells[1]), int(cells[2])};
    VP_TRY(box->vec3("size", &source.boxSize));
  }
  VP_TRY(obj.string("tetFile", &source.tetFile));
  VP_TRY(obj.string("surfaceFile", &source.surfaceFile));
  VP_TRY(obj.integer("voxelResolution", &source.voxelResolution));
  VP_TRY(parseSurfaceMesher(obj, &source.surfaceMesher));
  VP_TRY(obj.integer("meshGrading", &source.meshGrading));
  VP_TRY(parseSelfCollision(obj, &desc.selfCollision));
  VP_TRY(obj.string("renderFile", &source.renderFile));
  source.tetFile = resolvePath(source.tetFile, baseDirectory);
  source.surfaceFile = resolvePath(source.surfaceFile, baseDirectory);
  source.renderFile = resolvePath(source.renderFile, baseDirectory);
  VP_TRY(parsePose(obj, &desc.pose));
  VP_TRY(obj.vec3("linearVelocity", &desc.linearVelocity));
  VP_TRY(obj.number("youngsModulus", &desc.material.youngsModulus));
  VP_TRY(obj.number("poissonRatio", &desc.material.poissonRatio));
  VP_TRY(obj.number("density", &desc.material.density));
  VP_TRY(obj.number("massDamping", &desc.material.massDamping));
  VP_TRY(obj.number("stiffnessDamping", &desc.material.stiffnessDamping));
  VP_TRY(obj.number("friction", &desc.material.friction));
  VP_TRY(obj.number("solverTolerance", &desc.solver.tolerance));
  VP_TRY(obj.integer("solverMaxIterations", &desc.solver.maxIterations));
  VP_TRY(obj.number("targetResidual", &desc.solver.targetResidual));
  VP_TRY(obj.integer("priority", &desc.priority));
  VP_TRY(parseCollisionFilter(obj, &desc.filter));
  VP_TRY(obj.boolean("startAtRest", &out->startAtRest));
  // Resolve and validate now so that applying the scene cannot fail half-way.
  Status s = resolveDeformableMesh(source, &desc);
  if (!ok(s)) return addErrorContext(s, obj.path());
  VP_TRY(applyScale(obj, &desc));
  s = validateDeformableDesc(desc);
  if (!ok(s)) return addErrorContext(s, obj.path());
  if (obj.has("pinBox")) VP_TRY(parseNodeBox(obj, "pinBox", desc, &out->pinnedNodes));
  if (obj.has("attach")) {
    const json& list = obj.at("attach");
    if (!list.is_array()) return fail(Status::ParseError, "%s: expected an array", obj.pathOf("attach").c_str());
    for (size_t i = 0; i < list.size(); ++i) {
      JsonObject a(list[i], obj.pathOf("attach") + "[" + std::to_string(i) + "]");
      VP_TRY(a.checkKeys({"collider", "box"}));
      SceneAttachment attachment;
      VP_TRY(a.string("collider", &attachment.collider));
      if (attachment.collider.empty())
        return fail(Status::ParseError, "%s: missing required key", a.pathOf("collider").c_str());
      VP_TRY(parseNodeBox(a, "box", desc, &attachment.nodes));
      out->attachments.push_back(std::move(attachment));
    }
  }
  return Status::Ok;
}

Status parseScene(const json& root, const std::string& baseDirectory, Scene* scene) {
  JsonObject top(root, "$");
  VP_TRY(top.checkKeys({"version", "world", "colliders", "deformables", "fluids"}));
  int version = 1;
  VP_TRY(top.integer("version", &version));
  if (version != 1) return fail(Status::ParseError, "$.version = %d: this library reads version 1", version);
  std::optional<JsonObject> world;
  VP_TRY(top.object("world", &world, false));
  if (world) {
    VP_TRY(world->checkKeys({"gravity", "frameBudgetMs"}));
    if (world->has("gravity")) {
      Vec3 g;
      VP_TRY(world->vec3("gravity", &g));
      Status s = validateGravity(g);
      if (!ok(s)) return addErrorContext(s, world->path());
      scene->world.gravity = g;
    }
    if (world->has("frameBudgetMs")) {
      double ms = 0;
      VP_TRY(world->number("frameBudgetMs", &ms));
      Status s = validateFrameBudget(ms);
      if (!ok(s)) return addErrorContext(s, world->path());
      scene->world.frameBudgetMs = ms;
    }
  }
  if (top.has("colliders")) {
    const json& list = root.at("colliders");
    if (!list.is_array())
      return fail(Status::ParseError, "$.colliders: expected an array, got %s", jsonTypeName(list));
    for (size_t i = 0; i < list.size(); ++i) {
      JsonObject obj(list[i], "$.colliders[" + std::to_string(i) + "]");
      ColliderDesc desc;
      VP_TRY(parseCollider(obj, baseDirectory, &desc));
      scene->colliders.push_back(std::move(desc));
    }
  }
  if (top.has("deformables")) {
    const json& list = root.at("deformables");
    if (!list.is_array())
      return fail(Status::ParseError, "$.deformables: expected an array, got %s", jsonTypeName(list));
    for (size_t i = 0; i < list.size(); ++i) {
      JsonObject obj(list[i], "$.deformables[" + std::to_string(i) + "]");
      SceneDeformable d;
      VP_TRY(parseDeformable(obj, baseDirectory, &d));
      scene->deformables.push_back(std::move(d));
    }
  }
  if (top.has("fluids")) {
    const json& list = root.at("fluids");
    if (!list.is_array()) return fail(Status::ParseError, "$.fluids: expected an array, got %s", jsonTypeName(list));
    for (size_t i = 0; i < list.size(); ++i) {
      JsonObject obj(list[i], "$.fluids[" + std::to_string(i) + "]");
      FluidDesc f;
      VP_TRY(parseFluid(obj, &f));
      scene->fluids.push_back(std::move(f));
    }
  }
  return Status::Ok;
}

// Attachments name colliders of this scene or ones already in the world.
Status checkAttachmentTargets(const Scene& scene, const World& world) {
  for (size_t d = 0; d < scene.deformables.size(); ++d)
    for (size_t a = 0; a < scene.deformables[d].attachments.size(); ++a) {
      const std::string& name = scene.deformables[d].attachments[a].collider;
      bool found = false;
      for (const ColliderDesc& c : scene.colliders) found = found || c.name == name;
      ColliderHandle h;
      if (!found && !world.findCollider(name, &h))
        return fail(Status::ParseError, "$.deformables[%zu].attach[%zu].collider = \"%s\": no collider has this name",
                    d, a, name.c_str());
    }
  return Status::Ok;
}

struct SceneActors {
  std::vector<ColliderHandle> colliders;
  std::vector<DeformableHandle> deformables;
  std::vector<FluidHandle> fluids;
};

// Adds the validated scene's actors to the world, recording each in `added` (whose vectors
// have room reserved) as soon as it exists.
Status addSceneActors(World& world, Scene& scene, SceneActors* added) {
  for (ColliderDesc& desc : scene.colliders) {
    ColliderHandle h;
    VP_TRY(world.createCollider(std::move(desc), &h));
    added->colliders.push_back(h);
  }
  for (SceneDeformable& d : scene.deformables) {
    DeformableHandle h;
    VP_TRY(world.createDeformable(std::move(d.desc), &h));
    added->deformables.push_back(h);
    DeformableBody* body = world.deformable(h);
    VP_TRY(body->setPinned(d.pinnedNodes.data(), static_cast<int64_t>(d.pinnedNodes.size()), true));
    for (const SceneAttachment& a : d.attachments) {
      ColliderHandle c{};
      world.findCollider(a.collider, &c);
      VP_TRY(body->attach(a.nodes.data(), static_cast<int64_t>(a.nodes.size()), c.index1, c.generation,
                          *world.collider(c)));
    }
  }
  for (size_t i = 0; i < scene.fluids.size(); ++i) {
    FluidHandle h;
    Status s = world.createFluid(std::move(scene.fluids[i]), &h);
    if (!ok(s)) return addErrorContext(s, "$.fluids[" + std::to_string(i) + "]");
    added->fluids.push_back(h);
  }
  return Status::Ok;
}

// The deformables that start at rest, solved against the whole scene (its colliders and gravity).
Status settleAtRest(World& world, const Scene& scene, const SceneActors& added) {
  for (size_t i = 0; i < scene.deformables.size(); ++i) {
    if (!scene.deformables[i].startAtRest) continue;
    const Status s = world.solveDeformableStatic(added.deformables[i], kStartAtRestIterations, kStartAtRestTolerance,
                                                 nullptr);
    if (!ok(s)) return addErrorContext(s, "$.deformables[" + std::to_string(i) + "].startAtRest");
  }
  return Status::Ok;
}

}  // namespace

Status loadSceneFromString(World& world, const std::string& text, const std::string& baseDirectory) {
  json root;
  try {
    root = json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::exception& e) {
    // nlohmann's message carries the byte position of the error.
    return fail(Status::ParseError, "$: invalid JSON: %s", e.what());
  }
  Scene scene;
  VP_TRY(parseScene(root, baseDirectory, &scene));
  VP_TRY(checkAttachmentTargets(scene, world));

  // Apply. Everything was validated; only allocation and a "startAtRest" solve that does not
  // converge can fail from here, and then what was added so far is removed again.
  SceneActors added;
  const Vec3 gravityBefore = world.gravity();
  const double budgetBefore = world.config().frameBudgetMs;
  auto rollBack = [&](Status s) {
    world.setGravity(gravityBefore);
    world.setFrameBudget(budgetBefore);
    for (FluidHandle f : added.fluids) world.destroyFluid(f);
    for (DeformableHandle d : added.deformables) world.destroyDeformable(d);
    for (ColliderHandle c : added.colliders) world.destroyCollider(c);
    return s;
  };
  try {
    added.colliders.reserve(scene.colliders.size());
    added.deformables.reserve(scene.deformables.size());
    added.fluids.reserve(scene.fluids.size());
    if (Status s = addSceneActors(world, scene, &added); !ok(s)) return rollBack(s);
  } catch (const std::bad_alloc&) {
    return rollBack(fail(Status::OutOfMemory, "out of memory while adding the scene's actors; none was added"));
  }
  if (scene.world.gravity) world.setGravity(*scene.world.gravity);
  if (scene.world.frameBudgetMs) world.setFrameBudget(*scene.world.frameBudgetMs);
  if (Status s = settleAtRest(world, scene, added); !ok(s)) return rollBack(s);
  return Status::Ok;
}

Status loadScene(World& world, const std::string& path) {
  if (!ok(checkRegularFile(path))) {
    const std::string why = lastError();
    return fail(Status::IoError, "cannot open scene file '%s': %s", path.c_str(), why.c_str());
  }
  std::ifstream file(path);
  if (!file) return fail(Status::IoError, "cannot open scene file '%s'", path.c_str());
  std::stringstream text;
  text << file.rdbuf();
  const size_t slash = path.find_last_of('/');
  const std::string base = slash == std::string::npos ? "." : path.substr(0, slash);
  Status s = loadSceneFromString(world, text.str(), base);
  if (!ok(s)) return addErrorContext(s, "scene '" + path + "'");
  return Status::Ok;
}

}  // namespace vp
