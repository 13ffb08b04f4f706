#include "render/chart/chart_pen.hpp"

#include <algorithm>
#include <cstdio>

namespace gf::render {
namespace {

// ImGui's packed colour as SVG attributes: `name`="#rrggbb" and, when not opaque, its opacity.
std::string paint(const char* name, ImU32 c) {
  const unsigned r = (c >> IM_COL32_R_SHIFT) & 0xFF, g = (c >> IM_COL32_G_SHIFT) & 0xFF;
  const unsigned b = (c >> IM_COL32_B_SHIFT) & 0xFF, a = (c >> IM_COL32_A_SHIFT) & 0xFF;
  char out[96];
  if (a == 255) {
    std::snprintf(out, sizeof out, " %s=\"#%02x%02x%02x\"", name, r, g, b);
  } else {
    std::snprintf(out, sizeof out, " %s=\"#%02x%02x%02x\" %s-opacity=\"%.3f\"", name, r, g, b, name, a / 255.0);
  }
  return out;
}

std::string stroke(ImU32 c, float width) {
  char w[48];
  std::snprintf(w, sizeof w, " stroke-width=\"%.2f\" fill=\"none\"", width);
  return paint("stroke", c) + w;
}

std::string points(const std::vector<ImVec2>& p) {
  std::string out;
  char b[40];
  for (const ImVec2& v : p) {
    std::snprintf(b, sizeof b, "%s%.2f,%.2f", out.empty() ? "" : " ", v.x, v.y);
    out += b;
  }
  return out;
}

// Text with &, < and > escaped and control characters (which XML refuses) dropped; bytes from
// 0x80 pass (the labels are ASCII or UTF-8 from our own files).
std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (static_cast<unsigned char>(c) >= 0x20 || c == '\t') out += c;
  }
  return out;
}

// A length that SVG accepts: never negative (a rectangle under a pixel, a clip turned inside out).
float side(float length) { return std::max(0.0f, length); }

}  // namespace

std::string svgDocument(const SvgText& svg, int width, int height) {
  char head[256];
  std::snprintf(head, sizeof head,
                "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" "
                "height=\"%d\" viewBox=\"0 0 %d %d\">\n<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n",
                width, height, width, height, width, height);
  return head + svg.body + "</svg>\n";
}

void ChartPen::line(ImVec2 a, ImVec2 b, ImU32 colour, float width) {
  list_.AddLine(a, b, colour, width);
  if (!svg_) return;
  char e[128];
  std::snprintf(e, sizeof e, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"", a.x, a.y, b.x, b.y);
  svg_->body += e + stroke(colour, width) + "/>\n";
}

void ChartPen::rect(ImVec2 lo, ImVec2 hi, ImU32 colour, float width) {
  list_.AddRect(lo, hi, colour, 0.0f, 0, width);
  if (!svg_) return;
  // ImGui strokes a rectangle half a pixel inside its corners.
  char e[128];
  std::snprintf(e, sizeof e, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"", lo.x + 0.5f, lo.y + 0.5f,
                side(hi.x - lo.x - 1.0f), side(hi.y - lo.y - 1.0f));
  svg_->body += e + stroke(colour, width) + "/>\n";
}

void ChartPen::rectFilled(ImVec2 lo, ImVec2 hi, ImU32 colour) {
  list_.AddRectFilled(lo, hi, colour);
  if (!svg_) return;
  char e[128];
  std::snprintf(e, sizeof e, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"", lo.x, lo.y, side(hi.x - lo.x),
                side(hi.y - lo.y));
  svg_->body += e + paint("fill", colour) + "/>\n";
}

void ChartPen::polygonFilled(const std::vector<ImVec2>& p, ImU32 colour) {
  list_.AddConvexPolyFilled(p.data(), static_cast<int>(p.size()), colour);
  if (svg_) svg_->body += "<polygon points=\"" + points(p) + "\"" + paint("fill", colour) + "/>\n";
}

void ChartPen::polygon(const std::vector<ImVec2>& p, ImU32 colour, float width) {
  list_.AddPolyline(p.data(), static_cast<int>(p.size()), colour, ImDrawFlags_Closed, width);
  if (svg_) svg_->body += "<polygon points=\"" + points(p) + "\"" + stroke(colour, width) + "/>\n";
}

void ChartPen::circleFilled(ImVec2 c, float radius, ImU32 colour) {
  list_.AddCircleFilled(c, radius, colour, 16);
  if (!svg_) return;
  char e[96];
  std::snprintf(e, sizeof e, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"", c.x, c.y, radius);
  svg_->body += e + paint("fill", colour) + "/>\n";
}

void ChartPen::circle(ImVec2 c, float radius, ImU32 colour, float width) {
  list_.AddCircle(c, radius, colour, 16, width);
  if (!svg_) return;
  char e[96];
  std::snprintf(e, sizeof e, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"", c.x, c.y, radius);
  svg_->body += e + stroke(colour, width) + "/>\n";
}

void ChartPen::text(ImVec2 at, float size, ImU32 colour, const std::string& text) {
  list_.AddText(ImGui::GetFont(), size, at, colour, text.c_str());
  if (!svg_ || text.empty()) return;
  // The font's baseline is about 0.8 of its size below the text's top.
  char e[160];
  std::snprintf(e, sizeof e, "<text x=\"%.2f\" y=\"%.2f\" font-family=\"DejaVu Sans Mono, monospace\" font-size=\"%.1f\"",
                at.x, at.y + 0.8f * size, 0.9f * size);
  svg_->body += e + paint("fill", colour) + ">" + escaped(text) + "</text>\n";
}

void ChartPen::svgPolyline(const std::vector<ImVec2>& p, ImU32 colour, float width, const std::vector<float>& dash) {
  if (!svg_ || p.size() < 2) return;
  std::string pattern;
  char b[24];
  for (float d : dash) {
    std::snprintf(b, sizeof b, "%s%.1f", pattern.empty() ? "" : ",", d);
    pattern += b;
  }
  svg_->body += "<polyline points=\"" + points(p) + "\"" + stroke(colour, width) +
                (pattern.empty() ? "" : " stroke-dasharray=\"" + pattern + "\"") + "/>\n";
}

void ChartPen::pushClip(ImVec2 lo, ImVec2 hi) {
  list_.PushClipRect(lo, hi, true);
  if (!svg_) return;
  char e[200];
  const int id = svg_->next_clip++;
  std::snprintf(e, sizeof e,
                "<clipPath id=\"c%d\"><rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/></clipPath>\n"
                "<g clip-path=\"url(#c%d)\">\n",
                id, lo.x, lo.y, side(hi.x - lo.x), side(hi.y - lo.y), id);
  svg_->body += e;
}

void ChartPen::popClip() {
  list_.PopClipRect();
  if (svg_) svg_->body += "</g>\n";
}

}  // namespace gf::render
