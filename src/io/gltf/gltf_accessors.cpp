// glTF accessors → plain arrays. Nothing here trusts the file: every index
// is checked, and byteOffset + (count − 1) × stride + element size is
// checked against the buffer view and the buffer (in 64-bit arithmetic,
// without overflow) before a single byte is read, so a file's claims never
// size an allocation beyond the bytes it really holds.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/gltf/gltf.h"

namespace sombra::gltf {

namespace {

const char* component_name(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        default: return "an unknown component type";
    }
}

std::size_t component_size(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

const char* type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "an unknown type";
    }
}

// An accessor's bytes, checked: element i's component c lies at
// data + i × stride + c × component size. data is null for an accessor
// without a buffer view (all zeros, glTF 2.0 §3.6.2.1).
struct View {
    const unsigned char* data = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int component_type = 0;
    int components = 0;
    int type = 0;  // TINYGLTF_TYPE_*
    bool normalized = false;
};

[[noreturn]] void fail(const AccessorReader& r, int index, const std::string& what, const std::string& problem) {
    throw Error(r.file, "accessor " + std::to_string(index) + " (" + what + "): " + problem);
}

const tinygltf::Accessor& find_accessor(const AccessorReader& r, int index, const std::string& what) {
    if (index < 0 || static_cast<std::size_t>(index) >= r.model.accessors.size())
        throw Error(r.file, what + " names accessor " + std::to_string(index) + ", but the file has " +
                                std::to_string(r.model.accessors.size()));
    return r.model.accessors[static_cast<std::size_t>(index)];
}

View make_view(const AccessorReader& r, int index, const std::string& what) {
    const tinygltf::Accessor& a = find_accessor(r, index, what);
    if (a.sparse.isSparse) throw Unsupported{"sparse accessors"};
    View v;
    v.component_type = a.componentType;
    v.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    v.type = a.type;
    v.normalized = a.normalized;
    v.count = a.count;
    const std::size_t size = component_size(a.componentType);
    if (size == 0) fail(r, index, what, "unknown componentType " + std::to_string(a.componentType));
    if (v.components <= 0) fail(r, index, what, "unknown type");
    if (a.count == 0) fail(r, index, what, "count is 0");
    const std::size_t element = size * static_cast<std::size_t>(v.components);
    if (a.bufferView < 0) {
        v.stride = element;
        return v;
    }
    if (static_cast<std::size_t>(a.bufferView) >= r.model.bufferViews.size())
        fail(r, index, what, "bufferView " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& bv = r.model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= r.model.buffers.size())
        fail(r, index, what, "bufferView " + std::to_string(a.bufferView) + " names a buffer that does not exist");
    const std::vector<unsigned char>& buffer = r.model.buffers[static_cast<std::size_t>(bv.buffer)].data;

    v.stride = bv.byteStride == 0 ? element : bv.byteStride;
    if (bv.byteStride != 0 && (bv.byteStride < element || bv.byteStride % size != 0))
        fail(r, index, what,
             "byteStride " + std::to_string(bv.byteStride) + " does not fit elements of " + std::to_string(element) +
                 " bytes");
    if ((bv.byteOffset + a.byteOffset) % size != 0 || a.byteOffset % size != 0)
        fail(r, index, what, "byteOffset is not a multiple of the component size (" + std::to_string(size) + ")");

    // Everything read must lie in the view, and the view in the buffer.
    if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
        fail(r, index, what,
             "bufferView " + std::to_string(a.bufferView) + " (" + std::to_string(bv.byteLength) + " bytes at " +
                 std::to_string(bv.byteOffset) + ") overruns its buffer of " + std::to_string(buffer.size()) +
                 " bytes");
    // byteOffset + (count − 1) × stride + element ≤ byteLength, without overflow.
    const std::uint64_t last = static_cast<std::uint64_t>(a.count) - 1;
    const bool fits = a.byteOffset <= bv.byteLength && element <= bv.byteLength - a.byteOffset &&
                      last <= (bv.byteLength - a.byteOffset - element) / v.stride;
    if (!fits)
        fail(r, index, what,
             std::to_string(a.count) + " elements of " + std::to_string(element) + " bytes, stride " +
                 std::to_string(v.stride) + ", at byteOffset " + std::to_string(a.byteOffset) + " overrun bufferView " +
                 std::to_string(a.bufferView) + " (" + std::to_string(bv.byteLength) + " bytes)");
    v.data = buffer.data() + bv.byteOffset + a.byteOffset;
    return v;
}

// Component c of element i as a float: normalised integers per glTF 2.0
// §3.11 (signed ones clamped at −1), others converted as they are.
float component(const View& v, std::size_t i, int c) {
    if (!v.data) return 0.0f;
    const unsigned char* p = v.data + i * v.stride + static_cast<std::size_t>(c) * component_size(v.component_type);
    switch (v.component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const auto x = static_cast<float>(static_cast<std::int8_t>(p[0]));
            return v.normalized ? std::max(x / 127.0f, -1.0f) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? p[0] / 255.0f : float(p[0]);
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t s;
            std::memcpy(&s, p, 2);
            return v.normalized ? std::max(s / 32767.0f, -1.0f) : float(s);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t s;
            std::memcpy(&s, p, 2);
            return v.normalized ? s / 65535.0f : float(s);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t u;
            std::memcpy(&u, p, 4);
            return static_cast<float>(u);
        }
        default: return 0.0f;
    }
}

// Whether `semantic` may use this type and component type: the glTF 2.0
// table of §3.7.2.1, widened by KHR_mesh_quantization when the file uses it.
std::string type_problem(const View& v, Semantic semantic, bool quantized) {
    const int t = v.component_type;
    const bool is_float = t == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool small_int = t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                           t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool is_signed = t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_SHORT;
    const bool is_unsigned = t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    bool ok = false;
    int want = 0;
    switch (semantic) {
        case Semantic::Position:
            want = 3;
            ok = is_float || (quantized && small_int);
            break;
        case Semantic::Normal:
            want = 3;
            ok = is_float || (quantized && is_signed && v.normalized);
            break;
        case Semantic::Tangent:
            want = 4;
            ok = is_float || (quantized && is_signed && v.normalized);
            break;
        case Semantic::Texcoord:
            want = 2;
            ok = is_float || (is_unsigned && v.normalized) || (quantized && small_int);
            break;
        case Semantic::Color:
            want = v.components == 3 ? 3 : 4;
            ok = is_float || (is_unsigned && v.normalized);
            break;
        case Semantic::Rotation:
            want = 4;
            ok = is_float || (is_signed && v.normalized);
            break;
        case Semantic::KeyTimes:
            want = 1;
            ok = is_float;
            break;
        case Semantic::KeyVector:
            want = 3;
            ok = is_float;
            break;
        case Semantic::KeyRotation:
            want = 4;
            ok = is_float || (small_int && v.normalized);
            break;
    }
    if (v.components != want)
        return std::string("type ") + type_name(v.type) + " where " +
               (semantic == Semantic::Color ? "VEC3 or VEC4"
                                            : type_name(want == 1   ? TINYGLTF_TYPE_SCALAR
                                                        : want == 2 ? TINYGLTF_TYPE_VEC2
                                                        : want == 3 ? TINYGLTF_TYPE_VEC3
                                                                    : TINYGLTF_TYPE_VEC4)) +
               " is expected";
    if (!ok)
        return std::string(v.normalized ? "normalized " : "") + component_name(t) + " components are not allowed here" +
               (quantized || !small_int || semantic >= Semantic::KeyTimes ? "" : " (without KHR_mesh_quantization)");
    return {};
}

}  // namespace

std::size_t accessor_count(const AccessorReader& r, int index, const std::string& what) {
    return find_accessor(r, index, what).count;
}

std::vector<float> read_floats(const AccessorReader& r, int index, Semantic semantic, const std::string& what) {
    const View v = make_view(r, index, what);
    if (const std::string problem = type_problem(v, semantic, r.quantized); !problem.empty())
        fail(r, index, what, problem);
    const std::size_t out_components = semantic == Semantic::Color ? 4 : static_cast<std::size_t>(v.components);
    std::vector<float> out(v.count * out_components, 1.0f);  // colours without alpha keep 1
    for (std::size_t i = 0; i < v.count; ++i)
        for (int c = 0; c < v.components; ++c) {
            const float x = component(v, i, c);
            if (!std::isfinite(x)) fail(r, index, what, "element " + std::to_string(i) + " is not finite");
            out[i * out_components + static_cast<std::size_t>(c)] = x;
        }
    return out;
}

std::vector<std::uint32_t> read_indices(const AccessorReader& r, int index, std::size_t vertex_count,
                                        const std::string& what) {
    const View v = make_view(r, index, what);
    const int t = v.component_type;
    if (v.components != 1) fail(r, index, what, "indices must be SCALAR");
    if (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(r, index, what, std::string("indices must be unsigned integers, not ") + component_name(t));
    if (v.normalized) fail(r, index, what, "indices must not be normalized");
    if (!v.data) fail(r, index, what, "indices have no bufferView");
    std::vector<std::uint32_t> out(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
        const unsigned char* p = v.data + i * v.stride;
        std::uint32_t x = p[0];
        if (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            std::uint16_t s;
            std::memcpy(&s, p, 2);
            x = s;
        } else if (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            std::memcpy(&x, p, 4);
        }
        if (x >= vertex_count)
            fail(r, index, what,
                 "index " + std::to_string(x) + " (element " + std::to_string(i) +
                     ") is out of range: the primitive has " + std::to_string(vertex_count) + " vertices");
        out[i] = x;
    }
    return out;
}

std::vector<VertexTangent> tangents_of(const std::vector<float>& xyzw) {
    std::vector<VertexTangent> out(xyzw.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = {{xyzw[4 * i], xyzw[4 * i + 1], xyzw[4 * i + 2]}, xyzw[4 * i + 3] < 0.0f ? -1.0f : 1.0f};
    return out;
}

std::vector<Rgba> colors_of(const std::vector<float>& rgba, std::size_t& clamped) {
    std::vector<Rgba> out(rgba.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t c = 0; c < 4; ++c) {
            const float x = rgba[4 * i + c];
            out[i][c] = std::clamp(x, 0.0f, 1.0f);
            clamped += out[i][c] != x;
        }
    return out;
}

std::span<const unsigned char> buffer_view_bytes(const tinygltf::Model& model, int index, const std::string& file,
                                                 const std::string& what) {
    const std::string view_name = what + ": bufferView " + std::to_string(index);
    if (index < 0 || static_cast<std::size_t>(index) >= model.bufferViews.size())
        throw Error(file, view_name + " does not exist");
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(index)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
        throw Error(file, view_name + " names a buffer that does not exist");
    const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        throw Error(file, view_name + " overruns its buffer");
    return std::span(buffer).subspan(view.byteOffset, view.byteLength);
}

}  // namespace sombra::gltf
