// GBuffer resolve against a C++ reference. The visibility buffer is written by hand: a double-
// precision ray caster over a tiny known scene (a textured, rotated, scaled quad of two triangles
// and one sphere) fills ids and barycentrics for a 16x12 frame; the pass must reproduce the hit
// points, normals, textured albedo, emission, linear depth and velocity of a known motion
// (instance translated by a world offset, sphere moved, camera moved), and the normal of the
// side seen where the quad faces away.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "passes/gbuffer.h"
#include "passes/pass_names.h"
#include "render/gpu_scene.h"
#include "support/cl_fixture.h"

namespace {

// Default frame size: height not a multiple of 16 (the GPU layout's work-group side). The
// resolve test also runs at widths that leave partial pixel spans (kernels/common/span.h).
constexpr uint32_t kW = 16, kH = 12;
const glm::vec3 kOffset(0.03f, -0.02f, 0.01f);  // instance world motion this frame

double srgb_decode(int code) {
  double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// 4x4 texture with distinct texels (rows top to bottom).
rp::scene::Texture make_texture() {
  rp::scene::Texture t{"test", 4, 4, {}};
  for (int i = 0; i < 16; ++i) {
    t.rgba.push_back(uint8_t(17 * i + 5));
    t.rgba.push_back(uint8_t(250 - 13 * i));
    t.rgba.push_back(uint8_t((60 + 97 * i) % 256));
    t.rgba.push_back(255);
  }
  return t;
}

// Independent bilinear reference: wrap addressing, texel row = (1 - v) * height, decode first.
glm::dvec3 texture_ref(const rp::scene::Texture& t, glm::dvec2 uv) {
  double x = uv.x * t.width - 0.5, y = (1.0 - uv.y) * t.height - 0.5;
  double x0 = std::floor(x), y0 = std::floor(y);
  double fx = x - x0, fy = y - y0;
  auto texel = [&](double xi, double yi) {
    int tx = ((int(xi) % t.width) + t.width) % t.width;
    int ty = ((int(yi) % t.height) + t.height) % t.height;
    const uint8_t* p = &t.rgba[size_t(ty * t.width + tx) * 4];
    return glm::dvec3(srgb_decode(p[0]), srgb_decode(p[1]), srgb_decode(p[2]));
  };
  glm::dvec3 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx);
  glm::dvec3 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx);
  return glm::mix(top, bottom, fy);
}

struct Hit {
  bool sphere = false;
  uint32_t triangle = 0;
  double t = 0, b1 = 0, b2 = 0;
};

struct TestScene {
  uint32_t width = kW, height = kH;
  rp::scene::SceneAssets assets;
  rp::scene::FrameScene frame;
  glm::mat4 rotation;  // rotation part of the instance's model matrix

  // back: the quad faces away from the camera (winding and vertex normals reversed), as a
  // double-sided leaf seen from behind.
  explicit TestScene(uint32_t w = kW, uint32_t h = kH, bool back = false)
      : width(w), height(h) {
    assets.textures.push_back(make_texture());
    rp::scene::Material textured{"textured", {0.5f, 0.9f, 0.7f}, {0.1f, 0.2f, 0.3f}, 0};
    rp::scene::Material plain{"plain", {0.3f, 0.6f, 0.9f}, {0.0f, 0.0f, 0.0f}, -1};
    assets.materials = {textured, plain};
    rp::scene::Mesh quad;
    quad.name = "quad";
    // Unit quad in the object xy plane facing +z, uv from -0.5 to 1.5 so the texture tiles.
    quad.vertices = {{{-0.5f, -0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, {-0.5f, -0.5f}},
                     {{0.5f, -0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, {1.5f, -0.5f}},
                     {{0.5f, 0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, {1.5f, 1.5f}},
                     {{-0.5f, 0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}, {-0.5f, 1.5f}}};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    if (back) {
      quad.triangles = {{0, 2, 1}, {0, 3, 2}};
      for (auto& v : quad.vertices) v.normal = -v.normal;
    }
    quad.materials = {0, 1};
    assets.meshes.push_back(quad);

    frame.camera.position = {0.2f, 0.1f, 2.5f};
    frame.prev_camera = frame.camera;
    frame.prev_camera.position = {0.25f, 0.1f, 2.5f};
    rotation = glm::rotate(glm::mat4(1.0f), glm::radians(35.0f), glm::vec3(0, 1, 0)) *
               glm::rotate(glm::mat4(1.0f), glm::radians(-20.0f), glm::vec3(1, 0, 0));
    rp::scene::MeshInstance inst;
    inst.mesh = 0;
    // Non-uniform scale within the quad's plane: the normal is still the rotated +z.
    inst.model = glm::translate(glm::mat4(1.0f), glm::vec3(-0.2f, -0.1f, 0.2f)) * rotation *
                 glm::scale(glm::mat4(1.0f), glm::vec3(1.6f, 1.4f, 1.0f));
    inst.prev_model = glm::translate(glm::mat4(1.0f), -kOffset) * inst.model;
    frame.instances.push_back(inst);
    rp::scene::Sphere s;
    s.center = {0.5f, 0.35f, 0.5f};
    s.prev_center = s.center - glm::vec3(0.02f, 0.04f, 0.0f);
    s.radius = 0.3f;
    s.albedo = {0.9f, 0.2f, 0.1f};
    s.emission = {2.0f, 1.0f, 0.5f};
    frame.spheres.push_back(s);
  }

  glm::dmat4 view_proj(const rp::scene::Camera& c) const {
    return glm::dmat4(c.projection(float(width) / float(height))) * glm::dmat4(c.view());
  }

  // Camera ray through the centre of pixel (x, y): origin on the near plane, unit direction.
  void ray(uint32_t x, uint32_t y, glm::dvec3& origin, glm::dvec3& dir) const {
    glm::dmat4 inv = glm::inverse(view_proj(frame.camera));
    double nx = (x + 0.5) / width * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / height * 2.0;
    glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
    origin = glm::dvec3(a) / a.w;
    dir = glm::normalize(glm::dvec3(b) / b.w - origin);
  }

  glm::dvec3 world_vertex(uint32_t i) const {
    return glm::dvec3(glm::dmat4(frame.instances[0].model) *
                      glm::dvec4(glm::dvec3(assets.meshes[0].vertices[i].position), 1.0));
  }

  std::optional<Hit> cast(const glm::dvec3& o, const glm::dvec3& d) const {
    std::optional<Hit> best;
    const auto& tris = assets.meshes[0].triangles;
    for (uint32_t t = 0; t < tris.size(); ++t) {  // Moller-Trumbore
      glm::dvec3 v0 = world_vertex(tris[t].x), v1 = world_vertex(tris[t].y),
                 v2 = world_vertex(tris[t].z);
      glm::dvec3 e1 = v1 - v0, e2 = v2 - v0, pv = glm::cross(d, e2);
      double det = glm::dot(e1, pv);
      if (std::abs(det) < 1e-12) continue;
      glm::dvec3 tv = o - v0, qv = glm::cross(tv, e1);
      double b1 = glm::dot(tv, pv) / det, b2 = glm::dot(d, qv) / det, dist = glm::dot(e2, qv) / det;
      if (b1 < 0 || b2 < 0 || b1 + b2 > 1 || dist <= 0) continue;
      if (!best || dist < best->t) best = Hit{false, t, dist, b1, b2};
    }
    const auto& s = frame.spheres[0];
    glm::dvec3 oc = o - glm::dvec3(s.center);
    double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - double(s.radius) * s.radius);
    if (disc >= 0) {
      double dist = -b - std::sqrt(disc);
      if (dist > 0 && (!best || dist < best->t)) best = Hit{true, 0, dist, 0, 0};
    }
    return best;
  }
};

glm::dvec2 screen(const glm::dmat4& vp, const glm::dvec3& p, uint32_t w, uint32_t h) {
  glm::dvec4 c = vp * glm::dvec4(p, 1.0);
  return {(c.x / c.w * 0.5 + 0.5) * w, (0.5 - c.y / c.w * 0.5) * h};
}

template <typename T>
std::vector<T> read(const ::cl::Buffer& buffer, size_t count) {
  std::vector<T> out(count);
  rp::test::context().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(T), out.data());
  return out;
}

void expect_near3(const float* got, const glm::dvec3& want, double tol, const char* what,
                  uint32_t x, uint32_t y) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], want[c], tol) << what << "[" << c << "] at pixel " << x << "," << y;
}

// Runs the GBuffer pass (bilinear textures) over a hand-written W x H visibility buffer: ids
// and barycentrics per pixel, and the depths where given. Returns the GBuffer.
rp::render::GBuffer resolve(const rp::render::GpuScene& scene, const std::vector<uint32_t>& ids,
                            const std::vector<float>& bary, uint32_t W, uint32_t H,
                            const std::vector<float>* depth = nullptr) {
  auto& ctx = rp::test::context();
  const size_t n = size_t(W) * H;
  rp::render::VisibilityBuffer vis;
  vis.resize(ctx.context, W, H);
  ctx.queue.enqueueWriteBuffer(vis.ids, CL_TRUE, 0, n * 8, ids.data());
  ctx.queue.enqueueWriteBuffer(vis.bary, CL_TRUE, 0, n * 8, bary.data());
  if (depth) ctx.queue.enqueueWriteBuffer(vis.depth, CL_TRUE, 0, n * 4, depth->data());
  rp::render::GBuffer gb;
  gb.resize(ctx.context, W, H);
  rp::cl::Profiler profiler(ctx.queue);
  rp::passes::GBufferPass pass(ctx, rp::test::programs());
  pass.run(profiler, scene, vis, gb, RP_TEXTURE_FILTER_BILINEAR);
  EXPECT_EQ(profiler.collect().count(rp::passes::pass_name::kGBuffer), 1u);
  return gb;
}

// Resolves a hand-written visibility buffer of a W x H frame and checks every pixel against
// the double-precision reference.
void check_resolve(uint32_t W, uint32_t H, bool back = false) {
  auto& ctx = rp::test::context();
  TestScene ts(W, H, back);
  rp::render::GpuScene scene(ctx.context, ctx.queue, ts.assets);
  scene.update(ts.frame, W, H, 64);

  // Hand-written visibility buffer from the ray caster.
  const size_t n = size_t(W) * H;
  std::vector<uint32_t> ids(n * 2, RP_ID_NONE);
  std::vector<float> bary(n * 2, 0.0f), depth(n, 1.0f);
  std::vector<std::optional<Hit>> hits(n);
  int mesh_pixels[2] = {0, 0}, sphere_pixels = 0, background_pixels = 0;
  for (uint32_t y = 0; y < H; ++y) {
    for (uint32_t x = 0; x < W; ++x) {
      size_t i = size_t(y) * W + x;
      glm::dvec3 o, d;
      ts.ray(x, y, o, d);
      hits[i] = ts.cast(o, d);
      if (!hits[i]) {
        ++background_pixels;
        continue;
      }
      ids[i * 2] = hits[i]->sphere ? RP_ID_SPHERE_BIT : 0u;
      ids[i * 2 + 1] = hits[i]->sphere ? 0u : hits[i]->triangle;
      bary[i * 2] = float(hits[i]->b1);
      bary[i * 2 + 1] = float(hits[i]->b2);
      glm::dvec4 c = ts.view_proj(ts.frame.camera) * glm::dvec4(o + d * hits[i]->t, 1.0);
      depth[i] = float(c.z / c.w * 0.5 + 0.5);
      if (hits[i]->sphere) ++sphere_pixels; else ++mesh_pixels[hits[i]->triangle];
    }
  }
  // The scene must exercise every path.
  ASSERT_GE(mesh_pixels[0], 8);
  ASSERT_GE(mesh_pixels[1], 8);
  ASSERT_GE(sphere_pixels, 8);
  ASSERT_GE(background_pixels, 8);
  // Invalid ids resolve to background: an instance that does not exist, a triangle past the
  // mesh's count. Pixels 0 and 1 (top-left corner) are background in the ray cast.
  ASSERT_FALSE(hits[0] || hits[1]);
  ids[0] = 7;
  ids[2] = 0;
  ids[3] = 999;

  const rp::render::GBuffer gb = resolve(scene, ids, bary, W, H, &depth);

  auto albedo = read<float>(gb.albedo, n * 4), normal_depth = read<float>(gb.normal_depth, n * 4),
       position = read<float>(gb.position, n * 4), emission = read<float>(gb.emission, n * 4),
       velocity = read<float>(gb.velocity, n * 2);

  const glm::dmat4 view(ts.frame.camera.view());
  const glm::dmat4 vp = ts.view_proj(ts.frame.camera), prev_vp = ts.view_proj(ts.frame.prev_camera);
  const glm::dvec3 quad_normal = glm::dvec3(ts.rotation * glm::vec4(0, 0, 1, 0));
  const auto& sphere = ts.frame.spheres[0];
  const auto& mesh = ts.assets.meshes[0];
  for (uint32_t y = 0; y < H; ++y) {
    for (uint32_t x = 0; x < W; ++x) {
      const size_t i = size_t(y) * W + x;
      const float* a = &albedo[i * 4];
      const float* nd = &normal_depth[i * 4];
      const float* p = &position[i * 4];
      const float* e = &emission[i * 4];
      const float* v = &velocity[i * 2];
      if (!hits[i]) {
        for (int c = 0; c < 4; ++c) {
          EXPECT_EQ(a[c], 0.0f) << "background albedo at " << x << "," << y;
          EXPECT_EQ(p[c], 0.0f) << "background position at " << x << "," << y;
          EXPECT_EQ(e[c], 0.0f) << "background emission at " << x << "," << y;
        }
        EXPECT_EQ(nd[0], 0.0f);
        EXPECT_EQ(nd[1], 0.0f);
        EXPECT_EQ(nd[2], 0.0f);
        EXPECT_EQ(nd[3], ts.frame.camera.far_plane) << "background depth at " << x << "," << y;
        EXPECT_EQ(v[0], 0.0f);
        EXPECT_EQ(v[1], 0.0f);
        continue;
      }
      glm::dvec3 o, d;
      ts.ray(x, y, o, d);
      const glm::dvec3 ray_point = o + d * hits[i]->t;
      glm::dvec3 want_p, want_n, want_albedo, want_emission, prev_p;
      if (hits[i]->sphere) {
        want_p = ray_point;
        want_n = (want_p - glm::dvec3(sphere.center)) / double(sphere.radius);
        want_albedo = sphere.albedo;
        want_emission = sphere.emission;
        prev_p = want_p - glm::dvec3(sphere.center) + glm::dvec3(sphere.prev_center);
      } else {
        const glm::uvec3 tri = mesh.triangles[hits[i]->triangle];
        const double b1 = bary[i * 2], b2 = bary[i * 2 + 1], b0 = 1.0 - b1 - b2;
        const auto& v0 = mesh.vertices[tri.x];
        const auto& v1 = mesh.vertices[tri.y];
        const auto& v2 = mesh.vertices[tri.z];
        glm::dvec3 obj = b0 * glm::dvec3(v0.position) + b1 * glm::dvec3(v1.position) +
                         b2 * glm::dvec3(v2.position);
        glm::dvec2 uv = b0 * glm::dvec2(v0.uv) + b1 * glm::dvec2(v1.uv) + b2 * glm::dvec2(v2.uv);
        want_p = glm::dvec3(glm::dmat4(ts.frame.instances[0].model) * glm::dvec4(obj, 1.0));
        EXPECT_NEAR(glm::length(want_p - ray_point), 0.0, 1e-5);  // reference self-check
        want_n = quad_normal;  // towards the camera, also when the quad faces away
        const auto& mat = ts.assets.materials[mesh.materials[hits[i]->triangle]];
        want_albedo = glm::dvec3(mat.albedo);
        if (mat.texture >= 0) want_albedo *= texture_ref(ts.assets.textures[0], uv);
        want_emission = mat.emission;
        prev_p = want_p - glm::dvec3(kOffset);  // the instance moved by kOffset this frame
      }
      expect_near3(p, want_p, 1e-4, "position", x, y);
      EXPECT_EQ(p[3], 1.0f);
      expect_near3(nd, want_n, 1e-4, "normal", x, y);
      EXPECT_NEAR(nd[3], -(view * glm::dvec4(want_p, 1.0)).z, 1e-4) << "depth " << x << "," << y;
      expect_near3(a, want_albedo, 2e-6, "albedo", x, y);
      EXPECT_EQ(a[3], 1.0f);
      expect_near3(e, want_emission, 1e-7, "emission", x, y);
      glm::dvec2 want_v = screen(vp, want_p, W, H) - screen(prev_vp, prev_p, W, H);
      EXPECT_NEAR(v[0], want_v.x, 2e-3) << "velocity x at " << x << "," << y;
      EXPECT_NEAR(v[1], want_v.y, 2e-3) << "velocity y at " << x << "," << y;
    }
  }
}

TEST(GBuffer, ResolvesMeshSphereAndBackground) { check_resolve(kW, kH); }

// A surface seen from its back gets the normal of the side seen (the path tracer's rule): the
// same reference with the quad's winding and vertex normals reversed.
TEST(GBuffer, SurfacesSeenFromBehindFaceTheCamera) { check_resolve(kW, kH, true); }

// Every pixel-span layout (16 pixels a work-item on CPUs, 1 on GPUs; 4 and 8 too) at a width
// that leaves a partial span at the end of each row: same reference, same tolerances.
class GBufferSpans : public ::testing::TestWithParam<const char*> {};

TEST_P(GBufferSpans, ResolveMatchesReferenceWithPartialSpans) {
  setenv("ROLYPOLY_GBUFFER_SPAN", GetParam(), 1);
  try {
    check_resolve(21, 13);
  } catch (...) {
    unsetenv("ROLYPOLY_GBUFFER_SPAN");
    throw;
  }
  unsetenv("ROLYPOLY_GBUFFER_SPAN");
}

INSTANTIATE_TEST_SUITE_P(Spans, GBufferSpans, ::testing::Values("1", "4", "8", "16"));

// A point that does not move while the camera pans right: it moves left on screen by the hand-
// computed amount; the instance's own motion adds on top with the +y-down convention.
TEST(GBuffer, VelocityOfKnownMotion) {
  auto& ctx = rp::test::context();
  TestScene ts;
  ts.frame.instances[0].prev_model = ts.frame.instances[0].model;  // static instance
  ts.frame.spheres.clear();
  ts.frame.camera.position = {0.0f, 0.0f, 2.5f};  // axis-aligned: world x = view x
  ts.frame.camera.target = {0.0f, 0.0f, 0.0f};
  ts.frame.prev_camera = ts.frame.camera;
  ts.frame.prev_camera.position.x -= 0.1f;  // camera moved +x by 0.1 this frame...
  ts.frame.prev_camera.target.x -= 0.1f;    // ...as a pure pan (same orientation)
  rp::render::GpuScene scene(ctx.context, ctx.queue, ts.assets);
  scene.update(ts.frame, kW, kH, 64);

  // The quad centre (object origin, on the diagonal shared by both triangles: b1 = 0, b2 = 0.5
  // of triangle 0 = (v0, v1, v2) gives the midpoint of vertices 0 and 2, the origin).
  const glm::vec3 centre = glm::vec3(ts.frame.instances[0].model[3]);
  const size_t n = size_t(kW) * kH;
  std::vector<uint32_t> ids(n * 2, RP_ID_NONE);
  std::vector<float> bary(n * 2, 0.0f);
  ids[0] = 0;
  ids[1] = 0;
  bary[1] = 0.5f;
  const rp::render::GBuffer gb = resolve(scene, ids, bary, kW, kH);
  auto velocity = read<float>(gb.velocity, 2);
  auto position = read<float>(gb.position, 4);
  EXPECT_NEAR(position[0], centre.x, 1e-6);
  EXPECT_NEAR(position[1], centre.y, 1e-6);
  EXPECT_NEAR(position[2], centre.z, 1e-6);

  // Hand projection: in view space a pure pan shifts the point by -0.1 in x and leaves z; with
  // focal length f = 1 / tan(30 deg) and aspect a, x_ndc shifts by -0.1 f / (a z_dist), i.e.
  // -0.1 f / (a z_dist) * W / 2 pixels; y does not change.
  const glm::vec3 pv = glm::vec3(ts.frame.camera.view() * glm::vec4(centre, 1.0f));
  const double f = 1.0 / std::tan(glm::radians(30.0));
  const double aspect = double(kW) / kH;
  const double want_x = -0.1 * f / (aspect * -double(pv.z)) * kW / 2.0;
  EXPECT_NEAR(velocity[0], want_x, 2e-4);
  EXPECT_NEAR(velocity[1], 0.0, 2e-4);
  EXPECT_LT(velocity[0], -0.1);  // a visible shift, so the check is meaningful
}

// The visibility buffer of the test scene's quad by ray casting (its spheres left out).
void quad_visibility(const TestScene& ts, std::vector<uint32_t>& ids, std::vector<float>& bary) {
  const size_t n = size_t(kW) * kH;
  ids.assign(n * 2, RP_ID_NONE);
  bary.assign(n * 2, 0.0f);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      glm::dvec3 o, d;
      ts.ray(x, y, o, d);
      const std::optional<Hit> hit = ts.cast(o, d);
      if (!hit || hit->sphere) continue;
      const size_t i = size_t(y) * kW + x;
      ids[i * 2] = 0;
      ids[i * 2 + 1] = hit->triangle;
      bary[i * 2] = float(hit->b1);
      bary[i * 2 + 1] = float(hit->b2);
    }
}

// The plain triangle's normal map, seen from the front and from behind: the GBuffer normal is
// the path tracer's (truth/trace_scene.cpp): the map applied on the side of the vertex normal
// (tangent along the quad's +x, bitangent w cross(n, t), w = -1 on the reversed quad, so the
// texture keeps its orientation), then turned to the side the camera sees.
TEST(GBuffer, NormalMapsTurnWithTheSideSeen) {
  auto& ctx = rp::test::context();
  const glm::dvec3 map(200.0 / 255.0 * 2.0 - 1.0, 90.0 / 255.0 * 2.0 - 1.0,
                       230.0 / 255.0 * 2.0 - 1.0);
  for (const bool back : {false, true}) {
    TestScene ts(kW, kH, back);
    rp::scene::Texture normal_map{"normal", 2, 2, {}};
    const uint8_t texel[4] = {200, 90, 230, 255};
    for (int i = 0; i < 16; ++i) normal_map.rgba.push_back(texel[i % 4]);
    normal_map.srgb = false;
    ts.assets.textures.push_back(normal_map);
    ts.assets.materials[1].normal_texture = 1;
    ts.assets.materials[1].normal_scale = 0.7f;
    rp::scene::Mesh& quad = ts.assets.meshes[0];
    quad.tangents.assign(quad.vertices.size(), glm::vec4(1.0f, 0.0f, 0.0f, back ? -1.0f : 1.0f));
    ts.frame.spheres.clear();
    rp::render::GpuScene scene(ctx.context, ctx.queue, ts.assets);
    scene.update(ts.frame, kW, kH, 64);
    ASSERT_TRUE(scene.has_material_maps);
    const size_t n = size_t(kW) * kH;
    std::vector<uint32_t> ids;
    std::vector<float> bary;
    quad_visibility(ts, ids, bary);
    const rp::render::GBuffer gb = resolve(scene, ids, bary, kW, kH);
    const auto normal_depth = read<float>(gb.normal_depth, n * 4);

    // The path tracer's rule in world space: n, t through the model's rotation (the scale
    // is within the quad's plane), t orthogonal to n already.
    const glm::dmat3 r(ts.rotation);
    const glm::dvec3 nv = r * glm::dvec3(0.0, 0.0, back ? -1.0 : 1.0), t = r * glm::dvec3(1, 0, 0);
    const glm::dvec3 b = (back ? -1.0 : 1.0) * glm::cross(nv, t);
    glm::dvec3 want = glm::normalize(t * (map.x * 0.7) + b * (map.y * 0.7) + nv * map.z);
    const glm::dvec3 facing = r * glm::dvec3(0.0, 0.0, 1.0);  // the side the camera sees
    if (glm::dot(want, facing) < 0.0) want = -want;
    int mapped = 0;
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x) {
        const size_t i = size_t(y) * kW + x;
        if (ids[i * 2] == RP_ID_NONE) continue;
        const glm::dvec3 expected = ids[i * 2 + 1] == 1 ? want : facing;  // plain: mapped
        mapped += ids[i * 2 + 1] == 1;
        expect_near3(&normal_depth[i * 4], expected, 1e-4, back ? "back" : "front", x, y);
      }
    EXPECT_GE(mapped, 8);
  }
}

// The plain triangle's metallic-roughness and emission maps (one texel each, so every uv reads
// it): roughness = factor * G / 255, metal where factor * B / 255 >= 0.5, the gloss code of
// shared/brdf_layout.h rebuilt from them (metal: r + 65536; dielectric: r + 256 * round(f0 *
// 1024)); emission times the sRGB-decoded map. The textured triangle has no maps and keeps
// gbuffer_resolve's values.
TEST(GBuffer, MetallicRoughnessAndEmissionMapsSetTheGlossCodeAndEmission) {
  auto& ctx = rp::test::context();
  const auto srgb = [](double c) {
    c /= 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  struct Case {
    float metallic;
    bool metal;
  };
  for (const Case c : {Case{1.0f, true}, Case{0.5f, false}}) {
    TestScene ts(kW, kH);
    const uint8_t mr_texel[4] = {17, 128, 200, 255};     // G roughness, B metallic
    const uint8_t emission_texel[4] = {255, 128, 0, 255};  // sRGB
    for (const uint8_t* texel : {mr_texel, emission_texel}) {
      rp::scene::Texture t{"map", 2, 2, {}};
      for (int i = 0; i < 16; ++i) t.rgba.push_back(texel[i % 4]);
      t.srgb = texel == emission_texel;
      ts.assets.textures.push_back(t);
    }
    rp::scene::Material& m = ts.assets.materials[1];
    m.specular.roughness = 0.9f;
    m.specular.f0 = 0.04f;
    m.metallic = c.metallic;
    m.metallic_roughness_texture = 1;
    m.emission = {2.0f, 3.0f, 4.0f};
    m.emission_texture = 2;
    ts.frame.spheres.clear();
    rp::render::GpuScene scene(ctx.context, ctx.queue, ts.assets);
    scene.update(ts.frame, kW, kH, 64);
    ASSERT_TRUE(scene.has_material_maps);
    std::vector<uint32_t> ids;
    std::vector<float> bary;
    quad_visibility(ts, ids, bary);
    const rp::render::GBuffer gb = resolve(scene, ids, bary, kW, kH);
    const auto emission = read<float>(gb.emission, size_t(kW) * kH * 4);

    const double roughness = 0.9 * 128.0 / 255.0;
    const int r = int(roughness * 255.0 + 0.5);
    EXPECT_EQ(c.metal, c.metallic * 200.0 / 255.0 >= 0.5);  // the case's premise
    const double code = c.metal ? r + 65536 : r + 256 * int(0.04 * 1024.0 + 0.5);
    const glm::dvec3 want_mapped(2.0 * srgb(255), 3.0 * srgb(128), 4.0 * srgb(0));
    int mapped = 0, plain = 0;
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x) {
        const size_t i = size_t(y) * kW + x;
        if (ids[i * 2] == RP_ID_NONE) continue;
        const float* e = &emission[i * 4];
        if (ids[i * 2 + 1] == 1) {
          ++mapped;
          expect_near3(e, want_mapped, 1e-5, "mapped emission", x, y);
          EXPECT_EQ(e[3], code) << "gloss code at " << x << "," << y;
        } else {
          ++plain;
          expect_near3(e, glm::dvec3(0.1, 0.2, 0.3), 1e-6, "plain emission", x, y);
          EXPECT_EQ(e[3], 0.0f) << "matte at " << x << "," << y;
        }
      }
    EXPECT_GE(mapped, 8);
    EXPECT_GE(plain, 8);
  }
}

}  // namespace
