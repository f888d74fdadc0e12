#pragma once
// facet-bench accuracy: issue 13's measurement of the final image. The model (default
// builtin:spheres) is rendered under each environment with the views normal, position,
// base colour, metalness and roughness; every group of pixels (roughness band x metal)
// is compared with the double-precision truth of the frame's BRDF model
// (facet::reference, final_image_accuracy.h). Renderer and truth read the same texels.
// Tables on stdout, progress on stderr, optionally JSON.
namespace facet {

// argv[1] is "accuracy". Exit status: 0, 1 (a failure, named), 2 (bad usage).
int run_accuracy(int argc, char** argv);

}  // namespace facet
