// BakedEnvironment::load: a saved bake back into GPU images without baking. bake.json is
// the description; every file it names is read and checked against it (present, whole,
// the recorded size, levels and format), and an error names the file that is not.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <facet/gpu/context.h>
#include <facet/ibl/baked_environment.h>
#include <facet/io/environment_image.h>
#include <facet/io/ktx2.h>
#include "ibl/baked_outputs.h"
#include "io/json_reader.h"
#include "core/guarded.h"

namespace facet {

namespace {

namespace fs = std::filesystem;
using A = BakedEnvironmentAccess;

// A value of bake.json that is missing or of the wrong type: an error naming the file
// and the key. Thrown inside load() only, caught there.
struct Missing {
    std::string key;
};

struct Reader {
    const JsonValue& v;
    std::string where;
    const JsonValue& at(const char* key) const {
        const JsonValue* m = v.find(key);
        if (!m) throw Missing{where + key};
        return *m;
    }
    double number(const char* key) const {
        const JsonValue& m = at(key);
        if (!m.is_number()) throw Missing{where + key + " (a number)"};
        return m.number();
    }
    uint32_t count(const char* key) const {
        const double d = number(key);
        if (!(d >= 0 && d <= 4294967295.0) || d != std::floor(d)) throw Missing{where + key + " (a count)"};
        return uint32_t(d);
    }
    bool flag(const char* key) const {
        const JsonValue& m = at(key);
        if (m.type() != JsonValue::Type::boolean) throw Missing{where + key + " (true or false)"};
        return m.boolean();
    }
    std::string text(const char* key) const {
        const JsonValue& m = at(key);
        if (!m.is_string()) throw Missing{where + key + " (a string)"};
        return m.string();
    }
    Reader child(const char* key) const {
        const JsonValue& m = at(key);
        if (!m.is_object()) throw Missing{where + key + " (an object)"};
        return {m, where + key + "."};
    }
    const JsonValue* optional(const char* key) const { return v.find(key); }
};

Result<std::string> read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path + ": cannot read (" + (fs::exists(path) ? "permission denied?" : "missing") + ")"};
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The bake's files, each read whole once and shown to the caller's check before use.
struct BakeFiles {
    std::string dir;
    const BakedEnvironment::FileCheck& check;

    std::string path(const std::string& name) const { return (fs::path(dir) / name).string(); }
    Result<std::vector<std::byte>> read(const std::string& name) const {
        const std::string p = path(name);
        std::ifstream in(p, std::ios::binary | std::ios::ate);
        if (!in) return Error{p + ": cannot read (" + (fs::exists(p) ? "permission denied?" : "missing") + ")"};
        const std::streamoff size = in.tellg();
        std::vector<std::byte> bytes(size > 0 ? size_t(size) : 0);
        in.seekg(0);
        in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!in) return Error{p + ": read failed"};
        if (check)
            if (Status ok = check(name, bytes); !ok) return ok.error();
        return bytes;
    }
    Result<std::string> text(const std::string& name) const {
        auto bytes = read(name);
        if (!bytes) return bytes.error();
        return std::string(reinterpret_cast<const char*>(bytes->data()), bytes->size());
    }
};

// One KTX2 output: read, checked against its bake.json entry, uploaded.
Result<Image> load_cube(Context& context, const BakeFiles& files, const Reader& entry, bool cube, VkFormat& format,
                        const char* name) {
    const std::string path = files.path(entry.text("file"));
    auto bytes = files.read(entry.text("file"));
    if (!bytes) return bytes.error();
    auto k = parse_ktx2(*bytes, path);
    bytes->clear();
    bytes->shrink_to_fit();
    if (!k) return k.error();
    const uint32_t size = entry.count("size"), levels = entry.count("mip_levels");
    format = parse_format_name(entry.text("format"));
    auto mismatch = [&](const std::string& what, uint64_t file, uint64_t json) {
        return Error{path + ": " + what + " " + std::to_string(file) + ", but bake.json says " + std::to_string(json)};
    };
    if (format == VK_FORMAT_UNDEFINED) return Error{path + ": bake.json gives an unsupported format for it"};
    if (k->format != format)
        return Error{path + ": format " + format_name(k->format) + ", but bake.json says " + format_name(format)};
    if (k->width != size || k->height != size) return mismatch("size", k->width, size);
    if (k->levels != levels) return mismatch("levels", k->levels, levels);
    if (k->faces != (cube ? 6u : 1u)) return mismatch("faces", k->faces, cube ? 6 : 1);
    ImageDesc desc;
    desc.format = format;
    desc.width = desc.height = size;
    desc.mip_levels = levels;
    desc.array_layers = cube ? 6 : 1;
    desc.cube = cube;
    return make_baked_image(context, desc, k->level_data, std::string("loaded ") + name);
}

Result<std::vector<float>> load_sh9(const BakeFiles& files) {
    const std::string path = files.path("sh9.json");
    auto text = files.text("sh9.json");
    if (!text) return text.error();
    auto doc = parse_json(*text);
    if (!doc) return Error{path + ": " + doc.error().message};
    const JsonValue* coefficients = doc->find("coefficients");
    const JsonValue* window = doc->find("window_h");
    if (!coefficients || !coefficients->is_array() || coefficients->items().size() != 9 || !window ||
        !window->is_number())
        return Error{path + ": expected 9 coefficients and window_h"};
    std::vector<float> sh9(40, 0.0f);
    for (size_t i = 0; i < 9; ++i) {
        const JsonValue& rgb = coefficients->items()[i];
        if (!rgb.is_array() || rgb.items().size() != 3) return Error{path + ": coefficient " + std::to_string(i) + " is not RGB"};
        for (size_t c = 0; c < 3; ++c) {
            if (!rgb.items()[c].is_number()) return Error{path + ": coefficient " + std::to_string(i) + " is not RGB"};
            sh9[i * 4 + c] = float(rgb.items()[c].number());
        }
    }
    sh9[36] = float(window->number());
    return sh9;
}

Result<BakedEnvironment> load_dir(Context& context, const std::string& dir, const BakedEnvironment::FileCheck& check) {
    const BakeFiles files{dir, check};
    const std::string json_path = files.path("bake.json");
    auto text = files.text("bake.json");
    if (!text) return text.error();
    auto doc = parse_json(*text);
    if (!doc) return Error{json_path + ": " + doc.error().message};
    if (!doc->is_object()) return Error{json_path + ": not a JSON object"};
    BakedEnvironment out = A::make(context);
    BakeMetadata& meta = A::metadata(out);
    const Reader root{*doc, ""};
    meta.version = root.text("version");
    meta.device = root.text("device");
    meta.bake_key = root.text("bake_key");
    const Reader input = root.child("input");
    meta.input = input.text("name");
    meta.content_hash = input.text("content_hash");
    meta.width = input.count("width");
    meta.height = input.count("height");
    meta.source_width = input.count("source_width");
    meta.source_height = input.count("source_height");
    if (input.optional("max_env_width")) meta.max_env_width = input.count("max_env_width");
    meta.sanitized_texels = uint64_t(input.number("sanitized_texels"));
    for (const char* list : {"warnings", "format_notes"})
        if (const JsonValue* w = root.optional(list); w && w->is_array())
            for (const JsonValue& item : w->items())
                (std::string(list) == "warnings" ? meta.warnings : meta.format_notes).push_back(item.string());
    if (const JsonValue* v = root.optional("preview_exposure"); v && v->is_number()) meta.preview_exposure = float(v->number());

    // The environment, as baked (its content hash must be the one recorded).
    const Reader env = root.child("environment");
    const std::string env_path = files.path(env.text("file"));
    if (check) {
        // The image reader opens the file itself: the check reads it first (the one file
        // read twice, from the page cache the second time).
        if (auto bytes = files.read(env.text("file")); !bytes) return bytes.error();
    }
    auto image = load_environment(env_path, {false, kMaxEnvironmentSide});
    if (!image) return image.error();
    if (image->width != meta.width || image->height != meta.height)
        return Error{env_path + ": " + std::to_string(image->width) + "x" + std::to_string(image->height) +
                     ", but bake.json says " + std::to_string(meta.width) + "x" + std::to_string(meta.height)};
    ImageDesc env_desc;
    env_desc.width = image->width;
    env_desc.height = image->height;
    {
        Levels levels(1, std::vector<std::byte>(image->rgba.size() * sizeof(float)));
        std::memcpy(levels[0].data(), image->rgba.data(), levels[0].size());
        A::environment(out) = make_baked_image(context, env_desc, levels, "loaded environment");
    }
    IblSettings& s = meta.settings;
    s.want_irradiance = s.want_specular = s.want_lut = false;
    auto cube = load_cube(context, files, root.child("environment_cube"), true, meta.cube_format, "environment cube");
    if (!cube) return cube.error();
    A::cube(out) = std::move(*cube);
    s.cube_size = A::cube(out).desc().width;
    if (root.optional("specular")) {
        const Reader spec = root.child("specular");
        auto image = load_cube(context, files, spec, true, meta.specular_format, "specular");
        if (!image) return image.error();
        A::specular(out) = std::move(*image);
        s.want_specular = true;
        s.specular.levels = A::specular(out).desc().mip_levels;
        const auto method = parse_specular_method(spec.text("method"));
        if (!method) return Error{json_path + ": unknown specular method '" + spec.text("method") + "'"};
        s.specular.method = *method;
        s.specular.sample_count = spec.count("sample_count");
        s.specular.automatic_convolve_from = float(spec.number("automatic_convolve_from"));
        // Written since bake revision 6; older bakes made no hybrid level.
        if (spec.optional("hybrid_sample_count")) s.specular.hybrid_sample_count = spec.count("hybrid_sample_count");
        if (spec.optional("excess_factor")) s.specular.excess_factor = float(spec.number("excess_factor"));
        // Written since bake revision 8; older bakes sampled the residual at full size.
        s.specular.hybrid_half_size_residual =
            spec.optional("hybrid_half_size_residual") && spec.flag("hybrid_half_size_residual");
        s.specular.min_roughness = float(spec.number("min_roughness"));
        meta.first_specular_level = spec.count("first_level");
        const JsonValue& levels = spec.at("levels");
        if (!levels.is_array() || levels.items().size() != s.specular.levels)
            return Error{json_path + ": specular.levels lists " + std::to_string(levels.items().size()) +
                         " levels, but specular.ktx2 has " + std::to_string(s.specular.levels)};
        for (const JsonValue& level : levels.items()) meta.roughness.push_back(float(Reader{level, "specular.levels[]."}.number("roughness")));
    }
    if (root.optional("irradiance")) {
        const Reader irr = root.child("irradiance");
        auto image = load_cube(context, files, irr, true, meta.irradiance_format, "irradiance");
        if (!image) return image.error();
        A::irradiance(out) = std::move(*image);
        s.want_irradiance = true;
        s.irradiance.size = A::irradiance(out).desc().width;
        const auto method = parse_irradiance_method(irr.text("method"));
        if (!method) return Error{json_path + ": unknown irradiance method '" + irr.text("method") + "'"};
        s.irradiance.method = *method;
        s.irradiance.source_size = irr.count("source_size");
        s.irradiance.riemann_step = float(irr.number("riemann_step"));
        s.irradiance.blur_sigma = float(irr.number("blur_sigma"));
        s.irradiance.lowmip_size = irr.count("lowmip_size");
        if (s.irradiance.method == IrradianceMethod::sh9) {
            auto sh9 = load_sh9(files);
            if (!sh9) return sh9.error();
            A::sh9(out) = std::move(*sh9);
        }
    }
    if (root.optional("brdf_lut")) {
        const Reader lut = root.child("brdf_lut");
        VkFormat format;
        auto image = load_cube(context, files, lut, false, format, "brdf lut");
        if (!image) return image.error();
        A::lut(out) = std::move(*image);
        meta.lut_format = format;
        s.want_lut = true;
        s.lut.size = A::lut(out).desc().width;
        s.lut.sample_count = lut.count("samples");
        const auto brdf = parse_brdf_model(lut.text("brdf"));
        if (!brdf) throw Missing{"brdf_lut.brdf (gltf or thesis; a bake older than the BRDF models must be made again)"};
        s.lut.brdf = *brdf;
    }
    const Reader lights = root.child("lights");
    meta.light_split_level = lights.count("split_level");
    meta.extracted_power_fraction = lights.number("extracted_power_fraction");
    const JsonValue& disks = lights.at("disks");
    if (!disks.is_array()) throw Missing{"lights.disks (an array)"};
    for (const JsonValue& d : disks.items()) {
        const Reader r{d, "lights.disks[]."};
        DiskLight l;
        auto vec3 = [&](const char* key) {
            const JsonValue& a = r.at(key);
            if (!a.is_array() || a.items().size() != 3) throw Missing{r.where + key + " (3 numbers)"};
            glm::vec3 v;
            for (int c = 0; c < 3; ++c) {
                if (!a.items()[size_t(c)].is_number()) throw Missing{r.where + key + " (3 numbers)"};
                v[c] = float(a.items()[size_t(c)].number());
            }
            return v;
        };
        l.direction = vec3("direction");
        l.radiance = vec3("radiance");
        l.angular_radius = float(r.number("angular_radius"));
        l.solid_angle = float(r.number("solid_angle"));
        l.texels = r.count("texels");
        l.power_fraction = r.number("power_fraction");
        A::lights(out).push_back(l);
    }
    // The renderers shade only the disks' specular: their diffuse must be in the irradiance.
    if (!A::lights(out).empty() && !lights.optional("irradiance"))
        throw Missing{"lights.irradiance (a bake older than the irradiance of the whole environment must be made again)"};
    if (const JsonValue* passes = root.optional("passes"); passes && passes->is_array())
        for (const JsonValue& p : passes->items()) {
            const Reader r{p, "passes[]."};
            meta.timings.push_back({r.text("name"), r.number("gpu_time_ms")});
        }
    A::cube_sampler(out) = or_throw(Sampler::create(context, VK_FILTER_LINEAR, true, false, "baked cube sampler"));
    return out;
}

}  // namespace

Result<std::string> saved_bake_key(const std::string& dir) {
    const std::string json_path = (fs::path(dir) / "bake.json").string();
    auto text = read_text(json_path);
    if (!text) return text.error();
    auto doc = parse_json(*text);
    if (!doc) return Error{json_path + ": " + doc.error().message};
    const JsonValue* key = doc->find("bake_key");
    if (!key || !key->is_string()) return Error{json_path + ": bake_key is missing or malformed"};
    return key->string();
}

Result<BakedEnvironment> BakedEnvironment::load(Context& context, const std::string& dir, const FileCheck& check) {
    try {
        return load_dir(context, dir, check);
    } catch (const Missing& missing) {
        return Error{(fs::path(dir) / "bake.json").string() + ": " + missing.key + " is missing or malformed"};
    } catch (const VulkanError& error) {
        return Error{dir + ": " + error.what(), error.result()};
    } catch (const std::bad_alloc&) {
        return Error{dir + ": out of host memory"};
    }
}

}  // namespace facet
