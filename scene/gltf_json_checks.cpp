// The glTF JSON checked before tinygltf parses it: what tinygltf would truncate, trust or
// allocate for. Indices must be integers in int range; buffers must be backed by real data of
// their byteLength (GLB chunk, data URI or file), bufferViews must lie inside their buffers,
// images' bufferViews must exist; unsupported required extensions are refused.
#include <cstring>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>

#include "scene/gltf_internal.h"

namespace rp::scene::gltf {
namespace {

using Json = nlohmann::json;
constexpr uint64_t kMaxIndex = static_cast<uint64_t>(std::numeric_limits<int32_t>::max());

// Properties holding an index, a byte offset/length/count or an enum: tinygltf reads them as int
// (truncating larger ones) or as size_t (taking a negative one as absent). Each must be an
// integer in [0, 2^31 - 1]; no file the loader accepts (< 2 GiB) needs more.
const std::set<std::string> kIndexKeys = {
    "buffer",        "bufferView", "byteLength", "byteOffset", "byteStride", "camera",
    "componentType", "count",      "index",      "indices",    "input",      "inverseBindMatrices",
    "light",         "magFilter",  "material",   "mesh",       "minFilter",  "mode",
    "node",          "output",     "sampler",    "scene",      "skeleton",   "skin",
    "source",        "target",     "texCoord",   "wrapS",      "wrapT"};
const std::set<std::string> kIndexArrayKeys = {"children", "joints", "nodes"};
// Extensions whose contents the loader reads; others' contents are never looked at.
const std::set<std::string> kReadExtensions = {"KHR_lights_punctual", "KHR_texture_transform",
                                               "KHR_materials_emissive_strength",
                                               "KHR_materials_ior"};

bool is_index(const Json& v) {
  if (v.is_number_unsigned()) return v.get<uint64_t>() <= kMaxIndex;
  if (v.is_number_integer()) return v.get<int64_t>() >= 0 && v.get<int64_t>() <= int64_t{kMaxIndex};
  return false;
}

void require_index(const Context& ctx, const Json& v, const std::string& path) {
  if (!is_index(v))
    ctx.fail(path + " must be a non-negative integer below 2^31, not " + v.dump().substr(0, 40));
}

void check_indices(const Context& ctx, const Json& j, const std::string& path) {
  if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i)
      check_indices(ctx, j[i], path + "[" + std::to_string(i) + "]");
    return;
  }
  if (!j.is_object()) return;
  for (const auto& [key, value] : j.items()) {
    const std::string at = path.empty() ? key : path + "." + key;
    if (key == "extras") continue;  // free-form; read only where documented (volume)
    if (key == "extensions" && value.is_object()) {
      for (const auto& [name, ext] : value.items())
        if (kReadExtensions.count(name)) check_indices(ctx, ext, at + "." + name);
      continue;
    }
    // Objects are other things of the same name (an animation channel's target, a sparse
    // accessor's indices); their contents are checked by the recursion below.
    if (kIndexKeys.count(key) && !value.is_object()) require_index(ctx, value, at);
    if (kIndexArrayKeys.count(key) && value.is_array()) {
      for (size_t i = 0; i < value.size(); ++i)
        if (!value[i].is_object()) require_index(ctx, value[i], at + "[" + std::to_string(i) + "]");
    }
    if (key == "attributes" && value.is_object()) {
      for (const auto& [name, a] : value.items()) require_index(ctx, a, at + "." + name);
    } else if (key == "targets" && value.is_array()) {
      for (size_t t = 0; t < value.size(); ++t)
        if (value[t].is_object())
          for (const auto& [name, a] : value[t].items())
            require_index(ctx, a, at + "[" + std::to_string(t) + "]." + name);
    }
    check_indices(ctx, value, at);
  }
}

void check_version(const Context& ctx, const Json& root) {
  const auto asset = root.find("asset");
  if (asset == root.end() || !asset->is_object()) ctx.fail("not a glTF file: no \"asset\" object");
  const auto version = asset->find("version");
  if (version == asset->end() || !version->is_string())
    ctx.fail("not a glTF file: no asset.version");
  const std::string v = version->get<std::string>();
  if (v.size() < 2 || v[0] != '2' || v[1] != '.')
    ctx.fail("glTF version \"" + v.substr(0, 20) + "\" is not supported (only 2.x)");
  if (const auto min = asset->find("minVersion"); min != asset->end()) {
    if (!min->is_string() || min->get<std::string>() != "2.0")
      ctx.fail("asset.minVersion " + min->dump().substr(0, 20) + " is newer than glTF 2.0");
  }
}

void check_required_extensions(const Context& ctx, const Json& root) {
  const auto required = root.find("extensionsRequired");
  if (required == root.end()) return;
  if (!required->is_array()) ctx.fail("extensionsRequired is not an array");
  std::string missing;
  for (const Json& e : *required) {
    const std::string name = (e.is_string() ? e.get<std::string>() : e.dump()).substr(0, 64);
    if (name == "KHR_lights_punctual" || name == "KHR_materials_emissive_strength" ||
        name == "KHR_materials_ior")
      continue;
    missing += (missing.empty() ? "" : ", ") + name;
  }
  if (!missing.empty())
    ctx.fail("the file requires extension(s) rolypoly does not support: " + missing);
}

const Json* array_member(const Context& ctx, const Json& root, const char* name) {
  const auto it = root.find(name);
  if (it == root.end()) return nullptr;
  if (!it->is_array()) ctx.fail(std::string(name) + " is not an array");
  return &*it;
}

// An index or size member (`absent` when missing); an object there slipped past
// check_indices (it skips objects), so the type is checked again.
uint64_t size_member(const Context& ctx, const Json& o, const char* name, uint64_t absent,
                     const std::string& where) {
  const auto it = o.find(name);
  if (it == o.end()) return absent;
  require_index(ctx, *it, where + ": " + name);
  return it->get<uint64_t>();
}

// The bytes tinygltf's base64 decoder produces from a data URI's payload: it stops at the
// first '=' or character outside the alphabet.
uint64_t base64_decoded_size(const std::string& uri, size_t payload_at) {
  uint64_t n = 0;
  for (size_t i = payload_at; i < uri.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(uri[i]);
    const bool alnum = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    if (!(alnum || c == '+' || c == '/')) break;
    ++n;
  }
  return n / 4 * 3 + (n % 4 > 1 ? n % 4 - 1 : 0);
}

// The data URI prefixes tinygltf decodes (it treats any other "data:" as a file name).
size_t data_uri_payload(const std::string& uri, bool image) {
  static const char* const kBuffer[] = {"data:application/octet-stream;base64,",
                                        "data:application/gltf-buffer;base64,"};
  static const char* const kImage[] = {"data:image/png;base64,", "data:image/jpeg;base64,"};
  for (const char* p : image ? std::vector<const char*>(std::begin(kImage), std::end(kImage))
                             : std::vector<const char*>(std::begin(kBuffer), std::end(kBuffer)))
    if (uri.rfind(p, 0) == 0) return std::strlen(p);
  return 0;
}

// Buffers against the data they really have (so tinygltf never allocates for a claim),
// bufferViews inside their buffers, images' bufferViews in range.
void check_buffers(const Context& ctx, const Json& root, const GlbChunks& c,
                   const std::string& base_dir, std::map<std::string, uint64_t>* exact_size) {
  std::vector<uint64_t> buffer_sizes;
  if (const Json* buffers = array_member(ctx, root, "buffers")) {
    for (size_t i = 0; i < buffers->size(); ++i) {
      const Json& b = (*buffers)[i];
      const std::string where = "buffer " + std::to_string(i);
      if (!b.is_object()) ctx.fail(where + " is not an object");
      const uint64_t length = size_member(ctx, b, "byteLength", 0, where);
      if (length == 0) ctx.fail(where + ": byteLength missing or 0");
      const auto uri = b.find("uri");
      if (uri == b.end()) {
        if (!c.binary || i != 0)
          ctx.fail(where + " has no uri (only a GLB's buffer 0 may omit it)");
        if (!c.has_bin) ctx.fail(where + " refers to the GLB's BIN chunk, and the file has none");
        if (length > c.bin_size)
          ctx.fail(where + ": byteLength " + std::to_string(length) + " is more than the " +
                   std::to_string(c.bin_size) + " bytes of the GLB's BIN chunk");
      } else if (!uri->is_string()) {
        ctx.fail(where + ": uri is not a string");
      } else if (const std::string u = uri->get<std::string>(); u.rfind("data:", 0) == 0) {
        const size_t payload = data_uri_payload(u, false);
        if (payload == 0)
          ctx.fail(where +
                   ": unsupported data URI (base64 application/octet-stream or "
                   "application/gltf-buffer expected)");
        const uint64_t have = base64_decoded_size(u, payload);
        if (have != length)
          ctx.fail(where + ": its data URI holds " + std::to_string(have) +
                   " bytes, byteLength says " + std::to_string(length));
      } else {
        const std::string path = join_path(base_dir, uri_decode(u));
        uint64_t size = 0;
        std::string why;
        if (!regular_file_size(path, &size, &why))
          ctx.fail(where + ": cannot read '" + u + "' (" + path + "): " + why);
        if (size < length)
          ctx.fail(where + ": '" + u + "' has " + std::to_string(size) +
                   " bytes, fewer than its byteLength " + std::to_string(length));
        (*exact_size)[path] = length;
      }
      buffer_sizes.push_back(length);
    }
  }
  size_t views = 0;
  if (const Json* bufferViews = array_member(ctx, root, "bufferViews")) {
    views = bufferViews->size();
    for (size_t i = 0; i < views; ++i) {
      const Json& v = (*bufferViews)[i];
      const std::string where = "bufferView " + std::to_string(i);
      if (!v.is_object()) ctx.fail(where + " is not an object");
      if (!v.contains("buffer")) ctx.fail(where + " has no buffer");
      const uint64_t b = size_member(ctx, v, "buffer", 0, where);
      if (b >= buffer_sizes.size())
        ctx.fail(where + ": buffer " + std::to_string(b) + " does not exist (" +
                 std::to_string(buffer_sizes.size()) + " buffers)");
      const uint64_t offset = size_member(ctx, v, "byteOffset", 0, where);
      const uint64_t length = size_member(ctx, v, "byteLength", 0, where);
      if (length == 0) ctx.fail(where + ": byteLength missing or 0");
      if (offset + length > buffer_sizes[b])  // each < 2^31: no overflow
        ctx.fail(where + ": bytes " + std::to_string(offset) + ".." +
                 std::to_string(offset + length) + " run past the end of buffer " +
                 std::to_string(b) + " (" + std::to_string(buffer_sizes[b]) + " bytes)");
      const uint64_t stride = size_member(ctx, v, "byteStride", 0, where);
      if (v.contains("byteStride") && (stride < 4 || stride > 252 || stride % 4 != 0))
        ctx.fail(where + ": byteStride " + std::to_string(stride) +
                 " (must be a multiple of 4 from 4 to 252)");
    }
  }
  if (const Json* images = array_member(ctx, root, "images")) {
    for (size_t i = 0; i < images->size(); ++i) {
      const Json& im = (*images)[i];
      const std::string where = "image " + std::to_string(i);
      if (!im.is_object()) ctx.fail(where + " is not an object");
      if (im.contains("bufferView")) {
        const uint64_t view = size_member(ctx, im, "bufferView", 0, where);
        if (view >= views)
          ctx.fail(where + ": bufferView " + std::to_string(view) + " does not exist (" +
                   std::to_string(views) + " bufferViews)");
        if (im.contains("uri")) ctx.fail(where + " has both a uri and a bufferView");
      } else if (const auto uri = im.find("uri"); uri == im.end() || !uri->is_string()) {
        ctx.fail(where + " has neither a uri nor a bufferView");
      } else if (const std::string u = uri->get<std::string>();
                 u.rfind("data:", 0) == 0 && data_uri_payload(u, true) == 0) {
        ctx.fail(where + ": unsupported data URI (base64 image/png or image/jpeg expected)");
      }
    }
  }
}

}  // namespace

void check_json(const Context& ctx, const Json& root, const GlbChunks& glb,
                const std::string& base_dir, std::map<std::string, uint64_t>* exact_size) {
  if (!root.is_object()) ctx.fail("not a glTF file: the JSON is not an object");
  check_version(ctx, root);
  check_indices(ctx, root, "");
  check_required_extensions(ctx, root);
  check_buffers(ctx, root, glb, base_dir, exact_size);
}

}  // namespace rp::scene::gltf
