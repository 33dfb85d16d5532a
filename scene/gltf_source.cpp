// Handing a glTF file to tinygltf safely. tinygltf 2.7 trusts several things a broken or
// hostile file controls: it reads an image's bytes at a bufferView's offset without checking
// that the view lies inside its buffer, reads up to 8 bytes past a GLB whose BIN chunk header
// is cut short, recurses without limit into nested JSON (extras), truncates large indices to
// int, and its default file callbacks open whatever a URI names (a FIFO blocks forever). So
// the GLB container is checked here, the JSON is parsed here first (nlohmann, depth bounded)
// and checked (gltf_json_checks.cpp), and tinygltf reads files only through the callbacks
// below.
#include <cstring>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace rp::scene::gltf {
namespace {

using Json = nlohmann::json;

// ---- tinygltf's file access: regular files under the scene's folder, each with a bound ----

struct FileAccess {
  std::string prefix;                          // base folder + '/': the only place looked in
  std::map<std::string, uint64_t> exact_size;  // external buffers: their checked byteLength
  uint64_t max_bytes = 0;
};

bool file_exists(const std::string& path, void* user) {
  const auto* access = static_cast<const FileAccess*>(user);
  // tinygltf also tries "./<uri>" (the working folder); only the scene's folder counts.
  if (path.compare(0, access->prefix.size(), access->prefix) != 0) return false;
  uint64_t size = 0;
  std::string why;
  return regular_file_size(path, &size, &why);
}

std::string expand_path(const std::string& path, void*) { return path; }  // no ~ or $VAR

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* user) {
  const auto* access = static_cast<const FileAccess*>(user);
  uint64_t size = 0;
  std::string why;
  if (!regular_file_size(path, &size, &why)) {
    if (err) *err += path + ": " + why;
    return false;
  }
  uint64_t want = size;
  if (auto it = access->exact_size.find(path); it != access->exact_size.end()) {
    want = it->second;  // a .bin may be padded past its byteLength; read what the buffer holds
  } else if (size > access->max_bytes) {
    if (err) *err += path + ": larger than " + std::to_string(access->max_bytes) + " bytes";
    return false;
  }
  if (!read_file_start(path, want, out, &why)) {
    if (err) *err += path + ": " + why;
    return false;
  }
  return true;
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&,
                      void*) {
  if (err) *err += "the loader writes no files";
  return false;
}

// Images stay encoded until a material uses them (gltf_materials.cpp checks their size first
// and decodes only what is drawn).
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// ---- the GLB container ----

struct Container {
  bool binary = false;
  size_t json_offset = 0, json_size = 0;
  size_t length = 0;  // bytes tinygltf is given (the GLB's own length)
  bool has_bin = false;
  uint64_t bin_size = 0;
};

uint32_t le32(const std::vector<uint8_t>& b, size_t at) {
  return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 |
         uint32_t{b[at + 3]} << 24;
}

Container parse_container(const Context& ctx, const std::vector<uint8_t>& bytes) {
  Container c;
  if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0) {
    c.json_size = c.length = bytes.size();
    return c;
  }
  c.binary = true;
  if (bytes.size() < 20) ctx.fail("GLB file cut short: " + std::to_string(bytes.size()) + " bytes");
  if (const uint32_t version = le32(bytes, 4); version != 2)
    ctx.fail("GLB container version " + std::to_string(version) + " (only 2 is supported)");
  const uint64_t length = le32(bytes, 8);
  if (length > bytes.size() || length < 20)
    ctx.fail("GLB header claims " + std::to_string(length) + " bytes, the file has " +
             std::to_string(bytes.size()));
  const uint64_t json_size = le32(bytes, 12);
  if (le32(bytes, 16) != 0x4E4F534Au || json_size == 0 || 20 + json_size > length)
    ctx.fail("GLB's first chunk is not a JSON chunk inside the file");
  c.json_offset = 20;
  c.json_size = static_cast<size_t>(json_size);
  c.length = static_cast<size_t>(length);
  const uint64_t bin_at = 20 + json_size;
  if (bin_at == length) return c;
  // tinygltf reads the chunk after the JSON as BIN without checking that its 8-byte header
  // fits; check the header and the data it announces.
  if (bin_at + 8 > length) ctx.fail("GLB has a cut-short chunk after its JSON chunk");
  const uint64_t bin_size = le32(bytes, static_cast<size_t>(bin_at));
  if (le32(bytes, static_cast<size_t>(bin_at) + 4) != 0x004E4942u)
    ctx.fail("GLB's second chunk is not a BIN chunk");
  if (bin_size < 4 || bin_size % 4 != 0 || bin_at + 8 + bin_size > length)
    ctx.fail("GLB's BIN chunk claims " + std::to_string(bin_size) +
             " bytes, the file has room for " + std::to_string(length - bin_at - 8) +
             " (and it must be a multiple of 4)");
  c.has_bin = true;
  c.bin_size = bin_size;
  return c;
}

// ---- the JSON, checked before tinygltf sees it ----

struct TooDeep {};

Json parse_json(const Context& ctx, const char* begin, const char* end) {
  const int max_depth = ctx.limits.max_json_depth;
  const Json::parser_callback_t limit_depth = [max_depth](int depth, Json::parse_event_t, Json&) {
    if (depth > max_depth) throw TooDeep{};
    return true;
  };
  try {
    return Json::parse(begin, end, limit_depth);
  } catch (const TooDeep&) {
    ctx.fail("not a usable glTF file: its JSON nests deeper than " + std::to_string(max_depth) +
             " levels");
  } catch (const Json::exception& e) {
    ctx.fail(std::string("not a glTF file: bad JSON: ") + e.what());
  }
}

std::string first_lines(const std::string& text) {
  std::string s = text.substr(0, 300);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  for (char& ch : s)
    if (ch == '\n') ch = ';';
  return s.empty() ? "unknown error" : s;
}

}  // namespace

void load_model(Context& ctx, const std::vector<uint8_t>& bytes, tinygltf::Model* model) {
  if (bytes.size() > ctx.limits.max_file_bytes)
    ctx.fail("the file is larger than " + std::to_string(ctx.limits.max_file_bytes) + " bytes");
  const Container c = parse_container(ctx, bytes);
  const char* text = reinterpret_cast<const char*>(bytes.data()) + c.json_offset;
  const std::string base_dir = base_dir_of(ctx.file);
  FileAccess access;
  access.prefix = join_path(base_dir, "");
  access.max_bytes = ctx.limits.max_file_bytes;
  check_json(ctx, parse_json(ctx, text, text + c.json_size), {c.binary, c.has_bin, c.bin_size},
             base_dir, &access.exact_size);

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_path, &read_whole_file, &write_whole_file, &access});
  loader.SetImageLoader(&keep_encoded_image, nullptr);
  std::string err, warn;
  bool ok = false;
  try {
    ok = c.binary ? loader.LoadBinaryFromMemory(model, &err, &warn, bytes.data(),
                                                static_cast<unsigned>(c.length), base_dir)
                  : loader.LoadASCIIFromString(model, &err, &warn, text,
                                               static_cast<unsigned>(c.json_size), base_dir);
  } catch (const std::exception& e) {
    ctx.fail(std::string("not a valid glTF 2.0 file: ") + e.what());
  }
  if (!ok) ctx.fail("not a valid glTF 2.0 file: " + first_lines(err));
}

}  // namespace rp::scene::gltf
