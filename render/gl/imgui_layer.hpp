// Dear ImGui without a window: our own headless platform layer (display size, time step and
// input events set per frame) and our own OpenGL 3.3 renderer of its draw lists. Render thread
// only; one ImGui context per layer.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

struct ImGuiContext;
struct ImDrawData;
struct ImFont;

namespace gf::render {

/// Mouse and keyboard state injected for the next frame, in pixels from the top-left corner.
struct InputState {
  float mouse_x = -1.0f, mouse_y = -1.0f;  ///< -1: mouse outside the window
  bool mouse_down = false;                 ///< left button
  bool ctrl = false;
  bool enter = false, backspace = false, select_all = false;  ///< keys held this frame
  std::string text;                        ///< characters typed this frame (UTF-8)
};

/// ImGui's packed colour (ImU32) for a linear RGB colour, with the scene's display gamma (2).
unsigned imguiColour(const Eigen::Vector3f& linear, float alpha = 1.0f);

/// A headless ImGui context with a GL renderer. Fonts are ImGui's built-in font at
/// `font_px` pixels (the default) and at each of `more_px`: text is crisp at the size its font
/// was made for and smears when scaled.
class ImGuiLayer {
 public:
  ImGuiLayer(int width, int height, float font_px, const std::vector<float>& more_px = {});
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  /// Makes this layer's context current, sets display size, `dt_s` and the input, and starts
  /// an ImGui frame. Build widgets after it, then call render().
  void beginFrame(double dt_s, const InputState& input);
  /// Ends the frame and draws it over the bound framebuffer (alpha-blended, no depth).
  void render();
  /// Scales ImGui's paddings, spacings and roundings by `factor` (tighter panels in small frames).
  void scaleSizes(float factor);
  /// The font made for the size nearest to `px`.
  ImFont* font(float px) const;

 private:
  void drawLists(const ImDrawData& data);
  int width_, height_;
  ImGuiContext* context_ = nullptr;
  struct Gl;
  std::unique_ptr<Gl> gl_;
};

}  // namespace gf::render
