// Reading glTF accessors into plain arrays, with every offset checked against the data the
// buffer really holds (64-bit arithmetic) before anything is allocated for the accessor's
// count: byteStride interleaving, normalized integer texture coordinates, sparse substitution.
#include <cmath>
#include <cstring>

#include <tiny_gltf.h>

#include "scene/gltf_internal.h"

namespace rp::scene::gltf {
namespace {

constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;                     // 5120
constexpr int kUnsignedByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;    // 5121
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;                   // 5122
constexpr int kUnsignedShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;  // 5123
constexpr int kUnsignedInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;      // 5125
constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;                   // 5126

uint64_t component_size(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte: return 1;
    case kShort:
    case kUnsignedShort: return 2;
    case kUnsignedInt:
    case kFloat: return 4;
    default: return 0;
  }
}

const char* type_name(int components) {
  switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return "?";
  }
}

int components_of(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices: never vertex data the loader reads
  }
}

// `count` elements of `element` bytes, `stride` apart, starting `offset` bytes into bufferView
// `view`: the checked start of the data.
const uint8_t* locate(const Context& ctx, int view, uint64_t offset, uint64_t count,
                      uint64_t stride, uint64_t element, const std::string& where) {
  const tinygltf::Model& m = *ctx.model;
  if (view < 0 || static_cast<size_t>(view) >= m.bufferViews.size())
    ctx.fail(where + ": bufferView " + std::to_string(view) + " does not exist (" +
             std::to_string(m.bufferViews.size()) + " bufferViews)");
  const tinygltf::BufferView& bv = m.bufferViews[static_cast<size_t>(view)];
  if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= m.buffers.size())
    ctx.fail(where + ": bufferView " + std::to_string(view) + "'s buffer " +
             std::to_string(bv.buffer) + " does not exist");
  const std::vector<unsigned char>& data = m.buffers[static_cast<size_t>(bv.buffer)].data;
  // Every term is below 2^31 (the loader's file limit) or 2^39 (stride x count): no overflow.
  if (uint64_t{bv.byteOffset} + uint64_t{bv.byteLength} > data.size())
    ctx.fail(where + ": bufferView " + std::to_string(view) + " runs past the end of buffer " +
             std::to_string(bv.buffer) + " (" + std::to_string(data.size()) + " bytes)");
  const uint64_t end = count == 0 ? 0 : offset + stride * (count - 1) + element;
  if (count == 0 || end > bv.byteLength)
    ctx.fail(where + ": its " + std::to_string(count) + " elements reach byte " +
             std::to_string(end) + " of bufferView " + std::to_string(view) + ", which has " +
             std::to_string(bv.byteLength));
  return data.data() + bv.byteOffset + offset;
}

template <typename T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);  // glTF data need not be aligned for the host
  return v;
}

double component(const uint8_t* p, int type, bool normalized) {
  switch (type) {
    case kUnsignedByte: return normalized ? p[0] / 255.0 : p[0];
    case kUnsignedShort: return normalized ? load<uint16_t>(p) / 65535.0 : load<uint16_t>(p);
    case kUnsignedInt: return load<uint32_t>(p);
    case kFloat: return load<float>(p);
    case kByte: return normalized ? std::max(load<int8_t>(p) / 127.0, -1.0) : load<int8_t>(p);
    case kShort: return normalized ? std::max(load<int16_t>(p) / 32767.0, -1.0) : load<int16_t>(p);
    default: return 0.0;
  }
}

struct Checked {
  const tinygltf::Accessor* accessor;
  const uint8_t* data;
  uint64_t stride;
  uint64_t element;
};

// The accessor's index, type, component type (`component_ok`, else `must` says what it must
// be), count and data range, checked; `components` per element.
template <typename ComponentOk>
Checked check(Context& ctx, int index, int components, ComponentOk component_ok,
              const std::string& must, const std::string& where) {
  const tinygltf::Model& m = *ctx.model;
  if (index < 0 || static_cast<size_t>(index) >= m.accessors.size())
    ctx.fail(where + ": accessor " + std::to_string(index) + " does not exist (" +
             std::to_string(m.accessors.size()) + " accessors)");
  const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(index)];
  const std::string at = where + ": accessor " + std::to_string(index);
  if (components_of(a.type) != components) ctx.fail(at + " must be " + type_name(components));
  if (!component_ok(a)) ctx.fail(at + " must " + must);
  const uint64_t size = component_size(a.componentType);
  // Each element becomes at least one vertex or index: the scene's limit bounds any one read.
  if (a.count == 0 || a.count > ctx.limits.max_vertices * 3)
    ctx.fail(at + ": count " + std::to_string(a.count) + " (must be 1 to " +
             std::to_string(ctx.limits.max_vertices * 3) + ")");
  ctx.accessor_reads += a.count;
  if (ctx.accessor_reads > ctx.limits.max_accessor_reads)
    ctx.fail(at + ": the scene reads more than " + std::to_string(ctx.limits.max_accessor_reads) +
             " accessor elements");
  if (a.bufferView < 0)
    ctx.fail(at + " has no bufferView (zero-filled and sparse-only accessors are not supported)");
  const uint64_t element = size * static_cast<uint64_t>(components);
  uint64_t stride = element;
  if (static_cast<size_t>(a.bufferView) < m.bufferViews.size()) {
    const size_t view_stride = m.bufferViews[static_cast<size_t>(a.bufferView)].byteStride;
    if (view_stride != 0) stride = view_stride;
  }
  if (stride < element)
    ctx.fail(at + ": byteStride " + std::to_string(stride) + " is less than its element size " +
             std::to_string(element));
  const uint8_t* data = locate(ctx, a.bufferView, a.byteOffset, a.count, stride, element, at);
  return {&a, data, stride, element};
}

// Overwrites the elements a sparse accessor lists (`out` holds count x components values).
template <typename T, typename Convert>
void apply_sparse(Context& ctx, const Checked& c, int components, std::vector<T>& out,
                  Convert convert, const std::string& where) {
  const tinygltf::Accessor& a = *c.accessor;
  if (!a.sparse.isSparse) return;
  const std::string at =
      where + ": accessor " + std::to_string(&a - ctx.model->accessors.data()) + " (sparse)";
  const uint64_t n = static_cast<uint64_t>(std::max(a.sparse.count, 0));
  if (n == 0 || n > a.count)
    ctx.fail(at + ": count " + std::to_string(a.sparse.count) + " (must be 1 to " +
             std::to_string(a.count) + ")");
  const int index_type = a.sparse.indices.componentType;
  const uint64_t index_size =
      index_type == kUnsignedByte || index_type == kUnsignedShort || index_type == kUnsignedInt
          ? component_size(index_type)
          : 0;
  if (index_size == 0) ctx.fail(at + ": indices must be unsigned byte, short or int");
  if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
    ctx.fail(at + ": negative byteOffset");
  const uint8_t* indices =
      locate(ctx, a.sparse.indices.bufferView, static_cast<uint64_t>(a.sparse.indices.byteOffset),
             n, index_size, index_size, at + " indices");
  const uint8_t* values =
      locate(ctx, a.sparse.values.bufferView, static_cast<uint64_t>(a.sparse.values.byteOffset), n,
             c.element, c.element, at + " values");
  for (uint64_t i = 0; i < n; ++i) {
    const uint64_t target =
        static_cast<uint64_t>(component(indices + i * index_size, index_type, false));
    if (target >= a.count)
      ctx.fail(at + ": index " + std::to_string(target) + " is not below count " +
               std::to_string(a.count));
    const uint8_t* v = values + i * c.element;
    const uint64_t size = c.element / static_cast<uint64_t>(components);
    for (int k = 0; k < components; ++k)
      out[target * static_cast<uint64_t>(components) + static_cast<uint64_t>(k)] =
          convert(v + size * static_cast<uint64_t>(k));
  }
}

}  // namespace

std::vector<float> read_floats(Context& ctx, int index, int components, bool allow_unorm,
                               const std::string& where) {
  auto component_ok = [allow_unorm](const tinygltf::Accessor& a) {
    const bool unorm =
        (a.componentType == kUnsignedByte || a.componentType == kUnsignedShort) && a.normalized;
    return a.componentType == kFloat || (allow_unorm && unorm);
  };
  const Checked c =
      check(ctx, index, components, component_ok,
            allow_unorm ? "hold floats or normalized unsigned bytes/shorts" : "hold floats", where);
  const tinygltf::Accessor& a = *c.accessor;
  const int type = a.componentType;
  const uint64_t size = c.element / static_cast<uint64_t>(components);
  auto convert = [type](const uint8_t* p) { return static_cast<float>(component(p, type, true)); };
  std::vector<float> out(a.count * static_cast<size_t>(components));
  for (uint64_t i = 0; i < a.count; ++i)
    for (int k = 0; k < components; ++k)
      out[i * static_cast<uint64_t>(components) + static_cast<uint64_t>(k)] =
          convert(c.data + i * c.stride + size * static_cast<uint64_t>(k));
  apply_sparse(ctx, c, components, out, convert, where);
  for (size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      ctx.fail(where + ": accessor " + std::to_string(index) + " element " +
               std::to_string(i / static_cast<size_t>(components)) + " is not finite");
  return out;
}

std::vector<uint32_t> read_indices(Context& ctx, int index, const std::string& where) {
  auto component_ok = [](const tinygltf::Accessor& a) {
    return a.componentType == kUnsignedByte || a.componentType == kUnsignedShort ||
           a.componentType == kUnsignedInt;
  };
  const Checked c = check(ctx, index, 1, component_ok, "be unsigned byte, short or int", where);
  const tinygltf::Accessor& a = *c.accessor;
  const int type = a.componentType;
  auto convert = [type](const uint8_t* p) {
    return static_cast<uint32_t>(component(p, type, false));
  };
  std::vector<uint32_t> out(a.count);
  for (uint64_t i = 0; i < a.count; ++i) out[i] = convert(c.data + i * c.stride);
  apply_sparse(ctx, c, 1, out, convert, where);
  return out;
}

}  // namespace rp::scene::gltf
