// An application's fragment shader reading more of looptess's interface
// (tests/vulkan/test_vulkan_pipelines.cpp; looptess/vulkan.h): colour = the tangent
// (location 6, pipelines built with kSpecTangent) mapped to 0..1, alpha = the base
// face (location 2) modulo 256.
#version 450

layout(location = 2) flat in uint inFace;
layout(location = 6) in vec4 inTangent;
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(inTangent.xyz * 0.5 + 0.5, float(inFace & 255u) / 255.0); }
