// A game engine's use of Facet, from the installed headers only: the host owns the
// instance, device, queue, command buffers, fences, its colour and depth images and its
// camera matrices. Facet adopts the device, bakes the environment once (saved, then loaded
// back as an engine would at start-up), and records its passes into the host's command
// buffers, two frames in flight. The last frame is read back and written to --out.
//
//   host_engine --model M.glb --env E.hdr --out frame.png [--width W --height H --frames N
//               --bake-dir DIR --validation]
#include <facet/gpu/context.h>
#include <facet/gpu/memory.h>
#include <facet/gpu/requirements.h>
#include <facet/graph/graph_executor.h>
#include <facet/ibl/bake_rules.h>
#include <facet/ibl/baked_environment.h>
#include <facet/io/image_io.h>
#include <facet/render/forward_renderer.h>
#include <facet/render/gpu_scene.h>
#include <facet/render/tonemap.h>
#include <facet/scene/gltf_loader.h>
#include <facet/scene/scene_needs.h>
#include <facet/shader/program_cache.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "host_vulkan.h"

namespace {

struct Args {
    std::string model, env, out, bake_dir = "host_bake";
    uint32_t width = 320, height = 240, frames = 4;
    bool validation = false;
};

bool parse(int argc, char** argv, Args& a) {
    for (int i = 1; i < argc; ++i) {
        const std::string k = argv[i];
        if (k == "--validation") { a.validation = true; continue; }
        if (i + 1 >= argc) return false;
        const std::string v = argv[++i];
        if (k == "--model") a.model = v;
        else if (k == "--env") a.env = v;
        else if (k == "--out") a.out = v;
        else if (k == "--bake-dir") a.bake_dir = v;
        else if (k == "--width") a.width = uint32_t(std::atoi(v.c_str()));
        else if (k == "--height") a.height = uint32_t(std::atoi(v.c_str()));
        else if (k == "--frames") a.frames = uint32_t(std::atoi(v.c_str()));
        else return false;
    }
    return !a.model.empty() && !a.env.empty() && !a.out.empty() && a.frames >= 2;
}

template <class T>
T need(facet::Result<T> r, const char* what) {
    if (!r) host::fail(std::string(what) + ": " + r.error().message);
    return std::move(r.value());
}

// The engine's own camera: eye on +Z looking at the origin, reversed-Z infinite perspective.
facet::CameraMatrices host_camera(float aspect) {
    const float fov = glm::radians(45.0f), znear = 0.05f, f = 1.0f / std::tan(fov / 2);
    glm::mat4 projection(0.0f);
    projection[0][0] = f / aspect;
    projection[1][1] = -f;       // Vulkan's clip space: y down
    projection[2][3] = -1.0f;    // w = -z_view
    projection[3][2] = znear;    // depth = near / -z_view: 1 at the near plane, 0 at infinity
    return {glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0)), projection};
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    if (!parse(argc, argv, args)) {
        std::fprintf(stderr, "usage: host_engine --model M --env E --out FILE.png [--width W --height H "
                             "--frames N>=2 --bake-dir DIR --validation]\n");
        return 2;
    }
    // 1. The engine's Vulkan, with what Facet needs chained into its device.
    facet::DeviceRequirements needs = facet::device_requirements();
    host::Vulkan& vk = *host::create(needs, args.validation);

    facet::HostVulkan adopt{vk.instance, vk.physical_device, vk.device, vk.queue, vk.queue_family};
    adopt.api_version = needs.api_version;
    for (const char* e : needs.device_extensions) adopt.device_extensions.push_back(e);
    adopt.enabled_features = needs.chain();
    {
        // 2. Facet on the host's device: everything it makes is gone at the end of this scope.
        auto context = need(facet::Context::adopt(adopt), "adopt");
        facet::ShaderCompiler compiler;
        facet::ProgramCache programs(*context, compiler);
        facet::Scene scene = need(facet::load_gltf(args.model), "model");

        // 3. Bake once for this scene, save, load back (what a shipped game does at start-up).
        auto source = need(facet::resolve_environment(args.env), "environment");
        facet::BakeSettings bake;
        bake.ibl = facet::ibl_settings_for_scene({}, facet::scene_needs(scene), false);
        {
            auto baked = need(facet::bake_environment(*context, programs, source, bake), "bake");
            if (auto saved = baked.save(args.bake_dir); !saved) host::fail("save: " + saved.error().message);
        }
        const auto baked = need(facet::BakedEnvironment::load(*context, args.bake_dir), "load");

        // 4. The frame: Facet's passes into the host's images, two frames in flight.
        constexpr uint32_t in_flight = 2;
        const auto gpu_scene_owner = need(facet::GpuScene::create(*context, scene), "scene upload");
        const facet::GpuScene& gpu_scene = *gpu_scene_owner;
        const auto renderer_owner = need(facet::ForwardRenderer::create(*context, programs, in_flight), "renderer");
        facet::ForwardRenderer& renderer = *renderer_owner;
        facet::GraphExecutor executor(*context, in_flight);
        const facet::Sampler nearest =
            need(facet::Sampler::create(*context, VK_FILTER_NEAREST, false, false, "host tonemap"), "sampler");
        facet::FrameSettings settings;
        settings.width = args.width;
        settings.height = args.height;
        settings.environment_lights = baked.lights();
        settings.environment_light_level = baked.metadata().light_split_level;
        const facet::CameraMatrices camera = host_camera(float(args.width) / float(args.height));
        std::vector<host::FrameTargets> targets;
        for (uint32_t i = 0; i < in_flight; ++i) targets.push_back(host::create_targets(vk, args.width, args.height));

        uint64_t allocations_after_warmup = 0, images_after_warmup = 0;
        std::vector<double> cpu_ms;  // graph build + compile + record of the steady frames
        for (uint32_t frame = 0; frame < args.frames; ++frame) {
            const uint32_t slot = frame % in_flight;
            host::begin_frame(vk, slot);  // waits for the slot's fence: its images and Facet's slot are free
            const auto cpu_start = std::chrono::steady_clock::now();
            host::FrameTargets& t = targets[slot];
            facet::RenderGraph graph;
            const facet::IblInputs ibl = facet::import_baked_environment(graph, baked);
            auto import = [&](const char* name, VkImage image, const facet::ImageDesc& desc, facet::ResourceState final) {
                return graph.import_image(name, {image, desc, {}, final});  // contents discarded: redrawn each frame
            };
            facet::ForwardTargets ft;
            ft.color = import("host colour", t.color.image, t.color.desc, {});
            ft.depth = import("host depth", t.depth.image, t.depth.desc, {});
            ft.resolve = import("host hdr", t.hdr.image, t.hdr.desc, {});
            ft.store_depth = false;
            auto drawn = need(renderer.add_forward_pass(graph, gpu_scene, settings, camera, ft, ibl, slot), "forward");
            auto hdr = need(renderer.add_skybox_pass(graph, drawn.resolve, settings, camera, ibl, slot), "skybox");
            const auto ldr = import("host display", t.ldr.image, t.ldr.desc,
                                    {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                     VK_ACCESS_2_TRANSFER_READ_BIT});
            need(facet::add_tonemap_pass(graph, programs, nearest, hdr, ldr, settings.display), "tonemap");
            const facet::CompiledGraph compiled = graph.compile();
            need(executor.record(compiled, vk.commands[slot], slot), "record");
            if (frame >= in_flight)
                cpu_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpu_start).count());
            host::submit_frame(vk, slot);
            if (frame + 1 == in_flight) {  // every slot has run once
                const auto s = context->allocator().stats();
                allocations_after_warmup = s.allocations_made;
                images_after_warmup = s.images_bound;
            }
        }
        host::wait_all(vk);
        const auto s = context->allocator().stats();
        std::printf("host_engine: %u frames, %u in flight; device allocations after the first %u frames: %llu, "
                    "images: %llu\n",
                    args.frames, in_flight, in_flight,
                    static_cast<unsigned long long>(s.allocations_made - allocations_after_warmup),
                    static_cast<unsigned long long>(s.images_bound - images_after_warmup));

        if (!cpu_ms.empty()) {
            std::sort(cpu_ms.begin(), cpu_ms.end());
            std::printf("host_engine: steady frame CPU (graph build + compile + record), median of %zu: %.3f ms\n",
                        cpu_ms.size(), cpu_ms[cpu_ms.size() / 2]);
        }
        // 5. The last frame back to the host's memory.
        const std::vector<uint8_t> pixels = host::read_back(vk, targets[(args.frames - 1) % in_flight].ldr);
        if (auto written = facet::write_ldr_image(args.out, args.width, args.height, pixels); !written)
            host::fail("write: " + written.error().message);
        executor.release();
        for (auto& t : targets) host::destroy_targets(vk, t);
    }
    // Facet's objects are destroyed; the host's device still lives, and its validation
    // layer's object tracking reports any Facet object left behind at vkDestroyDevice.
    const uint32_t messages = host::destroy(&vk);
    std::printf("host_engine: %u validation messages\n", messages);
    return messages == 0 ? 0 : 1;
}
