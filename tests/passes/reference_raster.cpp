#include "passes/reference_raster.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "kernels/shared/types.h"
#include "scene/alpha_mask.h"

namespace rp::test {
namespace {

constexpr uint32_t kTile = 16;  // RP_RASTER_TILE: the edge frame of a pixel is its tile's

// ((c0 x + c1 y) + c2 z) + c3 w per component, as rp_raster_transform.
glm::vec4 transform(const glm::mat4& m, const glm::vec4& p) {
  glm::vec4 r;
  for (int k = 0; k < 4; ++k)
    r[k] = ((m[0][k] * p.x + m[1][k] * p.y) + m[2][k] * p.z) + m[3][k] * p.w;
  return r;
}

struct Edges {
  float a[3], b[3], c[3];  // oriented edge i: a dx + (b dy + c)
  float z[3], w[3];        // vertices' clip z and w (RP_RASTER_DEPTH)
  bool top_left[3];
  bool valid;
  float sign;              // sign of det[P0, P1, P2] before orienting
};

bool top_left(float a, float b, float c) {
  return a > 0.0f || (a == 0.0f && (b > 0.0f || (b == 0.0f && c > 0.0f)));
}

// Mirrors rp_raster_edges: homogeneous edge functions in the frame (ox, oy).
Edges tile_edges(const glm::vec4 v[3], float ox, float oy) {
  float x[3], y[3], w[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = v[i].x - ox * v[i].w;
    y[i] = v[i].y - oy * v[i].w;
    w[i] = v[i].w;
  }
  Edges r{};
  for (int i = 0; i < 3; ++i) {
    int j = (i + 1) % 3, k = (i + 2) % 3;
    r.a[i] = y[j] * w[k] - w[j] * y[k];
    r.b[i] = w[j] * x[k] - x[j] * w[k];
    r.c[i] = x[j] * y[k] - y[j] * x[k];
  }
  float det = (w[0] * r.c[0] + w[1] * r.c[1]) + w[2] * r.c[2];
  float s = det < 0.0f ? -1.0f : 1.0f;
  for (int i = 0; i < 3; ++i) {
    r.a[i] *= s;
    r.b[i] *= s;
    r.c[i] *= s;
  }
  det *= s;
  r.sign = s;
  r.valid = det > 0.0f && std::isfinite(det);
  if (!r.valid) return r;
  for (int i = 0; i < 3; ++i) {
    r.z[i] = v[i].z;
    r.w[i] = v[i].w;
  }
  for (int i = 0; i < 3; ++i) r.top_left[i] = top_left(r.a[i], r.b[i], r.c[i]);
  return r;
}

struct Tri {
  glm::vec4 v[3];  // homogeneous pixel space
  uint32_t instance, primitive;
  const scene::Mesh* mesh;  // the mesh drawn (a shadow map's proxy where it has one)
};

// Texture coordinates of `tri` at barycentrics (b1, b2), as kernels/common/alpha_mask.h.
glm::vec2 uv_at(const Tri& tri, float b1, float b2) {
  const glm::uvec3 t = tri.mesh->triangles[tri.primitive];
  const glm::vec2 u0 = tri.mesh->vertices[t.x].uv, u1 = tri.mesh->vertices[t.y].uv,
                  u2 = tri.mesh->vertices[t.z].uv;
  const float b0 = (1.0f - b1) - b2;
  return glm::vec2((b0 * u0.x + b1 * u1.x) + b2 * u2.x, (b0 * u0.y + b1 * u1.y) + b2 * u2.y);
}

}  // namespace

RefImage reference_raster(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                          const RefView& view) {
  const uint32_t W = view.width, H = view.height;
  const float half_w = 0.5f * float(W), half_h = 0.5f * float(H);
  RefImage img;
  img.width = W;
  img.height = H;
  const size_t n = size_t(W) * H;
  img.depth.assign(n, 1.0f);
  if (view.depth_only) img.back.assign(n, 0.0f);
  img.ids.assign(n, glm::uvec2(RP_ID_NONE, RP_ID_NONE));
  img.bary.assign(n, glm::vec2(0.0f));
  img.hits_positive.assign(n, 0);
  img.hits_negative.assign(n, 0);
  img.alpha_edge.assign(n, 0);
  const scene::AlphaMasks masks(assets);

  // Every (instance, triangle) in instance order: the index is the tie-break key.
  std::vector<Tri> tris;
  for (uint32_t i = 0; i < frame.instances.size(); ++i) {
    const scene::MeshInstance& inst = frame.instances[i];
    // a shadow map draws the mesh's proxy where it has one for the map's size
    const scene::Mesh& mesh = assets.meshes.at(
        view.depth_only ? scene::shadow_mesh(assets.meshes, inst.mesh, W) : inst.mesh);
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      Tri tri{};
      for (int k = 0; k < 3; ++k) {
        glm::vec3 p = mesh.vertices.at(mesh.triangles[t][k]).position;
        glm::vec4 clip = transform(view.view_proj, transform(inst.model, glm::vec4(p, 1.0f)));
        tri.v[k] = glm::vec4((clip.x + clip.w) * half_w, (clip.w - clip.y) * half_h, clip.z,
                             clip.w);
      }
      tri.instance = i;
      tri.primitive = t;
      tri.mesh = &mesh;
      if (view.depth_only && !inst.casts_shadow) tri.instance = RP_ID_NONE;  // not drawn
      // The camera does not draw the back face of a single-sided material: counter-clockwise
      // in the object's space is the front, which a mirroring model matrix turns clockwise.
      const glm::mat3 m3(inst.model);
      const bool mirrored = glm::dot(m3[0], glm::cross(m3[1], m3[2])) < 0.0f;
      const glm::vec4* v = tri.v;
      const float c0 = v[1].x * v[2].y - v[1].y * v[2].x;
      const float c1 = v[2].x * v[0].y - v[2].y * v[0].x;
      const float c2 = v[0].x * v[1].y - v[0].y * v[1].x;
      const float facing = (v[0].w * c0 + v[1].w * c1) + v[2].w * c2;
      const bool back = mirrored ? facing < 0.0f : facing > 0.0f;
      if (!view.depth_only && back && !assets.materials.at(mesh.materials.at(t)).double_sided)
        tri.instance = RP_ID_NONE;
      tris.push_back(tri);
    }
  }
  const uint32_t tri_count = static_cast<uint32_t>(tris.size());

  std::vector<float> best_z(n, 1.0f), back_z(n, -1.0f);
  std::vector<uint32_t> best_key(n, RP_ID_NONE);
  std::vector<Edges> edges(tris.size());
  for (uint32_t oy = 0; oy < H; oy += kTile) {
    for (uint32_t ox = 0; ox < W; ox += kTile) {
      for (size_t t = 0; t < tris.size(); ++t) edges[t] = tile_edges(tris[t].v, float(ox), float(oy));
      for (uint32_t y = oy; y < std::min(H, oy + kTile); ++y) {
        for (uint32_t x = ox; x < std::min(W, ox + kTile); ++x) {
          const float dx = float(x - ox) + 0.5f, dy = float(y - oy) + 0.5f;
          const size_t p = img.index(x, y);
          for (uint32_t t = 0; t < tri_count; ++t) {
            const Edges& e = edges[t];
            if (!e.valid || tris[t].instance == RP_ID_NONE) continue;
            bool in = true;
            float f[3];
            for (int i = 0; i < 3; ++i) {
              f[i] = e.a[i] * dx + (e.b[i] * dy + e.c[i]);
              in = in && (f[i] > 0.0f || (f[i] == 0.0f && e.top_left[i]));
            }
            // RP_RASTER_DEPTH: (e0 z0 + e1 z1 + e2 z2) / (e0 w0 + e1 w1 + e2 w2)
            float z = ((f[0] * e.z[0] + f[1] * e.z[1]) + f[2] * e.z[2]) /
                      ((f[0] * e.w[0] + f[1] * e.w[1]) + f[2] * e.w[2]);
            if (!in || !(z >= -1.0f)) continue;
            const uint32_t material = tris[t].mesh->materials[tris[t].primitive];
            if (masks.masked(material)) {
              const float sum = (f[0] + f[1]) + f[2], b1 = f[1] / sum, b2 = f[2] / sum;
              const bool solid = masks.solid(material, uv_at(tris[t], b1, b2));
              // the kernel's divisions may round differently: a point this close to the
              // cutoff's contour may go either way
              for (float d : {-1e-4f, 1e-4f})
                if (masks.solid(material, uv_at(tris[t], b1 + d, b2)) != solid ||
                    masks.solid(material, uv_at(tris[t], b1, b2 + d)) != solid)
                  img.alpha_edge[p] = 1;
              if (!solid) continue;
            }
            if (z <= 1.0f) ++(e.sign > 0.0f ? img.hits_positive[p] : img.hits_negative[p]);
            back_z[p] = std::max(back_z[p], std::min(z, 1.0f));
            if (z < best_z[p] || (z == best_z[p] && t < best_key[p])) {
              best_z[p] = z;
              best_key[p] = t;
            }
          }
        }
      }
    }
  }

  // Spheres: the ray through the pixel centre from the near plane, as in visibility_raster.
  const glm::mat4& inv = view.inv_view_proj;
  const glm::mat4& vp = view.view_proj;
  for (uint32_t s = 0; s < frame.spheres.size(); ++s) {
    const scene::Sphere& sp = frame.spheres[s];
    if (!(sp.radius > 0.0f) || (view.depth_only && !sp.casts_shadow)) continue;
    const float r2 = sp.radius * sp.radius;
    const uint32_t key = tri_count + s;
    for (uint32_t y = 0; y < H; ++y) {
      for (uint32_t x = 0; x < W; ++x) {
        const float nx = (float(x) + 0.5f) * (2.0f / float(W)) - 1.0f;
        const float ny = 1.0f - (float(y) + 0.5f) * (2.0f / float(H));
        auto unproject = [&](int k, float zn) {
          return ((inv[0][k] * nx + inv[1][k] * ny) + inv[2][k] * zn) + inv[3][k];
        };
        const float near_w = unproject(3, -1.0f), far_w = unproject(3, 1.0f);
        const float o[3] = {unproject(0, -1.0f) / near_w, unproject(1, -1.0f) / near_w,
                            unproject(2, -1.0f) / near_w};
        float d[3] = {unproject(0, 1.0f) / far_w - o[0], unproject(1, 1.0f) / far_w - o[1],
                      unproject(2, 1.0f) / far_w - o[2]};
        const float len = std::sqrt((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]);
        for (float& c : d) c = c / len;
        const float z_o = ((vp[0][2] * o[0] + vp[1][2] * o[1]) + vp[2][2] * o[2]) + vp[3][2];
        const float w_o = ((vp[0][3] * o[0] + vp[1][3] * o[1]) + vp[2][3] * o[2]) + vp[3][3];
        const float z_d = (vp[0][2] * d[0] + vp[1][2] * d[1]) + vp[2][2] * d[2];
        const float w_d = (vp[0][3] * d[0] + vp[1][3] * d[1]) + vp[2][3] * d[2];
        const float cx = o[0] - sp.center.x, cy = o[1] - sp.center.y, cz = o[2] - sp.center.z;
        const float b = (cx * d[0] + cy * d[1]) + cz * d[2];
        const float px = cx - b * d[0], py = cy - b * d[1], pz = cz - b * d[2];
        const float disc = r2 - ((px * px + py * py) + pz * pz);
        const float root = std::sqrt(std::max(disc, 0.0f));
        const float t0 = -b - root;
        const float t = t0 >= 0.0f ? t0 : -b + root;
        const float z = (z_o + t * z_d) / (w_o + t * w_d);
        const size_t p = img.index(x, y);
        const float t1 = -b + root;
        const float z1 = (z_o + t1 * z_d) / (w_o + t1 * w_d);
        if (disc >= 0.0f && t1 >= 0.0f && z1 >= -1.0f)
          back_z[p] = std::max(back_z[p], std::min(z1, 1.0f));
        if (disc >= 0.0f && t >= 0.0f && z >= -1.0f &&
            (z < best_z[p] || (z == best_z[p] && key < best_key[p]))) {
          best_z[p] = z;
          best_key[p] = key;
        }
      }
    }
  }

  // Resolve: ids and barycentrics of the winner, edges again in the pixel's tile frame.
  for (uint32_t y = 0; y < H; ++y) {
    for (uint32_t x = 0; x < W; ++x) {
      const size_t p = img.index(x, y);
      img.depth[p] = best_z[p] * 0.5f + 0.5f;
      if (view.depth_only) img.back[p] = back_z[p] * 0.5f + 0.5f;
      const uint32_t key = best_key[p];
      if (view.depth_only || key == RP_ID_NONE) continue;
      if (key >= tri_count) {
        img.ids[p] = glm::uvec2(RP_ID_SPHERE_BIT | (key - tri_count), 0u);
        continue;
      }
      const uint32_t ox = x / kTile * kTile, oy = y / kTile * kTile;
      const Edges e = tile_edges(tris[key].v, float(ox), float(oy));
      const float dx = float(x - ox) + 0.5f, dy = float(y - oy) + 0.5f;
      float f[3];
      for (int i = 0; i < 3; ++i) f[i] = e.a[i] * dx + (e.b[i] * dy + e.c[i]);
      const float sum = (f[0] + f[1]) + f[2];
      img.ids[p] = glm::uvec2(tris[key].instance, tris[key].primitive);
      img.bary[p] = glm::vec2(f[1] / sum, f[2] / sum);
    }
  }
  return img;
}

scene::Mesh make_test_mesh(const std::vector<glm::vec3>& positions,
                           const std::vector<glm::uvec3>& triangles) {
  scene::Mesh mesh;
  mesh.name = "test";
  for (const glm::vec3& p : positions)
    mesh.vertices.push_back({p, glm::vec3(0.0f, 0.0f, 1.0f), glm::vec2(0.0f)});
  mesh.triangles = triangles;
  mesh.materials.assign(triangles.size(), 0u);
  return mesh;
}

scene::Mesh make_icosphere(int levels, float radius) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (glm::vec3& p : v) p = glm::normalize(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      uint32_t id = static_cast<uint32_t>(v.size() - 1);
      midpoints.emplace(key, id);
      return id;
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& tri : f) {
      uint32_t a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
      next.insert(next.end(), {{tri.x, a, c}, {tri.y, b, a}, {tri.z, c, b}, {a, b, c}});
    }
    f = std::move(next);
  }
  for (glm::vec3& p : v) p *= radius;
  return make_test_mesh(v, f);
}

scene::SceneAssets make_test_assets(std::vector<scene::Mesh> meshes) {
  scene::SceneAssets assets;
  assets.meshes = std::move(meshes);
  scene::Material grey;
  grey.name = "grey";
  grey.double_sided = true;  // both windings drawn: the tests' triangles face either way
  assets.materials.push_back(grey);
  return assets;
}

scene::FrameScene make_test_frame() {
  scene::FrameScene frame;
  frame.camera.position = glm::vec3(0.0f, 0.0f, 2.75f);
  frame.camera.target = glm::vec3(0.0f);
  frame.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  frame.camera.fov_y_deg = 60.0f;
  frame.camera.near_plane = 0.1f;
  frame.camera.far_plane = 4.0f;
  frame.prev_camera = frame.camera;
  return frame;
}

RefView camera_view(const scene::FrameScene& frame, uint32_t width, uint32_t height) {
  RefView view;
  view.view_proj = frame.camera.projection(float(width) / float(height)) * frame.camera.view();
  view.inv_view_proj = glm::inverse(view.view_proj);
  view.width = width;
  view.height = height;
  return view;
}

}  // namespace rp::test
