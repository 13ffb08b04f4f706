#include "render/overlay/overlay.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <numbers>

#include "render/gl/context.hpp"
#include "render/overlay/labels.hpp"
#include "render/scene/scene_renderer.hpp"
#include "sim/assert.hpp"

namespace gf::render {
namespace {

constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                         ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_AlwaysAutoResize |
                                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing;

constexpr float kReferenceRows = 720.0f;  // the frame height font_px is given for
constexpr float kMinStyleScale = 0.5f;    // the tightest spacing (of ImGui's) at small frames
constexpr float kCellFonts = 6.5f;        // a slider's width, in text heights
constexpr float kPlotWidthShare = 0.34f, kPlotHeightShare = 0.2f;  // of the frame
constexpr float kPanelMarginPx = 10.0f;

// The font of a `rows`-high frame: font_px at 720 rows, scaled, never under kMinLabelPx.
float overlayFontPx(const OverlaySettings& o, int rows) {
  return std::max(kMinLabelPx, std::round(o.font_px * static_cast<float>(rows) / kReferenceRows));
}

// The scripted action in progress and how far it has got.
struct RunningAction {
  view::WidgetAction action;
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
  std::vector<char> changed_fingers;  // per finger: its settings changed this frame
  std::vector<std::deque<float>> force_history;
  std::map<std::string, ImVec4> widget_rects;  // from the previous frame, for scripted input
  std::size_t next_action = 0;
  std::deque<RunningAction> running;
  double last_time = -1.0;
  float below_scene_panel = 80.0f;  // y (px) where the finger panel starts

  Impl(const sim::SceneDesc& s, const OverlaySettings& o, int w, int h)
      : scene(s), settings(o), layer(w, h, overlayFontPx(o, h)), width(w), height(h) {
    // Spacing shrinks with the frame so that every panel fits a 640x360 frame.
    layer.scaleSizes(std::clamp(static_cast<float>(h) / kReferenceRows, kMinStyleScale, 1.0f));
    checkSliderSpans();
    for (const sim::FingerDesc& f : scene.fingers) {
      patch.push_back(f.patch);
      n_sgo_when_on.push_back(f.patch.n_sgo > 0 ? f.patch.n_sgo : sim::PatchSettings{}.n_sgo);
      force_history.emplace_back();
    }
  }

  // Every slider spans legal values only (what a slider gives needs no further check).
  static void checkSliderSpans() {
    for (const view::OverlayWidget& w : view::kOverlayWidgets) {
      if (w.field == "god_finger") continue;
      const sim::Setting<sim::FingerDesc>* s = sim::findSetting(sim::fingerSettings(), w.field);
      GF_ASSERT(s != nullptr && s->live && "an overlay slider shows a live finger setting of sim/scene/settings.cpp");
      GF_ASSERT(!sim::checkGiven(*s, w.lo / w.shown_per_unit) && !sim::checkGiven(*s, w.hi / w.shown_per_unit) &&
                "an overlay slider spans legal values only: narrow it in render/view/view_desc.hpp");
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
    if (++r.step >= view::kActionFrames) running.pop_front();
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

  // The current window's rectangle, as "panel/NAME" (before its End()).
  void rememberPanel(const char* name) {
    const ImVec2 lo = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    widget_rects[std::string("panel/") + name] = ImVec4(lo.x, lo.y, lo.x + size.x, lo.y + size.y);
  }

  void scenePanel(const sim::Snapshot& snap) {
    ImGui::SetNextWindowPos(ImVec2(10, 10));
    ImGui::Begin("godfinger", nullptr, kPanelFlags);
    ImGui::Text("%s", scene.name.c_str());
    ImGui::Text("t = %7.3f s   step %7ld", snap.time, snap.step);
    if (settings.arrow_m_per_n > 0.0) ImGui::TextDisabled("force arrow 1 cm = %g N", 0.01 / settings.arrow_m_per_n);
    if (snap.nan_recoveries > 0) {  // loud: the simulation is not what it shows
      ImGui::TextColored(ImVec4(1.0f, 0.25f, 0.2f, 1.0f), "%ld steps not finite, rolled back", snap.nan_recoveries);
    }
    below_scene_panel = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y + 8.0f;
    rememberPanel("godfinger");
    ImGui::End();
  }

  // One table: a row per widget, a column per finger (its name in its colour and its model
  // heading the column), so that two fingers' settings fit a 640x360 frame.
  void fingerPanel(std::vector<sim::SettingsCommand>& commands) {
    ImGui::SetNextWindowPos(ImVec2(kPanelMarginPx, below_scene_panel));
    ImGui::Begin("fingers", nullptr, kPanelFlags);
    const int columns = 1 + static_cast<int>(patch.size());
    if (!ImGui::BeginTable("settings", columns, ImGuiTableFlags_SizingFixedFit)) {
      ImGui::End();
      return;
    }
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    for (std::size_t i = 0; i < patch.size(); ++i) {
      ImGui::TableNextColumn();
      ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(imguiColour(fingerColour(static_cast<int>(i)))), "%s",
                         scene.fingers[i].name.c_str());
    }
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextDisabled("model");
    for (const sim::PatchSettings& p : patch) {
      ImGui::TableNextColumn();
      ImGui::TextDisabled("%s", sim::modelLabel(p).data());
    }
    changed_fingers.assign(patch.size(), 0);
    for (const view::OverlayWidget& w : view::kOverlayWidgets) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::AlignTextToFramePadding();
      ImGui::TextUnformatted(w.label);
      for (std::size_t i = 0; i < patch.size(); ++i) {
        ImGui::TableNextColumn();
        ImGui::PushID(static_cast<int>(i));
        ImGui::SetNextItemWidth(kCellFonts * ImGui::GetFontSize());
        changed_fingers[i] |= widget(w, i) ? 1 : 0;
        ImGui::PopID();
      }
    }
    ImGui::EndTable();
    for (std::size_t i = 0; i < patch.size(); ++i) {
      if (changed_fingers[i]) commands.push_back({static_cast<int>(i), patch[i]});
    }
    rememberPanel("fingers");
    ImGui::End();
  }

  // Finger i's widget `w` (the god-finger checkbox, the n_SGO slider, or a setting's slider);
  // whether it changed the finger's settings.
  bool widget(const view::OverlayWidget& w, std::size_t i) {
    const std::string& name = scene.fingers[i].name;
    sim::PatchSettings& p = patch[i];
    const bool on = p.n_sgo > 0;
    if (w.field == "god_finger") {
      bool checked = on;
      const bool clicked = ImGui::Checkbox("##god_finger", &checked);
      remember(name + "/god_finger");
      if (clicked) p.n_sgo = checked ? n_sgo_when_on[i] : 0;
      return clicked;
    }
    if (w.field == "n_sgo") {
      int n = on ? p.n_sgo : n_sgo_when_on[i];
      const bool moved = ImGui::SliderInt("##n_sgo", &n, static_cast<int>(w.lo), static_cast<int>(w.hi), w.format,
                                          ImGuiSliderFlags_AlwaysClamp);
      remember(name + "/n_sgo");
      if (!moved) return false;
      n_sgo_when_on[i] = n;
      if (on) p.n_sgo = n;
      return true;
    }
    return slider(w, name, p);
  }

  // The slider of widget `w` for the setting of the same name, shown in its unit times
  // w.shown_per_unit; writes the setting back when moved or typed.
  bool slider(const view::OverlayWidget& w, const std::string& finger, sim::PatchSettings& p) {
    const sim::Setting<sim::FingerDesc>& s = *sim::findSetting(sim::fingerSettings(), w.field);
    sim::FingerDesc f;
    f.patch = p;
    float shown = static_cast<float>(sim::givenValue(s, f) * w.shown_per_unit);
    char id[48];
    std::snprintf(id, sizeof id, "##%.*s", static_cast<int>(w.field.size()), w.field.data());
    const bool changed = ImGui::SliderFloat(id, &shown, w.lo, w.hi, w.format, ImGuiSliderFlags_AlwaysClamp);
    remember(finger + "/" + std::string(w.field));
    if (!changed) return false;
    sim::setGiven(s, f, shown / w.shown_per_unit);
    p = f.patch;
    return true;
  }

  // The haptic step's and the frame's timings: measured in a realtime run, the reference
  // picture's scripted figures (said in the title), or "offline" where a run has no wall clock.
  void timingPanel(const sim::Snapshot& snap, const RenderTimings& timings) {
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - kPanelMarginPx, kPanelMarginPx), 0, ImVec2(1, 0));
    const std::optional<ScriptedTimings>& scripted = settings.scripted_timings;
    ImGui::Begin(scripted ? "timings (scripted figures)###timings" : "timings###timings", nullptr, kPanelFlags);
    if (scripted || settings.wall_clock) {
      const sim::HapticTimings measured = snap.timings;
      ImGui::Text("haptic step  median %6.1f us", scripted ? scripted->step_median_us : measured.step_median_us);
      ImGui::Text("             p99    %6.1f us", scripted ? scripted->step_p99_us : measured.step_p99_us);
      ImGui::Text("deadline misses     %6ld", scripted ? scripted->late_steps : measured.late_steps);
    } else {
      ImGui::TextUnformatted("haptic step  offline run:");
      ImGui::TextUnformatted("             no wall clock");
    }
    const double render_ms = scripted ? scripted->render_ms : timings.render_ms;
    if (render_ms > 0.0) {
      ImGui::Text("render              %6.1f ms", render_ms);
    } else {
      ImGui::TextUnformatted("render              first frame");
    }
    rememberPanel("timings");
    ImGui::End();
  }

  std::size_t plotCapacity() const { return static_cast<std::size_t>(std::max(2.0, settings.plot_seconds * 60.0)); }

  // Each finger's coupling force at `snap`, when it is a new instant.
  void pushForces(const sim::Snapshot& snap) {
    if (!(snap.time > last_time)) return;
    for (std::size_t i = 0; i < force_history.size() && i < snap.fingers.size(); ++i) {
      std::deque<float>& h = force_history[i];
      h.push_back(static_cast<float>(snap.fingers[i].coupling_force.norm()));
      while (h.size() > plotCapacity()) h.pop_front();
    }
  }

  // The last plot_seconds of each finger's coupling force, newest at the right edge, with a dot
  // on the newest sample (so a history of one sample shows too).
  void forcePlot(const sim::Snapshot& snap) {
    pushForces(snap);
    const std::size_t capacity = plotCapacity();
    float top = 1.0f;
    for (const std::deque<float>& h : force_history) {
      for (float f : h) top = std::max(top, f);
    }
    top = std::ceil(top);
    const ImVec2 size(static_cast<float>(width) * kPlotWidthShare, static_cast<float>(height) * kPlotHeightShare);
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - kPanelMarginPx, static_cast<float>(height) - kPanelMarginPx), 0,
                            ImVec2(1, 1));
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
      if (h.empty()) continue;
      const auto at = [&](std::size_t j) {
        const float x = hi.x - (hi.x - lo.x) * static_cast<float>(h.size() - 1 - j) / static_cast<float>(capacity - 1);
        return ImVec2(x, hi.y - (hi.y - lo.y) * h[j] / top);
      };
      const ImU32 colour = imguiColour(fingerColour(static_cast<int>(i)) * 1.3f);
      for (std::size_t k = 1; k < h.size(); ++k) draw->AddLine(at(k - 1), at(k), colour, 2.0f);
      draw->AddCircleFilled(at(h.size() - 1), 3.0f, colour);
    }
    rememberPanel("force");
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

std::map<std::string, OverlayRect> Overlay::layout() const {
  std::map<std::string, OverlayRect> out;
  for (const auto& [id, r] : impl_->widget_rects) out[id] = {r.x, r.y, r.z, r.w};
  return out;
}

void Overlay::record(const sim::Snapshot& snapshot) {
  impl_->pushForces(snapshot);
  if (snapshot.time > impl_->last_time) impl_->last_time = snapshot.time;
}

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
