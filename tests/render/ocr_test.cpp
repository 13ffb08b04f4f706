// What a frame and a close-up say, read back by OCR (tesseract) as a reader's eye would: Fig. 8's
// squeeze at 2.333 s, the frame with its two insets and the left finger's close-up. The time, the
// model of every inset and close-up and the load colour bar's label with its unit must read back from the boxes they are drawn in (found as the render thread places
// them, render/overlay/layout.hpp). Each box is cut out, enlarged three times (bicubic) and
// inverted to dark text on light by ffmpeg first: the labels are 13 to 18 pixels high, light on
// dark over the scene, which tesseract reads poorly as drawn. (The charts' axis units: ChartOcr.*.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/compare/screenshots.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "render/frames/image.hpp"
#include "render/overlay/labels.hpp"
#include "render/overlay/layout.hpp"
#include "render/overlay/patch_insets.hpp"
#include "render/scene/geometry.hpp"
#include "render/render_thread.hpp"
#include "tests/render/still_layout.hpp"
#include "tests/scratch.hpp"

namespace gf::render {
namespace {

namespace fs = std::filesystem;

// The text tesseract reads in the box `box` (pixels) of PNG `png` (of `size` pixels square or
// wide), cut out with 8 pixels around it (tesseract misreads text that touches its picture's
// edge), enlarged and inverted first; `name` names the files it leaves beside the PNG.
std::string readBack(const fs::path& png, ScreenBox box, const std::string& name, float width = 480.0f,
                     float height = 480.0f) {
  const fs::path big = png.parent_path() / (name + ".png"), text = png.parent_path() / name;
  box = {std::max(0.0f, box.x0 - 8.0f), std::max(0.0f, box.y0 - 8.0f), std::min(width, box.x1 + 8.0f),
         std::min(height, box.y1 + 8.0f)};
  char crop[96];
  std::snprintf(crop, sizeof crop, "crop=%d:%d:%d:%d", static_cast<int>(box.x1 - box.x0), static_cast<int>(box.y1 - box.y0),
                static_cast<int>(box.x0), static_cast<int>(box.y0));
  const std::string scale = "ffmpeg -loglevel error -y -i " + png.string() + " -vf " + crop +
                            ",scale=iw*3:ih*3:flags=bicubic,format=gray,negate " + big.string();
  if (std::system(scale.c_str()) != 0) return "(ffmpeg failed)";
  const std::string ocr = "tesseract " + big.string() + " " + text.string() + " --psm 6 > /dev/null 2>&1";
  if (std::system(ocr.c_str()) != 0) return "(tesseract failed)";
  std::ifstream in(text.string() + ".txt");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FrameOcr, AFrameAndACloseUpReadBackTheirTimeModelsAndScales) {
  ASSERT_EQ(std::system("command -v tesseract > /dev/null && command -v ffmpeg > /dev/null"), 0)
      << "tesseract and ffmpeg are needed (scripts/test installs them)";
  const app::SessionDesc session = app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig8-pinch-oscillation.toml");
  const sim::Snapshot snap = app::snapshotAt(session, 2.333);
  const fs::path dir = gf::test::scratchRoot() / "gf_frame_ocr";
  fs::create_directories(dir);
  const FrameOutputSettings settings = app::frameSettings(session, {});
  const int w = settings.width, h = settings.height;
  const float fw = static_cast<float>(w), fh = static_cast<float>(h);
  writePng((dir / "frame.png").string(), renderStill(session.scene, snap, settings));
  // Where the render thread put the labels of this frame.
  const test::StillLayout layout = test::stillLayout(session.scene, snap, settings);
  const LabelSizes& sizes = layout.sizes;
  const LabelPlacement& at = layout.placement;
  const std::string stamp = readBack(dir / "frame.png", placedBoxes(at, sizes, w, h)[1], "stamp", fw, fh);
  EXPECT_NE(stamp.find("t = 2.333 s"), std::string::npos) << stamp;
  EXPECT_NE(stamp.find("force arrow 1 cm"), std::string::npos) << stamp;
  const std::vector<InsetRect> insets = insetRects(w, h, 2, at.insets, at.column);
  for (std::size_t f = 0; f < 2; ++f) {
    const InsetRect& r = insets[f];
    const float x = static_cast<float>(r.x), y = static_cast<float>(r.y), side = static_cast<float>(r.size);
    const float reserve = insetCaptionReserve(contactLabelPx(r.size));
    const std::string caption = readBack(dir / "frame.png", {x, y - reserve, x + side, y}, "caption" + std::to_string(f), fw, fh);
    EXPECT_NE(caption.find(f == 0 ? "left: god-finger" : "right: god-finger"), std::string::npos) << caption;
    const std::string bar = readBack(dir / "frame.png", {x, y + 0.75f * side, x + side, y + side}, "bar" + std::to_string(f), fw, fh);
    EXPECT_NE(bar.find("SGO load, N"), std::string::npos) << bar;
  }
  // The close-up (480 px): its caption along the top, the colour bar bottom right. (The scale
  // bar's "10 mm" reads as "10 mn", "10 mon" or "16 mm" by turns, at any enlargement: the built-in
  // font's m is too narrow for tesseract; it is left out.)
  renderCloseUps(session.scene, snap, (dir / "t2.333").string(), 480);
  const fs::path close = dir / "t2.333-left.png";
  const std::string top = readBack(close, {0, 0, 480, 100}, "close_caption");
  EXPECT_NE(top.find("left: god-finger"), std::string::npos) << top;
  EXPECT_NE(top.find("t = 2.333 s"), std::string::npos) << top;
  const std::string bar = readBack(close, {140, 405, 480, 480}, "close_bar");
  EXPECT_NE(bar.find("SGO load, N"), std::string::npos) << bar;
}

}  // namespace
}  // namespace gf::render
