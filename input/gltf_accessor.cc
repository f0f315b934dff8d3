#include "input/gltf_accessor.h"

#include <cstring>

namespace radfarm {
namespace {

// Where an accessor's elements lie: element i's first byte is data + i * stride.
struct ElementSpan {
  const unsigned char* data = nullptr;  // null: no buffer view, every element zero
  size_t stride = 0;
  size_t count = 0;
};

std::string Named(const std::string& what, int accessor) {
  return what + " (accessor " + std::to_string(accessor) + ")";
}

// Checks the accessor's type and component type and that all of its bytes lie inside its buffer.
Result<ElementSpan> Locate(const tinygltf::Model& model, int index, int type,
                           const std::vector<int>& component_types, const std::string& what) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
    return Error{what + ": accessor " + std::to_string(index) + " does not exist"};
  }
  const tinygltf::Accessor& a = model.accessors[index];
  const std::string name = Named(what, index);
  if (a.type != type) return Error{name + ": wrong element type"};
  bool known = false;
  for (int c : component_types) known = known || a.componentType == c;
  if (!known) {
    return Error{name + ": component type " + std::to_string(a.componentType) + " not allowed"};
  }
  if (a.sparse.isSparse) return Error{name + ": sparse accessors are not supported"};
  const size_t element = static_cast<size_t>(tinygltf::GetComponentSizeInBytes(a.componentType)) *
                         static_cast<size_t>(tinygltf::GetNumComponentsInType(a.type));
  ElementSpan span;
  span.count = a.count;
  if (a.bufferView < 0) return span;  // glTF: no buffer view means all zeros
  if (static_cast<size_t>(a.bufferView) >= model.bufferViews.size()) {
    return Error{name + ": buffer view " + std::to_string(a.bufferView) + " does not exist"};
  }
  const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    return Error{name + ": buffer " + std::to_string(view.buffer) + " does not exist"};
  }
  const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
  span.stride = view.byteStride != 0 ? view.byteStride : element;
  if (span.stride < element) return Error{name + ": byte stride smaller than an element"};
  // Sizes in 64 bits, each term bounded by the file, so nothing here overflows.
  const uint64_t needed = a.count == 0 ? 0 : (a.count - 1) * uint64_t{span.stride} + element;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
    return Error{name + ": buffer view " + std::to_string(a.bufferView) +
                 " runs past the end of its buffer"};
  }
  if (a.byteOffset > view.byteLength || needed > view.byteLength - a.byteOffset) {
    return Error{name + ": " + std::to_string(a.count) +
                 " elements run past the end of buffer view " + std::to_string(a.bufferView)};
  }
  span.data = buffer.data() + view.byteOffset + a.byteOffset;
  return span;
}

template <typename T>
T Load(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof value);  // glTF data is little-endian, as is every target we build
  return value;
}

// Component k of element i as a double: floats as they are, integers normalised when asked.
double Component(const ElementSpan& span, int component_type, bool normalized, size_t i, int k) {
  if (span.data == nullptr) return 0;
  const unsigned char* p = span.data + i * span.stride;
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return Load<float>(p + 4 * k);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[k] / 255.0 : p[k];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = Load<uint16_t>(p + 2 * k);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return Load<uint32_t>(p + 4 * k);
    default:
      return 0;  // Locate admits no other type
  }
}

}  // namespace

Result<std::vector<std::array<double, 3>>> ReadVec3Accessor(const tinygltf::Model& model,
                                                            int accessor, const std::string& what) {
  Result<ElementSpan> span =
      Locate(model, accessor, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, what);
  RADFARM_RETURN_IF_ERROR(span);
  std::vector<std::array<double, 3>> out(span->count);
  for (size_t i = 0; i < span->count; ++i) {
    for (int k = 0; k < 3; ++k)
      out[i][k] = Component(*span, TINYGLTF_COMPONENT_TYPE_FLOAT, false, i, k);
  }
  return out;
}

Result<std::vector<std::array<double, 2>>> ReadVec2Accessor(const tinygltf::Model& model,
                                                            int accessor, const std::string& what) {
  Result<ElementSpan> span =
      Locate(model, accessor, TINYGLTF_TYPE_VEC2,
             {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
             what);
  RADFARM_RETURN_IF_ERROR(span);
  const tinygltf::Accessor& a = model.accessors[accessor];
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized) {
    return Error{Named(what, accessor) + ": integer texture coordinates must be normalized"};
  }
  std::vector<std::array<double, 2>> out(span->count);
  for (size_t i = 0; i < span->count; ++i) {
    for (int k = 0; k < 2; ++k) out[i][k] = Component(*span, a.componentType, true, i, k);
  }
  return out;
}

Result<std::vector<uint32_t>> ReadIndexAccessor(const tinygltf::Model& model, int accessor,
                                                const std::string& what) {
  Result<ElementSpan> span =
      Locate(model, accessor, TINYGLTF_TYPE_SCALAR,
             {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
             what);
  RADFARM_RETURN_IF_ERROR(span);
  const int type = model.accessors[accessor].componentType;
  std::vector<uint32_t> out(span->count);
  for (size_t i = 0; i < span->count; ++i) {
    out[i] = static_cast<uint32_t>(Component(*span, type, false, i, 0));
  }
  return out;
}

}  // namespace radfarm
