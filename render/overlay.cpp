#include "render/overlay.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <numbers>

#include "render/context.hpp"
#include "render/scene_renderer.hpp"
#include "sim/assert.hpp"

namespace gf::render {
namespace {

constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                         ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_AlwaysAutoResize |
                                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing;

// The scripted action in progress and how far it has got.
struct RunningAction {
  sim::WidgetAction action;
  int step = 0;
  bool checkbox = false;
};

}  // namespace

struct Overlay::Impl {
  sim::SceneDesc scene;
  OverlaySettings settings;
  ImGuiLayer layer;
  int width, height;
  std::vector<sim::PatchSettings> patch;
  std::vector<int> n_sgo_when_on;  // restored when god-finger is switched back on
  std::vector<std::deque<float>> force_history;
  std::map<std::string, ImVec4> widget_rects;  // from the previous frame, for scripted input
  std::size_t next_action = 0;
  std::deque<RunningAction> running;
  double last_time = -1.0;
  float below_scene_panel = 80.0f;  // y (px) where the finger panel starts

  Impl(const sim::SceneDesc& s, const OverlaySettings& o, int w, int h)
      : scene(s), settings(o), layer(w, h, o.font_px * std::max(1.0f, h / 720.0f)), width(w), height(h) {
    checkSliderSpans();
    for (const sim::FingerDesc& f : scene.fingers) {
      patch.push_back(f.patch);
      n_sgo_when_on.push_back(f.patch.n_sgo > 0 ? f.patch.n_sgo : sim::PatchSettings{}.n_sgo);
      force_history.emplace_back();
    }
  }

  // Every slider spans legal values only (what a slider gives needs no further check).
  static void checkSliderSpans() {
    for (const sim::OverlayWidget& w : sim::kOverlayWidgets) {
      if (w.field == "god_finger") continue;
      const sim::Setting<sim::FingerDesc>* s = sim::findSetting(sim::fingerSettings(), w.field);
      GF_ASSERT(s != nullptr && s->live && "an overlay slider shows a live finger setting of sim/settings.cpp");
      GF_ASSERT(!sim::checkGiven(*s, w.lo / w.shown_per_unit) && !sim::checkGiven(*s, w.hi / w.shown_per_unit) &&
                "an overlay slider spans legal values only: narrow it in sim/view_desc.hpp");
    }
  }

  // The input of this frame: start actions that are due, advance the running one.
  InputState scriptedInput(double time) {
    while (next_action < settings.actions.size() && settings.actions[next_action].time <= time + 1e-9) {
      RunningAction r{settings.actions[next_action++]};
      r.checkbox = r.action.widget.ends_with("/god_finger");
      running.push_back(r);
    }
    InputState in;
    if (running.empty()) return in;
    RunningAction& r = running.front();
    const auto rect = widget_rects.find(r.action.widget);
    if (rect != widget_rects.end()) {
      in.mouse_x = 0.5f * (rect->second.x + rect->second.z);
      in.mouse_y = 0.5f * (rect->second.y + rect->second.w);
    }
    if (r.checkbox) {
      in.mouse_down = r.step == 1;
    } else {
      in.ctrl = r.step == 1;
      in.mouse_down = r.step == 1;
      in.select_all = r.step == 3;
      if (r.step == 4) in.text = r.action.value;
      in.enter = r.step == 5;
    }
    if (++r.step >= sim::kActionFrames) running.pop_front();
    return in;
  }

  // Every panel of one frame; returns the settings changes made.
  std::vector<sim::SettingsCommand> panels(const sim::Snapshot& snap, const RenderTimings& timings) {
    std::vector<sim::SettingsCommand> commands;
    scenePanel(snap);
    fingerPanel(commands);
    timingPanel(snap, timings);
    forcePlot(snap);
    return commands;
  }

  void remember(const std::string& id) {
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    widget_rects[id] = ImVec4(lo.x, lo.y, hi.x, hi.y);
  }

  void scenePanel(const sim::Snapshot& snap) {
    ImGui::SetNextWindowPos(ImVec2(10, 10));
    ImGui::Begin("godfinger", nullptr, kPanelFlags);
    ImGui::Text("%s", scene.name.c_str());
    ImGui::Text("t = %7.3f s   step %7ld", snap.time, snap.step);
    if (snap.nan_recoveries > 0) {  // loud: the simulation is not what it shows
      ImGui::TextColored(ImVec4(1.0f, 0.25f, 0.2f, 1.0f), "%ld steps not finite, rolled back", snap.nan_recoveries);
    }
    below_scene_panel = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y + 8.0f;
    ImGui::End();
  }

  // Which contact model the finger uses, as scene files name it.
  static const char* modelLabel(const sim::PatchSettings& p) {
    switch (sim::effectiveModel(p)) {
      case sim::ContactModel::kGodObject: return "(god_object)";
      case sim::ContactModel::kSoftFinger: return "(soft_finger)";
      case sim::ContactModel::kGodFinger: return p.fill == sim::PatchFill::kFilled ? "(god_finger, filled)" : "(god_finger, ring)";
    }
    return "";
  }

  void fingerPanel(std::vector<sim::SettingsCommand>& commands) {
    ImGui::SetNextWindowPos(ImVec2(10, below_scene_panel));
    ImGui::Begin("fingers", nullptr, kPanelFlags);
    for (std::size_t i = 0; i < patch.size(); ++i) {
      const std::string& name = scene.fingers[i].name;
      ImGui::PushID(static_cast<int>(i));
      ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(imguiColour(fingerColour(static_cast<int>(i)))),
                         "finger %s", name.c_str());
      sim::PatchSettings& p = patch[i];
      ImGui::SameLine();
      ImGui::TextUnformatted(modelLabel(p));
      bool changed = false;
      bool on = p.n_sgo > 0;
      if (ImGui::Checkbox("god-finger", &on)) {
        p.n_sgo = on ? n_sgo_when_on[i] : 0;
        changed = true;
      }
      remember(name + "/god_finger");
      ImGui::PushItemWidth(ImGui::GetFontSize() * 11);
      const sim::OverlayWidget& count = *sim::findOverlayWidget("n_sgo");
      int n = on ? p.n_sgo : n_sgo_when_on[i];
      if (ImGui::SliderInt(count.label, &n, static_cast<int>(count.lo), static_cast<int>(count.hi), count.format,
                           ImGuiSliderFlags_AlwaysClamp)) {
        n_sgo_when_on[i] = n;
        if (on) p.n_sgo = n;
        changed = true;
      }
      remember(name + "/n_sgo");
      for (const sim::OverlayWidget& w : sim::kOverlayWidgets) {
        if (w.field != "god_finger" && w.field != "n_sgo") changed |= slider(w, name, p);
      }
      ImGui::PopItemWidth();
      if (changed) commands.push_back({static_cast<int>(i), p});
      ImGui::PopID();
      if (i + 1 < patch.size()) ImGui::Separator();
    }
    ImGui::End();
  }

  // The slider of widget `w` for the setting of the same name, shown in its unit times
  // w.shown_per_unit; writes the setting back when moved or typed.
  bool slider(const sim::OverlayWidget& w, const std::string& finger, sim::PatchSettings& p) {
    const sim::Setting<sim::FingerDesc>& s = *sim::findSetting(sim::fingerSettings(), w.field);
    sim::FingerDesc f;
    f.patch = p;
    float shown = static_cast<float>(sim::givenValue(s, f) * w.shown_per_unit);
    const bool changed = ImGui::SliderFloat(w.label, &shown, w.lo, w.hi, w.format, ImGuiSliderFlags_AlwaysClamp);
    remember(finger + "/" + std::string(w.field));
    if (!changed) return false;
    sim::setGiven(s, f, shown / w.shown_per_unit);
    p = f.patch;
    return true;
  }

  void timingPanel(const sim::Snapshot& snap, const RenderTimings& timings) {
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - 10, 10), 0, ImVec2(1, 0));
    ImGui::Begin("timings", nullptr, kPanelFlags);
    ImGui::Text("haptic step  median %6.1f us", snap.timings.step_median_us);
    ImGui::Text("             p99    %6.1f us", snap.timings.step_p99_us);
    ImGui::Text("deadline misses     %6ld", snap.timings.late_steps);
    ImGui::Text("render              %6.1f ms", timings.render_ms);
    ImGui::End();
  }

  void forcePlot(const sim::Snapshot& snap) {
    const std::size_t capacity = static_cast<std::size_t>(std::max(2.0, settings.plot_seconds * 60.0));
    float top = 1.0f;
    for (std::size_t i = 0; i < force_history.size() && i < snap.fingers.size(); ++i) {
      std::deque<float>& h = force_history[i];
      if (snap.time > last_time) h.push_back(static_cast<float>(snap.fingers[i].coupling_force.norm()));
      while (h.size() > capacity) h.pop_front();
      for (float f : h) top = std::max(top, f);
    }
    top = std::ceil(top);
    const ImVec2 size(static_cast<float>(width) * 0.34f, static_cast<float>(height) * 0.2f);
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - 10, static_cast<float>(height) - 10), 0, ImVec2(1, 1));
    ImGui::Begin("coupling force |F| (N)", nullptr, kPanelFlags);
    ImGui::Dummy(size);
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(lo, hi, IM_COL32(20, 22, 28, 255));
    for (int g = 1; g < 4; ++g) {
      const float y = hi.y - (hi.y - lo.y) * g / 4.0f;
      draw->AddLine(ImVec2(lo.x, y), ImVec2(hi.x, y), IM_COL32(70, 70, 80, 255));
    }
    char label[32];
    std::snprintf(label, sizeof label, "%.0f N", top);
    draw->AddText(ImVec2(lo.x + 4, lo.y + 2), IM_COL32(200, 200, 200, 255), label);
    std::snprintf(label, sizeof label, "-%.0f s", settings.plot_seconds);
    draw->AddText(ImVec2(lo.x + 4, hi.y - ImGui::GetFontSize() - 2), IM_COL32(200, 200, 200, 255), label);
    for (std::size_t i = 0; i < force_history.size(); ++i) {
      const std::deque<float>& h = force_history[i];
      for (std::size_t k = 1; k < h.size(); ++k) {
        const auto at = [&](std::size_t j) {
          const float x = hi.x - (hi.x - lo.x) * static_cast<float>(h.size() - 1 - j) / static_cast<float>(capacity - 1);
          return ImVec2(x, hi.y - (hi.y - lo.y) * h[j] / top);
        };
        draw->AddLine(at(k - 1), at(k), imguiColour(fingerColour(static_cast<int>(i)) * 1.3f), 2.0f);
      }
    }
    ImGui::End();
  }
};

Overlay::Overlay(const sim::SceneDesc& scene, const OverlaySettings& settings, int width, int height)
    : impl_(std::make_unique<Impl>(scene, settings, width, height)) {
  // ImGui sizes auto-resizing windows during their first frame and shows them from the second:
  // lay the panels out once, undrawn, so the first real frame shows them (and scripted input
  // knows where every widget is).
  sim::Snapshot empty;
  empty.time = -1.0;
  empty.fingers.resize(scene.fingers.size());
  impl_->layer.beginFrame(1.0 / 60.0, {});
  impl_->panels(empty, {});
  ImGui::EndFrame();
}

Overlay::~Overlay() = default;

std::vector<sim::SettingsCommand> Overlay::draw(const sim::Snapshot& snapshot, const RenderTimings& timings) {
  GF_ASSERT_GL_THREAD();
  Impl& o = *impl_;
  const double dt = o.last_time >= 0.0 && snapshot.time > o.last_time ? snapshot.time - o.last_time : 1.0 / 60.0;
  o.layer.beginFrame(dt, o.scriptedInput(snapshot.time));
  std::vector<sim::SettingsCommand> commands = o.panels(snapshot, timings);
  o.layer.render();
  o.last_time = snapshot.time;
  return commands;
}

}  // namespace gf::render
