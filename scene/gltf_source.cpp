// Reading a glTF file and handing it to tinygltf safely. tinygltf 2.7 trusts several things a
// broken or hostile file controls: it reads an image's bytes at a bufferView's offset without
// checking that the view lies inside its buffer, reads up to 8 bytes past a GLB whose BIN chunk
// header is cut short, recurses without limit into nested JSON (extras), truncates large
// indices to int, and its default file callbacks open whatever a URI names (a FIFO blocks
// forever). So the JSON is checked here first (with nlohmann, depth bounded), the GLB container
// is checked here, and tinygltf reads files only through the callbacks below.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace rp::scene::gltf {
namespace {

using Json = nlohmann::json;
constexpr uint64_t kMaxIndex = static_cast<uint64_t>(std::numeric_limits<int32_t>::max());

}  // namespace

// stat() before open(): opening a FIFO for reading blocks until a writer appears.
bool regular_file_size(const std::string& path, uint64_t* size, std::string* why) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    *why = errno == ENOENT ? "not found" : std::strerror(errno);
    return false;
  }
  if (S_ISDIR(st.st_mode)) {
    *why = "is a directory";
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    *why = "is not a regular file (a FIFO, device or socket)";
    return false;
  }
  *size = static_cast<uint64_t>(st.st_size);
  return true;
}

namespace {

// Reads exactly `want` bytes (no more than the file has: checked by the caller).
bool read_bytes(const std::string& path, uint64_t want, std::vector<uint8_t>* out,
                std::string* why) {
  // O_NONBLOCK: should the path have been swapped for a FIFO since stat(), open() still
  // returns at once, and fstat() below refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    *why = std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || static_cast<uint64_t>(st.st_size) < want) {
    ::close(fd);
    *why = "changed while being opened";
    return false;
  }
  out->resize(static_cast<size_t>(want));
  size_t done = 0;
  while (done < want) {
    const ssize_t n = ::read(fd, out->data() + done, static_cast<size_t>(want) - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *why = n < 0 ? std::strerror(errno) : "shorter than expected (changed while being read)";
      ::close(fd);
      out->clear();
      return false;
    }
    done += static_cast<size_t>(n);
  }
  ::close(fd);
  return true;
}

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
  if (!read_bytes(path, want, out, &why)) {
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
void check_buffers(const Context& ctx, const Json& root, const Container& c,
                   const std::string& base_dir, FileAccess* access) {
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
        access->exact_size[path] = length;
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

std::string first_lines(const std::string& text) {
  std::string s = text.substr(0, 300);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  for (char& ch : s)
    if (ch == '\n') ch = ';';
  return s.empty() ? "unknown error" : s;
}

}  // namespace

bool read_regular_file(const std::string& path, uint64_t max_bytes, std::vector<uint8_t>* out,
                       std::string* why) {
  uint64_t size = 0;
  if (!regular_file_size(path, &size, why)) return false;
  if (size > max_bytes) {
    *why = "is " + std::to_string(size) + " bytes, more than the limit of " +
           std::to_string(max_bytes);
    return false;
  }
  return read_bytes(path, size, out, why);
}

std::string base_dir_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// The same decoding as tinygltf's (dlib's urldecode, '+' as a space), so the paths checked here
// are the paths tinygltf then opens.
std::string uri_decode(const std::string& uri) {
  auto hex = [](char ch) -> unsigned {
    if (ch >= '0' && ch <= '9') return unsigned(ch - '0');
    if (ch >= 'a' && ch <= 'f') return unsigned(ch - 'a' + 10);
    if (ch >= 'A' && ch <= 'F') return unsigned(ch - 'A' + 10);
    return 0;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      out += static_cast<char>((hex(uri[i + 1]) << 4) | hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::string join_path(const std::string& dir, const std::string& name) {
  if (dir.empty()) return name;
  return dir.back() == '/' ? dir + name : dir + "/" + name;
}

void load_model(Context& ctx, const std::vector<uint8_t>& bytes, tinygltf::Model* model) {
  if (bytes.size() > ctx.limits.max_file_bytes)
    ctx.fail("the file is larger than " + std::to_string(ctx.limits.max_file_bytes) + " bytes");
  const Container c = parse_container(ctx, bytes);
  const char* text = reinterpret_cast<const char*>(bytes.data()) + c.json_offset;
  const Json root = parse_json(ctx, text, text + c.json_size);
  if (!root.is_object()) ctx.fail("not a glTF file: the JSON is not an object");
  check_version(ctx, root);
  check_indices(ctx, root, "");
  check_required_extensions(ctx, root);
  const std::string base_dir = base_dir_of(ctx.file);
  FileAccess access;
  access.prefix = join_path(base_dir, "");
  access.max_bytes = ctx.limits.max_file_bytes;
  check_buffers(ctx, root, c, base_dir, &access);

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
