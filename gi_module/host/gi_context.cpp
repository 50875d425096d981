#include "dyngi/gi/gi_context.h"

#include <glm/gtc/quaternion.hpp>
#include <stdexcept>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/gpu_timer.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/components.h"
#include "dyngi/gi/gi_system.h"
#include "gpu_aliases.h"
#include "shaders/shared/gi_gpu_types.h"
#include "spirv/gi_export_rgba16f.comp.spv.h"
#include "spirv/gi_export_rgba32f.comp.spv.h"
#include "spirv/gi_gbuffer_import.comp.spv.h"

namespace dyngi::gi {

namespace {

// The GI's scene copy is an ECS world: the calls write its components and its change ticks give the
// GI system the change set, as in a dyngi host.
scene::Material toMaterial(const MaterialDesc& d, const std::vector<scene::TextureId>& textures) {
  auto texture = [&](TextureHandle h) { return h < textures.size() ? textures[h] : scene::kNoTexture; };
  scene::Material m;
  m.baseColor = d.baseColor;
  m.emissive = d.emissive;
  m.metallic = d.metallic;
  m.roughness = d.roughness;
  m.baseColorTexture = texture(d.baseColorTexture);
  m.emissiveTexture = texture(d.emissiveTexture);
  m.metallicRoughnessTexture = texture(d.metallicRoughnessTexture);
  return scene::inContentRange(m);  // the importer's ranges: a host's value cannot overflow the GI
}

// A light's world matrix: at its position, its -Z along its direction.
glm::mat4 lightMatrix(const LightDesc& l) {
  const float len = glm::length(l.direction);
  const glm::vec3 dir = len > 0.0f ? l.direction / len : glm::vec3(0, 0, -1);
  const glm::vec3 up = std::abs(dir.y) > 0.999f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  glm::mat4 m = glm::mat4_cast(glm::quatLookAtRH(dir, up));
  m[3] = glm::vec4(l.position, 1.0f);
  return m;
}

scene::Light toLight(const LightDesc& d) {
  scene::Light l;
  l.type = d.type == LightDesc::Type::Directional ? scene::LightType::Directional
           : d.type == LightDesc::Type::Spot     ? scene::LightType::Spot
                                                  : scene::LightType::Point;
  l.color = d.color;
  l.intensity = d.intensity;
  l.range = d.range;
  l.innerConeAngle = d.innerConeAngle;
  l.outerConeAngle = d.outerConeAngle;
  l.enabled = d.enabled;
  return scene::inContentRange(l);
}

// Standard depth from a reversed-Z projection: z' = w - z, so z'/w = 1 - z/w.
glm::mat4 standardDepth(const glm::mat4& projection, bool reversedZ) {
  if (!reversedZ) return projection;
  glm::mat4 flip(1.0f);
  flip[2][2] = -1.0f;
  flip[3][2] = 1.0f;
  return flip * projection;
}

template <class T>
T& checked(std::vector<T>& items, uint32_t handle, const char* what) {
  if (handle >= items.size()) throw std::invalid_argument(std::string("GiContext: no ") + what + " " + std::to_string(handle));
  return items[handle];
}

}  // namespace

struct GiContext::Impl {
  Impl(const render::ExternalDevice& device, const GiSettings& settings)
      : ctx(device, requirements()), renderer(ctx, render::RendererSettings{}) {
    if (settings.technique == "temporal" && settings.temporal.visibility == VisibilityBackend::Bvh)
      throw std::invalid_argument("GiContext: --visibility bvh reads the G-buffer back mid-frame, which a host's frame cannot; use svo");
    auto made = std::make_unique<GiSystem>(ctx, assets, settings);
    gi = made.get();
    gi->attach(renderer);
    scheduler.add(ecs::Phase::PostUpdate, std::move(made));
    createPipelines();
    const uint8_t black[4] = {0, 0, 0, 0}, white[4] = {255, 255, 255, 255};
    blackTexture = render::createTexture(ctx, 1, 1, black, false, "gi host black");
    whiteTexture = render::createTexture(ctx, 1, 1, white, false, "gi host white");
  }

  void createPipelines() {
    const Binding importB[] = {{DYNGI_GBUFFER_IMPORT_BINDING_FRAME, kUBO, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_DEPTH, kSampled, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_NORMAL, kSampled, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_BASE_COLOR, kSampled, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_ROUGHNESS, kSampled, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_METALLIC, kSampled, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_EMISSIVE, kSampled, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_OUT_POSITION, kStorageImage, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_OUT_NORMAL, kStorageImage, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_OUT_ALBEDO, kStorageImage, kCS},
                               {DYNGI_GBUFFER_IMPORT_BINDING_OUT_EMISSIVE, kStorageImage, kCS}};
    import_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_gi_gbuffer_import_comp), importB, sizeof(gpu::GBufferImportPush), "gi_gbuffer_import");
    const Binding exportB[] = {{DYNGI_EXPORT_BINDING_IN, kSampled, kCS}, {DYNGI_EXPORT_BINDING_OUT, kStorageImage, kCS}};
    export16_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_gi_export_rgba16f_comp), exportB, sizeof(gpu::ExportPush), "gi_export_rgba16f");
    export32_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_gi_export_rgba32f_comp), exportB, sizeof(gpu::ExportPush), "gi_export_rgba32f");
  }

  void importGBuffer(render::FrameContext& frame, const FrameDesc& desc);
  void exportOutputs(render::FrameContext& frame, const FrameDesc& desc);
  void exportImage(render::FrameContext& frame, render::Image& source, VkImageView destination, VkFormat format, bool zero);

  render::VulkanContext ctx;
  scene::AssetStore assets;
  ecs::World world;
  ecs::Scheduler scheduler;
  render::Renderer renderer;
  render::RenderSnapshot snapshot;  // this frame's, reusing last frame's memory
  GiSystem* gi = nullptr;  // owned by the scheduler
  Pipeline import_, export16_, export32_;
  render::Image blackTexture, whiteTexture;  // absent views: emission and metallic 0, roughness 1
  std::vector<scene::MeshId> meshes;
  std::vector<uint8_t> deforming;  // per mesh: updateMesh has rewritten it, so it deforms
  std::vector<scene::TextureId> textures;
  struct MaterialSlot {
    scene::Material material;
    std::vector<InstanceHandle> users;
  };
  std::vector<MaterialSlot> materials;
  std::vector<ecs::Entity> instances;  // null: removed
  std::vector<MaterialHandle> instanceMaterials;
  std::vector<ecs::Entity> lights;
  uint64_t frameCount = 0;  // frames recorded
  double lastTime = 0.0;
};

render::DeviceRequirements GiContext::requirements() {
  render::DeviceRequirements r = render::rendererRequirements();
  r.features.geometryShader = VK_TRUE;                     // voxelization: the dominant axis per triangle
  r.features.fragmentStoresAndAtomics = VK_TRUE;           // voxelization: fragments appended from the fragment stage
  r.features.shaderStorageImageExtendedFormats = VK_TRUE;  // rg32ui / rgba16f storage images (gather, temporal sets)
  r.subgroupBallotInCompute = true;                        // the SVO build's appends
  return r;
}

GiContext::GiContext(const render::ExternalDevice& device, const GiSettings& settings) : impl_(std::make_unique<Impl>(device, settings)) {}

GiContext::~GiContext() = default;

GiSystem& GiContext::system() { return *impl_->gi; }

MeshHandle GiContext::addMesh(const MeshDesc& d) {
  if (d.indices.size() % 3 != 0) throw std::invalid_argument("GiContext::addMesh: the index count is not a multiple of 3");
  for (uint32_t i : d.indices)
    if (i >= d.positions.size()) throw std::invalid_argument("GiContext::addMesh: an index past the positions");
  scene::MeshData m;
  m.name = d.name;
  m.positions.assign(d.positions.begin(), d.positions.end());
  m.normals.assign(d.normals.begin(), d.normals.end());
  m.uvs.assign(d.uvs.begin(), d.uvs.end());
  m.indices.assign(d.indices.begin(), d.indices.end());
  impl_->meshes.push_back(impl_->assets.addMesh(std::move(m)));
  impl_->deforming.push_back(0);
  return MeshHandle(impl_->meshes.size() - 1);
}

void GiContext::updateMesh(MeshHandle mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
  scene::MeshData& m = impl_->assets.meshForWrite(checked(impl_->meshes, mesh, "mesh"));
  if (positions.size() != m.positions.size()) throw std::invalid_argument("GiContext::updateMesh: the vertex count changed");
  m.positions.assign(positions.begin(), positions.end());
  if (!normals.empty()) m.normals.assign(normals.begin(), normals.end());
  m.computeBounds();
  // Its instances become deforming meshes (the ECS path's skinned meshes, the host doing the skinning):
  // a new version re-voxelizes, refits and invalidates them each frame. The first time, their mesh is
  // written, which rebuilds them from this pose.
  Impl& im = *impl_;
  if (im.deforming[mesh]) return;
  im.deforming[mesh] = 1;
  const scene::MeshId id = im.meshes[mesh];
  for (ecs::Entity e : im.instances)
    if (!e.isNull() && im.world.get<scene::MeshInstance>(e).mesh == id) {
      im.world.add(e, scene::SkinnedMesh{.bindPose = id, .deformed = id});
      im.world.write<scene::MeshInstance>(e);
    }
}

TextureHandle GiContext::addTexture(const TextureDesc& d) {
  if (d.width == 0 || d.height == 0 || d.rgba8.size() < size_t(d.width) * d.height * 4)
    throw std::invalid_argument("GiContext::addTexture: fewer bytes than width x height x 4");
  scene::TextureData t;
  t.width = d.width;
  t.height = d.height;
  t.rgba8.assign(d.rgba8.begin(), d.rgba8.begin() + ptrdiff_t(size_t(d.width) * d.height * 4));
  t.srgb = d.srgb;
  impl_->textures.push_back(impl_->assets.addTexture(std::move(t)));
  return TextureHandle(impl_->textures.size() - 1);
}

MaterialHandle GiContext::addMaterial(const MaterialDesc& d) {
  impl_->materials.push_back({toMaterial(d, impl_->textures), {}});
  return MaterialHandle(impl_->materials.size() - 1);
}

void GiContext::updateMaterial(MaterialHandle material, const MaterialDesc& d) {
  Impl::MaterialSlot& slot = checked(impl_->materials, material, "material");
  slot.material = toMaterial(d, impl_->textures);
  for (InstanceHandle i : slot.users)
    if (!impl_->instances[i].isNull()) impl_->world.write<scene::Material>(impl_->instances[i]) = slot.material;
}

InstanceHandle GiContext::addInstance(const InstanceDesc& d) {
  Impl& im = *impl_;
  const scene::MeshId mesh = checked(im.meshes, d.mesh, "mesh");
  ecs::Entity e = im.world.create();
  im.world.add(e, scene::WorldTransform{d.transform});
  im.world.add(e, scene::MeshInstance{mesh});
  if (im.deforming[d.mesh]) im.world.add(e, scene::SkinnedMesh{.bindPose = mesh, .deformed = mesh});
  if (d.dynamic) im.world.add(e, scene::DynamicTag{});
  else im.world.add(e, scene::StaticTag{});
  const InstanceHandle handle = InstanceHandle(im.instances.size());
  im.instances.push_back(e);
  im.instanceMaterials.push_back(kNoHandle);
  if (d.material != kNoHandle) {
    Impl::MaterialSlot& slot = checked(im.materials, d.material, "material");
    im.world.add(e, slot.material);
    slot.users.push_back(handle);
    im.instanceMaterials.back() = d.material;
  } else {
    im.world.add(e, scene::Material{});
  }
  return handle;
}

void GiContext::setTransform(InstanceHandle instance, const glm::mat4& transform) {
  const ecs::Entity e = checked(impl_->instances, instance, "instance");
  if (e.isNull()) throw std::invalid_argument("GiContext::setTransform: a removed instance");
  if (impl_->world.get<scene::WorldTransform>(e).matrix != transform) impl_->world.write<scene::WorldTransform>(e).matrix = transform;
}

void GiContext::setMaterial(InstanceHandle instance, MaterialHandle material) {
  Impl& im = *impl_;
  const ecs::Entity e = checked(im.instances, instance, "instance");
  if (e.isNull()) throw std::invalid_argument("GiContext::setMaterial: a removed instance");
  Impl::MaterialSlot& slot = checked(im.materials, material, "material");
  if (MaterialHandle before = im.instanceMaterials[instance]; before != kNoHandle) std::erase(im.materials[before].users, instance);
  slot.users.push_back(instance);
  im.instanceMaterials[instance] = material;
  im.world.write<scene::Material>(e) = slot.material;
}

void GiContext::removeInstance(InstanceHandle instance) {
  Impl& im = *impl_;
  ecs::Entity& e = checked(im.instances, instance, "instance");
  if (e.isNull()) return;
  if (MaterialHandle m = im.instanceMaterials[instance]; m != kNoHandle) std::erase(im.materials[m].users, instance);
  im.world.destroy(e);
  e = {};
}

LightHandle GiContext::addLight(const LightDesc& d) {
  ecs::Entity e = impl_->world.create();
  impl_->world.add(e, scene::WorldTransform{lightMatrix(d)});
  impl_->world.add(e, toLight(d));
  impl_->lights.push_back(e);
  return LightHandle(impl_->lights.size() - 1);
}

void GiContext::updateLight(LightHandle light, const LightDesc& d) {
  const ecs::Entity e = checked(impl_->lights, light, "light");
  if (e.isNull()) throw std::invalid_argument("GiContext::updateLight: a removed light");
  const glm::mat4 m = lightMatrix(d);
  if (impl_->world.get<scene::WorldTransform>(e).matrix != m) impl_->world.write<scene::WorldTransform>(e).matrix = m;
  impl_->world.write<scene::Light>(e) = toLight(d);
}

void GiContext::removeLight(LightHandle light) {
  ecs::Entity& e = checked(impl_->lights, light, "light");
  if (e.isNull()) return;
  impl_->world.destroy(e);
  e = {};
}

void GiContext::recordFrame(VkCommandBuffer cmd, const FrameDesc& desc) {
  Impl& im = *impl_;
  if (!cmd || desc.width == 0 || desc.height == 0) throw std::invalid_argument("GiContext::recordFrame: a null command buffer or a zero size");
  if (!desc.gbuffer.depth || !desc.gbuffer.normal || !desc.gbuffer.baseColor)
    throw std::invalid_argument("GiContext::recordFrame: the G-buffer needs its depth, normal and base colour views");
  if (desc.width != im.renderer.width() || desc.height != im.renderer.height()) im.renderer.resize(desc.width, desc.height);
  const double dt = im.frameCount == 0 ? 1.0 / 60.0 : std::max(desc.time - im.lastTime, 0.0);
  im.scheduler.runFrame(im.world, ecs::FrameTime{dt, desc.time, im.frameCount});
  im.lastTime = desc.time;
  render::extractSnapshot(im.world, im.assets, im.frameCount, im.snapshot);
  render::RenderSnapshot& snapshot = im.snapshot;
  snapshot.camera.view = desc.camera.view;
  snapshot.camera.position = glm::vec3(glm::inverse(desc.camera.view)[3]);
  snapshot.camera.fixedProjection = true;
  snapshot.camera.projectionMatrix = standardDepth(desc.camera.projection, desc.gbuffer.reversedZ);
  im.renderer.recordHostFrame(
      snapshot, cmd, [&](render::FrameContext& frame) { im.importGBuffer(frame, desc); },
      [&](render::FrameContext& frame) { im.exportOutputs(frame, desc); });
  ++im.frameCount;
}

// The host's G-buffer into the GI's targets, after every earlier write of the host.
void GiContext::Impl::importGBuffer(render::FrameContext& frame, const FrameDesc& desc) {
  VkCommandBuffer cmd = frame.cmd;
  render::ScopedPass scope(ctx, frame.timer, cmd, "gbuffer_import");
  render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  render::RenderTargets& t = frame.targets;
  for (render::Image* out : {&t.position, &t.normal, &t.albedo, &t.emissive})
    out->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  const GBufferDesc& g = desc.gbuffer;
  const VkImageLayout ro = g.colorLayout;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, import_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_GBUFFER_IMPORT_BINDING_FRAME, frame.frameUniforms.handle())
      .sampledImage(DYNGI_GBUFFER_IMPORT_BINDING_DEPTH, g.depth, frame.nearestSampler, g.depthLayout)
      .sampledImage(DYNGI_GBUFFER_IMPORT_BINDING_NORMAL, g.normal, frame.nearestSampler, ro)
      .sampledImage(DYNGI_GBUFFER_IMPORT_BINDING_BASE_COLOR, g.baseColor, frame.nearestSampler, ro)
      .sampledImage(DYNGI_GBUFFER_IMPORT_BINDING_ROUGHNESS, g.roughness ? g.roughness : whiteTexture.view(), frame.nearestSampler,
                    g.roughness ? ro : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .sampledImage(DYNGI_GBUFFER_IMPORT_BINDING_METALLIC, g.metallic ? g.metallic : blackTexture.view(), frame.nearestSampler,
                    g.metallic ? ro : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .sampledImage(DYNGI_GBUFFER_IMPORT_BINDING_EMISSIVE, g.emissive ? g.emissive : blackTexture.view(), frame.nearestSampler,
                    g.emissive ? ro : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .storageImage(DYNGI_GBUFFER_IMPORT_BINDING_OUT_POSITION, t.position.view())
      .storageImage(DYNGI_GBUFFER_IMPORT_BINDING_OUT_NORMAL, t.normal.view())
      .storageImage(DYNGI_GBUFFER_IMPORT_BINDING_OUT_ALBEDO, t.albedo.view())
      .storageImage(DYNGI_GBUFFER_IMPORT_BINDING_OUT_EMISSIVE, t.emissive.view())
      .push(ctx, cmd, import_);
  gpu::GBufferImportPush pc{};
  pc.normalEncoding = uint32_t(g.normalEncoding);
  pc.normalScale = g.normalScale;
  pc.normalBias = g.normalBias;
  pc.reversedZ = g.reversedZ ? 1u : 0u;
  pc.roughnessChannel = g.roughness ? std::min(g.roughnessChannel, 3u) : 0u;  // none: the white texture's 1
  pc.metallicChannel = g.metallic ? std::min(g.metallicChannel, 3u) : 0u;      // none: the black texture's 0
  pc.squaredRoughness = g.perceptualRoughness ? 0u : 1u;
  pc.width = desc.width;
  pc.height = desc.height;
  vkCmdPushConstants(cmd, import_.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(desc.width, 8), dispatchGroups(desc.height, 8), 1);
  render::computeWriteBarrier(cmd);
}

void GiContext::Impl::exportImage(render::FrameContext& frame, render::Image& source, VkImageView destination, VkFormat format, bool zero) {
  VkCommandBuffer cmd = frame.cmd;
  const uint32_t w = frame.targets.width, h = frame.targets.height;
  if (format != VK_FORMAT_R16G16B16A16_SFLOAT && format != VK_FORMAT_R32G32B32A32_SFLOAT)
    throw std::invalid_argument("GiContext::recordFrame: an output must be RGBA16F or RGBA32F");
  const Pipeline& p = format == VK_FORMAT_R32G32B32A32_SFLOAT ? export32_ : export16_;
  source.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
  DescriptorWrites()
      .sampledImage(DYNGI_EXPORT_BINDING_IN, source.view(), frame.nearestSampler, VK_IMAGE_LAYOUT_GENERAL)
      .storageImage(DYNGI_EXPORT_BINDING_OUT, destination)
      .push(ctx, cmd, p);
  const gpu::ExportPush pc{w, h, zero ? 1u : 0u};
  vkCmdPushConstants(cmd, p.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(w, 8), dispatchGroups(h, 8), 1);
}

// The indirect light and the specular light into the host's images, or the GI's own: the specular
// image holds the specular light whichever way the technique gave it (SpecularSource).
void GiContext::Impl::exportOutputs(render::FrameContext& frame, const FrameDesc& desc) {
  VkCommandBuffer cmd = frame.cmd;
  render::ScopedPass scope(ctx, frame.timer, cmd, "gi_export");
  render::RenderTargets& t = frame.targets;
  if (desc.outputs.indirect) exportImage(frame, t.indirect, desc.outputs.indirect, desc.outputs.indirectFormat, false);
  const bool fromIndirect = frame.specular == render::SpecularSource::Indirect, none = frame.specular == render::SpecularSource::None;
  if (desc.outputs.specular) {
    exportImage(frame, fromIndirect ? t.indirect : t.specular, desc.outputs.specular, desc.outputs.specularFormat, none);
  } else if (fromIndirect || none) {
    t.specular.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    exportImage(frame, t.indirect, t.specular.view(), VK_FORMAT_R16G16B16A16_SFLOAT, none);
  }
  render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  for (render::Image* img : {&t.indirect, &t.specular})
    img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

VkImageView GiContext::indirectView() const { return impl_->renderer.targetView(render::TargetId::Indirect); }
VkImageView GiContext::specularView() const { return impl_->renderer.targetView(render::TargetId::Specular); }

}  // namespace dyngi::gi
