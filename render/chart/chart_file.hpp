// A chart as files: the PNG drawn through ImGui into a framebuffer and the SVG of the same
// marks beside it (forces.png, the studies' and experiments' charts, `godfinger plot`).
#pragma once

#include <string>

#include "render/chart/chart.hpp"

namespace gf::render {

/// Draws `chart` with the calling thread's current GL context and writes the PNG `path` and
/// the SVG beside it. Throws GlError, ImageError; allocates.
void drawChartFile(const ChartSpec& chart, const std::string& path);

/// As drawChartFile, with a GL context of its own (the thread must not have one already): charts
/// from commands and tests without a render thread, and an offline run's chart after its last
/// frame (RenderThread::submitChart).
void writeChartPng(const ChartSpec& chart, const std::string& path);

}  // namespace gf::render
