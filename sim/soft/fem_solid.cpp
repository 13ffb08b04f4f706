#include "sim/soft/fem_solid.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gf::sim {
namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

constexpr int kFixed = -1, kFree = -2;  // before numbering: held in place, or to be numbered

// Isotropic elasticity in Voigt order (xx, yy, zz, xy, yz, zx), engineering shear strains.
Eigen::Matrix<double, 6, 6> elasticity(const FemMaterial& m) {
  const double mu = m.young_pa / (2.0 * (1.0 + m.poisson));
  const double lambda = m.young_pa * m.poisson / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  c.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) {
    c(i, i) = lambda + 2.0 * mu;
    c(i + 3, i + 3) = mu;
  }
  return c;
}

// The strain-displacement matrix of a tetrahedron whose inverse edge matrix is `dm_inverse`.
Eigen::Matrix<double, 6, 12> strainMatrix(const Eigen::Matrix3d& dm_inverse) {
  Eigen::Matrix<double, 4, 3> grad;  // each node's shape function gradient, a row each
  grad.bottomRows<3>() = dm_inverse;
  grad.row(0) = -dm_inverse.colwise().sum();
  Eigen::Matrix<double, 6, 12> b = Eigen::Matrix<double, 6, 12>::Zero();
  for (int a = 0; a < 4; ++a) {
    const double gx = grad(a, 0), gy = grad(a, 1), gz = grad(a, 2);
    b(0, 3 * a) = gx;
    b(1, 3 * a + 1) = gy;
    b(2, 3 * a + 2) = gz;
    b(3, 3 * a) = gy;
    b(3, 3 * a + 1) = gx;
    b(4, 3 * a + 1) = gz;
    b(4, 3 * a + 2) = gy;
    b(5, 3 * a) = gz;
    b(5, 3 * a + 2) = gx;
  }
  return b;
}

}  // namespace

// The rotation nearest to `f`, found by turning `q` (the element's last one, so a step or two
// suffices) by the torque that pulls its axes onto f's columns until the turn is under 1e-9
// rad (a strain of 1e-9 left: 0.3 mPa of stress at 300 kPa). A proper rotation even for an
// inverted `f`; no decomposition to fail.
Eigen::Quaterniond nearestRotation(const Eigen::Matrix3d& f, Eigen::Quaterniond q) {
  for (int pass = 0; pass < 100; ++pass) {
    const Eigen::Matrix3d r = q.toRotationMatrix();
    const Vec3 torque = r.col(0).cross(f.col(0)) + r.col(1).cross(f.col(1)) + r.col(2).cross(f.col(2));
    const double scale = std::abs(r.col(0).dot(f.col(0)) + r.col(1).dot(f.col(1)) + r.col(2).dot(f.col(2))) + 1e-9;
    const Vec3 omega = torque / scale;
    const double angle = omega.norm();
    if (angle < 1e-9) break;
    // Turned by omega: to first order q + (0, omega / 2) q, exact as the turn vanishes.
    const Eigen::Quaterniond turn(1.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z());
    q = (turn * q).normalized();
  }
  return q;
}

struct FemSolid::Element {
  Eigen::Matrix3d dm_inverse;
  Mat12 stiffness;  // at rest, K0 = V Bᵀ C B
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // this step's (and the next's start)
};

void validateMaterial(const FemMaterial& m) {
  const auto require = [](bool ok, const char* field, const std::string& what) {
    if (!ok) throw std::invalid_argument(std::string("pad.") + field + ": " + what);
  };
  require(m.young_pa >= 1e3 && m.young_pa <= 1e8, "young_pa", "must be in 1e3..1e8 Pa, got " + std::to_string(m.young_pa));
  require(m.poisson >= 0.0 && m.poisson <= 0.49, "poisson", "must be in 0..0.49, got " + std::to_string(m.poisson));
  require(m.density_kg_m3 >= 100.0 && m.density_kg_m3 <= 1e4, "density_kg_m3",
          "must be in 100..10000 kg/m³, got " + std::to_string(m.density_kg_m3));
  require(m.damping_s >= 0.0 && m.damping_s <= 0.1, "damping_s", "must be in 0..0.1 s, got " + std::to_string(m.damping_s));
}

FemSolid::FemSolid(const TetMesh& mesh, const FemMaterial& material)
    : tets_(mesh.tets), rest_(mesh.nodes), x_(mesh.nodes), v_(mesh.nodes.size(), Vec3::Zero()),
      mass_(mesh.nodes.size(), 0.0), material_(material), unknown_(mesh.nodes.size(), kFree) {
  validateMaterial(material);
  const Eigen::Matrix<double, 6, 6> c = elasticity(material);
  for (const std::array<int, 4>& t : tets_) {
    Eigen::Matrix3d dm;
    for (int k = 0; k < 3; ++k) dm.col(k) = rest_[static_cast<std::size_t>(t[k + 1])] - rest_[static_cast<std::size_t>(t[0])];
    const double volume = dm.determinant() / 6.0;
    if (!(volume > 0.0)) throw std::invalid_argument("FemSolid: a tetrahedron of no volume (or inverted)");
    Element e;
    e.dm_inverse = dm.inverse();
    const Eigen::Matrix<double, 6, 12> b = strainMatrix(e.dm_inverse);
    e.stiffness = volume * b.transpose() * c * b;
    elements_.push_back(e);
    for (int a : t) mass_[static_cast<std::size_t>(a)] += material.density_kg_m3 * volume / 4.0;  // lumped
  }
}

FemSolid::~FemSolid() = default;

void FemSolid::setBone(const std::vector<int>& nodes, double mass_kg) {
  bone_nodes_ = nodes;
  bone_mass_ = mass_kg;
  has_bone_ = true;
  for (int n : nodes) unknown_[static_cast<std::size_t>(n)] = 0;
}

int FemSolid::addPartner(const std::vector<int>& nodes) {
  Partner p;
  p.nodes = nodes;
  p.has.assign(x_.size(), 0);
  for (int n : nodes) p.has[static_cast<std::size_t>(n)] = 1;
  partners_.push_back(std::move(p));  // numbered at the first step
  return static_cast<int>(partners_.size()) - 1;
}

void FemSolid::setPartner(int k, double mass_kg, const Vec3& velocity, const Vec3& force) {
  Partner& p = partners_[static_cast<std::size_t>(k)];
  p.mass = mass_kg > 0.0 ? mass_kg : 1.0;
  p.v0 = velocity;
  p.force = force;
}

void FemSolid::fixNodes(const std::vector<int>& nodes) {
  for (int n : nodes) unknown_[static_cast<std::size_t>(n)] = kFixed;
}

Eigen::Matrix3d FemSolid::deformation(std::size_t e) const {
  const std::array<int, 4>& t = tets_[e];
  Eigen::Matrix3d ds;
  for (int k = 0; k < 3; ++k) ds.col(k) = x_[static_cast<std::size_t>(t[k + 1])] - x_[static_cast<std::size_t>(t[0])];
  return ds * elements_[e].dm_inverse;
}

// Element e's corotated force, −R K0 (Rᵀ x − X), added to `out`.
void FemSolid::addElementForce(std::size_t e, const Eigen::Matrix3d& r, std::vector<Vec3>& out) const {
  const std::array<int, 4>& t = tets_[e];
  Vec12 u;
  for (int a = 0; a < 4; ++a) {
    const std::size_t n = static_cast<std::size_t>(t[a]);
    u.segment<3>(3 * a) = r.transpose() * x_[n] - rest_[n];
  }
  const Vec12 f = elements_[e].stiffness * u;
  for (int a = 0; a < 4; ++a) out[static_cast<std::size_t>(t[a])] -= r * f.segment<3>(3 * a);
}

int FemSolid::invertedElements() const {
  int inverted = 0;
  for (std::size_t e = 0; e < tets_.size(); ++e) inverted += deformation(e).determinant() <= 0.0;
  return inverted;
}

void FemSolid::resetToRest() {
  if (!bone_offset_.allFinite()) bone_offset_.setZero();  // the caller moves the bone back (moveBone)
  for (std::size_t n = 0; n < x_.size(); ++n) {
    x_[n] = rest_[n] + bone_offset_;
    v_[n] = Vec3::Zero();
  }
  bone_v_ = Vec3::Zero();
  for (Element& e : elements_) e.rotation = Eigen::Quaterniond::Identity();
  std::fill(node_slips_.begin(), node_slips_.end(), Slip{});
}

void FemSolid::keepState() {
  kept_.x = x_;
  kept_.rotations.resize(elements_.size());
  for (std::size_t e = 0; e < elements_.size(); ++e) kept_.rotations[e] = elements_[e].rotation;
  kept_.bone_offset = bone_offset_;
  kept_.set = true;
}

void FemSolid::restoreState() {
  if (!kept_.set) {
    resetToRest();
    return;
  }
  std::copy(kept_.x.begin(), kept_.x.end(), x_.begin());
  for (std::size_t e = 0; e < elements_.size(); ++e) elements_[e].rotation = kept_.rotations[e];
  bone_offset_ = kept_.bone_offset;
  std::fill(v_.begin(), v_.end(), Vec3::Zero());
  bone_v_ = Vec3::Zero();
  std::fill(node_slips_.begin(), node_slips_.end(), Slip{});
}

void FemSolid::moveBone(const Vec3& offset, const Vec3& velocity) {
  const Vec3 shift = offset - bone_offset_;
  for (Vec3& x : x_) x += shift;
  bone_offset_ = offset;
  bone_v_ = velocity;
}

std::vector<Vec3> FemSolid::elasticForces() const {
  std::vector<Vec3> out(x_.size(), Vec3::Zero());
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    addElementForce(e, nearestRotation(deformation(e), elements_[e].rotation).toRotationMatrix(), out);
  }
  return out;
}

// The system's pattern, once: every block two unknowns share in an element, and the slot of each
// of its entries in the compressed matrix, so a step adds values in place.
void FemSolid::buildPattern() {
  std::vector<Eigen::Triplet<double>> pattern;
  for (const std::array<int, 4>& t : tets_) {
    for (int a : t) {
      for (int b : t) {
        const int ua = unknownOf(a), ub = unknownOf(b);
        if (ua < 0 || ub < 0) continue;
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) pattern.emplace_back(3 * ua + i, 3 * ub + j, 1.0);
        }
      }
    }
  }
  for (int u = 0; u < unknowns_; ++u) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) pattern.emplace_back(3 * u + i, 3 * u + j, 1.0);
    }
  }
  for (const Partner& p : partners_) {
    for (int node : p.nodes) {
      const int u = unknownOf(node);
      if (u < 0) continue;
      for (int k = 0; k < 9; ++k) {
        pattern.emplace_back(3 * u + k / 3, 3 * p.unknown + k % 3, 1.0);
        pattern.emplace_back(3 * p.unknown + k / 3, 3 * u + k % 3, 1.0);
      }
    }
  }
  system_.resize(3 * unknowns_, 3 * unknowns_);
  system_.setFromTriplets(pattern.begin(), pattern.end());
  system_.makeCompressed();
  const auto slot = [&](int row, int col) {
    const int* begin = system_.innerIndexPtr() + system_.outerIndexPtr()[col];
    const int* end = system_.innerIndexPtr() + system_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - system_.innerIndexPtr());
  };
  block_slots_.assign(tets_.size() * 16 * 9, -1);
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        const int ua = unknownOf(tets_[e][a]), ub = unknownOf(tets_[e][b]);
        if (ua < 0 || ub < 0) continue;
        for (int k = 0; k < 9; ++k) block_slots_[(e * 16 + a * 4 + b) * 9 + k] = slot(3 * ua + k / 3, 3 * ub + k % 3);
      }
    }
  }
  diagonal_slots_.resize(static_cast<std::size_t>(unknowns_) * 9);
  for (int u = 0; u < unknowns_; ++u) {
    for (int k = 0; k < 9; ++k) diagonal_slots_[static_cast<std::size_t>(u) * 9 + k] = slot(3 * u + k / 3, 3 * u + k % 3);
  }
}

// The system (M + (dt β + dt²) K) v' = M v + dt f of one implicit Euler step, in the unknowns'
// velocities: f the elastic, node and bone forces at the step's start, K the corotated
// stiffness, its values added in place in the pattern's slots. Contacts come on top
// (solveContacts).
void FemSolid::assemble(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force) {
  const double k_scale = dt * material_.damping_s + dt * dt;
  double* values = system_.valuePtr();
  std::fill(values, values + system_.nonZeros(), 0.0);
  rhs_.setZero(3 * unknowns_);
  std::fill(forces_.begin(), forces_.end(), Vec3::Zero());
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    Element& el = elements_[e];
    el.rotation = nearestRotation(deformation(e), el.rotation);
    const Eigen::Matrix3d r = el.rotation.toRotationMatrix();
    addElementForce(e, r, forces_);
    for (std::size_t ab = 0; ab < 16; ++ab) {
      const int* slots = &block_slots_[(e * 16 + ab) * 9];
      if (slots[0] < 0) continue;
      const Eigen::Matrix3d block = k_scale * r * el.stiffness.block<3, 3>(3 * (ab / 4), 3 * (ab % 4)) * r.transpose();
      for (int k = 0; k < 9; ++k) values[slots[k]] += block(k / 3, k % 3);
    }
  }
  for (std::size_t n = 0; n < x_.size(); ++n) {
    const int u = unknown_[n];
    if (u < 0) continue;
    const Vec3 f = forces_[n] + (node_forces.empty() ? Vec3::Zero() : node_forces[n]);
    rhs_.segment<3>(3 * u) += mass_[n] * (u == 0 && has_bone_ ? bone_v_ : v_[n]) + dt * f;
    for (int k = 0; k < 3; ++k) values[diagonal_slots_[static_cast<std::size_t>(u) * 9 + 4 * k]] += mass_[n];
  }
  if (has_bone_) {
    rhs_.head<3>() += bone_mass_ * bone_v_ + dt * bone_force;
    for (int k = 0; k < 3; ++k) values[diagonal_slots_[4 * k]] += bone_mass_;
  }
  for (const Partner& p : partners_) {
    rhs_.segment<3>(3 * p.unknown) += p.mass * p.v0 + dt * p.force;
    for (int k = 0; k < 3; ++k) values[diagonal_slots_[static_cast<std::size_t>(p.unknown) * 9 + 4 * k]] += p.mass;
  }
}

void FemSolid::addBlock(int ua, int ub, const Eigen::Matrix3d& block) {
  double* values = system_.valuePtr();
  const int* rows = system_.innerIndexPtr();
  for (int j = 0; j < 3; ++j) {
    const int col = 3 * ub + j;
    const int* begin = rows + system_.outerIndexPtr()[col];
    const int* end = rows + system_.outerIndexPtr()[col + 1];
    const std::ptrdiff_t first = std::lower_bound(begin, end, 3 * ua) - rows;  // the block's rows follow
    for (int i = 0; i < 3; ++i) values[first + i] += block(i, j);
  }
}

int FemSolid::contactUnknowns(const FemContact& c, std::array<int, 3>& u, std::array<double, 3>& w) const {
  const std::array<int, 3> nodes{c.node, c.others[0], c.others[1]};
  const bool face = c.others[0] >= 0 || c.others[1] >= 0;
  int count = 0;
  for (int a = 0; a < 3; ++a) {
    const double weight = face ? c.weights[a] : a == 0 ? 1.0 : 0.0;
    if (nodes[static_cast<std::size_t>(a)] < 0 || weight == 0.0) continue;
    const int un = unknownOf(nodes[static_cast<std::size_t>(a)]);
    if (un < 0) continue;
    int k = 0;
    while (k < count && u[static_cast<std::size_t>(k)] != un) ++k;
    if (k == count) {
      u[static_cast<std::size_t>(count)] = un;
      w[static_cast<std::size_t>(count++)] = 0.0;
    }
    w[static_cast<std::size_t>(k)] += weight;
  }
  return count;
}

// A rubbing contact's mode for the next pass from its spring's `trial` stretch and its friction
// `cap` (N) this pass: sticking within the cap, else slipping at it along the stretch,
// linearised there. True when it kept its mode and, slipping, its friction moved by at most
// kSlipSettled of its cap.
bool FemSolid::restick(double cap, const Vec3& trial, FemContactResult& r, Slip& slip) const {
  const double stretch = trial.norm();
  const Vec3 direction = stretch > 0.0 ? Vec3(trial / stretch) : Vec3::Zero();
  // Slipping the way it slipped turned round (its friction along the slip has no stiffness, so
  // a pass from a wrong direction overshoots): it sticks for the next pass, which finds its way.
  const bool turned = r.slipping && direction.dot(slip.direction) < 0.0;
  if (!(contact_stiffness_ * stretch > cap) || turned) {
    const bool kept = !r.slipping;
    r.slipping = false;
    return kept;
  }
  const bool kept = r.slipping && (cap * direction - slip.force).norm() <= kSlipSettled * cap;
  r.slipping = true;
  slip = {cap * direction, direction, cap / stretch};
  return kept;
}

// The contacts on the system without them, each in its mode, solved; each one's force from the
// solution, then its mode for another pass (a return mapping: the friction of a node is its
// tangential spring's trial force k s, s = P (slide + dt (v_s − v)), P the tangent plane's
// projection, when that is within the cap mu N; else mu N along s, the anchor dragged behind).
// A normal spring k (depth + dt (v_s − v)·n) n, implicit (k n nᵀ in the system); one that would
// pull is let go for the rest of the step. A sticking spring k P s, implicit (k P). A slipping
// one linearised about the last pass (its consistent tangent): mu N_k ŝ + c Q s, c = mu N_k / |s_k|,
// Q = P − ŝ ŝᵀ (the cap's circle: turning costs c, stretching nothing), N_k lagged by a pass.
// True when no mode changed and no slipping friction moved past kSlipSettled of its cap.
bool FemSolid::solveContacts(double dt, const std::vector<FemContact>& contacts, bool adjust) {
  std::copy(base_values_.begin(), base_values_.end(), system_.valuePtr());
  rhs_ = base_rhs_;
  for (std::size_t i = 0; i < contacts.size(); ++i) addContactRows(dt, contacts[i], i);
  solver_->factorize(system_);
  solver_->solve(rhs_, solution_);
  for (Partner& p : partners_) p.v = solution_.segment<3>(3 * p.unknown);
  bool settled = true;
  for (std::size_t i = 0; i < contacts.size(); ++i) settled = readContact(dt, contacts[i], i, adjust) && settled;
  return settled;
}

// Whether contact `c` is on a partner whose nodes hold every node of its point.
bool FemSolid::coupled(const FemContact& c) const {
  if (c.partner < 0 || c.partner >= partnerCount()) return false;
  const std::vector<char>& has = partners_[static_cast<std::size_t>(c.partner)].has;
  const auto in = [&](int n) { return n < 0 || has[static_cast<std::size_t>(n)] != 0; };
  return in(c.node) && in(c.others[0]) && in(c.others[1]);
}

// The velocity of contact `c`'s surface known before the solve: on a partner, all but the
// partner's translation (its turning).
Vec3 FemSolid::knownVelocity(const FemContact& c) const {
  return coupled(c) ? Vec3(c.surface_velocity - partners_[static_cast<std::size_t>(c.partner)].v0) : c.surface_velocity;
}

// Contact `i`'s springs in its mode added to the system: on its point's unknowns in their
// weights' products, and between them and its partner's.
void FemSolid::addContactRows(double dt, const FemContact& c, std::size_t i) {
  std::array<int, 3> u{};
  std::array<double, 3> w{};
  const int count = contactUnknowns(c, u, w);
  if (!((c.depth > 0.0 || c.bilateral) && count > 0 && !contact_results_[i].released)) return;
  const double k = contact_stiffness_;
  const Eigen::Matrix3d nn = c.normal * c.normal.transpose();
  const Vec3 vs = knownVelocity(c);
  Vec3 push = dt * k * (c.depth + dt * vs.dot(c.normal)) * c.normal;
  Eigen::Matrix3d block = dt * dt * k * nn;
  if (c.friction > 0.0) {
    const Slip& slip = slips_[i];
    const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - nn;
    const bool slipping = contact_results_[i].slipping;
    const Eigen::Matrix3d spring = slipping ? Eigen::Matrix3d(slip.stiffness * (tangent - slip.direction * slip.direction.transpose()))
                                            : Eigen::Matrix3d(k * tangent);
    push += dt * spring * (c.slide + dt * vs);
    if (slipping) push += dt * slip.force;
    block += dt * dt * spring;
  }
  const int pu = coupled(c) ? partners_[static_cast<std::size_t>(c.partner)].unknown : -1;
  for (std::size_t a = 0; a < static_cast<std::size_t>(count); ++a) {
    rhs_.segment<3>(3 * u[a]) += w[a] * push;
    for (std::size_t b = 0; b < static_cast<std::size_t>(count); ++b) {
      if (a == b) addDiagonal(u[a], w[a] * w[a] * block);
      else addBlock(u[a], u[b], w[a] * w[b] * block);
    }
    if (pu >= 0) {
      addBlock(u[a], pu, -w[a] * block);
      addBlock(pu, u[a], -w[a] * block);
    }
  }
  if (pu >= 0) {
    rhs_.segment<3>(3 * pu) -= push;
    addDiagonal(pu, block);
  }
}

// Contact `i`'s force from the solution, and (`adjust`) its mode for another pass; true when its
// mode holds.
bool FemSolid::readContact(double dt, const FemContact& c, std::size_t i, bool adjust) {
  FemContactResult& r = contact_results_[i];
  r.force = Vec3::Zero();
  std::array<int, 3> u{};
  std::array<double, 3> w{};
  const int count = contactUnknowns(c, u, w);
  if (!((c.depth > 0.0 || c.bilateral) && count > 0 && !r.released)) return true;
  Vec3 point_v = Vec3::Zero();
  for (std::size_t a = 0; a < static_cast<std::size_t>(count); ++a) point_v += w[a] * solution_.segment<3>(3 * u[a]);
  const Vec3 partner_v = coupled(c) ? partners_[static_cast<std::size_t>(c.partner)].v : Vec3::Zero();
  const Vec3 relative = knownVelocity(c) + partner_v - point_v;
  const double normal = contact_stiffness_ * (c.depth + dt * relative.dot(c.normal));
  Vec3 trial = c.slide + dt * relative;  // the tangential spring's stretch were it sticking
  trial -= trial.dot(c.normal) * c.normal;
  Slip& slip = slips_[i];
  Vec3 friction = Vec3::Zero();
  if (c.friction > 0.0) {
    friction = r.slipping ? Vec3(slip.force + slip.stiffness * (trial - trial.dot(slip.direction) * slip.direction))
                          : Vec3(contact_stiffness_ * trial);
  }
  r.force = normal * c.normal + friction;
  if (!adjust) return true;
  if (normal < 0.0 && !c.bilateral) {  // it would pull: let go
    r.released = true;
    return false;
  }
  return c.friction > 0.0 && !c.bilateral ? restick(c.friction * normal, trial, r, slip) : true;
}

void FemSolid::addDiagonal(int u, const Eigen::Matrix3d& block) {
  double* values = system_.valuePtr();
  for (int j = 0; j < 9; ++j) values[diagonal_slots_[static_cast<std::size_t>(u) * 9 + j]] += block(j / 3, j % 3);
}

void FemSolid::step(double dt, const std::vector<Vec3>& node_forces, const Vec3& bone_force,
                    const std::vector<FemContact>& contacts) {
  if (!analysed_) {  // number the unknowns: the bone first, then each free node
    unknowns_ = has_bone_ ? 1 : 0;
    for (Partner& p : partners_) p.unknown = unknowns_++;
    for (int& u : unknown_) {
      if (u == kFree) u = unknowns_++;
    }
    solver_ = std::make_unique<SparseLdlt>();
    forces_.assign(x_.size(), Vec3::Zero());
    buildPattern();
  }
  assemble(dt, node_forces, bone_force);
  if (!analysed_) {
    solver_->analyzePattern(system_);
    analysed_ = true;
  }
  base_values_.assign(system_.valuePtr(), system_.valuePtr() + system_.nonZeros());
  base_rhs_ = rhs_;
  // Each contact starts in the mode its node ended the last step in: slipping as it slipped then
  // (a node sliding on keeps sliding, a pass or two from settling), along the slip turned into
  // this step's tangent plane; else sticking. A contact whose anchor is new (no slide: it just
  // touched, or touches another surface) starts sticking.
  contact_results_.assign(contacts.size(), FemContactResult{});
  slips_.assign(contacts.size(), Slip{});
  node_slips_.resize(x_.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const FemContact& c = contacts[i];
    const Slip& last = node_slips_[static_cast<std::size_t>(c.node)];
    const Vec3 direction = last.direction - last.direction.dot(c.normal) * c.normal;
    const bool fresh = (c.slide - c.slide.dot(c.normal) * c.normal).squaredNorm() == 0.0;
    const bool node_contact = c.others[0] < 0 && c.others[1] < 0;  // a face's point starts sticking
    if (node_contact && c.friction > 0.0 && c.depth > 0.0 && unknownOf(c.node) >= 0 && last.stiffness > 0.0 && !fresh && direction.norm() > 0.5) {
      contact_results_[i].slipping = true;
      slips_[i] = {last.force.norm() * direction.normalized(), direction.normalized(), last.stiffness};
    }
  }
  bool settled = false;
  last_passes_ = 0;
  while (last_passes_ < kMaxContactPasses && !settled) {
    settled = solveContacts(dt, contacts);
    ++last_passes_;
  }
  if (!settled) {
    solveContacts(dt, contacts, false);
    ++last_passes_;
  }
  last_settled_ = settled;
  if (has_bone_) {
    bone_v_ = solution_.head<3>();
    bone_offset_ += dt * bone_v_;
  }
  for (std::size_t n = 0; n < x_.size(); ++n) {
    const int u = unknown_[n];
    v_[n] = u < 0 ? Vec3::Zero() : u == 0 && has_bone_ ? bone_v_ : Vec3(solution_.segment<3>(3 * u));
    x_[n] += dt * v_[n];
  }
  contact_forces_.resize(contacts.size());
  std::fill(node_slips_.begin(), node_slips_.end(), Slip{});
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    contact_forces_[i] = contact_results_[i].force;
    const FemContactResult& r = contact_results_[i];
    if (r.slipping && !r.released && contacts[i].others[0] < 0 && contacts[i].others[1] < 0) node_slips_[static_cast<std::size_t>(contacts[i].node)] = slips_[i];
  }
}

}  // namespace gf::sim
