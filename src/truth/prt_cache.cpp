// Disk cache of PRT transfer vectors (see prt_cache.h).
#include "truth/prt_cache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "io/atomic_file.h"
#include "io/fnv1a.h"

namespace rp::truth {
namespace {

// The file stores glow cells as they lie in memory: 6 floats each (prt_cache.h).
static_assert(sizeof(scene::GlowCell) == 6 * sizeof(float));

constexpr char kMagic[8] = {'R', 'P', 'P', 'R', 'T', 'B', 'I', 'N'};

void put_bytes(std::string& out, const void* data, size_t n) {
  if (n == 0) return;
  out.append(static_cast<const char*>(data), n);
}
void put_u32(std::string& out, uint32_t v) { put_bytes(out, &v, sizeof v); }

// Reads the file's fields in order; every read checks the bounds (a short file fails, no UB).
class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  bool get(void* dst, size_t n) {
    if (n == 0) return true;  // an empty array's data() may be null: memcpy must not see it
    if (n > bytes_.size() - pos_) return false;
    std::memcpy(dst, bytes_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  bool u32(uint32_t& v) { return get(&v, sizeof v); }
  size_t pos() const { return pos_; }
  size_t left() const { return bytes_.size() - pos_; }

 private:
  const std::string& bytes_;
  size_t pos_ = 0;
};

uint64_t checksum(const char* data, size_t n) {
  io::Fnv1a h;
  h.bytes(data, n);
  return h.get();
}

// The settings as the transfer records them (bounces only count for kInterreflected, samples
// not for kUnshadowed): what the key hashes and what a file must hold.
PrtSettings effective(const PrtSettings& s) {
  PrtSettings e = s;
  if (e.kind != PrtKind::kInterreflected) e.bounces = 0;
  if (e.kind == PrtKind::kUnshadowed) e.samples = 0;
  e.threads = 0;
  if (e.kind != PrtKind::kInterreflected || e.bounces == 0) e.sun_directions.clear();
  for (glm::vec3& d : e.sun_directions) d = glm::normalize(d);
  if (e.kind == PrtKind::kUnshadowed) e.glow_cells.clear();
  for (scene::GlowCell& c : e.glow_cells) c.direction = glm::normalize(c.direction);
  return e;
}

}  // namespace

std::string prt_key(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                    const PrtSettings& settings) {
  const PrtSettings s = effective(settings);
  io::Fnv1a h;
  h.text(kPrtVersion);
  h.value(int32_t(s.bands));
  h.value(uint32_t(s.kind));
  h.value(s.bounces);
  h.value(s.samples);
  h.value(uint64_t(s.sun_directions.size()));
  for (const glm::vec3& d : s.sun_directions) h.vec(d);
  h.value(uint64_t(s.glow_cells.size()));
  for (const scene::GlowCell& c : s.glow_cells) {
    h.vec(c.direction);
    h.vec(c.irradiance);
  }
  for (const scene::Mesh& m : assets.meshes) {
    h.text(m.name);
    h.value(uint64_t(m.vertices.size()));
    for (const scene::Vertex& v : m.vertices) {
      h.vec(v.position);
      h.vec(v.normal);
      h.bytes(&v.uv.x, 2 * sizeof(float));
    }
    h.value(uint64_t(m.triangles.size()));
    h.bytes(m.triangles.data(), m.triangles.size() * sizeof(glm::uvec3));
    h.bytes(m.materials.data(), m.materials.size() * sizeof(uint32_t));
  }
  h.value(uint64_t(assets.materials.size()));
  for (const scene::Material& m : assets.materials) {
    h.vec(m.albedo);
    h.value(m.texture);
    h.value(uint8_t(m.alpha_mode));
    h.value(m.alpha_cutoff);
    h.value(m.opacity);
  }
  h.value(uint64_t(assets.textures.size()));
  for (const scene::Texture& t : assets.textures) {
    h.value(t.width);
    h.value(t.height);
    h.value(uint8_t(t.srgb));
    h.value(uint8_t(t.wrap_u));
    h.value(uint8_t(t.wrap_v));
    h.bytes(t.rgba.data(), t.rgba.size());
  }
  h.value(uint64_t(frame.instances.size()));
  for (const scene::MeshInstance& i : frame.instances) {
    h.value(i.mesh);
    h.mat(i.model);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.get()));
  return hex;
}

std::filesystem::path default_prt_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "rolypoly" / "prt";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "rolypoly" / "prt";
  return std::filesystem::path(".rolypoly-cache") / "prt";
}

std::filesystem::path prt_cache_file(const std::filesystem::path& dir, const std::string& key) {
  return dir / ("prt-" + key + ".bin");
}

void write_prt_file(const std::filesystem::path& path, const std::string& key,
                    const PrtTransfer& t) {
  std::string out;
  out.reserve(64 + t.positions.size() * 24 + (t.coefficients.size() + t.shadowed.size()) * 4);
  put_bytes(out, kMagic, sizeof kMagic);
  const std::string version = kPrtVersion;
  put_u32(out, uint32_t(version.size()));
  out += version;
  out += key;
  for (uint32_t v : {uint32_t(t.bands), uint32_t(t.kind), t.bounces, t.samples, t.channels,
                     t.vertex_count(), uint32_t(t.instances.size()),
                     uint32_t(t.sun_directions.size()), uint32_t(t.glow_cells.size())})
    put_u32(out, v);
  for (const PrtInstanceRange& r : t.instances) {
    put_u32(out, r.first);
    put_u32(out, r.count);
  }
  put_bytes(out, t.positions.data(), t.positions.size() * sizeof(glm::vec3));
  put_bytes(out, t.normals.data(), t.normals.size() * sizeof(glm::vec3));
  put_bytes(out, t.coefficients.data(), t.coefficients.size() * sizeof(float));
  put_bytes(out, t.shadowed.data(), t.shadowed.size() * sizeof(float));
  put_bytes(out, t.sun_directions.data(), t.sun_directions.size() * sizeof(glm::vec3));
  put_bytes(out, t.sun_bounce.data(), t.sun_bounce.size() * sizeof(float));
  put_bytes(out, t.glow_cells.data(), t.glow_cells.size() * sizeof(scene::GlowCell));
  put_bytes(out, t.glow.data(), t.glow.size() * sizeof(float));
  const uint64_t sum = checksum(out.data(), out.size());
  put_bytes(out, &sum, sizeof sum);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  io::write_file(path, out);
}

std::optional<PrtTransfer> read_prt_file(const std::filesystem::path& path,
                                         const std::string& key, const PrtSettings& settings) {
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) return std::nullopt;
  }
  // The checksum first: it covers everything, so the fields below are as written.
  if (bytes.size() < sizeof(uint64_t)) return std::nullopt;
  const size_t body = bytes.size() - sizeof(uint64_t);
  uint64_t stored = 0;
  std::memcpy(&stored, bytes.data() + body, sizeof stored);
  if (stored != checksum(bytes.data(), body)) return std::nullopt;

  Reader r(bytes);
  char magic[8];
  uint32_t version_size = 0;
  if (!r.get(magic, 8) || std::memcmp(magic, kMagic, 8) != 0 || !r.u32(version_size) ||
      version_size > 256)
    return std::nullopt;
  std::string version(version_size, '\0'), file_key(16, '\0');
  if (!r.get(version.data(), version_size) || version != kPrtVersion ||
      !r.get(file_key.data(), 16) || file_key != key)
    return std::nullopt;
  uint32_t f[9];
  for (uint32_t& v : f)
    if (!r.u32(v)) return std::nullopt;
  const PrtSettings want = effective(settings);
  PrtTransfer t;
  t.bands = int(f[0]);
  t.kind = PrtKind(f[1]);
  t.bounces = f[2];
  t.samples = f[3];
  t.channels = f[4];
  const uint32_t nv = f[5], ni = f[6], suns = f[7], cells = f[8];
  if (t.bands != want.bands || t.kind != want.kind || t.bounces != want.bounces ||
      t.samples != want.samples || t.channels != (t.kind == PrtKind::kInterreflected ? 3u : 1u) ||
      suns != want.sun_directions.size() || cells != want.glow_cells.size())
    return std::nullopt;
  // The exact size the counts call for (64-bit arithmetic: no overflow for u32 counts).
  const uint64_t coefficients = uint64_t(nv) * t.channels * uint64_t(t.count());
  const uint64_t shadowed =
      t.kind == PrtKind::kInterreflected && t.bounces > 0 ? uint64_t(nv) * uint64_t(t.count())
                                                          : 0;
  const uint64_t payload = uint64_t(ni) * 8 + uint64_t(nv) * 24 + (coefficients + shadowed) * 4 +
                           uint64_t(suns) * 12 + uint64_t(nv) * suns * 12 +
                           uint64_t(cells) * sizeof(scene::GlowCell) +
                           (cells > 0 ? uint64_t(nv) * 12 : 0);
  if (payload != uint64_t(body - r.pos())) return std::nullopt;
  t.instances.resize(ni);
  uint64_t covered = 0;
  for (PrtInstanceRange& range : t.instances) {
    if (!r.u32(range.first) || !r.u32(range.count)) return std::nullopt;
    if (range.first != covered || uint64_t(range.first) + range.count > nv) return std::nullopt;
    covered += range.count;
  }
  if (covered != nv) return std::nullopt;
  t.positions.resize(nv);
  t.normals.resize(nv);
  t.coefficients.resize(size_t(coefficients));
  t.shadowed.resize(size_t(shadowed));
  t.sun_directions.resize(suns);
  t.sun_bounce.resize(size_t(nv) * suns * 3);
  t.glow_cells.resize(cells);
  t.glow.resize(cells > 0 ? size_t(nv) * 3 : 0);
  if (!r.get(t.positions.data(), size_t(nv) * sizeof(glm::vec3)) ||
      !r.get(t.normals.data(), size_t(nv) * sizeof(glm::vec3)) ||
      !r.get(t.coefficients.data(), t.coefficients.size() * sizeof(float)) ||
      !r.get(t.shadowed.data(), t.shadowed.size() * sizeof(float)) ||
      !r.get(t.sun_directions.data(), size_t(suns) * sizeof(glm::vec3)) ||
      !r.get(t.sun_bounce.data(), t.sun_bounce.size() * sizeof(float)) ||
      !r.get(t.glow_cells.data(), size_t(cells) * sizeof(scene::GlowCell)) ||
      !r.get(t.glow.data(), t.glow.size() * sizeof(float)))
    return std::nullopt;
  if (t.sun_directions != want.sun_directions || t.glow_cells != want.glow_cells)
    return std::nullopt;
  return t;
}

CachedPrt cached_prt_transfer(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                              const PrtSettings& settings, const std::filesystem::path& dir,
                              const PrtProgressFn& progress, const std::atomic<bool>* cancel) {
  const std::string key = prt_key(assets, frame, settings);
  CachedPrt out;
  out.file = prt_cache_file(dir, key);
  if (std::optional<PrtTransfer> t = read_prt_file(out.file, key, settings)) {
    out.transfer = std::move(*t);
    out.from_cache = true;
    if (progress) progress(1.0);
    return out;
  }
  out.transfer = compute_prt_transfer(assets, frame, settings, progress, cancel);
  try {
    write_prt_file(out.file, key, out.transfer);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rolypoly: warning: could not store the PRT transfer in the cache: %s\n",
                 e.what());
  }
  return out;
}

}  // namespace rp::truth
