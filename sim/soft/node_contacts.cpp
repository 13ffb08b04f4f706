#include "sim/soft/node_contacts.hpp"

#include <algorithm>
#include <limits>

namespace gf::sim {
namespace {

Vec3 toLocal(const Pose& frame, const Vec3& world) { return frame.orientation.conjugate() * (world - frame.position); }

}  // namespace

NodeContacts::NodeContacts(int node_count, std::vector<std::array<int, 3>> surface)
    : surface_(std::move(surface)), anchors_(static_cast<std::size_t>(node_count)), node_area_(static_cast<std::size_t>(node_count)) {}

void NodeContacts::find(const std::vector<Vec3>& x, const std::vector<int>& nodes, const Vec3& inner, const PadSurfaces& surfaces,
                        double friction, bool combine, std::vector<FemContact>& out) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int n : nodes) {
    lo = lo.cwiseMin(x[static_cast<std::size_t>(n)]);
    hi = hi.cwiseMax(x[static_cast<std::size_t>(n)]);
  }
  surfaces.near(lo, hi, near_);
  out.clear();
  contact_body_.clear();
  for (int n : nodes) {
    const std::size_t i = static_cast<std::size_t>(n);
    double deepest = 0.0, depth = 0.0;
    Vec3 normal = Vec3::UnitY(), best_normal = normal;
    int body = -1;
    const Vec3 inward = inner - x[i];
    for (int b : near_) {
      if (surfaces.inside(b, x[i], depth, normal) && depth > deepest && normal.dot(inward) > 0.0) {
        deepest = depth;
        best_normal = normal;
        body = b;
      }
    }
    Anchor& anchor = anchors_[i];
    if (body < 0) {
      anchor.body = -1;
      continue;
    }
    FemContact c{n, best_normal, deepest, surfaces.velocityAt(body, x[i]), Vec3::Zero(), combine ? friction * surfaces.friction(body) : friction};
    if (anchor.body == body) c.slide = surfaces.frame(body).toWorld(anchor.local) - x[i];
    out.push_back(c);
    contact_body_.push_back(body);
  }
}

// The dynamic body pressed by the most nodes this step is solved with the solid (its translation;
// FemSolid::addPartner): the others' contacts, and every body's turning, stay explicit.
int NodeContacts::choosePartner(FemSolid& solid, int partner, const PadSurfaces& surfaces, std::vector<FemContact>& out) const {
  int best = -1, best_count = 0;
  for (std::size_t k = 0; k < contact_body_.size(); ++k) {
    const int body = contact_body_[k];
    if (body == best || !(surfaces.mass(body) > 0.0)) continue;
    const int count = static_cast<int>(std::count(contact_body_.begin(), contact_body_.end(), body));
    if (count > best_count) {
      best = body;
      best_count = count;
    }
  }
  solid.setPartner(partner, best >= 0 ? surfaces.mass(best) : 1.0, best >= 0 ? surfaces.velocity(best) : Vec3::Zero());
  for (std::size_t k = 0; k < contact_body_.size(); ++k) out[k].partner = best >= 0 && contact_body_[k] == best ? partner : -1;
  return best;
}

void NodeContacts::read(double dt, const FemSolid& solid, const std::vector<FemContact>& contacts, const PadSurfaces& surfaces,
                        double contact_stiffness) {
  const std::vector<Vec3>& x = solid.positions();
  const std::vector<FemContactResult>& results = solid.contactResults();
  contacts_.clear();
  for (std::size_t k = 0; k < contact_body_.size(); ++k) {
    const FemContact& c = contacts[k];
    const std::size_t i = static_cast<std::size_t>(c.node);
    const FemContactResult& r = results[k];
    if (r.released) {
      anchors_[i].body = -1;
      continue;
    }
    const int body = contact_body_[k];
    const Vec3 friction = r.force - r.force.dot(c.normal) * c.normal;
    const Vec3 anchor = x[i] + friction / contact_stiffness - dt * c.surface_velocity;
    anchors_[i] = {body, toLocal(surfaces.frame(body), anchor)};
    node_area_[i] = 0.0;
    contacts_.push_back({c.node, body, x[i], c.normal, -r.force, c.depth, 0.0, r.slipping});
  }
  if (contacts_.empty()) return;
  for (const std::array<int, 3>& t : surface_) {
    const double third = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm() / 6.0;
    for (int n : t) node_area_[static_cast<std::size_t>(n)] += third;
  }
  for (PadNodeContact& c : contacts_) c.area = node_area_[static_cast<std::size_t>(c.node)];
  for (const std::array<int, 3>& t : surface_) {
    for (int n : t) node_area_[static_cast<std::size_t>(n)] = 0.0;
  }
}

void NodeContacts::clear() {
  contacts_.clear();
  for (Anchor& a : anchors_) a.body = -1;
}

}  // namespace gf::sim
