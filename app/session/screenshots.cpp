#include "app/session/screenshots.hpp"

#include "app/compare/compare.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "render/render_thread.hpp"
#include "sim/haptic_loop.hpp"
#include "sim/world.hpp"

namespace gf::app {

const std::vector<Shot>& referenceShots() {
  static const std::vector<Shot> kShots = {
      {"fig5-push-ball", "fig5-push-ball", 1.5, "", {}},
      {"fig6-lift-one-finger", "fig6-lift-one-finger", 2.5, "", {}},
      {"fig7-lift-two-fingers", "fig7-lift-two-fingers", 2.0, "", {}},
      {"fig7-side-pick", "fig7-side-pick", 2.5, "", {}},
      {"fig8-pinch-oscillation", "fig8-pinch-oscillation", 4.0, "", {}},
      {"fig8-god-object", "fig8-pinch-oscillation", 4.0, "", {"fingers.left.n_sgo=0", "fingers.right.n_sgo=0"}},
      {"concave-mesh", "concave-mesh", 1.5, "", {}},
      {"edge-contact", "edge-contact", 1.2, "", {}},
      {"vertex-contact", "vertex-contact", 1.2, "", {}},
      {"overlay", "overlay-demo", 2.0, "", {}},
      {"compare-fig5", "fig5-push-ball", 1.5, "", {}, {"god_object", "god_finger"}, 3.0, 1280, 720},
      {"compare-fig8", "fig8-pinch-oscillation", 2.5, "", {}, {"god_object", "god_finger"}, 5.0, 1280, 720},
  };
  return kShots;
}

sim::Snapshot snapshotAt(const SessionDesc& session, double time) {
  sim::World world(session.scene);
  sim::runHapticLoop(world, sim::deviceTracks(session.scene), {session.scene.world.haptic_rate_hz, time}, nullptr);
  sim::Snapshot snapshot;
  world.snapshot(snapshot);
  return snapshot;
}

render::Image renderShot(const Shot& shot) {
  if (!shot.models.empty()) {
    return renderCompareFrame(shot.scene, shot.models, shot.overrides, shot.time, shot.chart_duration, shot.width,
                              shot.height, shot.camera);
  }
  SessionDesc session = loadSceneFile(resolveScenePath(shot.scene), shot.overrides);
  session.view.width = shot.width;
  session.view.height = shot.height;
  SessionOptions options;
  options.camera = shot.camera;
  return render::renderStill(session.scene, snapshotAt(session, shot.time), frameSettings(session, options));
}

}  // namespace gf::app
