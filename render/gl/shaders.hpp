// GLSL 3.30 core sources of the scene and overlay programs.
#pragma once

#include <string>

namespace gf::render::shaders {

/// Surfaces: world position, normal and light-space position for the fragment programs below;
/// PATTERN: the body-frame position too.
inline constexpr const char* kSurfaceVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_proj;
uniform mat4 u_light_view_proj;
out vec3 v_world;
out vec3 v_normal;
out vec4 v_light;
#ifdef PATTERN
out vec3 v_local;  // the body's own frame (m): its pattern turns with it
#endif
void main() {
#ifdef PATTERN
  v_local = a_position;
#endif
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_light = u_light_view_proj * world;
  gl_Position = u_view_proj * world;
}
)";

/// Shared by the lit, ground and shadow-receiver programs: lighting constants, the shadow
/// lookup and the display transfer. Programs are specialised by #defines (Program's
/// `defines`) rather than uniform branches: llvmpipe runs both sides of a branch.
inline constexpr const char* kSurfaceCommon = R"(
in vec3 v_world;
in vec3 v_normal;
in vec4 v_light;
uniform vec4 u_colour;        // linear RGB, alpha
uniform vec3 u_light_dir;     // unit, towards the key light
uniform vec3 u_camera;
uniform vec3 u_background;    // linear RGB the ground fades into
uniform sampler2DShadow u_shadow;
uniform float u_shadow_texel; // 1 / shadow map size
uniform vec2 u_grid;          // minor, major spacing (m)
uniform vec2 u_fog;           // distances (m) where the ground starts and ends fading
out vec4 frag;

const vec3 kKey = vec3(0.95, 0.92, 0.86);
vec3 sky(vec3 n) { return mix(vec3(0.16, 0.15, 0.14), vec3(0.30, 0.33, 0.38), 0.5 + 0.5 * n.y); }

// Share of the key light reaching this point: two bilinear depth comparisons (each a 2x2
// filter) offset along the diagonal give a soft edge for little cost on a CPU rasteriser.
float lightVisible() {
  vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
  vec2 d = vec2(0.75 * u_shadow_texel);
  return 0.5 * (texture(u_shadow, vec3(p.xy - d, p.z - 0.0005)) + texture(u_shadow, vec3(p.xy + d, p.z - 0.0005)));
}

float fogAmount() { return smoothstep(u_fog.x, u_fog.y, length(u_camera - v_world)); }

// Linear to display values: gamma 2 (a square root is far cheaper than pow on llvmpipe).
vec3 display(vec3 linear) { return sqrt(max(linear, vec3(0.0))); }
)";

/// Lit surfaces: bodies, patches, fingers, arrows. SHADOWS: receives the key light's shadow.
/// PATTERN: a body's stripes (view::BodyPattern), fixed in its own frame.
inline const std::string kLitFragment = std::string(kSurfaceCommon) + R"(
#ifdef PATTERN
in vec3 v_local;
uniform vec3 u_pattern_centre;  // the body's centre in its own frame (m)

// Scale of the body colour's display value: eight bands about the body's y axis, lighter and
// darker by turns, +-15 % on the upper half (+y) and +-6 % on the lower, where they are shifted
// by one band: a turn about any axis moves them, seen from any side, and a half turn puts the
// strong ones below. Edges are smoothed over about a pixel (fwidth); where the bands crowd
// together (near the axis) they fade to plain.
float bodyPattern() {
  vec3 p = v_local - u_pattern_centre;
  float band = atan(p.z, p.x) * (4.0 / 3.14159265);   // one unit per band
  float wave = abs(fract(0.5 * band) - 0.5) * 2.0;    // 0 at a light band's middle, 1 at a dark one's
  // A pixel, in bands (wave's slope is 1); the angle measured from -x too, whose seam (where
  // atan jumps) lies elsewhere.
  float soft = min(fwidth(band), fwidth(atan(-p.z, -p.x) * (4.0 / 3.14159265))) + 1e-4;
  float bands = smoothstep(0.5 - soft, 0.5 + soft, wave);
  float crowded = smoothstep(0.3, 0.6, soft);          // bands under about two pixels wide
  float soft_y = fwidth(p.y) + 1e-6;
  float upper = smoothstep(-soft_y, soft_y, p.y);
  return 1.0 + 0.15 * mix(-0.4, 1.0, upper) * (1.0 - crowded) * (1.0 - 2.0 * bands);
}
#endif

void main() {
  vec3 n = normalize(v_normal);
  vec3 l = u_light_dir;
  vec3 h = normalize(l + normalize(u_camera - v_world));
  float diffuse = max(dot(n, l), 0.0);
  float s2 = max(dot(n, h), 0.0);
  s2 *= s2; s2 *= s2; s2 *= s2; s2 *= s2; s2 *= s2; s2 *= s2;  // ^64
#ifdef SHADOWS
  float lit = lightVisible();
#else
  float lit = 1.0;
#endif
  vec3 base = u_colour.rgb;
#ifdef PATTERN
  float scale = bodyPattern();
  base *= scale * scale;  // the display value is the square root
#endif
  vec3 colour = base * sky(n) + lit * (base * diffuse * kKey + vec3(0.3 * s2));
  frag = vec4(display(colour), u_colour.a);
}
)";

/// The ground: grid lines and fog, no shadow (drawn once per camera into the backdrop).
inline const std::string kGroundFragment = std::string(kSurfaceCommon) + R"(
float gridLine(vec2 coord) {
  vec2 d = abs(fract(coord - 0.5) - 0.5) / max(fwidth(coord), vec2(1e-6));
  return 1.0 - min(min(d.x, d.y), 1.0);
}

void main() {
  vec3 n = normalize(v_normal);
  vec2 coord = v_world.xz;
  float minor_fade = clamp(1.0 - 2.0 * length(fwidth(coord / u_grid.x)), 0.0, 1.0);
  vec3 base = u_colour.rgb;
  base *= 1.0 - 0.25 * gridLine(coord / u_grid.x) * minor_fade - 0.35 * gridLine(coord / u_grid.y);
  float diffuse = max(dot(n, u_light_dir), 0.0);
  vec3 colour = base * sky(n) + base * diffuse * kKey;
  frag = vec4(display(mix(colour, u_background, fogAmount())), 1.0);
}
)";

/// Shadow on the ground: multiplies the backdrop by the display value of shadowed / lit light
/// (the ground's base colour cancels), fading with the fog. Blend: destination colour x source.
inline const std::string kShadowReceiverFragment = std::string(kSurfaceCommon) + R"(
void main() {
  vec3 n = normalize(v_normal);
  vec3 key = max(dot(n, u_light_dir), 0.0) * kKey;
  vec3 ratio = (sky(n) + lightVisible() * key) / (sky(n) + key);
  frag = vec4(sqrt(mix(ratio, vec3(1.0), fogAmount())), 1.0);
}
)";

/// One flat colour: lines, the spring.
inline constexpr const char* kFlatFragment = R"(#version 330 core
uniform vec4 u_colour;
out vec4 frag;
void main() { frag = vec4(sqrt(max(u_colour.rgb, vec3(0.0))), u_colour.a); }
)";

/// A triangle covering the viewport; no vertex attributes (a vertex array must still be bound).
inline constexpr const char* kFullScreenVertex = R"(#version 330 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)";

/// Post-process anti-aliasing of the scene image (a directional filter in the spirit of FXAA):
/// pixels whose neighbourhood has little luma contrast are left alone; elsewhere the luma of
/// the four neighbours gives the direction across the edge, two pairs of filtered taps along
/// the edge blend it, and the wider pair is dropped when it leaves the local luma range.
/// With GF_FXAA_MARK defined, only the contrast test: the pixels it keeps are marked in the
/// stencil, and the whole filter then runs under a stencil test. llvmpipe runs every line of a
/// shader for every pixel of a block, discarded or not, but skips blocks that fail an early
/// stencil test: so the filtered taps are paid for on edges only.
inline constexpr const char* kFxaaFragment = R"(#version 330 core
uniform sampler2D u_scene;
uniform vec2 u_texel;  // 1 / size in pixels
out vec4 frag;

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  // Unfiltered reads of the pixel and its four neighbours (cheaper than filtered ones).
  vec3 centre = texelFetch(u_scene, p, 0).rgb;
  float n = luma(texelFetch(u_scene, p + ivec2(0, 1), 0).rgb);
  float s = luma(texelFetch(u_scene, p + ivec2(0, -1), 0).rgb);
  float e = luma(texelFetch(u_scene, p + ivec2(1, 0), 0).rgb);
  float w = luma(texelFetch(u_scene, p + ivec2(-1, 0), 0).rgb);
  float c = luma(centre);
  float lo = min(c, min(min(n, s), min(e, w)));
  float hi = max(c, max(max(n, s), max(e, w)));
  // No edge here: keep the pixel. (The pass writes over the scene it reads a copy of.)
  if (hi - lo < max(1.0 / 32.0, 0.125 * hi)) discard;
#ifdef GF_FXAA_MARK
  // The marking pass: the stencil under this pixel is set; the filter runs only where it is.
  frag = vec4(0.0);
  return;
#endif
  // Along the edge: perpendicular to the luma gradient, stretched towards the nearer axis.
  vec2 along = vec2(n - s, w - e);
  float bias = max(0.0625 * (n + s + e + w), 1.0 / 128.0);
  along = clamp(along / (min(abs(along.x), abs(along.y)) + bias), -8.0, 8.0) * u_texel;
  vec2 uv = gl_FragCoord.xy * u_texel;
  vec3 near = 0.5 * (texture(u_scene, uv - along / 6.0).rgb + texture(u_scene, uv + along / 6.0).rgb);
  vec3 far = 0.5 * near + 0.25 * (texture(u_scene, uv - 0.5 * along).rgb + texture(u_scene, uv + 0.5 * along).rgb);
  float f = luma(far);
  frag = vec4(f < lo || f > hi ? near : far, 1.0);
}
)";

/// Depth only, for the shadow map.
inline constexpr const char* kDepthVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_light_view_proj;
void main() { gl_Position = u_light_view_proj * u_model * vec4(a_position, 1.0); }
)";

inline constexpr const char* kDepthFragment = R"(#version 330 core
void main() {}
)";

/// ImGui draw lists: 2D positions in pixels, texture coordinates, packed RGBA colour.
inline constexpr const char* kOverlayVertex = R"(#version 330 core
layout(location = 0) in vec2 a_position;
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_colour;
uniform mat4 u_projection;
out vec2 v_uv;
out vec4 v_colour;
void main() {
  v_uv = a_uv;
  v_colour = a_colour;
  gl_Position = u_projection * vec4(a_position, 0.0, 1.0);
}
)";

inline constexpr const char* kOverlayFragment = R"(#version 330 core
in vec2 v_uv;
in vec4 v_colour;
uniform sampler2D u_texture;
out vec4 frag;
void main() { frag = v_colour * texture(u_texture, v_uv); }
)";

}  // namespace gf::render::shaders
