// How a chart's series look: line or markers, the line's dash, the markers' shape, and the
// palette that tells series apart for every reader: Okabe and Ito's colours, each series also
// with a marker shape and a dash of its own, so that colour is never the only difference.
// Shared by the chart (chart.hpp), the marks that draw it (chart_marks.hpp) and its users.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>

namespace gf::render {

/// How a series is drawn.
enum class SeriesStyle {
  kLine,            ///< segments between consecutive points
  kMarkers,         ///< a filled circle at each point
  kLineAndMarkers,  ///< both
};

/// How a series' line is stroked. Solid lines are drawn first, then dashed, dash-dotted and
/// dotted ones over them, so a broken curve lying on a solid one leaves both visible.
enum class LineDash { kSolid, kDashed, kDashDot, kDotted };

/// The shape of a series' markers (and of its legend swatch's).
enum class MarkerShape { kCircle, kSquare, kTriangle, kDiamond, kTriangleDown, kCross, kPlus };

/// An sRGB colour as published (0..255 a channel).
struct Srgb8 {
  std::uint8_t r, g, b;
};

/// The Okabe–Ito palette (Okabe & Ito 2008, "Color Universal Design"), in the order charts use
/// it: blue, vermillion, bluish green, reddish purple, orange, sky blue, black; yellow, too pale
/// on white, is left out.
inline constexpr std::array<Srgb8, 7> kOkabeIto = {{{0, 114, 178},
                                                    {213, 94, 0},
                                                    {0, 158, 115},
                                                    {204, 121, 167},
                                                    {230, 159, 0},
                                                    {86, 180, 233},
                                                    {0, 0, 0}}};

/// The chart colours are linear RGB shown through the display gamma 2 (imguiColour()): the
/// linear value that shows as `c`.
inline Eigen::Vector3f linearFromSrgb(Srgb8 c) {
  const auto l = [](std::uint8_t v) { return static_cast<float>(v) * static_cast<float>(v) / (255.0f * 255.0f); };
  return {l(c.r), l(c.g), l(c.b)};
}

/// Series `i`'s look: colour, marker and dash. The first seven differ in colour and marker
/// alike; colour, marker and dash repeat with periods 7, 7 and 4, so the first 28 differ in
/// marker and dash together.
struct SeriesLook {
  Eigen::Vector3f colour;  ///< linear RGB
  MarkerShape marker;
  LineDash dash;
};

inline SeriesLook seriesLook(std::size_t i) {
  constexpr std::array<MarkerShape, 7> kShapes = {MarkerShape::kCircle,       MarkerShape::kSquare,
                                                  MarkerShape::kTriangle,     MarkerShape::kDiamond,
                                                  MarkerShape::kTriangleDown, MarkerShape::kCross,
                                                  MarkerShape::kPlus};
  constexpr std::array<LineDash, 4> kDashes = {LineDash::kSolid, LineDash::kDashed, LineDash::kDotted,
                                               LineDash::kDashDot};
  return {linearFromSrgb(kOkabeIto[i % kOkabeIto.size()]), kShapes[i % kShapes.size()],
          kDashes[i % kDashes.size()]};
}

}  // namespace gf::render
