// An application's own fragment shader over looptess's vertex stages
// (tests/vulkan/test_vulkan_pipelines.cpp): colour = the texture coordinate, from the
// documented interface (looptess/vulkan.h: location 5, TEXCOORD_0).
#version 450

layout(location = 5) in vec2 inTexcoord;
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(clamp(inTexcoord, 0.0, 1.0), 0.0, 1.0); }
