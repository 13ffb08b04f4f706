// GLSL 3.30 core sources of the scene and overlay programs.
#pragma once

namespace gf::render::shaders {

/// Lit surfaces: bodies, ground (grid), fingers, arrows; also flat colour (u_mode 2).
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
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_light = u_light_view_proj * world;
  gl_Position = u_view_proj * world;
}
)";

inline constexpr const char* kSurfaceFragment = R"(#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec4 v_light;
uniform vec4 u_colour;        // linear RGB, alpha
uniform vec3 u_light_dir;     // unit, towards the key light
uniform vec3 u_camera;
uniform vec3 u_background;    // linear RGB the ground fades into
uniform sampler2DShadow u_shadow;
uniform int u_use_shadow;
uniform int u_mode;           // 0 lit, 1 ground with grid, 2 flat colour
uniform float u_shadow_texel; // 1 / shadow map size
uniform vec2 u_grid;          // minor, major spacing (m)
uniform vec2 u_fog;           // distances (m) where the ground starts and ends fading
out vec4 frag;

float lightVisible() {
  if (u_use_shadow == 0) return 1.0;
  vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
  if (p.z >= 1.0 || any(lessThan(p.xy, vec2(0.0))) || any(greaterThan(p.xy, vec2(1.0)))) return 1.0;
  // Four bilinear depth comparisons (each already a 2x2 filter): a soft edge for little cost on
  // a CPU rasteriser.
  float sum = 0.0;
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 2; ++y)
      sum += texture(u_shadow, vec3(p.xy + (vec2(x, y) - 0.5) * 1.5 * u_shadow_texel, p.z - 0.0005));
  return 0.25 * sum;
}

float gridLine(vec2 coord) {
  vec2 d = abs(fract(coord - 0.5) - 0.5) / max(fwidth(coord), vec2(1e-6));
  return 1.0 - min(min(d.x, d.y), 1.0);
}

// Linear to display values: gamma 2 (a square root is far cheaper than pow on llvmpipe).
vec3 display(vec3 linear) { return sqrt(max(linear, vec3(0.0))); }

void main() {
  if (u_mode == 2) {
    frag = vec4(display(u_colour.rgb), u_colour.a);
    return;
  }
  vec3 n = normalize(v_normal);
  vec3 base = u_colour.rgb;
  float distance_to_camera = length(u_camera - v_world);
  if (u_mode == 1) {
    vec2 coord = v_world.xz;
    float minor_fade = clamp(1.0 - 8.0 * length(fwidth(coord / u_grid.x)) * 0.25, 0.0, 1.0);
    base *= 1.0 - 0.25 * gridLine(coord / u_grid.x) * minor_fade - 0.35 * gridLine(coord / u_grid.y);
  }
  vec3 l = normalize(u_light_dir);
  vec3 v = normalize(u_camera - v_world);
  vec3 h = normalize(l + v);
  float diffuse = max(dot(n, l), 0.0);
  float s2 = max(dot(n, h), 0.0);
  s2 *= s2; s2 *= s2; s2 *= s2; s2 *= s2; s2 *= s2; s2 *= s2;  // ^64
  float specular = u_mode == 1 ? 0.0 : 0.3 * s2;
  float lit = lightVisible();
  vec3 sky = mix(vec3(0.16, 0.15, 0.14), vec3(0.30, 0.33, 0.38), 0.5 + 0.5 * n.y);
  vec3 colour = base * sky + lit * (base * diffuse * vec3(0.95, 0.92, 0.86) + vec3(specular));
  if (u_mode == 1) colour = mix(colour, u_background, smoothstep(u_fog.x, u_fog.y, distance_to_camera));
  frag = vec4(display(colour), u_colour.a);
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
