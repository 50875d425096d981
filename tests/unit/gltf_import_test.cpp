#include <gtest/gtest.h>

#include "support/shared_scenes.h"

#include <cmath>
#include <filesystem>

#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "support/gltf_writer.h"
#include "support/temp_dir.h"

using namespace dyngi;
using namespace dyngi::scene;
using dyngi::test::GltfSpec;
using dyngi::test::TempDir;

namespace {
GltfSpec oneQuad() {
  GltfSpec s;
  s.meshes = {{test::quadPrimitive(1.0f)}};
  s.nodes = {{.name = "floor", .mesh = 0}};
  return s;
}

struct Loaded {
  ecs::World world;
  AssetStore assets;
  ImportReport report;
  std::string error;
};

std::unique_ptr<Loaded> load(const std::string& path) {
  auto l = std::make_unique<Loaded>();
  l->error = importGltf(path, l->world, l->assets, &l->report);
  return l;
}

std::unique_ptr<Loaded> loadSpec(const TempDir& dir, const GltfSpec& spec) { return load(dir.write("scene.gltf", test::writeGltf(spec))); }

void expectCleanFailure(const Loaded& l, const std::string& path, const std::string& mentions) {
  EXPECT_FALSE(l.error.empty());
  EXPECT_EQ(l.error.find('\n'), std::string::npos) << "one line: " << l.error;
  EXPECT_EQ(l.error.rfind(path, 0), 0u) << "names the file: " << l.error;
  EXPECT_NE(l.error.find(mentions), std::string::npos) << "says what is wrong: " << l.error;
  EXPECT_EQ(l.world.aliveCount(), 0u) << "a failed import leaves the world untouched";
  EXPECT_EQ(l.assets.meshCount(), 0u);
}
}  // namespace

TEST(GltfImport, LoadsHierarchyMaterialsLightsAndCamera) {
  TempDir dir;
  GltfSpec s;
  auto prim = test::quadPrimitive(1.0f);
  prim.material = 0;
  auto noNormals = test::quadPrimitive(0.5f);
  noNormals.normals.clear();
  s.meshes = {{prim, noNormals}};
  s.materialsJson = {R"({"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,0.125,1],"metallicFactor":0.2,"roughnessFactor":0.7},
                         "emissiveFactor":[1,0.5,0],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":4}}})"};
  s.lightsJson = {R"({"type":"spot","color":[1,0.9,0.8],"intensity":12,"spot":{"innerConeAngle":0.2,"outerConeAngle":0.5}})",
                  R"({"type":"directional","intensity":3})", R"({"type":"point","intensity":7,"range":5})"};
  s.camerasJson = {R"({"type":"perspective","perspective":{"yfov":0.9,"znear":0.1,"zfar":50,"aspectRatio":1.5}})"};
  s.nodes = {{.name = "root", .children = {1, 2, 3, 4, 5}, .transformJson = R"("translation":[0,1,0])"},
             {.name = "mesh", .mesh = 0, .transformJson = R"("scale":[2,2,2])"},
             {.name = "spot", .light = 0},
             {.name = "sun", .light = 1},
             {.name = "bulb", .light = 2},
             {.name = "cam", .camera = 0, .transformJson = R"("matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1])"}};
  auto l = loadSpec(dir, s);
  ASSERT_EQ(l->error, "");
  EXPECT_EQ(l->report.meshInstances, 2u);
  EXPECT_EQ(l->report.triangles, 4u);
  EXPECT_EQ(l->report.lights, 3u);
  EXPECT_EQ(l->report.cameras, 1u);
  ASSERT_FALSE(l->report.activeCamera.isNull());
  EXPECT_TRUE(l->world.has<ActiveCamera>(l->report.activeCamera));
  EXPECT_NEAR(l->world.get<WorldTransform>(l->report.activeCamera).matrix[3].z, 5.0f, 1e-6f);
  EXPECT_NEAR(l->world.get<WorldTransform>(l->report.activeCamera).matrix[3].y, 1.0f, 1e-6f) << "parent translation applies";
  EXPECT_NEAR(l->world.get<Camera>(l->report.activeCamera).yfov, 0.9f, 1e-6f);

  // Bounds: quad of half size 1, scaled 2, lifted 1.
  EXPECT_NEAR(l->report.worldBounds.min.x, -2.0f, 1e-5f);
  EXPECT_NEAR(l->report.worldBounds.max.y, 1.0f, 1e-5f);

  int withMaterial = 0;
  l->world.each<MeshInstance, Material>([&](Entity, const MeshInstance& mi, const Material& m) {
    EXPECT_TRUE(l->world.has<StaticTag>(l->world.poolIfAny<MeshInstance>()->entities()[0]));
    const MeshData& mesh = l->assets.mesh(mi.mesh);
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (auto& n : mesh.normals) EXPECT_NEAR(n.y, 1.0f, 1e-5f) << "generated normals face +Y for a CCW quad";
    if (m.baseColor.r == 0.5f) {
      ++withMaterial;
      EXPECT_FLOAT_EQ(m.baseColor.g, 0.25f);
      EXPECT_FLOAT_EQ(m.metallic, 0.2f);
      EXPECT_FLOAT_EQ(m.roughness, 0.7f);
      EXPECT_FLOAT_EQ(m.emissive.r, 4.0f) << "emissive factor x KHR_materials_emissive_strength";
      EXPECT_FLOAT_EQ(m.emissive.g, 2.0f);
    }
  });
  EXPECT_EQ(withMaterial, 1);

  int spots = 0, dirs = 0, points = 0;
  l->world.each<Light>([&](Entity, const Light& light) {
    if (light.type == LightType::Spot) {
      ++spots;
      EXPECT_FLOAT_EQ(light.intensity, 12.0f);
      EXPECT_FLOAT_EQ(light.outerConeAngle, 0.5f);
      EXPECT_FLOAT_EQ(light.innerConeAngle, 0.2f);
      EXPECT_FLOAT_EQ(light.color.b, 0.8f);
    } else if (light.type == LightType::Directional) {
      ++dirs;
      EXPECT_FLOAT_EQ(light.intensity, 3.0f);
    } else {
      ++points;
      EXPECT_FLOAT_EQ(light.range, 5.0f);
    }
  });
  EXPECT_EQ(spots + dirs + points, 3);
}

TEST(GltfImport, MissingFile) {
  auto l = load("/nonexistent/dir/scene.gltf");
  expectCleanFailure(*l, "/nonexistent/dir/scene.gltf", "not found");
}

TEST(GltfImport, MalformedJson) {
  TempDir dir;
  std::string p = dir.write("bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {");
  expectCleanFailure(*load(p), p, "not a valid glTF");
}

TEST(GltfImport, GarbageGlb) {
  TempDir dir;
  std::string p = dir.write("bad.glb", std::string("glTF\x02\x00\x00\x00garbage-that-is-not-a-glb", 32));
  expectCleanFailure(*load(p), p, "not a valid glTF");
}

TEST(GltfImport, AccessorReadingPastBufferIsRejected) {
  TempDir dir;
  GltfSpec s = oneQuad();
  s.meshes[0][0].positionCountOverride = 1000;
  auto l = loadSpec(dir, s);
  // tinygltf may catch this itself; either way the message is one line naming the file.
  EXPECT_FALSE(l->error.empty());
  EXPECT_EQ(l->error.find('\n'), std::string::npos);
  EXPECT_EQ(l->world.aliveCount(), 0u);
}

TEST(GltfImport, IndexOutOfRangeIsRejected) {
  TempDir dir;
  GltfSpec s = oneQuad();
  s.meshes[0][0].indices = {0, 1, 2, 0, 2, 99};
  std::string p = dir.file("scene.gltf");
  auto l = loadSpec(dir, s);
  expectCleanFailure(*l, p, "index out of range");
}

TEST(GltfImport, NonTrianglePrimitiveIsRejected) {
  TempDir dir;
  GltfSpec s = oneQuad();
  s.meshes[0][0].mode = 1;  // lines
  std::string p = dir.file("scene.gltf");
  expectCleanFailure(*loadSpec(dir, s), p, "only triangles");
}

TEST(GltfImport, EmptySceneIsRejected) {
  TempDir dir;
  GltfSpec s;
  s.lightsJson = {R"({"type":"point","intensity":1})"};
  s.nodes = {{.name = "lonely light", .light = 0}};
  std::string p = dir.file("scene.gltf");
  expectCleanFailure(*loadSpec(dir, s), p, "empty scene");
}

TEST(GltfImport, NonFiniteTransformIsRejected) {
  // 1e39 is a finite double (the JSON parser takes it) but an infinite float: the importer's own check
  // must catch it, with its own message, for each way a node states its transform.
  const std::pair<const char*, const char*> cases[] = {
      {R"("translation":[0,1e39,0])", "translation that is not finite"},
      {R"("scale":[1,-1e39,1])", "scale that is not finite"},
      {R"("matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 1e39,0,0,1])", "matrix that is not finite"},
      {R"("rotation":[0,0,0,0])", "zero rotation quaternion"},
      {R"("translation":[0,2e18,0])", "beyond the coordinate range"},
  };
  for (const auto& [json, message] : cases) {
    TempDir dir;
    GltfSpec s = oneQuad();
    s.nodes[0].transformJson = json;
    expectCleanFailure(*loadSpec(dir, s), dir.file("scene.gltf"), message);
  }
}

TEST(GltfImport, WorldTransformThatOverflowsIsRejected) {
  // Each node's own scale is finite and in range; their product is not.
  TempDir dir;
  GltfSpec s = oneQuad();
  s.nodes = {{.name = "outer", .children = {1}, .transformJson = R"("scale":[1e15,1e15,1e15])"},
             {.name = "inner", .mesh = 0, .transformJson = R"("scale":[1e15,1e15,1e15])"}};
  expectCleanFailure(*loadSpec(dir, s), dir.file("scene.gltf"), "world transform");
}

TEST(GltfImport, ZeroScaleIsLegalAndLoads) {
  // glTF allows scale 0 (animations hide parts that way): it loads, with a finite world matrix.
  TempDir dir;
  GltfSpec s = oneQuad();
  s.nodes[0].transformJson = R"("scale":[0,0,0])";
  auto l = loadSpec(dir, s);
  ASSERT_EQ(l->error, "");
  EXPECT_EQ(l->report.meshInstances, 1u);
  s.nodes[0].transformJson = R"("matrix":[0,0,0,0, 0,0,0,0, 0,0,0,0, 1,2,3,1])";
  auto m = loadSpec(dir, s);
  ASSERT_EQ(m->error, "");
  m->world.each<WorldTransform>([](Entity, const WorldTransform& wt) { EXPECT_TRUE(isFinite(wt.matrix)); });
}

TEST(GltfImport, NonFiniteBinaryDataIsRejectedWithItsOwnMessage) {
  const float nan = std::nanf("");
  {  // vertex positions
    TempDir dir;
    GltfSpec s = oneQuad();
    s.meshes[0][0].positions[2].y = nan;
    expectCleanFailure(*loadSpec(dir, s), dir.file("scene.gltf"), "non-finite vertex position");
  }
  {  // +-3e38 is a finite float, but bounds and distances of such a mesh overflow: refused as such, not as "empty"
    TempDir dir;
    GltfSpec s = oneQuad();
    for (auto& p : s.meshes[0][0].positions) p *= 3e38f;
    expectCleanFailure(*loadSpec(dir, s), dir.file("scene.gltf"), "vertex position beyond the coordinate range");
  }
  {  // inverse bind matrices
    TempDir dir;
    GltfSpec s = oneQuad();
    s.nodes.push_back({.name = "joint"});
    s.nodes[0].skin = 0;
    glm::mat4 ibm(1.0f);
    ibm[3][1] = nan;
    s.skins = {{.joints = {1}, .inverseBind = {ibm}}};
    expectCleanFailure(*loadSpec(dir, s), dir.file("scene.gltf"), "non-finite inverse bind matrix");
  }
  {  // animation key values
    TempDir dir;
    GltfSpec s = oneQuad();
    s.animations = {{.name = "a", .channels = {{.node = 0, .times = {0, 1}, .values = {glm::vec4(0), glm::vec4(nan)}}}}};
    expectCleanFailure(*loadSpec(dir, s), dir.file("scene.gltf"), "non-finite key values");
  }
  {  // animation key times
    TempDir dir;
    GltfSpec s = oneQuad();
    s.animations = {{.name = "a", .channels = {{.node = 0, .times = {0, nan}, .values = {glm::vec4(0), glm::vec4(1)}}}}};
    expectCleanFailure(*loadSpec(dir, s), dir.file("scene.gltf"), "key time that is negative or not finite");
  }
}

TEST(GltfImport, OffsetsThatWrapAroundAreRejectedInGltfAndGlb) {
  // byteOffset + byteLength wraps past 2^64 to a small number: it must not pass the bounds check.
  GltfSpec s = oneQuad();
  s.meshes[0][0].positionViewOffsetRaw = "18446744073709551600";
  TempDir dir;
  expectCleanFailure(*load(dir.write("scene.gltf", test::writeGltf(s))), dir.file("scene.gltf"), "bufferView lies outside its buffer");
  expectCleanFailure(*load(dir.write("scene.glb", test::writeGlb(s))), dir.file("scene.glb"), "bufferView lies outside its buffer");
}

TEST(GltfImport, HugeAccessorCountIsABadInputErrorNamingTheAccessor) {
  // count * stride overflows: a bad-input line naming the accessor, not an exception from std::vector.
  for (const char* count : {"4611686018427387904", "1537228672809129302"}) {
    GltfSpec s = oneQuad();
    s.meshes[0][0].positionCountRaw = count;
    TempDir dir;
    for (bool glb : {false, true}) {
      std::string name = glb ? "scene.glb" : "scene.gltf";
      auto l = load(dir.write(name, glb ? test::writeGlb(s) : test::writeGltf(s)));
      expectCleanFailure(*l, dir.file(name), "POSITION accessor 0");
      EXPECT_NE(l->error.find("reads past the end"), std::string::npos) << l->error;
    }
  }
}

TEST(GltfImport, GlbWriterRoundTrips) {
  // The GLB container the tests above use loads like the .gltf text of the same scene.
  TempDir dir;
  GltfSpec s = oneQuad();
  auto l = load(dir.write("scene.glb", test::writeGlb(s)));
  ASSERT_EQ(l->error, "");
  EXPECT_EQ(l->report.triangles, 2u);
}

TEST(GltfImport, MissingChildNodeIsRejected) {
  TempDir dir;
  GltfSpec s = oneQuad();
  s.nodes[0].children = {42};
  s.sceneNodes = {0};
  std::string p = dir.file("scene.gltf");
  auto l = loadSpec(dir, s);
  EXPECT_FALSE(l->error.empty());
  EXPECT_EQ(l->world.aliveCount(), 0u);
}

TEST(GltfImport, DegenerateTrianglesAreDropped) {
  TempDir dir;
  GltfSpec s = oneQuad();
  auto& p = s.meshes[0][0];
  p.positions.push_back({5, 0, 5});
  p.normals.push_back({0, 1, 0});
  p.indices.insert(p.indices.end(), {4, 4, 4, 0, 1, 1});  // zero-area triangles
  auto l = loadSpec(dir, s);
  ASSERT_EQ(l->error, "");
  EXPECT_EQ(l->report.triangles, 2u);
}

TEST(GltfImport, UnknownLightTypeIsRejected) {
  TempDir dir;
  GltfSpec s = oneQuad();
  s.lightsJson = {R"({"type":"area","intensity":1})"};
  s.nodes.push_back({.name = "l", .light = 0});
  std::string p = dir.file("scene.gltf");
  auto l = loadSpec(dir, s);
  EXPECT_FALSE(l->error.empty());
  EXPECT_EQ(l->world.aliveCount(), 0u);
}

TEST(GltfImport, SharedScenesLoadWhenPresent) {
  for (const char* name : {"CornellBox.glb", "Fox.glb", "IrradianceVolumeExample.glb"}) {
    DYNGI_SHARED_SCENE_OR_SKIP(path, name);
    auto l = load(path);
    EXPECT_EQ(l->error, "") << name;
    EXPECT_GT(l->report.triangles, 0u) << name;
    EXPECT_TRUE(l->report.worldBounds.valid()) << name;
  }
}

TEST(GltfFuzzRegressions, EveryKeptInputGetsAnAnswer) {
  // Inputs that once crashed, hung or tripped a sanitizer (tests/fuzz/regressions): each now ends in
  // success or one error line naming the file, and a failed import leaves the world untouched.
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(DYNGI_FUZZ_REGRESSIONS)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    ++files;
    const std::string path = entry.path().string();
    auto l = load(path);
    if (l->error.empty()) continue;
    EXPECT_EQ(l->error.find('\n'), std::string::npos) << path << ": " << l->error;
    EXPECT_EQ(l->error.rfind(path, 0), 0u) << path << ": " << l->error;
    EXPECT_EQ(l->world.aliveCount(), 0u) << path;
  }
  EXPECT_GE(files, 4u) << "the regression files are there";
}

// glTF materials as artists author them: the metallic-roughness and occlusion textures reach the
// Material, as linear data (a texture also used for colour is kept twice: sRGB for colour, linear for
// data), with the occlusion strength.
TEST(GltfImport, MetallicRoughnessAndOcclusionTexturesAreImportedAsLinearData) {
  TempDir dir;
  // 2 x 2 texels whose green and blue are data (roughness, metallic).
  const std::vector<uint8_t> texels = {10, 64, 200, 255, 20, 128, 0, 255, 30, 192, 50, 255, 40, 255, 255, 255};
  ASSERT_EQ(render::writePng(dir.file("mr.png"), 2, 2, texels), "");
  GltfSpec s = oneQuad();
  s.meshes[0][0].uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.meshes[0][0].material = 0;
  s.imagesJson = {R"({"uri":"mr.png"})"};
  s.texturesJson = {R"({"source":0})"};
  s.materialsJson = {R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},"metallicRoughnessTexture":{"index":0},
                        "metallicFactor":0.5,"roughnessFactor":0.25},"occlusionTexture":{"index":0,"strength":0.75}})"};
  auto l = loadSpec(dir, s);
  ASSERT_EQ(l->error, "");
  const Material* m = nullptr;
  l->world.each<Material>([&](Entity, const Material& mat) { m = &mat; });
  ASSERT_NE(m, nullptr);
  ASSERT_NE(m->metallicRoughnessTexture, kNoTexture);
  EXPECT_EQ(m->occlusionTexture, m->metallicRoughnessTexture) << "one linear copy serves both data uses";
  ASSERT_NE(m->baseColorTexture, kNoTexture);
  EXPECT_NE(m->baseColorTexture, m->metallicRoughnessTexture) << "colour and data copies apart";
  EXPECT_TRUE(l->assets.texture(m->baseColorTexture).srgb);
  const TextureData& data = l->assets.texture(m->metallicRoughnessTexture);
  EXPECT_FALSE(data.srgb);
  EXPECT_EQ(data.rgba8, texels);
  EXPECT_FLOAT_EQ(m->metallic, 0.5f);
  EXPECT_FLOAT_EQ(m->roughness, 0.25f);
  EXPECT_FLOAT_EQ(m->occlusionStrength, 0.75f);
  EXPECT_TRUE(l->report.ignoredExtensions.empty());
}

// An extension the file requires and dyngi does not support is refused in one line naming it; one the
// file only uses is named in the report (the sample prints it once) and the file imports.
TEST(GltfImport, UnsupportedRequiredExtensionsAreRefusedAndOptionalOnesNamed) {
  TempDir dir;
  GltfSpec s = oneQuad();
  s.extensionsUsed = {"KHR_materials_transmission", "KHR_materials_emissive_strength"};
  auto optional = loadSpec(dir, s);
  ASSERT_EQ(optional->error, "");
  EXPECT_EQ(optional->report.ignoredExtensions, std::vector<std::string>{"KHR_materials_transmission"});

  s.extensionsRequired = {"KHR_materials_transmission"};
  const std::string path = dir.write("required.gltf", test::writeGltf(s));
  auto required = load(path);
  expectCleanFailure(*required, path, "requires the glTF extension KHR_materials_transmission");
  for (const std::string& name : supportedGltfExtensions()) {
    s.extensionsUsed = s.extensionsRequired = {name};
    EXPECT_EQ(loadSpec(dir, s)->error, "") << name;
  }
}

// KHR_texture_transform reaches the Material (one per material); a material whose textures carry
// different transforms keeps the first and is named once in the report's notes.
TEST(GltfImport, TextureTransformIsImportedAndDifferingOnesNoted) {
  TempDir dir;
  ASSERT_EQ(render::writePng(dir.file("t.png"), 1, 1, {255, 255, 255, 255}), "");
  GltfSpec s = oneQuad();
  s.nodes.push_back({.name = "second", .mesh = 0});
  s.meshes[0][0].uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.meshes[0][0].material = 0;
  s.imagesJson = {R"({"uri":"t.png"})"};
  s.texturesJson = {R"({"source":0})"};
  s.extensionsUsed = {"KHR_texture_transform"};
  const std::string transform = R"("extensions":{"KHR_texture_transform":{"offset":[0.25,0.5],"rotation":0.3,"scale":[2,3]}})";
  s.materialsJson = {R"({"name":"tiles","pbrMetallicRoughness":{"baseColorTexture":{"index":0,)" + transform + R"(}}})"};
  auto same = loadSpec(dir, s);
  ASSERT_EQ(same->error, "");
  const Material* m = nullptr;
  same->world.each<Material>([&](Entity, const Material& mat) { m = &mat; });
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->uvTransform, (TextureTransform{.offset = {0.25f, 0.5f}, .rotation = 0.3f, .scale = {2.0f, 3.0f}}));
  EXPECT_TRUE(same->report.notes.empty());
  EXPECT_TRUE(same->report.ignoredExtensions.empty());

  s.materialsJson = {R"({"name":"tiles","pbrMetallicRoughness":{"baseColorTexture":{"index":0,)" + transform +
                     R"(}},"emissiveTexture":{"index":0}})"};
  auto differ = loadSpec(dir, s);
  ASSERT_EQ(differ->error, "");
  ASSERT_EQ(differ->report.notes.size(), 1u) << "once, though two nodes use the material";
  EXPECT_NE(differ->report.notes[0].find("tiles"), std::string::npos) << differ->report.notes[0];
}

// alphaMode MASK with its cutoff reaches the Material; BLEND (not drawn as blending) is drawn opaque and
// named once in the notes.
TEST(GltfImport, AlphaMaskIsImportedAndBlendNoted) {
  TempDir dir;
  GltfSpec s = oneQuad();
  s.meshes[0][0].material = 0;
  s.materialsJson = {R"({"name":"leaves","alphaMode":"MASK","alphaCutoff":0.3})"};
  auto mask = loadSpec(dir, s);
  ASSERT_EQ(mask->error, "");
  mask->world.each<Material>([&](Entity, const Material& m) {
    EXPECT_TRUE(m.alphaMask);
    EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
  });
  EXPECT_TRUE(mask->report.notes.empty());
  s.materialsJson = {R"({"name":"glass","alphaMode":"BLEND"})"};
  auto blend = loadSpec(dir, s);
  ASSERT_EQ(blend->error, "");
  blend->world.each<Material>([&](Entity, const Material& m) { EXPECT_FALSE(m.alphaMask); });
  ASSERT_EQ(blend->report.notes.size(), 1u);
  EXPECT_NE(blend->report.notes[0].find("BLEND"), std::string::npos);
}

// A normal texture reaches the Material (linear, with its scale) and gives its mesh tangents: the uvs'
// frame (u grows along +x on the writer's quad) when the file has none.
TEST(GltfImport, NormalTextureGivesTheMeshTangents) {
  TempDir dir;
  ASSERT_EQ(render::writePng(dir.file("n.png"), 1, 1, {128, 128, 255, 255}), "");
  GltfSpec s = oneQuad();
  s.meshes[0][0].uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.meshes[0][0].material = 0;
  s.imagesJson = {R"({"uri":"n.png"})"};
  s.texturesJson = {R"({"source":0})"};
  s.materialsJson = {R"({"normalTexture":{"index":0,"scale":0.5}})"};
  auto l = loadSpec(dir, s);
  ASSERT_EQ(l->error, "");
  const Material* m = nullptr;
  MeshId mesh = 0;
  l->world.each<Material>([&](Entity e, const Material& mat) { m = &mat, mesh = l->world.get<MeshInstance>(e).mesh; });
  ASSERT_NE(m, nullptr);
  ASSERT_NE(m->normalTexture, kNoTexture);
  EXPECT_FALSE(l->assets.texture(m->normalTexture).srgb);
  EXPECT_FLOAT_EQ(m->normalScale, 0.5f);
  const MeshData& md = l->assets.mesh(mesh);
  ASSERT_EQ(md.tangents.size(), md.positions.size());
  for (size_t i = 0; i < md.positions.size(); ++i) {
    // The tangent follows u across the quad; whatever its direction, it lies in the surface.
    EXPECT_NEAR(glm::dot(glm::vec3(md.tangents[i]), md.normals[i]), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::vec3(md.tangents[i])), 1.0f, 1e-5f);
    EXPECT_EQ(std::abs(md.tangents[i].w), 1.0f);
    const glm::vec3 du = md.positions[1] - md.positions[0];  // from uv (0,0) to (1,0)
    EXPECT_GT(glm::dot(glm::vec3(md.tangents[i]), glm::normalize(du)), 0.999f);
  }
}
