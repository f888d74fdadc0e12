// The names the command lines take for IBL methods and built-in environments, apart
// from the passes so that option parsing (and its fuzz target) needs no GPU code.
#include <facet/ibl/ibl_bake.h>
#include <facet/ibl/irradiance.h>
#include <facet/ibl/specular.h>

namespace facet {

std::string builtin_environment_names() { return "builtin:sky, builtin:white"; }

const char* irradiance_method_name(IrradianceMethod method) {
    switch (method) {
        case IrradianceMethod::convolve: return "convolve";
        case IrradianceMethod::riemann: return "riemann";
        case IrradianceMethod::sh9: return "sh9";
        case IrradianceMethod::blur: return "blur";
        case IrradianceMethod::lowmip: return "lowmip";
    }
    return "?";
}

std::optional<IrradianceMethod> parse_irradiance_method(const std::string& name) {
    for (auto m : {IrradianceMethod::convolve, IrradianceMethod::riemann, IrradianceMethod::sh9, IrradianceMethod::blur,
                   IrradianceMethod::lowmip})
        if (name == irradiance_method_name(m)) return m;
    return std::nullopt;
}

const char* specular_method_name(SpecularMethod method) {
    switch (method) {
        case SpecularMethod::automatic: return "automatic";
        case SpecularMethod::importance: return "importance";
        case SpecularMethod::filtered: return "filtered";
        case SpecularMethod::convolve: return "convolve";
        case SpecularMethod::mips: return "mips";
        case SpecularMethod::hybrid: return "hybrid";
    }
    return "?";
}

std::optional<SpecularMethod> parse_specular_method(const std::string& name) {
    for (auto m : {SpecularMethod::automatic, SpecularMethod::importance, SpecularMethod::filtered,
                   SpecularMethod::convolve, SpecularMethod::mips, SpecularMethod::hybrid})
        if (name == specular_method_name(m)) return m;
    return std::nullopt;
}

}  // namespace facet
