#version 460
// Ground truth inside the engine: the reflectance equation integrated per pixel by Monte
// Carlo over the whole environment, with no split sum and no prefiltering. Each batch
// takes one BRDF sample (GGX for the specular lobe, cosine for the diffuse one) and one
// environment sample (texels in proportion to luminance x solid angle) per pixel and
// combines them with the balance heuristic (Veach and Guibas 1995); punctual lights are
// added in closed form. The BRDF is the forward pass's model (facet/shading.glsl's
// facet_reflect_light, glTF's or the thesis'). The environment is piecewise constant per texel,
// as in the brute-force sums of the tests.
// KHR_materials_iridescence's film, KHR_materials_anisotropy's stretch and KHR_materials_sheen's
// layer are shaded wherever their views say so; the sheen's lobe (wide, strongest at grazing
// angles) has a strategy of its own: directions uniform over the hemisphere.
#define FACET_IRIDESCENCE 1
#define FACET_ANISOTROPY 1
#define FACET_SHEEN 1
#define FACET_TRANSMISSION 1
#include "facet/shading.glsl"
#include "ibl/equirect.glsl"
#include "ibl/sampling.glsl"
#include "render/packed_light.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D normal_view;     // world normal, a = coverage
layout(binding = 1) uniform sampler2D position_view;   // world position
layout(binding = 2) uniform sampler2D basecolor_view;
layout(binding = 3) uniform sampler2D metallic_view;
layout(binding = 4) uniform sampler2D roughness_view;
layout(binding = 5) uniform sampler2D f0_view;          // rgb F0, a specular weight
layout(binding = 6) uniform sampler2D emissive_view;
layout(binding = 7, std430) readonly buffer Radiance { vec4 radiance[]; };  // W x H, row 0 = top
// marginal[H] (row CDF, last = 1), then conditional[H * W] (per-row column CDFs),
// then pdf_texel[H * W]: probability of picking each texel.
layout(binding = 8, std430) readonly buffer Distribution { float distribution[]; };
layout(binding = 9, std430) readonly buffer Lights { PackedLight lights[]; };  // punctual only
layout(binding = 10, rgba32f) uniform image2D accumulation;  // rgb sum, a = samples
layout(binding = 11, rgba32f) uniform image2D moments;       // x: sum of Y, y: sum of Y^2 (per batch mean)
layout(binding = 12) uniform sampler2D clearcoat_view;         // KHR_materials_clearcoat: weight, roughness
layout(binding = 13) uniform sampler2D clearcoat_normal_view;  // the clear coat's normal
layout(binding = 14) uniform sampler2D iridescence_view;       // KHR_materials_iridescence: weight, ior, thickness
layout(binding = 15) uniform sampler2D anisotropy_view;        // KHR_materials_anisotropy: direction, strength
layout(binding = 16) uniform sampler2D sheen_view;             // KHR_materials_sheen: colour, roughness
layout(binding = 17) uniform sampler2D transmission_view;      // KHR_materials_transmission: weight, lobe roughness

layout(push_constant) uniform Params {
    vec4 camera_position;  // xyz
    uvec4 env;             // width, height, light count, flags (1: the thesis' BRDF model, else glTF's)
    uvec4 batch;           // samples in this batch, first sample index
    vec4 scale;            // x: environment intensity
} params;

uint hash(uint x) {
    // PCG-style integer hash (O'Neill 2014 output function).
    x = x * 747796405u + 2891336453u;
    uint word = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
    return (word >> 22u) ^ word;
}

float random(inout uint state) {
    state = hash(state);
    return float(state >> 8) * (1.0 / 16777216.0);
}

uvec2 env_size() { return params.env.xy; }

// Smallest index i of cdf[first .. first + count) with cdf[i] > u.
uint search(uint first, uint count, float u) {
    uint lo = 0u, hi = count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (distribution[first + mid] > u) hi = mid;
        else lo = mid + 1u;
    }
    return lo;
}

float env_pdf(vec3 d) {
    uvec2 t = equirect_texel(d, env_size());
    uint W = params.env.x, H = params.env.y;
    return distribution[H + H * W + t.y * W + t.x] / equirect_texel_solid_angle(t.y, env_size());
}

vec3 env_radiance(vec3 d) {
    uvec2 t = equirect_texel(d, env_size());
    return radiance[t.y * params.env.x + t.x].rgb * params.scale.x;
}

struct Surface {
    FacetSurface shading;
    vec3 v;
    float NdotV;
    float p_specular;  // probability of sampling the specular lobe (of the surface below a clear coat)
    float p_coat;      // probability of sampling the clear coat's lobe
    float p_sheen;     // probability of sampling the sheen's (uniform over the hemisphere)
    float p_transmission;  // probability of sampling the transmitted lobe (below the surface)
};

// BRDF x cos x radiance arriving along l (facet/shading.glsl's composition).
vec3 reflected(Surface s, vec3 l, vec3 radiance, bool punctual) {
    vec3 diffuse, specular;
    facet_reflect_light(s.shading, s.v, s.NdotV, l, radiance, punctual, diffuse, specular);
    return diffuse + specular;
}

// Density of the BRDF sampling strategy over solid angle.
float reflection_pdf(Surface s, vec3 l);

// The transmitted lobe is the specular lobe mirrored below the surface (facet/transmission.glsl):
// sampled as the reflection of GGX's normals at its roughness, mirrored, the same density.
float brdf_pdf(Surface s, vec3 l) {
    vec3 n = s.shading.n;
    if (s.p_transmission > 0.0 && dot(n, l) < 0.0) {
        vec3 h = normalize(s.v + facet_mirrored(n, l));
        return s.p_transmission *
               ggx_sample_pdf(clamp(dot(n, h), 0.0, 1.0), dot(h, s.v), s.shading.transmission_roughness);
    }
    return (1.0 - s.p_transmission) * reflection_pdf(s, l);
}

float reflection_pdf(Surface s, vec3 l) {
    vec3 n = s.shading.n;
    float NdotL = dot(n, l);
    float coat_NdotL = s.p_coat > 0.0 ? dot(s.shading.clearcoat_n, l) : 0.0;
    if (NdotL <= 0.0 && coat_NdotL <= 0.0) return 0.0;
    vec3 h = normalize(s.v + l);
    float pdf = 0.0;
    if (NdotL > 0.0) {
        float specular = ggx_sample_pdf(clamp(dot(n, h), 0.0, 1.0), dot(h, s.v), s.shading.roughness);
        pdf = s.p_specular * specular + (1.0 - s.p_specular) * NdotL / PI;
    }
    pdf *= 1.0 - s.p_coat;
    if (coat_NdotL > 0.0)
        pdf += s.p_coat * ggx_sample_pdf(clamp(dot(s.shading.clearcoat_n, h), 0.0, 1.0), dot(h, s.v),
                                         s.shading.clearcoat_roughness);
    return (1.0 - s.p_sheen) * pdf + (NdotL > 0.0 ? s.p_sheen / (2.0 * PI) : 0.0);
}

// Randomised quasi-Monte Carlo: sample i of a batch takes the i-th point of a 7-D
// Kronecker sequence (Roberts 2018: alpha_k = 1 / phi^k, phi^8 = phi + 1), shifted by a
// random offset per pixel and batch (Cranley-Patterson). Each batch stays an unbiased,
// independent estimate, so batch means still measure the noise; within a batch the
// points are spread evenly, which converges faster than independent random numbers.
const float PHI7 = 1.0905077326652577;
float kronecker(uint i, uint dim, float shift) {
    float alpha = 1.0 / pow(PHI7, float(dim + 1u));
    return fract(shift + float(i + 1u) * alpha);
}

vec3 sample_reflection(Surface s, vec3 u);

// A direction from the BRDF's lobes; zero where a lobe's sample falls on the side it does not
// shade (where a transmission makes the side below the surface its lobe's alone).
vec3 sample_brdf(Surface s, vec3 u) {
    vec3 n = s.shading.n;
    if (u.z < s.p_transmission) {
        vec3 t, b;
        facet_tangent_frame(n, t, b);
        vec3 h = mat3(t, b, n) * importance_sample_ggx_tangent(u.xy, s.shading.transmission_roughness);
        vec3 l = facet_mirrored(n, reflect(-s.v, h));
        return dot(n, l) < 0.0 ? l : vec3(0.0);
    }
    u.z = (u.z - s.p_transmission) / (1.0 - s.p_transmission);
    vec3 l = sample_reflection(s, u);
    return s.p_transmission > 0.0 && dot(n, l) < 0.0 ? vec3(0.0) : l;
}

vec3 sample_reflection(Surface s, vec3 u) {
    if (u.z < s.p_sheen) {
        // Uniform over the hemisphere of n: cos theta = u.x.
        vec3 t, b;
        facet_tangent_frame(s.shading.n, t, b);
        float r = sqrt(max(1.0 - u.x * u.x, 0.0));
        return t * (r * cos(2.0 * PI * u.y)) + b * (r * sin(2.0 * PI * u.y)) + s.shading.n * u.x;
    }
    u.z = (u.z - s.p_sheen) / (1.0 - s.p_sheen);
    if (u.z < s.p_coat) {
        // The clear coat's lobe, around its own normal.
        vec3 ct, cb;
        facet_tangent_frame(s.shading.clearcoat_n, ct, cb);
        vec3 h = mat3(ct, cb, s.shading.clearcoat_n) *
                 importance_sample_ggx_tangent(u.xy, s.shading.clearcoat_roughness);
        return reflect(-s.v, h);
    }
    u.z = (u.z - s.p_coat) / (1.0 - s.p_coat);
    vec3 n = s.shading.n;
    vec3 t, b;
    facet_tangent_frame(n, t, b);
    float u1 = u.x, u2 = u.y;
    if (u.z < s.p_specular) {
        vec3 h = mat3(t, b, n) * importance_sample_ggx_tangent(vec2(u1, u2), s.shading.roughness);
        return reflect(-s.v, h);
    }
    // Cosine-weighted hemisphere.
    float r = sqrt(u1);
    return t * (r * cos(2.0 * PI * u2)) + b * (r * sin(2.0 * PI * u2)) + n * sqrt(max(0.0, 1.0 - u1));
}

vec3 sample_environment(vec4 u, out float pdf) {
    uint W = params.env.x, H = params.env.y;
    uint y = search(0u, H, u.x);
    uint x = search(H + y * W, W, u.y);
    vec3 d = equirect_texel_direction(uvec2(x, y), u.zw, env_size());
    pdf = distribution[H + H * W + y * W + x] / equirect_texel_solid_angle(y, env_size());
    return d;
}

vec3 punctual(Surface s, vec3 p) {
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < params.env.z; ++i) {
        vec3 l;
        vec3 incident = facet_punctual_incidence(unpack_punctual_light(lights[i]), p, l);
        sum += reflected(s, l, incident, true);
    }
    return sum;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(accumulation);
    if (any(greaterThanEqual(pixel, size))) return;
    vec4 normal = texelFetch(normal_view, pixel, 0);
    vec4 position = texelFetch(position_view, pixel, 0);
    vec3 batch_sum = vec3(0.0);
    uint count = params.batch.x;
    if (normal.a < 0.5) {
        // No surface: the skybox pass composites the environment here afterwards.
        vec4 acc = imageLoad(accumulation, pixel);
        imageStore(accumulation, pixel, vec4(acc.rgb, acc.a + float(count)));
        return;
    }
    Surface s;
    // The views hold the forward pass's surface terms (the dielectric F0 and the specular
    // factor included), so the shading surface is read back, not derived again.
    vec4 f0 = texelFetch(f0_view, pixel, 0);  // the dielectric F0 and specular factor
    s.shading = facet_surface((params.env.w & 1u) != 0u ? FACET_BRDF_THESIS : FACET_BRDF_GLTF, normalize(normal.xyz),
                              texelFetch(basecolor_view, pixel, 0).rgb, texelFetch(metallic_view, pixel, 0).r,
                              texelFetch(roughness_view, pixel, 0).r, 1.0, f0.a, 1.0);
    facet_surface_specular_color(s.shading, f0.rgb);
    s.v = normalize(params.camera_position.xyz - position.xyz);
    s.NdotV = clamp(dot(s.shading.n, s.v), 0.0, 1.0);
    s.p_specular = s.shading.specular_weight <= 0.0 ? 0.0 : mix(0.5, 1.0, s.shading.metallic);
    vec4 coat = texelFetch(clearcoat_view, pixel, 0);
    s.p_coat = 0.0;
    if (coat.r > 0.0) {
        facet_surface_clearcoat(s.shading, coat.r, coat.g, normalize(texelFetch(clearcoat_normal_view, pixel, 0).xyz));
        s.p_coat = 0.5 * coat.r;
    }
    vec4 film = texelFetch(iridescence_view, pixel, 0);
    if (film.r > 0.0) facet_surface_iridescence(s.shading, film.r, film.g, film.b);
    vec4 stretch = texelFetch(anisotropy_view, pixel, 0);
    if (stretch.a > 0.0) facet_surface_anisotropy(s.shading, stretch.a, stretch.xyz);
    vec4 sheen = texelFetch(sheen_view, pixel, 0);
    s.p_sheen = 0.0;
    if (facet_max3(sheen.rgb) > 0.0) {
        facet_surface_sheen(s.shading, sheen.rgb, sheen.a);
        s.p_sheen = 0.25;
    }
    vec4 through = texelFetch(transmission_view, pixel, 0);
    s.p_transmission = 0.0;
    if (through.r > 0.0) {
        s.shading.transmission = through.r;
        s.shading.transmission_roughness = through.g;
        s.p_transmission = 0.5 * through.r * (1.0 - s.shading.metallic);
    }
    vec3 p = position.xyz;
    // An unlit surface (KHR_materials_unlit, points, lines: the metallic view's alpha 0) is
    // its base colour and emission, exactly, with nothing to sample.
    bool unlit = texelFetch(metallic_view, pixel, 0).a < 0.5;

    uint rng = hash(uint(pixel.x) * 1973u + uint(pixel.y) * 9277u + params.batch.y * 26699u);
    float shift[7];
    for (uint d = 0u; d < 7u; ++d) shift[d] = random(rng);
    bool has_env = params.env.x > 0u;
    for (uint i = 0u; i < count && has_env && !unlit; ++i) {
        // BRDF sample.
        vec3 l = sample_brdf(s, vec3(kronecker(i, 0u, shift[0]), kronecker(i, 1u, shift[1]), kronecker(i, 2u, shift[2])));
        float pb = brdf_pdf(s, l);
        if (pb > 0.0) {
            float pe = env_pdf(l);
            batch_sum += reflected(s, l, env_radiance(l), false) / (pb + pe);
        }
        // Environment sample.
        float pe;
        l = sample_environment(vec4(kronecker(i, 3u, shift[3]), kronecker(i, 4u, shift[4]), kronecker(i, 5u, shift[5]),
                                    kronecker(i, 6u, shift[6])), pe);
        if (pe > 0.0 && (dot(s.shading.n, l) > 0.0 || (s.p_coat > 0.0 && dot(s.shading.clearcoat_n, l) > 0.0) ||
                         s.p_transmission > 0.0)) {
            float pb2 = brdf_pdf(s, l);
            batch_sum += reflected(s, l, env_radiance(l), false) / (pb2 + pe);
        }
    }
    vec3 batch_mean = count > 0u ? batch_sum / float(count) : vec3(0.0);
    vec3 exact = (unlit ? s.shading.albedo : punctual(s, p)) + texelFetch(emissive_view, pixel, 0).rgb;
    vec4 acc = imageLoad(accumulation, pixel);
    imageStore(accumulation, pixel, vec4(acc.rgb + batch_sum + exact * float(count), acc.a + float(count)));
    // Batch means give the noise estimate: their spread over batches of equal size.
    float y = facet_luminance(batch_mean + exact);
    vec4 m = imageLoad(moments, pixel);
    imageStore(moments, pixel, vec4(m.x + y, m.y + y * y, m.z + 1.0, 0.0));
}
