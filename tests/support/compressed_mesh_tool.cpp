// What a large compressed model costs to load (issue 14: a 2-million-triangle meshopt or
// Draco file), measured by hand, not a test:
//   facet_compressed_mesh_tool write meshopt|draco|plain TRIANGLES OUT.glb|OUT.gltf
//   facet_compressed_mesh_tool load FILE
// `write` makes a wavy grid of about TRIANGLES triangles (tests/support/compressed_gltf.h);
// `load` runs load_gltf once and prints its wall time; run it under /usr/bin/time -v for
// the peak memory.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <facet/scene/gltf_loader.h>
#include "support/compressed_gltf.h"

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "write" && argc == 5) {
        const std::string kind = argv[2];
        const double triangles = std::atof(argv[3]);
        // A square grid of n x n quads holds 2 n^2 triangles.
        const uint32_t n = uint32_t(std::ceil(std::sqrt(std::max(triangles, 2.0) / 2.0)));
        const facet::test::TestGeometry g = facet::test::wavy_grid(n, n);
        if (kind == "meshopt") facet::test::write_meshopt_gltf(argv[4], g);
        else if (kind == "draco") facet::test::write_draco_gltf(argv[4], g);
        else if (kind == "plain") facet::test::write_plain_gltf(argv[4], g);
        else return std::fprintf(stderr, "unknown kind %s\n", kind.c_str()), 2;
        std::printf("%s: %zu vertices, %zu triangles\n", argv[4], g.vertex_count(), g.indices.size() / 3);
        return 0;
    }
    if (mode == "load" && argc == 3) {
        const auto start = std::chrono::steady_clock::now();
        const facet::Result<facet::Scene> scene = facet::load_gltf(argv[2]);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (!scene.ok()) return std::fprintf(stderr, "%s\n", scene.error().message.c_str()), 1;
        std::printf("%s: %zu vertices, %zu triangles, loaded in %.1f ms\n", argv[2], scene->vertices.size(),
                    scene->indices.size() / 3, ms);
        return 0;
    }
    std::fprintf(stderr, "usage: facet_compressed_mesh_tool write meshopt|draco|plain TRIANGLES OUT | load FILE\n");
    return 2;
}
