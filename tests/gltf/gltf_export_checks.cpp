#include "gltf/gltf_export_checks.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>

namespace rp::test::gltf_export_checks {
namespace {

using Json = nlohmann::json;

constexpr double kUnitTolerance = 5e-4;  // how far from 1 a "unit" normal or tangent may be

uint32_t u32_at(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<uint8_t>(s[at + static_cast<size_t>(k)]);
  return v;
}

int component_size(int type) {
  switch (type) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

int component_count(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  if (type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

std::string decode_base64(const std::string& text, bool* ok) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  *ok = text.size() % 4 == 0;
  for (size_t i = 0; *ok && i < text.size(); i += 4) {
    uint32_t group = 0;
    int pad = 0;
    for (size_t k = 0; k < 4; ++k) {
      const char c = text[i + k];
      const int v = c == '=' ? (++pad, 0) : value(c);
      if (v < 0 || (c != '=' && pad > 0)) *ok = false;
      group = (group << 6) | static_cast<uint32_t>(v < 0 ? 0 : v);
    }
    for (int k = 0; k < 3 - pad; ++k)
      out.push_back(static_cast<char>((group >> (16 - 8 * k)) & 0xFFu));
  }
  return out;
}

class Checker {
 public:
  explicit Checker(ExportedFile& f) : f_(f), doc_(f.doc) {}

  void document();

 private:
  void problem(const std::string& what) { f_.problems.push_back(what); }
  size_t count(const char* array) const {
    return doc_.contains(array) && doc_[array].is_array() ? doc_[array].size() : 0;
  }
  // `v` is an index into the top-level array `array`.
  bool index(const Json& v, const char* array, const std::string& where) {
    if (v.is_number_unsigned() && v.get<size_t>() < count(array)) return true;
    problem(where + ": " + v.dump() + " is no index into " + array);
    return false;
  }
  bool numbers(const Json& v, size_t n, double lo, double hi, const std::string& where) {
    bool ok = v.is_array() && v.size() == n;
    for (size_t i = 0; ok && i < n; ++i)
      ok = v[i].is_number() && v[i].get<double>() >= lo && v[i].get<double>() <= hi;
    if (!ok)
      problem(where + ": " + v.dump().substr(0, 80) + " is not " + std::to_string(n) +
              " numbers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return ok;
  }
  void note_extensions(const Json& object) {
    if (object.contains("extensions"))
      for (const auto& [name, value] : object["extensions"].items()) used_.insert(name);
  }

  void buffers_and_views();
  void accessors();
  void primitive(const Json& p, const std::string& where);
  void nodes_and_scenes();
  void materials_and_textures();
  void cameras_and_lights();
  void extensions();

  ExportedFile& f_;
  const Json& doc_;
  std::set<std::string> used_;
};

void Checker::document() {
  if (!doc_.contains("asset") || doc_["asset"].value("version", "") != "2.0")
    problem("asset.version is not \"2.0\"");
  for (const auto& [key, value] : doc_.items())
    if (value.is_array() && value.empty())
      problem(key + " is an empty array (glTF wants at least one item or none)");
  buffers_and_views();
  accessors();
  for (size_t m = 0; m < count("meshes"); ++m) {
    const Json& mesh = doc_["meshes"][m];
    if (!mesh.contains("primitives") || mesh["primitives"].empty())
      problem("mesh " + std::to_string(m) + " has no primitives");
    for (size_t p = 0; p < mesh.value("primitives", Json::array()).size(); ++p)
      primitive(mesh["primitives"][p],
                "mesh " + std::to_string(m) + " primitive " + std::to_string(p));
  }
  nodes_and_scenes();
  materials_and_textures();
  cameras_and_lights();
  extensions();
}

void Checker::buffers_and_views() {
  if (count("buffers") != 1) problem("there is not exactly one buffer");
  if (count("buffers") >= 1) {
    const Json& b = doc_["buffers"][0];
    if (!b.contains("byteLength") || !b["byteLength"].is_number_unsigned() ||
        b["byteLength"].get<size_t>() < 1)
      problem("buffer 0 has no byteLength >= 1");
    else if (b["byteLength"].get<size_t>() != f_.bin.size())
      problem("buffer 0's byteLength " + b["byteLength"].dump() + " is not its " +
              std::to_string(f_.bin.size()) + " bytes");
  }
  for (size_t i = 0; i < count("bufferViews"); ++i) {
    const Json& v = doc_["bufferViews"][i];
    const std::string at = "bufferView " + std::to_string(i);
    index(v.value("buffer", Json()), "buffers", at + " buffer");
    const size_t offset = v.value("byteOffset", size_t{0}),
                 length = v.value("byteLength", size_t{0});
    if (length < 1) problem(at + " has no byteLength >= 1");
    if (offset % 4 != 0) problem(at + " starts at " + std::to_string(offset) + ", not 4-aligned");
    if (offset + length > f_.bin.size()) problem(at + " ends past buffer 0");
    if (v.contains("byteStride")) problem(at + " has a byteStride (the exporter packs tightly)");
    if (v.contains("target") && v["target"] != 34962 && v["target"] != 34963)
      problem(at + " has target " + v["target"].dump());
  }
}

void Checker::accessors() {
  for (size_t i = 0; i < count("accessors"); ++i) {
    const Json& a = doc_["accessors"][i];
    const std::string at = "accessor " + std::to_string(i);
    const int size = component_size(a.value("componentType", 0));
    const int n = component_count(a.value("type", ""));
    const size_t elements = a.value("count", size_t{0});
    if (size == 0 || n == 0) problem(at + " has no valid componentType and type");
    if (elements < 1) problem(at + " has no count >= 1");
    if (!index(a.value("bufferView", Json()), "bufferViews", at + " bufferView") || size == 0)
      continue;
    const Json& view = doc_["bufferViews"][a["bufferView"].get<size_t>()];
    const size_t offset = a.value("byteOffset", size_t{0});
    const size_t s = static_cast<size_t>(size);
    if (offset % s != 0 || (view.value("byteOffset", size_t{0}) + offset) % s != 0)
      problem(at + " is not aligned to its component size");
    if (offset + elements * s * static_cast<size_t>(n) > view.value("byteLength", size_t{0}))
      problem(at + " reaches past its buffer view");
  }
}

void Checker::primitive(const Json& p, const std::string& where) {
  if (p.value("mode", 4) != 4) problem(where + " is not TRIANGLES");
  if (p.contains("material")) index(p["material"], "materials", where + " material");
  const Json attributes = p.value("attributes", Json::object());
  if (!attributes.contains("POSITION")) {
    problem(where + " has no POSITION");
    return;
  }
  if (!index(attributes["POSITION"], "accessors", where + " POSITION")) return;
  const size_t vertices =
      doc_["accessors"][attributes["POSITION"].get<size_t>()].value("count", size_t{0});
  for (const auto& [name, value] : attributes.items()) {
    if (!index(value, "accessors", where + " " + name)) return;
    const Json& a = doc_["accessors"][value.get<size_t>()];
    const std::string want = name == "TEXCOORD_0" ? "VEC2" : name == "TANGENT" ? "VEC4" : "VEC3";
    if (a.value("type", "") != want || a.value("componentType", 0) != 5126)
      problem(where + " " + name + " is not a float " + want);
    const Json& view = doc_["bufferViews"][a.value("bufferView", size_t{0})];
    if (view.value("target", 34962) != 34962)
      problem(where + " " + name + "'s view is no ARRAY_BUFFER");
    if (a.value("count", size_t{0}) != vertices) problem(where + " " + name + " count differs");
  }
  const Json& pos = doc_["accessors"][attributes["POSITION"].get<size_t>()];
  if (!pos.contains("min") || !pos.contains("max")) {
    problem(where + " POSITION has no min and max (required)");
  } else {
    const std::vector<float> v = floats(f_, attributes["POSITION"].get<int>());
    for (size_t c = 0; c < 3; ++c) {
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;
      for (size_t i = c; i < v.size(); i += 3) {
        lo = std::min(lo, v[i]);
        hi = std::max(hi, v[i]);
      }
      if (pos["min"].size() != 3 || pos["max"].size() != 3 ||
          pos["min"][c].get<double>() != static_cast<double>(lo) ||
          pos["max"][c].get<double>() != static_cast<double>(hi))
        problem(where + " POSITION min/max are not the data's");
    }
  }
  for (const char* name : {"NORMAL", "TANGENT"}) {
    if (!attributes.contains(name)) continue;
    const size_t n = std::string(name) == "NORMAL" ? 3 : 4;
    const std::vector<float> v = floats(f_, attributes[name].get<int>());
    for (size_t i = 0; i + n <= v.size(); i += n) {
      const double len = std::sqrt(double(v[i]) * v[i] + double(v[i + 1]) * v[i + 1] +
                                   double(v[i + 2]) * v[i + 2]);
      if (std::abs(len - 1.0) > kUnitTolerance || (n == 4 && std::abs(v[i + 3]) != 1.0f)) {
        problem(where + " " + name + " " + std::to_string(i / n) + " is not unit (w = +-1)");
        break;
      }
    }
  }
  if (!p.contains("indices") || !index(p["indices"], "accessors", where + " indices")) return;
  const Json& a = doc_["accessors"][p["indices"].get<size_t>()];
  const int type = a.value("componentType", 0);
  if (a.value("type", "") != "SCALAR" || (type != 5121 && type != 5123 && type != 5125))
    problem(where + " indices are not unsigned SCALARs");
  const Json& view = doc_["bufferViews"][a.value("bufferView", size_t{0})];
  if (view.value("target", 34963) != 34963)
    problem(where + " indices' view is no ELEMENT_ARRAY_BUFFER");
  const std::vector<uint32_t> idx = indices(f_, p["indices"].get<int>());
  if (idx.size() % 3 != 0) problem(where + " index count is not a multiple of 3");
  const uint32_t restart = type == 5121 ? 0xFFu : type == 5123 ? 0xFFFFu : 0xFFFFFFFFu;
  for (const uint32_t i : idx) {
    if (i >= vertices || i == restart) {
      problem(where + " index " + std::to_string(i) + " is out of range or primitive restart");
      break;
    }
  }
}

void Checker::nodes_and_scenes() {
  for (size_t i = 0; i < count("nodes"); ++i) {
    const Json& n = doc_["nodes"][i];
    const std::string at = "node " + std::to_string(i);
    note_extensions(n);
    if (n.contains("mesh")) index(n["mesh"], "meshes", at + " mesh");
    if (n.contains("camera")) index(n["camera"], "cameras", at + " camera");
    if (n.contains("children")) problem(at + " has children (the exporter writes a flat list)");
    if (n.contains("matrix")) {
      const Json& m = n["matrix"];
      if (numbers(m, 16, -1e30, 1e30, at + " matrix") &&
          (m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0))
        problem(at + " matrix's last row is not 0 0 0 1");
      if (n.contains("translation") || n.contains("rotation") || n.contains("scale"))
        problem(at + " has both a matrix and TRS");
    }
    if (n.contains("translation")) numbers(n["translation"], 3, -1e30, 1e30, at + " translation");
    if (n.contains("rotation") && numbers(n["rotation"], 4, -1.0, 1.0, at + " rotation")) {
      double len = 0.0;
      for (const Json& q : n["rotation"]) len += q.get<double>() * q.get<double>();
      if (std::abs(std::sqrt(len) - 1.0) > 1e-6) problem(at + " rotation is not unit");
    }
    if (n.contains("extensions") && n["extensions"].contains("KHR_lights_punctual")) {
      const Json& l = n["extensions"]["KHR_lights_punctual"].value("light", Json());
      const size_t lights =
          doc_.contains("extensions") && doc_["extensions"].contains("KHR_lights_punctual")
              ? doc_["extensions"]["KHR_lights_punctual"]["lights"].size()
              : 0;
      if (!l.is_number_unsigned() || l.get<size_t>() >= lights) problem(at + " light is no index");
    }
  }
  if (!doc_.contains("scene") || !index(doc_["scene"], "scenes", "scene")) return;
  std::set<size_t> roots;
  for (const Json& r : doc_["scenes"][doc_["scene"].get<size_t>()].value("nodes", Json::array()))
    if (index(r, "nodes", "scene nodes") && !roots.insert(r.get<size_t>()).second)
      problem("scene lists node " + r.dump() + " twice");
}

void Checker::materials_and_textures() {
  for (size_t i = 0; i < count("materials"); ++i) {
    const Json& m = doc_["materials"][i];
    const std::string at = "material " + std::to_string(i);
    note_extensions(m);
    const Json pbr = m.value("pbrMetallicRoughness", Json::object());
    if (pbr.contains("baseColorFactor"))
      numbers(pbr["baseColorFactor"], 4, 0.0, 1.0, at + " baseColorFactor");
    for (const char* k : {"metallicFactor", "roughnessFactor"})
      if (pbr.contains(k)) numbers(Json::array({pbr[k]}), 1, 0.0, 1.0, at + " " + k);
    if (m.contains("emissiveFactor"))
      numbers(m["emissiveFactor"], 3, 0.0, 1.0, at + " emissiveFactor");
    for (const char* k : {"baseColorTexture", "metallicRoughnessTexture"})
      if (pbr.contains(k)) index(pbr[k].value("index", Json()), "textures", at + " " + k);
    for (const char* k : {"normalTexture", "emissiveTexture", "occlusionTexture"})
      if (m.contains(k)) index(m[k].value("index", Json()), "textures", at + " " + k);
    const std::string mode = m.value("alphaMode", "OPAQUE");
    if (mode != "OPAQUE" && mode != "MASK" && mode != "BLEND") problem(at + " alphaMode " + mode);
    if (m.contains("alphaCutoff") && mode != "MASK") problem(at + " has alphaCutoff without MASK");
    const Json ext = m.value("extensions", Json::object());
    if (ext.contains("KHR_materials_ior")) {
      const double ior = ext["KHR_materials_ior"].value("ior", 1.5);
      if (!(ior == 0.0 || ior >= 1.0)) problem(at + " ior " + std::to_string(ior));
    }
    if (ext.contains("KHR_materials_emissive_strength") &&
        !(ext["KHR_materials_emissive_strength"].value("emissiveStrength", 1.0) >= 0.0))
      problem(at + " emissiveStrength < 0");
  }
  for (size_t i = 0; i < count("textures"); ++i) {
    const Json& t = doc_["textures"][i];
    const std::string at = "texture " + std::to_string(i);
    index(t.value("source", Json()), "images", at + " source");
    if (t.contains("sampler")) index(t["sampler"], "samplers", at + " sampler");
  }
  for (size_t i = 0; i < count("images"); ++i) {
    const Json& im = doc_["images"][i];
    const std::string at = "image " + std::to_string(i);
    if (im.value("mimeType", "") != "image/png") problem(at + " is not image/png");
    if (!index(im.value("bufferView", Json()), "bufferViews", at + " bufferView")) continue;
    const Json& view = doc_["bufferViews"][im["bufferView"].get<size_t>()];
    if (view.contains("target")) problem(at + "'s view has a target");
    if (view_bytes(f_, im["bufferView"].get<int>()).rfind("\x89PNG\r\n\x1a\n", 0) != 0)
      problem(at + " does not start with the PNG signature");
  }
  for (size_t i = 0; i < count("samplers"); ++i)
    for (const char* k : {"wrapS", "wrapT"}) {
      const int w = doc_["samplers"][i].value(k, 10497);
      if (w != 10497 && w != 33071 && w != 33648)
        problem("sampler " + std::to_string(i) + " " + k + " " + std::to_string(w));
    }
}

void Checker::cameras_and_lights() {
  for (size_t i = 0; i < count("cameras"); ++i) {
    const Json& c = doc_["cameras"][i];
    const Json p = c.value("perspective", Json::object());
    if (c.value("type", "") != "perspective" || !(p.value("yfov", 0.0) > 0.0) ||
        !(p.value("znear", 0.0) > 0.0) || (p.contains("zfar") && !(p["zfar"] > p["znear"])))
      problem("camera " + std::to_string(i) + " is no valid perspective camera");
  }
  note_extensions(doc_);
  if (!doc_.contains("extensions") || !doc_["extensions"].contains("KHR_lights_punctual")) return;
  const Json lights = doc_["extensions"]["KHR_lights_punctual"].value("lights", Json::array());
  if (lights.empty()) problem("KHR_lights_punctual has no lights");
  for (size_t i = 0; i < lights.size(); ++i) {
    const Json& l = lights[i];
    const std::string at = "light " + std::to_string(i), type = l.value("type", "");
    if (type != "directional" && type != "point" && type != "spot") problem(at + " type " + type);
    if (l.contains("color")) numbers(l["color"], 3, 0.0, 1.0, at + " color");
    if (!(l.value("intensity", 1.0) >= 0.0)) problem(at + " intensity < 0");
    if (l.contains("range") && !(l["range"].get<double>() > 0.0)) problem(at + " range <= 0");
    if (type == "spot") {
      const Json s = l.value("spot", Json::object());
      const double inner = s.value("innerConeAngle", 0.0),
                   outer = s.value("outerConeAngle", 0.7853981633974483);
      if (!(inner >= 0.0 && inner < outer && outer <= 1.5707963267948966))
        problem(at + " spot angles break 0 <= inner < outer <= pi/2");
    }
  }
}

void Checker::extensions() {
  if (doc_.contains("extensionsRequired")) problem("extensionsRequired is present");
  const std::vector<std::string> listed = doc_.value("extensionsUsed", std::vector<std::string>{});
  const std::set<std::string> declared(listed.begin(), listed.end());
  if (declared.size() != listed.size()) problem("extensionsUsed lists an extension twice");
  for (const std::string& e : used_)
    if (!declared.count(e)) problem(e + " is used but not in extensionsUsed");
  for (const std::string& e : declared)
    if (!used_.count(e)) problem(e + " is in extensionsUsed but not used");
}

void read_glb(const std::string& bytes, ExportedFile& f) {
  if (bytes.size() < 20 || u32_at(bytes, 4) != 2 || u32_at(bytes, 8) != bytes.size()) {
    f.problems.push_back("GLB header: version not 2 or length not the file's size");
    return;
  }
  size_t at = 12;
  int chunk = 0;
  std::string json_text, bin_chunk;
  while (at + 8 <= bytes.size()) {
    const uint32_t length = u32_at(bytes, at), type = u32_at(bytes, at + 4);
    if (length % 4 != 0 || at + 8 + length > bytes.size()) {
      f.problems.push_back("GLB chunk " + std::to_string(chunk) +
                           " length is not 4-aligned or too long");
      return;
    }
    const std::string data = bytes.substr(at + 8, length);
    if (chunk == 0 && type == 0x4E4F534Au)
      json_text = data;
    else if (chunk == 1 && type == 0x004E4942u)
      bin_chunk = data;
    else
      f.problems.push_back("GLB chunk " + std::to_string(chunk) + " has an unexpected type");
    at += 8 + length;
    ++chunk;
  }
  if (at != bytes.size()) f.problems.push_back("GLB has trailing bytes");
  const size_t end = json_text.find_last_of('}');
  if (end == std::string::npos || json_text.size() - end - 1 > 3 ||
      json_text.find_first_not_of(' ', end + 1) != std::string::npos)
    f.problems.push_back("GLB JSON chunk is not padded with up to 3 spaces");
  f.doc = Json::parse(json_text);
  const size_t length =
      f.doc.contains("buffers") ? f.doc["buffers"][0].value("byteLength", size_t{0}) : 0;
  if (f.doc.contains("buffers") && f.doc["buffers"][0].contains("uri"))
    f.problems.push_back("GLB buffer 0 has a uri");
  if (length > bin_chunk.size() || bin_chunk.size() - length > 3)
    f.problems.push_back("GLB BIN chunk does not hold buffer 0 (up to 3 bytes of padding)");
  if (bin_chunk.find_first_not_of('\0', std::min(length, bin_chunk.size())) != std::string::npos)
    f.problems.push_back("GLB BIN chunk is not padded with zeros");
  f.bin = bin_chunk.substr(0, std::min(length, bin_chunk.size()));
}

void read_gltf_text(const std::string& bytes, ExportedFile& f) {
  f.doc = Json::parse(bytes);
  if (!f.doc.contains("buffers")) return;
  const std::string uri = f.doc["buffers"][0].value("uri", "");
  const std::string prefix = "data:application/octet-stream;base64,";
  if (uri.rfind(prefix, 0) != 0) {
    f.problems.push_back("buffer 0's uri is not an octet-stream base64 data URI");
    return;
  }
  bool ok = false;
  f.bin = decode_base64(uri.substr(prefix.size()), &ok);
  if (!ok) f.problems.push_back("buffer 0's data URI is not valid base64");
}

const Json& accessor_view(const ExportedFile& f, int index, const Json** view) {
  const Json& a = f.doc.at("accessors").at(static_cast<size_t>(index));
  *view = &f.doc.at("bufferViews").at(a.at("bufferView").get<size_t>());
  return a;
}

}  // namespace

ExportedFile read_exported(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + file.string());
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ExportedFile f;
  if (bytes.rfind("glTF", 0) == 0)
    read_glb(bytes, f);
  else
    read_gltf_text(bytes, f);
  if (!f.doc.is_object()) {
    f.problems.push_back("no JSON document");
    return f;
  }
  try {
    Checker(f).document();
  } catch (const std::exception& e) {
    // A read the earlier checks already reported (an accessor past its buffer, ...).
    f.problems.push_back(std::string("checking stopped: ") + e.what());
  }
  return f;
}

std::string describe(const std::vector<std::string>& problems) {
  std::string out;
  for (const std::string& p : problems) out += p + "\n";
  return out;
}

std::string view_bytes(const ExportedFile& f, int index) {
  const Json& v = f.doc.at("bufferViews").at(static_cast<size_t>(index));
  const size_t offset = v.value("byteOffset", size_t{0}), length = v.at("byteLength").get<size_t>();
  if (offset + length > f.bin.size()) throw std::runtime_error("buffer view past the buffer");
  return f.bin.substr(offset, length);
}

std::vector<float> floats(const ExportedFile& f, int index) {
  const Json* view = nullptr;
  const Json& a = accessor_view(f, index, &view);
  if (a.at("componentType") != 5126) throw std::runtime_error("not a float accessor");
  const size_t n = a.at("count").get<size_t>() * static_cast<size_t>(component_count(a.at("type")));
  const size_t offset = view->value("byteOffset", size_t{0}) + a.value("byteOffset", size_t{0});
  if (offset + n * 4 > f.bin.size()) throw std::runtime_error("accessor past the buffer");
  std::vector<float> out(n);
  std::memcpy(out.data(), f.bin.data() + offset, n * 4);
  return out;
}

std::vector<uint32_t> indices(const ExportedFile& f, int index) {
  const Json* view = nullptr;
  const Json& a = accessor_view(f, index, &view);
  const int type = a.at("componentType").get<int>();
  const size_t size = static_cast<size_t>(component_size(type)), n = a.at("count").get<size_t>();
  const size_t offset = view->value("byteOffset", size_t{0}) + a.value("byteOffset", size_t{0});
  if (size == 0 || (size == 4 && type != 5125) || offset + n * size > f.bin.size())
    throw std::runtime_error("not an index accessor inside the buffer");
  std::vector<uint32_t> out(n);
  for (size_t i = 0; i < n; ++i) {
    uint32_t v = 0;
    for (size_t k = size; k-- > 0;)
      v = (v << 8) | static_cast<uint8_t>(f.bin[offset + i * size + k]);
    out[i] = v;
  }
  return out;
}

}  // namespace rp::test::gltf_export_checks
