// render_programs.h: the two OpenCL programs a render builds. The trace stages (eye
// rays, both intersect kernels, the sort by shader, close, compact, retire, treelets)
// are one program, the shading (the scene's shaders, their shade kernels, the uniform
// preparation, the imager) the other, each built with only the options its source
// reads. Scenes that differ only in their shaders share the first from the caches, so a
// shader edit rebuilds and recompiles the second alone; and scenes that differ only in
// what the trace stages read (packets, the tree's width) share the second.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "ocl/program.h"

namespace rd {

struct ShadingSetup;

// The embedded kernel files of the trace program.
extern const std::vector<std::string> kTraceSources;

// The -D options of `options` whose macro `source` names (as a whole word), with every
// other option kept: what can change the program built from `source`.
std::string optionsUsedBy(const std::string& source, const std::string& options);

struct RenderPrograms {
    // Builds both, the trace program first (`options`: the scene's build options).
    RenderPrograms(const ClContext& ctx, const ShadingSetup& shading, const std::string& options);
    std::string options;  // the scene's; each program is built with those its source reads
    std::unique_ptr<Program> trace, shade;
    // The two as --stats reports them: the scene's options, hit when both were cached,
    // the build times added, both keys.
    ProgramBuildInfo info() const;
};

}  // namespace rd
