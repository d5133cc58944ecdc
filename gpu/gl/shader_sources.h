// trispline::gpu shader sources — every gpu/shaders/*.glsl file, embedded into the binary at build time by
// cmake/EmbedShaders.cmake (the definitions live in a generated shader_sources.cpp in the build tree).
// Each file starts with `#version`; ShaderProgram specialises it by inserting #define lines after that line.
#pragma once

#include <span>
#include <string_view>

namespace trispline::gpu {

// Text of an embedded shader by file name (e.g. "mesh.vert.glsl"). Throws std::out_of_range naming the known
// files if there is none by that name.
std::string_view shader_source(std::string_view file_name);

// File names of all embedded shaders, in gpu/shaders/ directory order (sorted).
std::span<const std::string_view> shader_names();

}  // namespace trispline::gpu
