#include "sinew/forms/self_contact_form.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {

// ---- uniform grid -------------------------------------------------------------------------

long long UniformGrid::key(const Eigen::Vector3i& c) {
  // 21 bits per axis (offset so that negative cells hash too).
  const auto u = [](int v) { return static_cast<long long>(v + (1 << 20)) & ((1LL << 21) - 1); };
  return (u(c.x()) << 42) | (u(c.y()) << 21) | u(c.z());
}

Eigen::Vector3i UniformGrid::cell_of(const Eigen::Vector3d& p) const {
  return (p / cell_).array().floor().cast<int>();
}

void UniformGrid::insert(int item, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3i a = cell_of(lo), b = cell_of(hi);
  for (int i = a.x(); i <= b.x(); ++i)
    for (int j = a.y(); j <= b.y(); ++j)
      for (int k = a.z(); k <= b.z(); ++k) cells_[key(Eigen::Vector3i(i, j, k))].push_back(item);
}

const std::vector<int>* UniformGrid::at(const Eigen::Vector3i& c) const {
  const auto it = cells_.find(key(c));
  return it == cells_.end() ? nullptr : &it->second;
}

// ---- geometry ----------------------------------------------------------------------------

Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  // Voronoi regions of the vertices, edges and face in turn (Ericson, Real-Time Collision
  // Detection §5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {1.0 - v, v, 0.0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1.0 - v - w, v, w};
}

namespace {

Eigen::Vector3d position(const Eigen::VectorXd& x, int v) { return x.segment<3>(3 * v); }

}  // namespace

// ---- the form ------------------------------------------------------------------------------

SelfContactForm::SelfContactForm(const VolumeMesh& mesh, const SelfContactSettings& settings)
    : settings_(settings), rest_(mesh.vertices) {
  if (!(std::isfinite(settings.stiffness) && settings.stiffness > 0.0))
    throw Error("self-contact stiffness must be positive", "self_contact");
  if (settings.refine_iterations < 0) throw Error("refine_iterations must be non-negative", "self_contact");
  tets_ = mesh.kind == ElementKind::Hex8 ? tetrahedralize_hexes(mesh).elements : mesh.elements;
  const BoundarySurface surface = boundary_surface(mesh);
  sample_ring_.assign(rest_.rows(), {});
  for (Eigen::Index e = 0; e < mesh.elements.rows(); ++e)
    for (Eigen::Index a = 0; a < mesh.elements.cols(); ++a)
      for (Eigen::Index b = 0; b < mesh.elements.cols(); ++b) sample_ring_[mesh.elements(e, a)].push_back(mesh.elements(e, b));
  for (auto& ring : sample_ring_) {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  }
  triangles_ = surface.triangles;
  samples_ = surface.vertices;
  area_.assign(rest_.rows(), 0.0);
  vertex_triangles_.assign(rest_.rows(), {});
  double edge_sum = 0.0;
  for (Eigen::Index t = 0; t < triangles_.rows(); ++t) {
    const Eigen::Vector3d a = rest_.row(triangles_(t, 0)), b = rest_.row(triangles_(t, 1)), c = rest_.row(triangles_(t, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    edge_sum += (b - a).norm() + (c - b).norm() + (a - c).norm();
    for (int k = 0; k < 3; ++k) {
      area_[triangles_(t, k)] += area / 3.0;
      vertex_triangles_[triangles_(t, k)].push_back(static_cast<int>(t));
    }
  }
  if (triangles_.rows() == 0) throw Error("the mesh has no boundary", "self_contact");
  // Grid cells about one and a half boundary edges wide.
  cell_ = 1.5 * edge_sum / (3.0 * static_cast<double>(triangles_.rows()));
  rest_triangle_grid_ = UniformGrid(cell_);
  for (Eigen::Index t = 0; t < triangles_.rows(); ++t) {
    Eigen::AlignedBox3d box;
    for (int k = 0; k < 3; ++k) box.extend(rest_.row(triangles_(t, k)).transpose());
    rest_triangle_grid_.insert(static_cast<int>(t), box.min(), box.max());
    rest_bounds_.extend(box);
  }
}

bool SelfContactForm::triangle_has(int triangle, int vertex) const {
  return triangles_(triangle, 0) == vertex || triangles_(triangle, 1) == vertex || triangles_(triangle, 2) == vertex;
}

Eigen::Vector3d SelfContactForm::closest_rest_point(const Eigen::Vector3d& X, int sample, int& triangle) const {
  // Rings of grid cells around X's cell, outwards, until no unseen cell can hold a closer point:
  // a point at distance d lies at most floor(d / h) + 1 cells away per axis.
  const Eigen::Vector3i c = rest_triangle_grid_.cell_of(X);
  const double h = rest_triangle_grid_.cell_size();
  const int max_ring = static_cast<int>(std::ceil((rest_bounds_.diagonal().norm() + (X - rest_bounds_.center()).norm()) / h)) + 2;
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_weights = Eigen::Vector3d(1.0, 0.0, 0.0);
  triangle = -1;
  for (int ring = 0; ring <= max_ring; ++ring) {
    for (int i = -ring; i <= ring; ++i)
      for (int j = -ring; j <= ring; ++j)
        for (int k = -ring; k <= ring; ++k) {
          if (std::max({std::abs(i), std::abs(j), std::abs(k)}) != ring) continue;
          const std::vector<int>* items = rest_triangle_grid_.at(c + Eigen::Vector3i(i, j, k));
          if (!items) continue;
          for (int t : *items) {
            if (triangle_has(t, sample)) continue;  // the sample's own neighbourhood
            const Eigen::Vector3d a = rest_.row(triangles_(t, 0)), b = rest_.row(triangles_(t, 1)),
                                  cc = rest_.row(triangles_(t, 2));
            const Eigen::Vector3d w = closest_point_barycentric(X, a, b, cc);
            const Eigen::Vector3d p = w(0) * a + w(1) * b + w(2) * cc;
            const double d = (p - X).norm();
            if (d < best) {
              best = d;
              best_weights = w;
              triangle = t;
            }
          }
        }
    if (triangle >= 0 && best <= (ring - 1) * h) break;
  }
  return best_weights;
}

void SelfContactForm::refine_target(const Eigen::VectorXd& x, int sample, int& triangle, Eigen::Vector3d& weights) const {
  // Local descent over the deformed boundary: move to a neighbouring triangle (one sharing a
  // vertex) while it holds a point closer to the sample.
  const Eigen::Vector3d xs = position(x, sample);
  auto point = [&](int t, const Eigen::Vector3d& w) -> Eigen::Vector3d {
    return w(0) * position(x, triangles_(t, 0)) + w(1) * position(x, triangles_(t, 1)) + w(2) * position(x, triangles_(t, 2));
  };
  double best = (point(triangle, weights) - xs).norm();
  for (int it = 0; it < settings_.refine_iterations; ++it) {
    int next = -1;
    Eigen::Vector3d next_weights = weights;
    for (int k = 0; k < 3; ++k)
      for (int t : vertex_triangles_[triangles_(triangle, k)]) {
        if (triangle_has(t, sample)) continue;
        const Eigen::Vector3d w = closest_point_barycentric(xs, position(x, triangles_(t, 0)), position(x, triangles_(t, 1)),
                                                            position(x, triangles_(t, 2)));
        const double d = (point(t, w) - xs).norm();
        if (d < best * (1.0 - 1e-12)) {
          best = d;
          next = t;
          next_weights = w;
        }
      }
    if (next < 0) break;
    triangle = next;
    weights = next_weights;
  }
}

Eigen::Vector3d SelfContactForm::target(const Eigen::VectorXd& x, const SurfaceContact& c) const {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) t += c.weights(k) * position(x, triangles_(c.triangle, k));
  return t;
}

Eigen::MatrixX3d SelfContactForm::vertex_normals(const Eigen::VectorXd& x) const {
  // Area-weighted (unnormalised cross products) sums of the incident deformed triangle normals.
  Eigen::MatrixX3d n = Eigen::MatrixX3d::Zero(rest_.rows(), 3);
  for (Eigen::Index t = 0; t < triangles_.rows(); ++t) {
    const Eigen::Vector3d a = position(x, triangles_(t, 0));
    const Eigen::RowVector3d c = (position(x, triangles_(t, 1)) - a).cross(position(x, triangles_(t, 2)) - a).transpose();
    for (int k = 0; k < 3; ++k) n.row(triangles_(t, k)) += c;
  }
  return n;
}

Eigen::Vector3d SelfContactForm::surface_normal(const Eigen::VectorXd& /*x*/, const Eigen::MatrixX3d& normals,
                                                const SurfaceContact& c) const {
  // Vertex normals interpolated with the target's weights: continuous across triangle edges, so
  // a target on an edge or vertex gets the same normal whichever triangle holds it.
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = normals.row(triangles_(c.triangle, k)).transpose();
    if (v.norm() > 0.0) n += c.weights(k) * v.normalized();
  }
  return n;
}

std::vector<SurfaceContact> SelfContactForm::detect(const Eigen::VectorXd& x) const {
  if (x.size() != 3 * rest_.rows()) throw Error("positions have the wrong size", "self_contact");
  const Eigen::MatrixX3d normals = vertex_normals(x);
  // 1. Grid over the deformed tetrahedra.
  UniformGrid grid(cell_);
  for (Eigen::Index t = 0; t < tets_.rows(); ++t) {
    Eigen::AlignedBox3d box;
    for (int k = 0; k < 4; ++k) box.extend(position(x, tets_(t, k)));
    grid.insert(static_cast<int>(t), box.min(), box.max());
  }
  std::vector<SurfaceContact> out;
  for (int s : samples_) {
    const Eigen::Vector3d xs = position(x, s);
    const std::vector<int>* candidates = grid.at(grid.cell_of(xs));
    if (!candidates) continue;
    // 2. The containing tetrahedron (deepest one if several overlap) and its barycentric map.
    // Closed tetrahedra (a small negative tolerance): a sample on a face or edge shared by two
    // tetrahedra is inside, e.g. lattice-aligned blocks pressed together.
    int found = -1;
    double depth_in_tet = -1e-10;
    Eigen::Vector4d bary_found;
    for (int t : *candidates) {
      const std::vector<int>& ring = sample_ring_[s];
      bool near = false;
      for (int k = 0; k < 4 && !near; ++k) near = std::binary_search(ring.begin(), ring.end(), tets_(t, k));
      if (near) continue;  // the sample's own neighbourhood
      const Eigen::Vector3d p0 = position(x, tets_(t, 0));
      Mat3 M;
      for (int k = 0; k < 3; ++k) M.col(k) = position(x, tets_(t, k + 1)) - p0;
      const double det = M.determinant();
      if (!(std::abs(det) > 1e-30)) continue;
      const Eigen::Vector3d l = M.inverse() * (xs - p0);
      const Eigen::Vector4d bary(1.0 - l.sum(), l(0), l(1), l(2));
      const double m = bary.minCoeff();
      if (m > depth_in_tet) {
        found = t;
        depth_in_tet = m;
        bary_found = bary;
      }
    }
    if (found < 0) continue;
    Eigen::Vector3d X = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) X += bary_found(k) * rest_.row(tets_(found, k)).transpose();
    // 3. Closest rest boundary point, mapped back through its triangle.
    SurfaceContact c;
    c.sample = s;
    c.tet = found;
    c.weights = closest_rest_point(X, s, c.triangle);
    if (c.triangle < 0) continue;
    if (settings_.refine) refine_target(x, s, c.triangle, c.weights);
    c.target = target(x, c);
    const Eigen::Vector3d n = surface_normal(x, normals, c);
    if (!(n.norm() > 0.0)) continue;  // collapsed surface: no direction to push
    c.normal = n.normalized();
    c.depth = (c.target - xs).norm();
    if (c.depth <= 1e-12 * cell_) continue;  // touching, not penetrating
    out.push_back(c);
  }
  return out;
}

double SelfContactForm::surface_depth(const Eigen::VectorXd& x, int sample) const {
  if (x.size() != 3 * rest_.rows()) throw Error("positions have the wrong size", "self_contact");
  if (sample < 0 || sample >= rest_.rows()) throw Error("sample out of range", "self_contact");
  const Eigen::Vector3d xs = position(x, sample);
  const std::vector<int>& ring = sample_ring_[sample];
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < triangles_.rows(); ++t) {
    bool near = false;
    for (int k = 0; k < 3 && !near; ++k) near = std::binary_search(ring.begin(), ring.end(), triangles_(t, k));
    if (near) continue;
    const Eigen::Vector3d a = position(x, triangles_(t, 0)), b = position(x, triangles_(t, 1)), c = position(x, triangles_(t, 2));
    const Eigen::Vector3d w = closest_point_barycentric(xs, a, b, c);
    best = std::min(best, (w(0) * a + w(1) * b + w(2) * c - xs).norm());
  }
  return best;
}

bool SelfContactForm::begin_solve(const Eigen::VectorXd& x) {
  // Contacts carried over from the last solve are refitted where their sample is still found
  // inside the body (fresh triangle, weights and normal). No contact is added here: at a
  // solve's start the bones have just jumped and the flesh next to them is distorted, so new
  // detections there would be false ones.
  if (contacts_.empty()) return false;
  std::vector<int> index(rest_.rows(), -1);
  for (size_t i = 0; i < contacts_.size(); ++i) index[contacts_[i].sample] = static_cast<int>(i);
  couplings_changed_ = false;
  for (SurfaceContact& fresh : detect(x)) {
    const int i = index[fresh.sample];
    if (i < 0) continue;
    couplings_changed_ = couplings_changed_ || fresh.triangle != contacts_[i].triangle;
    contacts_[i] = std::move(fresh);
  }
  return true;
}

bool SelfContactForm::refresh(const Eigen::VectorXd& x) {
  // Called at a converged state. Newly penetrating samples are added; contacts whose sample is
  // now more than a quarter cell outside are dropped (they contribute neither energy nor force
  // at x). The others keep their triangle, weights and normal, so the energy changes only by
  // additions, finitely often per solve, and Newton minimises one fixed C1 energy in between
  // (re-fitting every contact at every iteration made the residual stall).
  std::vector<char> known(rest_.rows(), 0);
  for (const auto& c : contacts_) known[c.sample] = 1;
  std::vector<SurfaceContact> next;
  for (const SurfaceContact& c : contacts_) {
    const double gap = c.normal.dot(position(x, c.sample) - target(x, c));
    if (gap <= 0.25 * cell_) next.push_back(c);
  }
  const bool removed = next.size() != contacts_.size();
  const bool added = add_new_samples(x, known, std::numeric_limits<double>::infinity(), next);
  couplings_changed_ = added || removed;
  contacts_ = std::move(next);
  return added;
}

bool SelfContactForm::add_new_samples(const Eigen::VectorXd& x, const std::vector<char>& known, double max_depth,
                                      std::vector<SurfaceContact>& contacts) const {
  bool added = false;
  for (SurfaceContact& c : detect(x))
    if (!known[c.sample] && c.depth <= max_depth) {
      contacts.push_back(std::move(c));
      added = true;
    }
  if (added)
    std::sort(contacts.begin(), contacts.end(), [](const SurfaceContact& a, const SurfaceContact& b) { return a.sample < b.sample; });
  return added;
}

// Samples found deeper than this many grid cells (cell_: 1.5 mean boundary edges) at an iterate
// are left to the next converged state: at an iterate they are mostly transient (distorted flesh
// next to a bone that just moved) and would get a far target; the ones worth catching early are
// shallow.
constexpr double kIterateDepth = 1.0 / 6.0;

bool SelfContactForm::add_at_iterate(const Eigen::VectorXd& x) {
  // Not before the first contact: the iterates of a solve's start are distorted where the bones
  // jumped, and samples there would be false contacts.
  couplings_changed_ = false;
  if (contacts_.empty()) return false;
  std::vector<char> known(rest_.rows(), 0);
  for (const auto& c : contacts_) known[c.sample] = 1;
  couplings_changed_ = add_new_samples(x, known, kIterateDepth * cell_, contacts_);
  return couplings_changed_;
}

double SelfContactForm::value(const Eigen::VectorXd& x) const {
  double e = 0.0;
  for (const auto& c : contacts_) {
    const double gap = std::min(0.0, c.normal.dot(position(x, c.sample) - target(x, c)));
    e += 0.5 * settings_.stiffness * area_[c.sample] * gap * gap;
  }
  return e;
}

void SelfContactForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (const auto& c : contacts_) {
    const double gap = std::min(0.0, c.normal.dot(position(x, c.sample) - target(x, c)));
    const Eigen::Vector3d f = settings_.stiffness * area_[c.sample] * gap * c.normal;
    g.segment<3>(3 * c.sample) += f;
    for (int k = 0; k < 3; ++k) g.segment<3>(3 * triangles_(c.triangle, k)) -= c.weights(k) * f;
  }
}

void SelfContactForm::add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const {
  for (const auto& c : contacts_) {
    if (c.normal.dot(position(x, c.sample) - target(x, c)) >= 0.0) continue;  // separated
    // k A [1, -w]^T [1, -w] (x) n n^T over (sample, triangle vertices).
    const Mat3 knn = settings_.stiffness * area_[c.sample] * c.normal * c.normal.transpose();
    const int nodes[4] = {c.sample, triangles_(c.triangle, 0), triangles_(c.triangle, 1), triangles_(c.triangle, 2)};
    const double coef[4] = {1.0, -c.weights(0), -c.weights(1), -c.weights(2)};
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) H.add_block(nodes[a], nodes[b], coef[a] * coef[b] * knn);
  }
}

void SelfContactForm::couplings(std::vector<std::vector<int>>& cliques) const {
  for (const auto& c : contacts_) cliques.push_back({c.sample, triangles_(c.triangle, 0), triangles_(c.triangle, 1), triangles_(c.triangle, 2)});
}

}  // namespace sinew
