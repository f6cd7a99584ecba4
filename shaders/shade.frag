// shade.frag -- simple shading for images: two-sided Lambert with a headlight
// (pc.light, object space) and a little ambient. With LT_FLAG_COLOR_LEVELS in
// pc.flags the base colour shows each patch's subdivision level and class (paper
// Fig. 7 and 9): one hue per level, non-plain sub-patches paler, IPPs dark blue.
// With LT_FLAG_FACETED (displaced surfaces) the normal is the drawn triangle's own,
// from the screen-space derivatives of the object-space position, so the
// displacement shows in the shading, not only in the silhouette. With
// LT_FLAG_COLOR_TEXCOORDS the base colour is a checker of TEXCOORD_0 (8 x 8 squares
// per unit square of texture space): seams and stretch show as they would in a
// texture.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 4) flat in uint inStyle;  // level | class << 8 (surface_out.glsl)
layout(location = 5) in vec2 inTexcoord;    // TEXCOORD_0 (surface_out.glsl)
layout(location = 0) out vec4 outColor;

const vec3 kLevelColors[8] = vec3[8](vec3(0.95, 0.82, 0.30), vec3(0.50, 0.80, 0.40), vec3(0.35, 0.70, 0.90),
                                     vec3(0.75, 0.50, 0.90), vec3(0.95, 0.55, 0.35), vec3(0.40, 0.85, 0.75),
                                     vec3(0.90, 0.45, 0.65), vec3(0.65, 0.65, 0.65));

vec3 styleColor(uint style) {
    uint patchClass = style >> 8;
    if (patchClass == LT_CLASS_IPP) return vec3(0.20, 0.30, 0.85);
    vec3 c = kLevelColors[min(style & 0xffu, 7u)];
    return patchClass == LT_CLASS_NPP ? mix(c, vec3(1.0), 0.5) : c;
}

void main() {
    vec3 n = (pc.flags & LT_FLAG_FACETED) != 0u ? normalize(cross(dFdx(inPosition), dFdy(inPosition))) : normalize(inNormal);
    float lambert = abs(dot(n, pc.light.xyz));
    vec3 base = vec3(0.80, 0.78, 0.74);
    if ((pc.flags & LT_FLAG_COLOR_LEVELS) != 0u) base = styleColor(inStyle);
    if ((pc.flags & LT_FLAG_COLOR_TEXCOORDS) != 0u) {
        vec2 cell = floor(8.0 * inTexcoord);
        bool odd = mod(cell.x + cell.y, 2.0) != 0.0;
        base = odd ? vec3(0.90, 0.55, 0.20) : vec3(0.25, 0.50, 0.85);
    }
    outColor = vec4(base * (0.12 + 0.88 * lambert), 1.0);
}
