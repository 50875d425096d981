#include <embree3/rtcore.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "dyngi/engine/ecs/entity_map.h"

#include "dyngi/engine/scene/alpha_cut.h"
#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/components.h"
#include "dyngi/gi/bvh.h"

namespace dyngi::gi {

namespace {
void onEmbreeError(void*, RTCError code, const char* msg) {
  std::fprintf(stderr, "dyngi: embree error %d: %s\n", int(code), msg ? msg : "");
}
}  // namespace

struct EmbreeScene::Impl {
  struct Blas {
    RTCScene scene = nullptr;
    RTCGeometry geometry = nullptr;
    uint32_t version = 0;
    size_t vertexCount = 0, indexCount = 0;
    bool refittable = false;
    bool filtered = false;  // the alpha cut's filter functions are set (a masked instance uses the mesh)
  };
  // Per top-level geomID: an alpha-masked instance's mesh and cut (glTF alphaMode MASK), read by alphaFilter.
  struct MaskedInstance {
    scene::MeshId mesh = 0;
    scene::AlphaCut cut;
  };
  std::vector<MaskedInstance> alphaByGeomId;
  const scene::AssetStore* assets = nullptr;  // the last sync's (the filter reads meshes and textures there)

  // True where the masked instance's surface is cut, as the raster passes' alpha test decides.
  bool cut(const MaskedInstance& a, unsigned primitive, float u, float v) const {
    if (!assets || a.mesh >= assets->meshCount()) return false;
    return a.cut.cuts(*assets, assets->mesh(a.mesh), primitive, u, v);
  }
  // Embree's filter (intersection and occlusion alike) on the meshes masked instances use: rejects the
  // candidate hits an instance's alpha cuts away, so the rays pass through the cut-outs.
  static void alphaFilter(const RTCFilterFunctionNArguments* args) {
    const Impl* im = static_cast<const Impl*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
      if (args->valid[i] != -1) continue;
      const unsigned inst = RTCHitN_instID(args->hit, args->N, i, 0);
      if (inst >= im->alphaByGeomId.size() || !im->alphaByGeomId[inst].cut.masked) continue;
      if (im->cut(im->alphaByGeomId[inst], RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                  RTCHitN_v(args->hit, args->N, i)))
        args->valid[i] = 0;
    }
  }
  struct Instance {
    RTCGeometry geometry = nullptr;
    unsigned geomId = RTC_INVALID_GEOMETRY_ID;
    scene::MeshId mesh = 0;
  };

  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::unordered_map<scene::MeshId, Blas> blas;
  ecs::EntityMap<Instance> instances;
  std::vector<ecs::Entity> byGeomId;  // top-level geomID -> entity
  std::vector<scene::MeshId> meshByGeomId;

  Impl() {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("Embree device creation failed");
    rtcSetDeviceErrorFunction(device, onEmbreeError, nullptr);
    newTop();
  }
  ~Impl() { clear(); rtcReleaseScene(top); rtcReleaseDevice(device); }

  void newTop() {
    top = rtcNewScene(device);
    rtcSetSceneFlags(top, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(top, RTC_BUILD_QUALITY_LOW);  // few instances, rebuilt often
  }

  void clear() {
    parked.clear();
    for (auto& [_, inst] : instances) {
      rtcDetachGeometry(top, inst.geomId);
      rtcReleaseGeometry(inst.geometry);
    }
    instances.clear();
    for (auto& [_, b] : blas) {
      rtcReleaseGeometry(b.geometry);
      rtcReleaseScene(b.scene);
    }
    blas.clear();
    byGeomId.clear();
    meshByGeomId.clear();
  }

  void writeVertices(RTCGeometry g, const scene::MeshData& m, bool create) {
    float* v = create ? static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, m.positions.size()))
                      : static_cast<float*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0));
    std::memcpy(v, m.positions.data(), m.positions.size() * 12);
  }

  std::unordered_set<scene::MeshId> rebuiltThisSync, refitThisSync;
  ecs::EntitySet parked;  // instances out of the BVH while their mesh is not usable

  // Builds, refits or returns the bottom-level BVH of a mesh as its version requires.
  Blas& ensureBlas(const scene::MeshData& m, scene::MeshId id, bool deforming, BvhStats& st) {
    auto it = blas.find(id);
    if (it != blas.end()) {
      Blas& b = it->second;
      if (b.version == m.version) return b;
      if (b.vertexCount == m.positions.size() && b.indexCount == m.indices.size() && b.refittable) {
        writeVertices(b.geometry, m, false);
        rtcUpdateGeometryBuffer(b.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(b.geometry);
        rtcCommitScene(b.scene);  // REFIT geometry quality: refits the existing tree
        b.version = m.version;
        ++st.meshesRefit;
        refitThisSync.insert(id);
        return b;
      }
      rtcReleaseGeometry(b.geometry);
      rtcReleaseScene(b.scene);
      blas.erase(it);
    }
    Blas b;
    b.scene = rtcNewScene(device);
    b.refittable = deforming;
    // Scenes take LOW/MEDIUM/HIGH; REFIT is a geometry quality (it makes commits refit the tree).
    rtcSetSceneBuildQuality(b.scene, deforming ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
    if (deforming) rtcSetSceneFlags(b.scene, RTC_SCENE_FLAG_DYNAMIC);
    b.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(b.geometry, deforming ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_HIGH);
    writeVertices(b.geometry, m, true);
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(b.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, m.indices.size() / 3));
    std::memcpy(idx, m.indices.data(), m.indices.size() * 4);
    rtcCommitGeometry(b.geometry);
    rtcAttachGeometry(b.scene, b.geometry);
    rtcCommitScene(b.scene);
    b.version = m.version;
    b.vertexCount = m.positions.size();
    b.indexCount = m.indices.size();
    ++st.meshesRebuilt;
    rebuiltThisSync.insert(id);
    return blas.emplace(id, b).first->second;
  }

  // The instance's matrix as Embree holds it (exactly the floats set: a copy here would cost 64 bytes
  // an instance, a quarter of Embree's own).
  static glm::mat4 transformOf(const Instance& inst) {
    glm::mat4 m(1.0f);
    rtcGetGeometryTransform(inst.geometry, 0.0f, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &m[0][0]);
    return m;
  }
  void setTransform(Instance& inst, const glm::mat4& m) {
    rtcSetGeometryTransform(inst.geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &m[0][0]);
    rtcCommitGeometry(inst.geometry);
  }

  void addInstance(ecs::Entity e, scene::MeshId mesh, const glm::mat4& m, const Blas& b) {
    Instance inst;
    inst.mesh = mesh;
    inst.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst.geometry, b.scene);
    setTransform(inst, m);
    inst.geomId = rtcAttachGeometry(top, inst.geometry);
    if (byGeomId.size() <= inst.geomId) byGeomId.resize(inst.geomId + 1), meshByGeomId.resize(inst.geomId + 1);
    byGeomId[inst.geomId] = e;
    meshByGeomId[inst.geomId] = mesh;
    instances.emplace(e, inst);
  }

  // One sync(): what it reads, and what it found.
  struct SyncPass {
    const ecs::World& world;
    const scene::AssetStore& assets;
    std::unordered_set<scene::MeshId> deforming;  // written by skinning: built for refit
    BvhStats stats;
    bool topDirty = false;  // the top level must be committed again
  };
  void removeGone(SyncPass& pass, const ChangeSet& changes);
  void refitDeformed(SyncPass& pass);
  void upsert(SyncPass& pass, ecs::Entity e);
  void applyAlphaCuts(SyncPass& pass);

  void removeInstance(ecs::Entity e) {
    auto it = instances.find(e);
    if (it == instances.end()) return;
    rtcDetachGeometry(top, it->second.geomId);
    rtcReleaseGeometry(it->second.geometry);
    byGeomId[it->second.geomId] = ecs::kNullEntity;
    instances.erase(it);
  }
};

namespace {
// Within the coordinate range, with a 3x3 part that Embree can invert in float.
bool usableInstanceTransform(const glm::mat4& m) {
  if (!scene::withinCoordinateRange(m)) return false;
  const float det = glm::determinant(glm::mat3(m));
  return std::isfinite(det) && std::abs(det) >= 1e-24f;
}

// Embree asserts (in Debian's build) on rays with non-finite origins or directions; a NaN that reaches a
// query from a caller's data is answered as a miss instead.
bool finiteRay(const glm::vec3& o, const glm::vec3& d) {
  return std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && std::isfinite(d.x) && std::isfinite(d.y) &&
         std::isfinite(d.z);
}
}  // namespace

EmbreeScene::EmbreeScene() : impl_(std::make_unique<Impl>()) {}
EmbreeScene::~EmbreeScene() = default;

const BvhStats& EmbreeScene::sync(const ecs::World& world, const scene::AssetStore& assets, ecs::Tick since) {
  // Deformations are found from the BLAS versions below, so a fresh tracker serves.
  return sync(world, assets, ChangeTracker().compute(world, assets, since));
}

const BvhStats& EmbreeScene::sync(const ecs::World& world, const scene::AssetStore& assets, const ChangeSet& changes) {
  auto t0 = std::chrono::steady_clock::now();
  Impl& im = *impl_;
  Impl::SyncPass pass{world, assets, {}, {}};
  im.rebuiltThisSync.clear();
  im.refitThisSync.clear();
  // Meshes written by skinning deform every frame: build those for refit.
  world.each<scene::SkinnedMesh>([&](ecs::Entity, const scene::SkinnedMesh& s) { pass.deforming.insert(s.deformed); });
  im.removeGone(pass, changes);
  im.refitDeformed(pass);
  // A first sync adds every instance (a new one is both moved and mesh-written): room for them at once.
  // Only then: an exact reserve on a later sync would copy every instance each time the moved count grew.
  if (im.instances.empty()) {
    const size_t mayAdd = std::max(changes.moved.size(), changes.meshWritten.size());
    im.instances.reserve(mayAdd);
    im.byGeomId.reserve(im.byGeomId.size() + mayAdd);
    im.meshByGeomId.reserve(im.meshByGeomId.size() + mayAdd);
  }
  for (ecs::Entity e : changes.moved) im.upsert(pass, e);
  for (ecs::Entity e : changes.meshWritten) im.upsert(pass, e);
  // Entities whose mesh was unusable come back as soon as it is usable again, changed or not.
  if (!im.parked.empty()) {
    std::vector<ecs::Entity> parked(im.parked.begin(), im.parked.end());
    for (ecs::Entity e : parked) {
      if (!world.alive(e) || !world.has<scene::MeshInstance>(e)) im.parked.erase(e);
      else im.upsert(pass, e);
    }
  }
  im.applyAlphaCuts(pass);
  if (pass.topDirty || changes.since == 0) rtcCommitScene(im.top);
  pass.stats.instances = im.instances.size();
  pass.stats.meshes = im.blas.size();
  pass.stats.updateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  stats_ = pass.stats;
  return stats_;
}

// Removed instances (entity destroyed or MeshInstance removed), and stale handles (cheap: instances only).
void EmbreeScene::Impl::removeGone(SyncPass& pass, const ChangeSet& changes) {
  for (ecs::Entity e : changes.removed)
    if (instances.count(e)) removeInstance(e), ++pass.stats.instancesRemoved, pass.topDirty = true;
  std::vector<ecs::Entity> gone;  // found first: removing moves another entry into the removed one's place
  for (const auto& [e, inst] : instances)
    if (!pass.world.alive(e) || !pass.world.has<scene::MeshInstance>(e)) gone.push_back(e);
  for (ecs::Entity e : gone) removeInstance(e), ++pass.stats.instancesRemoved, pass.topDirty = true;
}

// Deformed meshes: refit once per mesh, whichever entities use them. (Ids first: a rebuild replaces the
// map's entry, which must not happen while the map is being walked.) A mesh deformed into NaN or beyond
// the coordinate range is not refit: its instances leave the BVH and wait in `parked`.
void EmbreeScene::Impl::refitDeformed(SyncPass& pass) {
  std::vector<scene::MeshId> changedMeshes;
  std::unordered_set<scene::MeshId> unusable;
  for (auto& [id, b] : blas)
    if (id < pass.assets.meshCount() && pass.assets.mesh(id).version != b.version) changedMeshes.push_back(id);
  for (scene::MeshId id : changedMeshes) {
    if (!pass.assets.mesh(id).usable) {
      unusable.insert(id);
      continue;
    }
    ensureBlas(pass.assets.mesh(id), id, pass.deforming.count(id) > 0, pass.stats);
    pass.topDirty = true;  // instance bounds changed
  }
  if (!unusable.empty()) {
    std::vector<ecs::Entity> leaving;
    for (auto& [e, inst] : instances)
      if (unusable.count(inst.mesh)) leaving.push_back(e);
    for (ecs::Entity e : leaving) removeInstance(e), parked.insert(e), ++pass.stats.instancesRemoved, pass.topDirty = true;
  }
  // A rebuilt BLAS is a new RTCScene: point its existing instances at it. A refit one has new bounds: its
  // instances must be committed again too, or the top level keeps their old bounds (Embree rebuilds only
  // modified geometries' entries) and rays miss whatever deformed out of them.
  if (rebuiltThisSync.empty() && refitThisSync.empty()) return;
  for (auto& [e, inst] : instances) {
    if (rebuiltThisSync.count(inst.mesh)) {
      rtcSetGeometryInstancedScene(inst.geometry, blas.at(inst.mesh).scene);
      rtcCommitGeometry(inst.geometry);
    } else if (refitThisSync.count(inst.mesh)) {
      rtcCommitGeometry(inst.geometry);
    }
  }
}

// A new or changed instance: added, pointed at another mesh, moved, or parked while its mesh or
// transform cannot be traced.
void EmbreeScene::Impl::upsert(SyncPass& pass, ecs::Entity e) {
  const auto* mi = pass.world.tryGet<scene::MeshInstance>(e);
  const auto* wt = pass.world.tryGet<scene::WorldTransform>(e);
  if (!mi || !wt || mi->mesh >= pass.assets.meshCount()) return;
  const scene::MeshData& mesh = pass.assets.mesh(mi->mesh);
  if (mesh.indices.empty()) return;
  auto it = instances.find(e);
  if (!mesh.usable) {  // NaN or runaway vertices: out of the BVH (and of the frame) until usable again
    if (it != instances.end()) removeInstance(e), ++pass.stats.instancesRemoved, pass.topDirty = true;
    parked.insert(e);
    return;
  }
  parked.erase(e);
  // Embree transforms each ray into an instance's space with the inverse of its matrix: a singular
  // matrix (scale 0: a legal way to hide an object) would make NaN rays, which Embree asserts on. Such an
  // instance has no surface to hit, so it leaves the BVH until its transform is usable again.
  if (!usableInstanceTransform(wt->matrix)) {
    if (it != instances.end()) removeInstance(e), ++pass.stats.instancesRemoved, pass.topDirty = true;
    return;
  }
  if (it == instances.end()) {
    Blas& b = ensureBlas(mesh, mi->mesh, pass.deforming.count(mi->mesh) > 0, pass.stats);
    addInstance(e, mi->mesh, wt->matrix, b);
    ++pass.stats.instancesAdded;
    pass.topDirty = true;
    return;
  }
  Instance& inst = it->second;
  if (inst.mesh != mi->mesh) {
    Blas& b = ensureBlas(mesh, mi->mesh, pass.deforming.count(mi->mesh) > 0, pass.stats);
    rtcSetGeometryInstancedScene(inst.geometry, b.scene);
    inst.mesh = mi->mesh;
    meshByGeomId[inst.geomId] = mi->mesh;
    rtcCommitGeometry(inst.geometry);
    pass.topDirty = true;
  }
  if (transformOf(inst) != wt->matrix) {
    setTransform(inst, wt->matrix);
    ++pass.stats.instancesUpdated;
    pass.topDirty = true;
  }
}

// The alpha cuts, from every instance's material as it is now (cheap: instances only). A mesh a masked
// instance uses gets the filter functions once; its instances are committed again with the changed BLAS.
void EmbreeScene::Impl::applyAlphaCuts(SyncPass& pass) {
  assets = &pass.assets;
  alphaByGeomId = {};  // sized only when an instance is masked (most scenes have none)
  for (auto& [e, inst] : instances) {
    const auto* mat = pass.world.tryGet<scene::Material>(e);
    if (!mat || !mat->alphaMask) continue;
    if (alphaByGeomId.empty()) alphaByGeomId.resize(byGeomId.size());
    alphaByGeomId[inst.geomId] = {inst.mesh, scene::AlphaCut::of(*mat)};
    Blas& b = blas.at(inst.mesh);
    if (b.filtered) continue;
    rtcSetGeometryUserData(b.geometry, this);
    rtcSetGeometryIntersectFilterFunction(b.geometry, &alphaFilter);
    rtcSetGeometryOccludedFilterFunction(b.geometry, &alphaFilter);
    rtcCommitGeometry(b.geometry);
    rtcCommitScene(b.scene);
    b.filtered = true;
    for (auto& [e2, other] : instances)
      if (other.mesh == inst.mesh) rtcCommitGeometry(other.geometry);
    pass.topDirty = true;
  }
}

const BvhStats& EmbreeScene::rebuild(const ecs::World& world, const scene::AssetStore& assets) {
  auto t0 = std::chrono::steady_clock::now();
  impl_->clear();
  rtcReleaseScene(impl_->top);
  impl_->newTop();
  sync(world, assets, 0);
  stats_.updateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return stats_;
}

RayHit EmbreeScene::intersect(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (!finiteRay(o, d) || !(tmin <= tmax)) return RayHit{};
  RTCRayHit rh{};
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = tmin;
  rh.ray.tfar = tmax;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->top, &ctx, &rh);
  RayHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  unsigned inst = rh.hit.instID[0];
  h.hit = true;
  h.t = rh.ray.tfar;
  h.primitive = rh.hit.primID;
  h.u = rh.hit.u;
  h.v = rh.hit.v;
  if (inst < impl_->byGeomId.size()) {
    h.entity = impl_->byGeomId[inst];
    h.mesh = impl_->meshByGeomId[inst];
  }
  return h;
}

bool EmbreeScene::occluded(const Segment& s, float eps) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  glm::vec3 d = s.to - s.from;
  float len = glm::length(d);
  if (!(len > 2.0f * eps) || !finiteRay(s.from, d)) return false;
  RTCRay r{};
  r.org_x = s.from.x, r.org_y = s.from.y, r.org_z = s.from.z;
  r.dir_x = d.x / len, r.dir_y = d.y / len, r.dir_z = d.z / len;
  r.tnear = eps;
  r.tfar = len - eps;
  r.mask = 0xFFFFFFFFu;
  rtcOccluded1(impl_->top, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

bool EmbreeScene::occluded(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (!finiteRay(o, d) || !(tmin <= tmax)) return false;
  RTCRay r{};
  r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
  r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
  r.tnear = tmin;
  r.tfar = tmax;
  r.mask = 0xFFFFFFFFu;
  rtcOccluded1(impl_->top, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

void EmbreeScene::occluded(const Segment* segs, size_t count, uint8_t* out, float eps, BatchMode mode) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  if (mode == BatchMode::Stream) {
    // Streams of single rays: Embree reorders them internally.
    constexpr size_t kChunk = 256;
    RTCRay rays[kChunk];
    for (size_t base = 0; base < count; base += kChunk) {
      size_t m = std::min(kChunk, count - base);
      for (size_t k = 0; k < m; ++k) {
        const Segment& sg = segs[base + k];
        glm::vec3 d = sg.to - sg.from;
        float len = glm::length(d);
        RTCRay& r = rays[k];
        r = RTCRay{};
        r.org_x = sg.from.x, r.org_y = sg.from.y, r.org_z = sg.from.z;
        r.mask = 0xFFFFFFFFu;
        if (!(len > 2.0f * eps) || !finiteRay(sg.from, d)) {  // degenerate or NaN: an empty interval never hits
          r.org_x = r.org_y = r.org_z = 0.0f;
          r.dir_z = 1.0f;
          r.tnear = 1.0f;
          r.tfar = 0.5f;
          continue;
        }
        r.dir_x = d.x / len, r.dir_y = d.y / len, r.dir_z = d.z / len;
        r.tnear = eps;
        r.tfar = len - eps;
      }
      rtcOccluded1M(impl_->top, &ctx, rays, unsigned(m), sizeof(RTCRay));
      for (size_t k = 0; k < m; ++k) out[base + k] = rays[k].tfar < 0.0f ? 1 : 0;
    }
    return;
  }
  for (size_t base = 0; base < count; base += 8) {
    RTCRay8 r;  // RTC_ALIGN(32) in Embree's header
    // Embree reads the validity mask with 8-wide aligned loads: it must be 32-byte aligned too.
    alignas(32) int valid[8];
    for (int k = 0; k < 8; ++k) {
      size_t i = base + size_t(k);
      valid[k] = 0;
      r.tnear[k] = 0.0f;
      r.tfar[k] = -1.0f;
      r.mask[k] = 0xFFFFFFFFu;
      r.time[k] = 0.0f;
      r.flags[k] = 0;
      r.id[k] = 0;
      r.org_x[k] = r.org_y[k] = r.org_z[k] = 0.0f;
      r.dir_x[k] = 0.0f, r.dir_y[k] = 0.0f, r.dir_z[k] = 1.0f;
      if (i >= count) continue;
      glm::vec3 d = segs[i].to - segs[i].from;
      float len = glm::length(d);
      if (!(len > 2.0f * eps) || !finiteRay(segs[i].from, d)) continue;
      valid[k] = -1;
      r.org_x[k] = segs[i].from.x, r.org_y[k] = segs[i].from.y, r.org_z[k] = segs[i].from.z;
      r.dir_x[k] = d.x / len, r.dir_y[k] = d.y / len, r.dir_z[k] = d.z / len;
      r.tnear[k] = eps;
      r.tfar[k] = len - eps;
    }
    rtcOccluded8(valid, impl_->top, &ctx, &r);
    for (int k = 0; k < 8 && base + size_t(k) < count; ++k) out[base + size_t(k)] = valid[k] && r.tfar[k] < 0.0f ? 1 : 0;
  }
}

glm::mat4 EmbreeScene::instanceTransform(ecs::Entity e) const {
  auto it = impl_->instances.find(e);
  return it == impl_->instances.end() ? glm::mat4(1.0f) : Impl::transformOf(it->second);
}

}  // namespace dyngi::gi
