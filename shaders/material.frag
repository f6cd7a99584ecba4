// material.frag -- looprender's scene shading (viewer/scene_render.cpp): a
// client of looptess's output interface (vulkan.h, "An application's own
// pipelines"), not part of the library. glTF 2.0 metallic-roughness (spec Appendix
// B: Lambert diffuse, GGX distribution, Smith-GGX visibility, Schlick Fresnel) under
// one directional light and an ambient term, with base colour, metallic-roughness,
// normal, occlusion and emissive textures and COLOR_0. Writes sRGB-encoded colour
// into a UNORM attachment.
//
// Built with kSpecTangent and kSpecAttributes: it reads the base face (to draw one
// cage primitive's faces with its material), both texture coordinate sets, the
// tangent and COLOR_0.
#version 450

layout(location = 0) in vec3 position;        // object space
layout(location = 1) in vec3 normal;          // object space, unit
layout(location = 2) flat in uint face;       // base face
layout(location = 5) in vec2 texcoord0;
layout(location = 6) in vec4 tangent;         // object space xyz, w handedness
layout(location = 7) in vec2 texcoord1;
layout(location = 8) in vec4 color;

// One cage primitive of one node (scene_render.cpp's DrawBlock, std140).
layout(set = 1, binding = 0) uniform Draw {
    mat4 model;         // object to world
    mat4 normalMatrix;  // inverse transpose of model (upper 3x3)
    vec4 baseColor;
    vec4 emissive;      // rgb
    vec4 light;         // xyz: unit direction towards the light (world), w: ambient
    vec4 eye;           // xyz: camera position (world)
    vec4 factors;       // metallic, roughness, normal scale, occlusion strength
    vec4 alpha;         // x: cut-off (MASK), y: 1 for MASK, z: 1 for double-sided
    uvec4 faces;        // x, y: the primitive's base faces [x, y); z: texCoord bit per
                        // texture (1: TEXCOORD_1); w: 1 where a normal map is bound
} d;
layout(set = 1, binding = 1) uniform sampler2D baseColorTexture;
layout(set = 1, binding = 2) uniform sampler2D metallicRoughnessTexture;
layout(set = 1, binding = 3) uniform sampler2D normalTexture;
layout(set = 1, binding = 4) uniform sampler2D occlusionTexture;
layout(set = 1, binding = 5) uniform sampler2D emissiveTexture;

layout(location = 0) out vec4 outColor;

const float kPi = 3.14159265;

vec2 uvOf(uint texture) { return ((d.faces.z >> texture) & 1u) != 0u ? texcoord1 : texcoord0; }

vec3 toSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    if (face < d.faces.x || face >= d.faces.y) discard;   // another primitive's face
    vec4 base = d.baseColor * texture(baseColorTexture, uvOf(0u)) * color;
    if (d.alpha.y > 0.5 && base.a < d.alpha.x) discard;
    vec4 mr = texture(metallicRoughnessTexture, uvOf(1u));
    float metallic = clamp(d.factors.x * mr.b, 0.0, 1.0);
    float roughness = clamp(d.factors.y * mr.g, 0.04, 1.0);

    vec3 worldPos = (d.model * vec4(position, 1.0)).xyz;
    vec3 n = normalize(mat3(d.normalMatrix) * normal);
    if (d.faces.w != 0u && dot(tangent.xyz, tangent.xyz) > 0.0) {
        vec3 t = normalize(mat3(d.model) * tangent.xyz);
        t = normalize(t - n * dot(n, t));
        vec3 b = cross(n, t) * tangent.w;
        vec3 m = texture(normalTexture, uvOf(2u)).xyz * 2.0 - 1.0;
        m.xy *= d.factors.z;
        n = normalize(mat3(t, b, n) * m);
    }
    vec3 v = normalize(d.eye.xyz - worldPos);
    if (d.alpha.z > 0.5 && dot(n, v) < 0.0) n = -n;   // double-sided: the side facing the eye

    vec3 l = d.light.xyz, h = normalize(l + v);
    float nl = max(dot(n, l), 0.0), nv = max(abs(dot(n, v)), 1e-4), nh = max(dot(n, h), 0.0), vh = max(dot(v, h), 0.0);
    float a2 = roughness * roughness * roughness * roughness;
    float dist = a2 / (kPi * pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
    float vis = 0.5 / max(nl * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nl * nl * (1.0 - a2) + a2), 1e-6);
    vec3 f0 = mix(vec3(0.04), base.rgb, metallic);
    vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vh, 5.0);
    vec3 diffuse = mix(base.rgb * (1.0 - 0.04), vec3(0.0), metallic);
    vec3 direct = ((1.0 - fresnel) * diffuse / kPi + fresnel * dist * vis) * nl * kPi;   // light of intensity pi
    float occlusion = 1.0 + d.factors.w * (texture(occlusionTexture, uvOf(3u)).r - 1.0);
    vec3 ambient = d.light.w * (diffuse + f0 * 0.5) * occlusion;
    vec3 emissive = d.emissive.rgb * texture(emissiveTexture, uvOf(4u)).rgb;
    outColor = vec4(toSrgb(direct + ambient + emissive), 1.0);
}
