// Files the loader must refuse before reading their content: missing files, directories,
// FIFOs and devices, what is not glTF 2.0 JSON, damaged GLB containers, and buffers whose
// claimed sizes the real data does not back (refused without allocating for the claim).
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iterator>

#include "gltf/gltf_writer.h"
#include "scene/gltf_loader.h"

namespace rp::test {
namespace {

std::string error_of(const std::string& path) {
  try {
    scene::load_gltf(path);
  } catch (const scene::SceneFileError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without an error";
  return {};
}

// The error starts with the file's name and contains every fragment.
void expect_error(const std::string& path, const std::vector<std::string>& fragments) {
  const std::string message = error_of(path);
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  for (const std::string& f : fragments)
    EXPECT_NE(message.find(f), std::string::npos) << "'" << f << "' is not in: " << message;
}

// A valid scene: a quad with normals (accessors 0 POSITION, 1 TEXCOORD_0, 2 indices, 3 NORMAL;
// bufferView i holds accessor i), mesh 0, node 0.
GltfBuilder valid() {
  GltfBuilder b;
  const GltfBuilder::Quad q = b.quad();
  const int nrm = b.vec3s(std::vector<glm::vec3>(4, {0, 0, 1}));
  b.mesh({{{"attributes", {{"POSITION", q.position}, {"NORMAL", nrm}}}, {"indices", q.indices}}});
  b.scene({b.node({{"mesh", 0}})});
  return b;
}

TEST(GltfBadFiles, RefusesAMissingFileADirectoryAFifoAndADevice) {
  TempFolder dir;
  expect_error(dir.file("absent.gltf"), {"No such file or directory"});
  expect_error(dir.path(), {"is a directory"});
  const std::string fifo = dir.file("pipe.gltf");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  expect_error(fifo, {"not a regular file"});  // never opened: opening would block
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  expect_error("/dev/zero", {"not a regular file"});
}

TEST(GltfBadFiles, RefusesWhatIsNotGltfTwoJson) {
  TempFolder dir;
  expect_error(dir.write("text.gltf", std::string("hello, world")), {"bad JSON"});
  expect_error(dir.write("empty.gltf", std::string()), {"bad JSON"});
  expect_error(dir.write("array.gltf", std::string("[1, 2]")), {"not an object"});
  expect_error(dir.write("noasset.gltf", std::string("{\"nodes\": []}")), {"asset"});
  GltfBuilder b = valid();
  b.doc["asset"]["version"] = "1.0";
  expect_error(b.write_gltf(dir, "v1"), {"version \"1.0\""});
  b.doc["asset"]["version"] = "2.0";
  b.doc["asset"]["minVersion"] = "2.1";
  expect_error(b.write_gltf(dir, "v21"), {"minVersion"});
}

TEST(GltfBadFiles, RefusesJsonNestedDeeperThanTheLimit) {
  TempFolder dir;
  GltfBuilder b = valid();
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string path = b.write_gltf(dir, "deep", [](Json& d) { d["extras"] = "DEEP"; });
  // Splice the nesting in as text: building it as a Json would recurse in the test itself.
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("\"DEEP\""), 6, deep);
  dir.write("deep.gltf", text);
  expect_error(path, {"nests deeper than 64"});
}

TEST(GltfBadFiles, RefusesIndicesThatAreNotNonNegativeIntegers) {
  TempFolder dir;
  GltfBuilder b = valid();
  b.doc["nodes"][0]["mesh"] = -1;
  expect_error(b.write_gltf(dir, "negative"), {"nodes[0].mesh", "non-negative integer"});
  b.doc["nodes"][0]["mesh"] = 4294967296.0;
  expect_error(b.write_gltf(dir, "float"), {"nodes[0].mesh"});
  b.doc["nodes"][0]["mesh"] = 4294967296u;  // would wrap to 0 as an int
  expect_error(b.write_gltf(dir, "huge"), {"nodes[0].mesh"});
}

TEST(GltfBadFiles, RefusesRequiredExtensionsItDoesNotImplement) {
  TempFolder dir;
  GltfBuilder b = valid();
  b.use_extension("KHR_draco_mesh_compression", true);
  b.use_extension("KHR_lights_punctual", true);
  const std::string message = error_of(b.write_gltf(dir, "draco"));
  EXPECT_NE(message.find("KHR_draco_mesh_compression"), std::string::npos) << message;
  EXPECT_EQ(message.find("KHR_lights_punctual"), std::string::npos) << message;
}

TEST(GltfBadFiles, RefusesDamagedGlbContainers) {
  TempFolder dir;
  const GltfBuilder b = valid();
  std::vector<uint8_t> glb = b.glb_bytes();
  auto put32 = [](std::vector<uint8_t>& v, size_t at, uint32_t x) {
    for (int k = 0; k < 4; ++k) v[at + static_cast<size_t>(k)] = static_cast<uint8_t>(x >> (8 * k));
  };
  expect_error(dir.write("short.glb", std::vector<uint8_t>(glb.begin(), glb.begin() + 16)),
               {"cut short"});
  std::vector<uint8_t> v1 = glb;
  put32(v1, 4, 1);
  expect_error(dir.write("v1.glb", v1), {"version 1"});
  std::vector<uint8_t> longer = glb;
  put32(longer, 8, static_cast<uint32_t>(glb.size() + 100));
  expect_error(dir.write("length.glb", longer), {"claims"});
  // The BIN chunk's header says more bytes than the file has.
  const uint32_t json_size = glb[12] | glb[13] << 8 | glb[14] << 16 | glb[15] << 24;
  std::vector<uint8_t> bin = glb;
  put32(bin, 20 + json_size, 1u << 30);
  expect_error(dir.write("bin.glb", bin), {"BIN chunk claims 1073741824 bytes"});
  // Cut inside the BIN chunk's header: tinygltf alone would read past the end.
  std::vector<uint8_t> cut(glb.begin(), glb.begin() + 20 + json_size + 4);
  put32(cut, 8, static_cast<uint32_t>(cut.size()));
  expect_error(dir.write("cut.glb", cut), {"cut-short chunk"});
}

TEST(GltfBadFiles, RefusesMissingShortAndUnreadableBuffers) {
  TempFolder dir;
  const GltfBuilder b = valid();
  const std::string missing =
      b.write_gltf(dir, "missing", [](Json& d) { d["buffers"][0]["uri"] = "gone.bin"; });
  expect_error(missing, {"buffer 0", "gone.bin", "No such file or directory"});
  const std::string longer = b.write_gltf(
      dir, "longer", [&](Json& d) { d["buffers"][0]["byteLength"] = b.bin.size() + 1; });
  expect_error(longer, {"buffer 0", "fewer than its byteLength"});
  ::mkdir(dir.file("a_folder.bin").c_str(), 0700);
  const std::string folder =
      b.write_gltf(dir, "folder", [](Json& d) { d["buffers"][0]["uri"] = "a_folder.bin"; });
  expect_error(folder, {"buffer 0", "is a directory"});
  const std::string no_uri =
      b.write_gltf(dir, "nouri", [](Json& d) { d["buffers"][0].erase("uri"); });
  expect_error(no_uri, {"buffer 0 has no uri"});
  const std::string bad_uri = b.write_embedded(dir, "baduri", [](Json& d) {
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAAA";
  });
  expect_error(bad_uri, {"buffer 0", "data URI holds 3 bytes"});
  const std::string html =
      b.write_embedded(dir, "html", [](Json& d) { d["buffers"][0]["uri"] = "data:text/html,<p>"; });
  expect_error(html, {"buffer 0", "unsupported data URI"});
  const std::string glb_claim =
      b.write_glb(dir, "claim", [&](Json& d) { d["buffers"][0]["byteLength"] = b.bin.size() + 8; });
  expect_error(glb_claim, {"buffer 0", "BIN chunk"});
}

TEST(GltfBadFiles, RefusesBufferViewsOutsideTheirBuffer) {
  TempFolder dir;
  const GltfBuilder b = valid();
  expect_error(
      b.write_gltf(dir, "past", [&](Json& d) { d["bufferViews"][3]["byteLength"] = b.bin.size(); }),
      {"bufferView 3", "run past the end of buffer 0"});
  expect_error(b.write_gltf(dir, "nobuffer", [](Json& d) { d["bufferViews"][1]["buffer"] = 3; }),
               {"bufferView 1", "buffer 3 does not exist"});
  expect_error(b.write_gltf(dir, "stride", [](Json& d) { d["bufferViews"][0]["byteStride"] = 6; }),
               {"bufferView 0", "byteStride 6"});
  // An image in a bufferView that does not exist (tinygltf would read through it unchecked).
  expect_error(b.write_gltf(dir, "image",
                            [](Json& d) {
                              d["images"] = {{{"bufferView", 40}, {"mimeType", "image/png"}}};
                            }),
               {"image 0", "bufferView 40"});
}

// A 2 GiB buffer claimed by a file of a few hundred bytes is refused at once, and without
// allocating for the claim: the load runs in a child process whose address space is too
// small for it.
TEST(GltfBadFiles, RefusesAHugeClaimedBufferQuicklyWithoutAllocatingIt) {
  TempFolder dir;
  const GltfBuilder b = valid();
  const uint64_t claim = (uint64_t{1} << 31) - 1;
  const std::vector<std::string> paths = {
      b.write_glb(dir, "claim", [&](Json& d) { d["buffers"][0]["byteLength"] = claim; }),
      b.write_gltf(dir, "claim", [&](Json& d) { d["buffers"][0]["byteLength"] = claim; }),
      b.write_gltf(dir, "accessor", [&](Json& d) { d["accessors"][0]["count"] = 1u << 30; })};
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const auto start = std::chrono::steady_clock::now();
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
#if !defined(__SANITIZE_ADDRESS__)  // ASan reserves terabytes of address space up front
      const rlimit limit{uint64_t{512} << 20, uint64_t{512} << 20};
      ::setrlimit(RLIMIT_AS, &limit);
#endif
      int code = 3;
      try {
        scene::load_gltf(path);
        code = 1;
      } catch (const scene::SceneFileError&) {
        code = 0;
      } catch (const std::bad_alloc&) {
        code = 2;
      }
      ::_exit(code);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "1: loaded, 2: out of memory";
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
    expect_error(path, {});
  }
}

}  // namespace
}  // namespace rp::test
