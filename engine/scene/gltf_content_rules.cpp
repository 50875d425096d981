#include "gltf_content_rules.h"

#include <jpeglib.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <filesystem>

#include "dyngi/engine/platform/files.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::scene::content {

std::string checkJsonDepth(const uint8_t* data, size_t size) {
  // A .glb's JSON is its first chunk; anything malformed is left for tinygltf to name.
  if (size >= 20 && std::memcmp(data, "glTF", 4) == 0) {
    uint32_t length = 0;
    std::memcpy(&length, data + 12, 4);
    size = std::min<size_t>(size - 20, length);
    data += 20;
  }
  int depth = 0;
  bool inString = false, escaped = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = char(data[i]);
    if (inString) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return {};
}

namespace {
namespace fs = std::filesystem;

bool inside(const ReadRules& rules, const std::string& path) {
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) return false;
  for (const std::string& folder : rules.folders) {
    const fs::path relative = resolved.lexically_relative(folder);
    if (!relative.empty() && *relative.begin() != ".." && relative.is_relative()) return true;
  }
  return false;
}

bool fileExists(const std::string& path, void* user) {
  std::error_code ec;
  return inside(*static_cast<ReadRules*>(user), path) && fs::exists(path, ec);
}

std::string expandFilePath(const std::string& path, void*) { return path; }

bool readFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (!inside(*static_cast<ReadRules*>(user), path)) {
    if (err) *err += platform::oneLine(path) + ": outside the scene's folder\n";
    return false;
  }
  std::vector<uint8_t> bytes;
  if (std::string bad = platform::readInputFile(path, bytes); !bad.empty()) {
    if (err) *err += bad + "\n";
    return false;
  }
  out->assign(bytes.begin(), bytes.end());
  return true;
}

bool writeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the importer writes no files\n";
  return false;
}

// "" unless the image's bytes are not all there: a bufferView reaching past its buffer, or a length
// tinygltf's int could not hold.
std::string imageBytesMissing(const ReadRules& rules, const tinygltf::Image& image, int size) {
  if (image.bufferView < 0 || !rules.loading) return size < 0 ? "is over 2 GiB" : "";
  const auto& views = rules.loading->bufferViews;
  const auto& buffers = rules.loading->buffers;
  if (size_t(image.bufferView) >= views.size()) return "names a bufferView that does not exist";
  const tinygltf::BufferView& view = views[size_t(image.bufferView)];
  if (view.buffer < 0 || size_t(view.buffer) >= buffers.size()) return "names a buffer that does not exist";
  const size_t have = buffers[size_t(view.buffer)].data.size();
  if (view.byteOffset > have || view.byteLength > have - view.byteOffset) return "has a bufferView that lies outside its buffer";
  return size < 0 ? "is over 2 GiB" : "";
}

enum class Format { Png, Jpeg, Other };

Format sniff(const unsigned char* bytes, int size) {
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 8 && std::memcmp(bytes, png, 8) == 0) return Format::Png;
  if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return Format::Jpeg;
  return Format::Other;
}

// "" when a width x height RGBA image of `bytesPerChannel` fits the rules (and is counted against them).
std::string admit(ReadRules& rules, uint32_t width, uint32_t height, uint32_t bytesPerChannel) {
  if (width == 0 || height == 0) return "has no pixels";
  if (width > rules.maxImageDimension || height > rules.maxImageDimension)
    return "is " + std::to_string(width) + " x " + std::to_string(height) + ", over the limit of " +
           std::to_string(rules.maxImageDimension) + " a side";
  const uint64_t bytes = uint64_t(width) * height * 4 * bytesPerChannel;
  if (rules.imageBytes + bytes > rules.maxImageBytes)
    return "would bring the file's decoded images to " + std::to_string((rules.imageBytes + bytes) >> 20) + " MiB, over the limit of " +
           std::to_string(rules.maxImageBytes >> 20) + " MiB";
  rules.imageBytes += bytes;
  return {};
}

std::string decodePng(ReadRules& rules, const unsigned char* bytes, int size, tinygltf::Image& out) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes, size_t(size))) return std::string("is not a valid PNG (") + png.message + ")";
  // 16-bit files stay 16-bit and linear (their values untouched, as data textures need); their alpha comes
  // back premultiplied and is divided out below.
  const bool wide = (png.format & PNG_FORMAT_FLAG_LINEAR) != 0;
  if (std::string bad = admit(rules, png.width, png.height, wide ? 2 : 1); !bad.empty()) {
    png_image_free(&png);
    return bad;
  }
  png.format = wide ? PNG_FORMAT_LINEAR_RGB_ALPHA : PNG_FORMAT_RGBA;
  out.image.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, out.image.data(), 0, nullptr)) {
    std::string why = std::string("is not a valid PNG (") + png.message + ")";
    png_image_free(&png);
    return why;
  }
  if (wide) {
    auto* texels = reinterpret_cast<uint16_t*>(out.image.data());
    for (size_t i = 0; i < size_t(png.width) * png.height; ++i) {
      uint16_t* t = texels + i * 4;
      if (t[3] != 0 && t[3] != 65535)
        for (int c = 0; c < 3; ++c) t[c] = uint16_t(std::min<uint32_t>(65535u, uint32_t(t[c]) * 65535u / t[3]));
    }
  }
  out.width = int(png.width);
  out.height = int(png.height);
  out.component = 4;
  out.bits = wide ? 16 : 8;
  out.pixel_type = wide ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  return {};
}

struct JpegErrors {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

constexpr int kMaxJpegScans = 256;

// The frame size from the first SOF marker, read before libjpeg allocates anything for it.
bool jpegFrameSize(const unsigned char* bytes, int size, uint32_t& width, uint32_t& height) {
  int i = 2;
  while (i + 4 <= size) {
    if (bytes[i] != 0xff) return false;
    const unsigned char marker = bytes[i + 1];
    if (marker == 0xff) {  // fill byte
      ++i;
      continue;
    }
    const int length = bytes[i + 2] << 8 | bytes[i + 3];
    const bool sof = marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
    if (sof) {
      if (i + 9 > size) return false;
      height = uint32_t(bytes[i + 5] << 8 | bytes[i + 6]);
      width = uint32_t(bytes[i + 7] << 8 | bytes[i + 8]);
      return true;
    }
    if (length < 2 || marker == 0xda) return false;  // scan data before a frame header
    i += 2 + length;
  }
  return false;
}  // progressive files with thousands of scans decode for minutes

std::string decodeJpeg(ReadRules& rules, const unsigned char* bytes, int size, tinygltf::Image& out) {
  jpeg_decompress_struct info;
  JpegErrors errors;
  jpeg_progress_mgr progress;
  info.err = jpeg_std_error(&errors.base);
  errors.message[0] = 0;
  errors.base.error_exit = [](j_common_ptr c) {
    auto* e = reinterpret_cast<JpegErrors*>(c->err);
    c->err->format_message(c, e->message);
    std::longjmp(e->jump, 1);
  };
  errors.base.output_message = [](j_common_ptr) {};
  progress.progress_monitor = [](j_common_ptr c) {
    auto* d = reinterpret_cast<j_decompress_ptr>(c);
    if (d->input_scan_number > kMaxJpegScans) {
      std::snprintf(reinterpret_cast<JpegErrors*>(c->err)->message, JMSG_LENGTH_MAX, "more than %d scans", kMaxJpegScans);
      std::longjmp(reinterpret_cast<JpegErrors*>(c->err)->jump, 2);
    }
  };
  uint32_t width = 0, height = 0;
  if (!jpegFrameSize(bytes, size, width, height)) return "is not a valid JPEG (no frame header)";
  if (std::string bad = admit(rules, width, height, 1); !bad.empty()) return bad;
  if (int code = setjmp(errors.jump); code != 0) {
    jpeg_destroy_decompress(&info);
    return code == 2 ? std::string("is a JPEG with ") + errors.message : std::string("is not a valid JPEG (") + errors.message + ")";
  }
  jpeg_create_decompress(&info);
  info.progress = &progress;
  jpeg_mem_src(&info, bytes, static_cast<unsigned long>(size));
  jpeg_read_header(&info, TRUE);
  if (info.image_width != width || info.image_height != height) {
    jpeg_destroy_decompress(&info);
    return "is not a valid JPEG (two frame sizes)";
  }
  info.out_color_space = JCS_EXT_RGBA;
  jpeg_start_decompress(&info);
  out.image.resize(size_t(info.output_width) * info.output_height * 4);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = out.image.data() + size_t(info.output_scanline) * info.output_width * 4;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  out.width = int(info.output_width);
  out.height = int(info.output_height);
  jpeg_destroy_decompress(&info);
  out.component = 4;
  out.bits = 8;
  out.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  return {};
}
}  // namespace

tinygltf::FsCallbacks containedFiles(ReadRules& rules) { return {&fileExists, &expandFilePath, &readFile, &writeFile, &rules}; }

bool decodeImage(tinygltf::Image* image, int index, std::string* err, std::string*, int, int, const unsigned char* bytes, int size,
                 void* user) {
  ReadRules& rules = *static_cast<ReadRules*>(user);
  const std::string name = "image " + std::to_string(index);
  std::string why = imageBytesMissing(rules, *image, size);
  if (why.empty()) {
    const Format format = sniff(bytes, size);
    if (format == Format::Other) {
      why = "is neither PNG nor JPEG (the formats glTF allows)";
    } else if (!image->mimeType.empty() && image->mimeType != (format == Format::Png ? "image/png" : "image/jpeg")) {
      why = "is declared " + platform::oneLine(image->mimeType) + " but is " + (format == Format::Png ? "a PNG" : "a JPEG");
    } else {
      why = format == Format::Png ? decodePng(rules, bytes, size, *image) : decodeJpeg(rules, bytes, size, *image);
    }
  }
  if (why.empty()) return true;
  image->image.clear();
  if (err) *err += name + " " + why + "\n";
  return false;
}

namespace {
constexpr double kPi = 3.14159265358979323846;

// As the float it becomes: 1e39 is a finite double but an infinite float.
bool finiteFloat(double v) { return std::isfinite(float(v)); }
bool inUnit(double v) { return v >= 0.0 && v <= 1.0; }

std::string checkCamera(const tinygltf::Camera& c, size_t i) {
  const std::string where = "camera " + std::to_string(i);
  if (c.type == "orthographic") return where + " is orthographic; dyngi draws perspective cameras only";
  if (c.type != "perspective") return where + " has unknown type '" + platform::oneLine(c.type) + "'";
  const auto& p = c.perspective;
  if (!(p.yfov > 0.0 && p.yfov < kPi) || !finiteFloat(p.yfov)) return where + " has yfov outside (0, pi)";
  if (!(p.znear > 0.0) || !finiteFloat(p.znear)) return where + " has znear that is not > 0";
  if (p.zfar != 0.0 && (!(p.zfar > p.znear) || !finiteFloat(p.zfar) || !(float(p.zfar) > float(p.znear))))
    return where + " has zfar that is not > znear";
  if (p.aspectRatio < 0.0 || !finiteFloat(p.aspectRatio)) return where + " has an aspectRatio that is not > 0";
  return {};
}

// KHR_lights_punctual's raw light object, for the values tinygltf leaves at 0 when absent.
const tinygltf::Value* rawLight(const tinygltf::Model& model, size_t i) {
  auto it = model.extensions.find("KHR_lights_punctual");
  if (it == model.extensions.end() || !it->second.Has("lights")) return nullptr;
  const tinygltf::Value& lights = it->second.Get("lights");
  return lights.IsArray() && i < lights.ArrayLen() ? &lights.Get(int(i)) : nullptr;
}

std::string checkLight(const tinygltf::Model& model, size_t i) {
  const tinygltf::Light& l = model.lights[i];
  const std::string where = "light " + std::to_string(i);
  if (l.type != "directional" && l.type != "spot" && l.type != "point") return where + " has unknown type '" + platform::oneLine(l.type) + "'";
  if (!l.color.empty() && l.color.size() != 3) return where + " has a colour that is not 3 numbers";
  for (double c : l.color)
    if (!(c >= 0.0) || !finiteFloat(c)) return where + " has a colour that is negative or not finite";
  if (!(l.intensity >= 0.0 && l.intensity <= kMaxLightIntensity))
    return where + " has intensity outside [0, " + std::to_string(int64_t(kMaxLightIntensity)) + "]";
  const tinygltf::Value* raw = rawLight(model, i);
  if ((raw && raw->Has("range") && !(l.range > 0.0)) || l.range < 0.0 || !finiteFloat(l.range)) return where + " has a range that is not > 0";
  if (l.type == "spot") {
    const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
    if (!(inner >= 0.0 && inner < outer && outer <= kPi / 2 + 1e-6)) return where + " has cone angles outside 0 <= inner < outer <= pi/2";
  }
  return {};
}

std::string checkMaterial(const tinygltf::Material& m, size_t i) {
  const std::string where = "material " + std::to_string(i);
  const auto& pbr = m.pbrMetallicRoughness;
  for (double v : pbr.baseColorFactor)
    if (!inUnit(v)) return where + " has a baseColorFactor outside [0, 1]";
  if (!inUnit(pbr.metallicFactor) || !inUnit(pbr.roughnessFactor)) return where + " has a metallic or roughness factor outside [0, 1]";
  for (double v : m.emissiveFactor)
    if (!inUnit(v)) return where + " has an emissiveFactor outside [0, 1]";
  if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end() && it->second.Has("emissiveStrength")) {
    const tinygltf::Value& v = it->second.Get("emissiveStrength");
    if (!v.IsNumber() || !(v.GetNumberAsDouble() >= 0.0 && v.GetNumberAsDouble() <= kMaxEmission))
      return where + " has an emissiveStrength outside [0, " + std::to_string(int64_t(kMaxEmission)) + "]";
  }
  if (!(m.alphaCutoff >= 0.0) || !finiteFloat(m.alphaCutoff)) return where + " has an alphaCutoff that is negative or not finite";
  if (!inUnit(m.occlusionTexture.strength)) return where + " has an occlusion strength outside [0, 1]";
  if (!finiteFloat(m.normalTexture.scale)) return where + " has a normal scale that is not finite";
  return {};
}

std::string checkSampler(const tinygltf::Sampler& s, size_t i) {
  const std::string where = "sampler " + std::to_string(i);
  auto oneOf = [](int v, std::initializer_list<int> allowed) { return std::find(allowed.begin(), allowed.end(), v) != allowed.end(); };
  if (!oneOf(s.magFilter, {-1, 9728, 9729})) return where + " has a magFilter glTF does not define";
  if (!oneOf(s.minFilter, {-1, 9728, 9729, 9984, 9985, 9986, 9987})) return where + " has a minFilter glTF does not define";
  if (!oneOf(s.wrapS, {33071, 33648, 10497}) || !oneOf(s.wrapT, {33071, 33648, 10497})) return where + " has a wrap mode glTF does not define";
  return {};
}
}  // namespace

std::string checkValues(const tinygltf::Model& model) {
  for (size_t i = 0; i < model.cameras.size(); ++i)
    if (std::string bad = checkCamera(model.cameras[i], i); !bad.empty()) return bad;
  for (size_t i = 0; i < model.lights.size(); ++i)
    if (std::string bad = checkLight(model, i); !bad.empty()) return bad;
  for (size_t i = 0; i < model.materials.size(); ++i)
    if (std::string bad = checkMaterial(model.materials[i], i); !bad.empty()) return bad;
  for (size_t i = 0; i < model.samplers.size(); ++i)
    if (std::string bad = checkSampler(model.samplers[i], i); !bad.empty()) return bad;
  for (size_t i = 0; i < model.textures.size(); ++i)
    if (model.textures[i].sampler < -1 || model.textures[i].sampler >= int(model.samplers.size()))
      return "texture " + std::to_string(i) + " references a missing sampler";
  return {};
}

std::string sceneRoots(const tinygltf::Model& model, std::vector<int>& roots) {
  const size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i)
    for (int c : model.nodes[i].children) {
      if (c < 0 || size_t(c) >= n) return "node " + std::to_string(i) + " has a missing child node";
      if (parent[size_t(c)] >= 0 || size_t(c) == i)
        return "node " + std::to_string(c) + " has two parents (nodes " + std::to_string(parent[size_t(c)] >= 0 ? parent[size_t(c)] : c) +
               " and " + std::to_string(i) + "); glTF nodes form a forest";
      parent[size_t(c)] = int(i);
    }
  roots.clear();
  if (model.scenes.empty()) {
    if (model.defaultScene >= 0) return "scene " + std::to_string(model.defaultScene) + " does not exist";
    for (size_t i = 0; i < n; ++i)
      if (parent[i] < 0) roots.push_back(int(i));
    return {};
  }
  if (model.defaultScene >= int(model.scenes.size())) return "scene " + std::to_string(model.defaultScene) + " does not exist";
  roots = model.scenes[size_t(std::max(model.defaultScene, 0))].nodes;
  std::vector<uint8_t> listed(n, 0);
  for (int r : roots) {
    if (r < 0 || size_t(r) >= n) return "scene references a missing node";
    if (listed[size_t(r)]++) return "node " + std::to_string(r) + " is listed twice in the scene";
    if (parent[size_t(r)] >= 0) return "node " + std::to_string(r) + " is a scene root and a child of node " + std::to_string(parent[size_t(r)]);
  }
  return {};
}

}  // namespace dyngi::scene::content
