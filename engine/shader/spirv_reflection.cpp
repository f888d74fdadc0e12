// Reads a shader's interface from its SPIR-V module (SPIR-V specification, sections 2.3
// "Physical Layout" and 3 "Binary Form"): one pass collects the types, constants,
// decorations and variables by result id, then the resources of set 0, the push-constant
// block and the workgroup size are derived from them. Reading the module, rather than
// glslang's TProgram reflection, gives the same answer for SPIR-V served from the disk
// cache, handed in by a host, or compiled by another tool.
#include <facet/shader/reflection.h>

#include <algorithm>
#include <map>
#include <optional>

namespace facet {

namespace {

// Opcodes, decorations and enumerants used here (SPIR-V specification, section 3).
namespace op {
constexpr uint32_t name = 5, entry_point = 15, execution_mode = 16, type_int = 21, type_float = 22,
                   type_vector = 23, type_matrix = 24, type_image = 25, type_sampler = 26, type_sampled_image = 27,
                   type_array = 28, type_runtime_array = 29, type_struct = 30, type_pointer = 32, constant = 43,
                   constant_composite = 44, spec_constant = 50, spec_constant_composite = 51, variable = 59,
                   decorate = 71, member_decorate = 72, execution_mode_id = 331,
                   type_acceleration_structure = 5341;
}
namespace decoration {
constexpr uint32_t block = 2, buffer_block = 3, row_major = 4, array_stride = 6, matrix_stride = 7, built_in = 11,
                   binding = 33, descriptor_set = 34, offset = 35;
}
constexpr uint32_t built_in_workgroup_size = 25;
constexpr uint32_t mode_local_size = 17, mode_local_size_id = 38;
namespace storage {
constexpr uint32_t uniform_constant = 0, uniform = 2, push_constant = 9, storage_buffer = 12;
}
constexpr uint32_t dim_buffer = 5, dim_subpass_data = 6;

struct Instruction {
    uint32_t opcode = 0;
    std::span<const uint32_t> operands;  // the words after the opcode word
};

struct Member {
    std::optional<uint32_t> offset, matrix_stride;
    bool row_major = false;
};

struct Module {
    std::map<uint32_t, Instruction> types;      // OpType* by result id
    std::map<uint32_t, Instruction> constants;  // OpConstant*, OpSpecConstant* by result id
    std::map<uint32_t, std::string> names;
    std::map<uint32_t, std::map<uint32_t, uint32_t>> decorations;  // id -> decoration -> first literal
    std::map<uint32_t, std::map<uint32_t, Member>> members;        // struct id -> member index -> decorations
    std::vector<Instruction> variables;
    uint32_t execution_model = ~0u;
    std::array<uint32_t, 3> local_size{0, 0, 0};
    std::optional<std::array<uint32_t, 3>> local_size_ids;
};

std::string literal_string(std::span<const uint32_t> words) {
    std::string s;
    for (uint32_t w : words)
        for (int b = 0; b < 4; ++b) {
            const char c = char((w >> (8 * b)) & 0xffu);
            if (c == '\0') return s;
            s.push_back(c);
        }
    return s;
}

// The operands the reader indexes, so that a malformed module is an error, never a read
// past the instruction.
size_t min_type_operands(uint32_t opcode) {
    if (opcode == op::type_image) return 8;
    if (opcode == op::type_int || opcode == op::type_vector || opcode == op::type_matrix ||
        opcode == op::type_array || opcode == op::type_pointer)
        return 3;
    if (opcode == op::type_float || opcode == op::type_sampled_image || opcode == op::type_runtime_array) return 2;
    return 1;
}

bool has(const Module& m, uint32_t id, uint32_t d) {
    auto it = m.decorations.find(id);
    return it != m.decorations.end() && it->second.count(d);
}

std::optional<uint32_t> decoration_value(const Module& m, uint32_t id, uint32_t d) {
    auto it = m.decorations.find(id);
    if (it == m.decorations.end()) return std::nullopt;
    auto found = it->second.find(d);
    if (found == it->second.end()) return std::nullopt;
    return found->second;
}

Result<Module> parse(std::span<const uint32_t> words, const std::string& where) {
    if (words.size() < 5 || words[0] != 0x07230203u) return Error{where + ": not a SPIR-V module"};
    Module m;
    bool entry_seen = false;
    for (size_t at = 5; at < words.size();) {
        const uint32_t count = words[at] >> 16, opcode = words[at] & 0xffffu;
        if (count == 0 || at + count > words.size())
            return Error{where + ": truncated SPIR-V instruction at word " + std::to_string(at)};
        const Instruction in{opcode, words.subspan(at + 1, count - 1)};
        const auto& o = in.operands;
        at += count;
        switch (opcode) {
            case op::name:
                if (!o.empty()) m.names[o[0]] = literal_string(o.subspan(1));
                break;
            case op::entry_point:
                if (!entry_seen && !o.empty()) m.execution_model = o[0];
                entry_seen = true;
                break;
            case op::execution_mode:
                if (o.size() >= 5 && o[1] == mode_local_size) m.local_size = {o[2], o[3], o[4]};
                break;
            case op::execution_mode_id:
                if (o.size() >= 5 && o[1] == mode_local_size_id) m.local_size_ids = std::array{o[2], o[3], o[4]};
                break;
            case op::decorate:
                if (o.size() >= 2) m.decorations[o[0]][o[1]] = o.size() >= 3 ? o[2] : 0;
                break;
            case op::member_decorate:
                if (o.size() >= 3) {
                    Member& member = m.members[o[0]][o[1]];
                    if (o[2] == decoration::offset && o.size() >= 4) member.offset = o[3];
                    if (o[2] == decoration::matrix_stride && o.size() >= 4) member.matrix_stride = o[3];
                    if (o[2] == decoration::row_major) member.row_major = true;
                }
                break;
            case op::constant:
            case op::constant_composite:
            case op::spec_constant:
            case op::spec_constant_composite:
                if (o.size() >= 2) m.constants[o[1]] = in;
                break;
            case op::variable:
                if (o.size() >= 3) m.variables.push_back(in);
                break;
            default:
                if ((opcode >= 19 && opcode <= 39) || opcode == op::type_acceleration_structure) {
                    if (o.size() < min_type_operands(opcode))
                        return Error{where + ": malformed SPIR-V type at word " + std::to_string(at - count)};
                    m.types[o[0]] = in;
                }
                break;
        }
    }
    if (!entry_seen) return Error{where + ": the SPIR-V module has no entry point"};
    return m;
}

// A scalar constant's value (a specialisation constant's default, which is what a
// pipeline built without VkSpecializationInfo uses).
std::optional<uint32_t> constant_value(const Module& m, uint32_t id) {
    auto it = m.constants.find(id);
    if (it == m.constants.end()) return std::nullopt;
    const Instruction& c = it->second;
    if ((c.opcode != op::constant && c.opcode != op::spec_constant) || c.operands.size() < 3) return std::nullopt;
    return c.operands[2];
}

const Instruction* type(const Module& m, uint32_t id) {
    auto it = m.types.find(id);
    return it == m.types.end() ? nullptr : &it->second;
}

// Bytes a value of type `id` occupies in a block with explicit layout; `member` carries
// a matrix's stride and majorness, which SPIR-V decorates on the enclosing struct.
Result<uint32_t> layout_size(const Module& m, uint32_t id, const Member* member, const std::string& where,
                             int depth = 0) {
    const Instruction* t = type(m, id);
    if (depth > 32) return Error{where + ": push constant types nest too deeply"};
    if (!t) return Error{where + ": push constant member of unknown type %" + std::to_string(id)};
    const auto& o = t->operands;
    switch (t->opcode) {
        case op::type_int:
        case op::type_float: return o[1] / 8;
        case op::type_vector: {
            auto component = layout_size(m, o[1], nullptr, where, depth + 1);
            if (!component) return component;
            return *component * o[2];
        }
        case op::type_matrix: {
            if (!member || !member->matrix_stride) return Error{where + ": push constant matrix without a MatrixStride"};
            const Instruction* column = type(m, o[1]);
            const uint32_t rows = column && column->opcode == op::type_vector ? column->operands[2] : 0;
            return *member->matrix_stride * (member->row_major ? rows : o[2]);
        }
        case op::type_array: {
            auto length = constant_value(m, o[2]);
            auto stride = decoration_value(m, id, decoration::array_stride);
            if (!length || !stride) return Error{where + ": push constant array without a length or ArrayStride"};
            return *length * *stride;
        }
        case op::type_struct: {
            uint32_t end = 0;
            for (uint32_t i = 1; i < o.size(); ++i) {
                auto mit = m.members.find(id);
                const Member* mm = nullptr;
                if (mit != m.members.end())
                    if (auto f = mit->second.find(i - 1); f != mit->second.end()) mm = &f->second;
                if (!mm || !mm->offset) return Error{where + ": push constant member without an Offset"};
                auto size = layout_size(m, o[i], mm, where, depth + 1);
                if (!size) return size;
                end = std::max(end, *mm->offset + *size);
            }
            return end;
        }
        default: return Error{where + ": push constant member of a type Facet cannot size"};
    }
}

// The descriptor type of a resource variable's (array-stripped) type, or an error.
Result<VkDescriptorType> descriptor_type(const Module& m, uint32_t storage_class, uint32_t type_id,
                                         const std::string& where) {
    const Instruction* t = type(m, type_id);
    if (!t) return Error{where + ": of unknown type"};
    if (storage_class == storage::storage_buffer) return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    if (storage_class == storage::uniform) {
        if (has(m, type_id, decoration::buffer_block)) return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        if (has(m, type_id, decoration::block)) return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        return Error{where + ": a uniform that is not a block"};
    }
    switch (t->opcode) {
        case op::type_sampler: return VK_DESCRIPTOR_TYPE_SAMPLER;
        case op::type_acceleration_structure: return VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
        case op::type_sampled_image: {
            const Instruction* image = type(m, t->operands[1]);
            if (image && image->opcode == op::type_image && image->operands[2] == dim_buffer) return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
            return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        }
        case op::type_image: {
            const uint32_t dim = t->operands[2], sampled = t->operands[6];
            if (dim == dim_subpass_data) return VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
            if (sampled == 1)
                return dim == dim_buffer ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
            if (sampled == 2)
                return dim == dim_buffer ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
            return Error{where + ": an image whose use (sampled or storage) is known only at run time"};
        }
        default: return Error{where + ": a resource of a type Facet cannot bind"};
    }
}

VkShaderStageFlags stage_of(uint32_t execution_model) {
    switch (execution_model) {
        case 0: return VK_SHADER_STAGE_VERTEX_BIT;
        case 1: return VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
        case 2: return VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
        case 3: return VK_SHADER_STAGE_GEOMETRY_BIT;
        case 4: return VK_SHADER_STAGE_FRAGMENT_BIT;
        case 5: return VK_SHADER_STAGE_COMPUTE_BIT;
        default: return 0;
    }
}

// gl_WorkGroupSize as a constant decorated BuiltIn WorkgroupSize overrides LocalSize
// (SPIR-V specification, BuiltIn WorkgroupSize); glslang emits one for local_size_*_id.
Result<std::array<uint32_t, 3>> workgroup_size(const Module& m, const std::string& where) {
    auto from_ids = [&](std::span<const uint32_t> ids) -> Result<std::array<uint32_t, 3>> {
        std::array<uint32_t, 3> size{};
        for (int i = 0; i < 3; ++i) {
            auto v = constant_value(m, ids[i]);
            if (!v) return Error{where + ": the workgroup size is not a constant"};
            size[i] = *v;
        }
        return size;
    };
    for (const auto& [id, decorations] : m.decorations) {
        auto b = decorations.find(decoration::built_in);
        if (b == decorations.end() || b->second != built_in_workgroup_size) continue;
        auto c = m.constants.find(id);
        if (c == m.constants.end() || c->second.operands.size() < 5)
            return Error{where + ": gl_WorkGroupSize is not a constant vector"};
        return from_ids(c->second.operands.subspan(2, 3));
    }
    if (m.local_size_ids) return from_ids(*m.local_size_ids);
    return m.local_size;
}

}  // namespace

const DescriptorBinding* ShaderReflection::find(uint32_t binding) const {
    for (const DescriptorBinding& b : bindings)
        if (b.binding == binding) return &b;
    return nullptr;
}

uint32_t ShaderReflection::descriptor_count() const {
    uint32_t n = 0;
    for (const DescriptorBinding& b : bindings) n += b.count;
    return n;
}

Result<ShaderReflection> reflect_spirv(std::span<const uint32_t> words, std::string_view shader_name) {
    const std::string shader(shader_name);
    auto parsed = parse(words, shader);
    if (!parsed) return parsed.error();
    const Module& m = *parsed;
    ShaderReflection r;
    r.stages = stage_of(m.execution_model);
    if (!r.stages) return Error{shader + ": an entry point of an execution model Facet does not run"};

    for (const Instruction& v : m.variables) {
        const uint32_t pointer_id = v.operands[0], id = v.operands[1], storage_class = v.operands[2];
        if (storage_class != storage::uniform_constant && storage_class != storage::uniform &&
            storage_class != storage::push_constant && storage_class != storage::storage_buffer)
            continue;
        const Instruction* pointer = type(m, pointer_id);
        if (!pointer || pointer->opcode != op::type_pointer) return Error{shader + ": a variable that is not a pointer"};
        uint32_t type_id = pointer->operands[2];
        std::string name = m.names.count(id) ? m.names.at(id) : "";
        if (name.empty() && m.names.count(type_id)) name = m.names.at(type_id);  // an anonymous block
        const std::string where = shader + ": '" + name + "'";

        if (storage_class == storage::push_constant) {
            auto size = layout_size(m, type_id, nullptr, where);
            if (!size) return size.error();
            r.push_constant_bytes = std::max(r.push_constant_bytes, (*size + 3u) & ~3u);
            continue;
        }
        DescriptorBinding b;
        b.name = name;
        // Arrays of resources: one binding of `count` descriptors.
        int dimensions = 0;
        for (const Instruction* t = type(m, type_id); t && (t->opcode == op::type_array ||
                                                           t->opcode == op::type_runtime_array);
             t = type(m, type_id)) {
            if (++dimensions > 8) return Error{where + ": an array of descriptors nested too deeply"};
            if (t->opcode == op::type_runtime_array)
                return Error{where + ": an unsized array of descriptors (Facet pushes a fixed set)"};
            auto length = constant_value(m, t->operands[2]);
            if (!length) return Error{where + ": an array of descriptors whose length is not a constant"};
            b.count *= *length;
            type_id = t->operands[1];
        }
        auto kind = descriptor_type(m, storage_class, type_id, where);
        if (!kind) return kind.error();
        b.type = *kind;
        auto binding = decoration_value(m, id, decoration::binding);
        if (!binding) return Error{where + ": a resource without layout(binding = ...)"};
        b.binding = *binding;
        if (auto set = decoration_value(m, id, decoration::descriptor_set); set && *set != 0)
            return Error{where + ": in descriptor set " + std::to_string(*set) + "; Facet pushes set 0 only"};
        if (const DescriptorBinding* same = r.find(b.binding)) {
            // GLSL lets two variables alias one binding; they must agree on what it holds.
            if (same->type != b.type || same->count != b.count)
                return Error{where + ": binding " + std::to_string(b.binding) + " declared twice, as " +
                             descriptor_type_name(same->type) + " and " + descriptor_type_name(b.type)};
            continue;
        }
        r.bindings.push_back(std::move(b));
    }
    std::sort(r.bindings.begin(), r.bindings.end(),
              [](const DescriptorBinding& a, const DescriptorBinding& b) { return a.binding < b.binding; });
    if (r.stages == VK_SHADER_STAGE_COMPUTE_BIT) {
        auto size = workgroup_size(m, shader);
        if (!size) return size.error();
        r.workgroup_size = *size;
        if (r.workgroup_size[0] == 0 || r.workgroup_size[1] == 0 || r.workgroup_size[2] == 0)
            return Error{shader + ": a compute shader without a workgroup size (layout(local_size_x = ...) in)"};
    }
    return r;
}

Result<ShaderReflection> merge_stages(const ShaderReflection& a, const ShaderReflection& b, std::string_view name) {
    ShaderReflection r = a;
    r.stages |= b.stages;
    r.push_constant_bytes = std::max(a.push_constant_bytes, b.push_constant_bytes);
    r.workgroup_size = {0, 0, 0};
    for (const DescriptorBinding& binding : b.bindings) {
        if (const DescriptorBinding* same = r.find(binding.binding)) {
            if (same->type != binding.type || same->count != binding.count)
                return Error{std::string(name) + ": binding " + std::to_string(binding.binding) + " is " +
                             descriptor_type_name(same->type) + " ('" + same->name + "') in one stage and " +
                             descriptor_type_name(binding.type) + " ('" + binding.name + "') in the other"};
            continue;
        }
        r.bindings.push_back(binding);
    }
    std::sort(r.bindings.begin(), r.bindings.end(),
              [](const DescriptorBinding& x, const DescriptorBinding& y) { return x.binding < y.binding; });
    return r;
}

const char* descriptor_type_name(VkDescriptorType type) {
    switch (type) {
        case VK_DESCRIPTOR_TYPE_SAMPLER: return "sampler";
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return "combined image sampler";
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE: return "sampled image";
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: return "storage image";
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER: return "uniform texel buffer";
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER: return "storage texel buffer";
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return "uniform buffer";
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return "storage buffer";
        case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT: return "input attachment";
        case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR: return "acceleration structure";
        default: return "descriptor of another type";
    }
}

}  // namespace facet
