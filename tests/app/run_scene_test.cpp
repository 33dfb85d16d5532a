// `rolypoly run --scene FILE`: the simulation's options are refused for a scene file (exit 2,
// naming the option), a broken file fails before any window, and on a private Xvfb a tiny
// generated scene (a floor and a glowing panel, one .gltf with a data-URI buffer) is shown for
// a few frames; with --frames 0 its title names the file and the fly speed, the demo's keys do
// nothing but say so once, the fly keys move, and Esc ends it cleanly.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/image_metrics.h"
#include "xvfb_server.h"

namespace rp::test {
namespace {

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* const kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 |
                       (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0u) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0u);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kAlphabet[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

template <typename T>
void append(std::vector<uint8_t>& buffer, const std::vector<T>& values) {
  const size_t at = buffer.size();
  buffer.resize(at + values.size() * sizeof(T));
  std::memcpy(buffer.data() + at, values.data(), values.size() * sizeof(T));
}

// A 4 x 4 m white floor (y = 0, facing up) and a 1 x 1 m emissive panel standing behind its
// centre, facing +z (towards the default camera): one quad mesh placed twice.
std::string tiny_scene_gltf() {
  const std::vector<float> positions = {-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2};
  const std::vector<float> normals = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::vector<uint16_t> indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise from +y
  std::vector<uint8_t> bin;
  append(bin, positions);
  append(bin, normals);
  append(bin, indices);
  using Json = nlohmann::json;
  Json doc;
  doc["asset"] = {{"version", "2.0"}};
  doc["buffers"] = Json::array({{{"byteLength", bin.size()},
                                 {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
  doc["bufferViews"] = Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                                    {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                                    {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 12}}});
  doc["accessors"] = Json::array(
      {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
        {"min", {-2, 0, -2}}, {"max", {2, 0, 2}}},
       {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
       {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}});
  const Json primitive = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}};
  Json floor_primitive = primitive, panel_primitive = primitive;
  floor_primitive["material"] = 0;
  panel_primitive["material"] = 1;
  doc["materials"] = Json::array(
      {{{"name", "floor"},
        {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0}}}},
       {{"name", "panel"},
        {"emissiveFactor", {1, 1, 1}},
        {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}}}}});
  doc["meshes"] = Json::array({{{"primitives", Json::array({floor_primitive})}},
                               {{"primitives", Json::array({panel_primitive})}}});
  // The panel: the quad scaled to 1 x 1 m, turned +90 degrees about x (its +y normal to +z),
  // raised and set back.
  doc["nodes"] = Json::array({{{"mesh", 0}},
                              {{"mesh", 1},
                               {"scale", {0.25, 1, 0.25}},
                               {"rotation", {0.70710678, 0, 0, 0.70710678}},
                               {"translation", {0, 1, -1.5}}}});
  doc["scenes"] = Json::array({{{"nodes", {0, 1}}}});
  doc["scene"] = 0;
  return doc.dump();
}

struct TinyScene {
  TempDir dir;
  std::string file = (dir / "tiny.gltf").string();
  TinyScene() { write_plain(file, tiny_scene_gltf()); }
};

TEST(RunScene, SimulationOptionsAreRefusedForASceneFile) {
  TinyScene scene;
  for (const std::string option :
       {"--seed 3", "--marbles", "--fireball", "--replay x.log", "--record x.log"}) {
    SCOPED_TRACE(option);
    const CommandResult r = run_rolypoly("run --scene " + shell_quote(scene.file) + " " + option,
                                         "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    const std::string name = option.substr(0, option.find(' '));
    EXPECT_NE(r.err.find(name + " applies to the simulated demo, not to a scene file"),
              std::string::npos)
        << r.err;
  }
  // The demo still takes them (here it stops at the missing display, after parsing).
  const CommandResult demo =
      run_rolypoly("run --seed 3 --marbles --fireball", "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_NE(demo.exit_code, 2) << demo.err;
  EXPECT_EQ(demo.err.find("applies to the simulated demo"), std::string::npos) << demo.err;
}

TEST(RunScene, ABrokenSceneFileFailsBeforeTheWindow) {
  TempDir dir;
  const std::string file = (dir / "broken.gltf").string();
  write_plain(file, "{ not json");
  // No display: a scene error must come first (exit 2), not "cannot open a window".
  const CommandResult r =
      run_rolypoly("run --scene " + shell_quote(file), "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("broken.gltf"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("window"), std::string::npos) << r.err;
}

bool have_x_tools() { return have_program("Xvfb") && have_program("xdotool"); }

TEST(RunScene, ShowsAFewFramesOfTheFileAndExits) {
  if (!have_x_tools()) GTEST_SKIP() << "Xvfb or xdotool not installed (tools/setup.sh)";
  XvfbServer x;
  ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
  TinyScene scene;
  const std::string shot = (scene.dir / "window.png").string();
  const CommandResult r =
      run_rolypoly("run --scene " + shell_quote(scene.file) + " --frames 3 --size 48 --capture " +
                       shell_quote(shot),
                   "DISPLAY=" + x.display());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("3 frames"), std::string::npos) << r.out;
  // The panel glows: the window shows more than a black frame.
  const Rgba8Image image = load_png(shot);
  int bright = 0;
  for (size_t i = 0; i + 3 < image.rgba.size(); i += 4)
    bright += image.rgba[i] > 128 && image.rgba[i + 1] > 128 && image.rgba[i + 2] > 128;
  EXPECT_GT(bright, 0) << "no bright pixel: the emissive panel is not in view";
}

// The window's title, once it holds `part` (it refreshes twice a second); the last one read
// when that did not happen within 60 s.
std::string title_with(const std::string& display, unsigned long window, const std::string& part) {
  std::string title;
  for (const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
       std::chrono::steady_clock::now() < end;
       std::this_thread::sleep_for(std::chrono::milliseconds(200))) {
    title = output_of("DISPLAY=" + display + " xdotool getwindowname " + std::to_string(window) +
                      " 2>/dev/null");
    if (title.find(part) != std::string::npos) break;
  }
  return title;
}

// Focus, then real key events through XTEST (see shadow_key_test.cpp).
void keys(const std::string& display, unsigned long window, const std::string& what) {
  output_of("DISPLAY=" + display + " xdotool windowfocus --sync " + std::to_string(window) + " " +
            what + " 2>&1");
}

TEST(RunScene, TitleNamesTheFileAndTheDemoKeysOnlyNoteThemselves) {
  if (!have_x_tools()) GTEST_SKIP() << "Xvfb or xdotool not installed (tools/setup.sh)";
  XvfbServer x;
  ASSERT_FALSE(x.display().empty()) << "Xvfb did not start";
  TinyScene scene;
  const pid_t pid =
      spawn_shell("exec env DISPLAY=" + x.display() + " " + shell_quote(ROLYPOLY_BINARY) +
                  " run --frames 0 --size 48 --scene " + shell_quote(scene.file) + " >" +
                  shell_quote((scene.dir / "out.txt").string()) + " 2>" +
                  shell_quote((scene.dir / "err.txt").string()));
  const unsigned long window = wait_for_rolypoly_window(x.display());
  ASSERT_NE(window, 0ul) << read_text(scene.dir / "err.txt");
  const std::string title = title_with(x.display(), window, "m/s");
  EXPECT_EQ(title.rfind("rolypoly | tiny.gltf | ", 0), 0u) << title;
  EXPECT_NE(title.find(" speed "), std::string::npos) << title;
  // The demo's keys (F fireball, R reset, a left drag) and the fly keys: no crash, one note.
  keys(x.display(), window,
       "key f key r mousemove --window " + std::to_string(window) +
           " 10 10 mousedown 1 mouseup 1 key Home");
  keys(x.display(), window, "keydown w sleep 0.3 keyup w keydown e sleep 0.2 keyup e");
  keys(x.display(), window, "key Escape");
  EXPECT_EQ(wait_exit(pid, std::chrono::seconds(60)), 0) << read_text(scene.dir / "err.txt");
  const std::string err = read_text(scene.dir / "err.txt");
  const std::string note = "acts on the simulated demo; a scene file has no simulation";
  const size_t first = err.find(note);
  EXPECT_NE(first, std::string::npos) << err;
  EXPECT_EQ(err.find(note, first + 1), std::string::npos) << "the note comes once:\n" << err;
  EXPECT_NE(read_text(scene.dir / "out.txt").find("window closed after"), std::string::npos);
}

}  // namespace
}  // namespace rp::test
