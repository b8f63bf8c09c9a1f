#include "sinew/forms/elastic_form.hpp"

#include <atomic>
#include <cstdint>
#include <type_traits>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "sinew/core/error.hpp"
#include "sinew/core/svd.hpp"
#include "sinew/element/fixed_element.hpp"
#include "hex_invariant_stiffness.hpp"

namespace sinew {
namespace {

using fixed_element::gradients;
using fixed_element::positions;

// Runs body(std::integral_constant<int, N>) for the fixed node counts (8, 4), else with
// Eigen::Dynamic.
template <class Body>
auto with_nodes(int nodes, const Body& body) {
  if (nodes == 8) return body(std::integral_constant<int, 8>());
  if (nodes == 4) return body(std::integral_constant<int, 4>());
  return body(std::integral_constant<int, Eigen::Dynamic>());
}

}  // namespace

ElasticForm::ElasticForm(std::shared_ptr<const Discretization> disc,
                         std::shared_ptr<const Material> material, Projection projection)
    : disc_(std::move(disc)), material_(std::move(material)), projection_(projection) {
  const Discretization& d = *disc_;
  if (d.nodes() == 8 && d.quadrature_points() == 8) invariant_ = dynamic_cast<const InvariantMaterial*>(material_.get());
  // One gradient set per rest shape when shapes repeat (3 kB each); else built per element.
  if (invariant_ && d.num_rest_shapes() * 8 <= d.num_elements()) {
    shape_lanes_.resize(static_cast<size_t>(d.num_rest_shapes()));
    std::vector<char> done(shape_lanes_.size(), 0);
    for (Eigen::Index e = 0; e < d.num_elements(); ++e) {
      const auto s = static_cast<size_t>(d.rest_shape(e));
      if (!done[s]) shape_lanes_[s] = hex_gradient_lanes(d, e);
      done[s] = 1;
    }
  }
}

ElasticForm::~ElasticForm() = default;

const HexGradientLanes* ElasticForm::hex_lanes(Eigen::Index e, HexGradientLanes& scratch) const {
  if (!invariant_) return nullptr;
  if (!shape_lanes_.empty()) return &shape_lanes_[static_cast<size_t>(disc_->rest_shape(e))];
  scratch = hex_gradient_lanes(*disc_, e);
  return &scratch;
}

double ElasticForm::value(const Eigen::VectorXd& x) const {
  return with_nodes(disc_->nodes(), [&](auto nodes) { return value_fixed<decltype(nodes)::value>(x); });
}

template <int N>
double ElasticForm::value_fixed(const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  // Deterministic reduction: the same x gives bit-identical energies, which the line search needs.
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, d.num_elements(), 256), 0.0,
      [&](const tbb::blocked_range<Eigen::Index>& r, double acc) {
        for (Eigen::Index e = r.begin(); e != r.end(); ++e) {
          const auto xe = positions<N>(d, e, x);
          for (int q = 0; q < d.quadrature_points(); ++q) {
            const Mat3 F = xe * gradients<N>(d, e, q);
            acc += material_->in_domain(F) ? d.weight(e, q) * material_->psi(F)
                                           : std::numeric_limits<double>::infinity();
          }
        }
        return acc;
      },
      std::plus<double>());
}

void ElasticForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  with_nodes(disc_->nodes(), [&](auto nodes) {
    add_gradient_fixed<decltype(nodes)::value>(x, g);
    return 0;
  });
}

template <int N>
void ElasticForm::add_gradient_fixed(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  const Discretization& d = *disc_;
  const auto& elements = d.mesh().elements;
  for (const auto& runs : d.run_colors()) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, runs.size(), 1), [&](const auto& r) {
      for (size_t run = r.begin(); run != r.end(); ++run)
      for (Eigen::Index e = runs[run].first; e != runs[run].end; ++e) {
        const auto xe = positions<N>(d, e, x);
        Eigen::Matrix<double, 3, N> ge = Eigen::Matrix<double, 3, N>::Zero(3, d.nodes());
        if (add_invariant_gradient<N>(e, xe, ge)) {
          for (int a = 0; a < d.nodes(); ++a) g.segment<3>(3 * elements(e, a)) += ge.col(a);
          continue;
        }
        for (int q = 0; q < d.quadrature_points(); ++q) {
          const auto D = gradients<N>(d, e, q);
          ge.noalias() += d.weight(e, q) * material_->pk1(xe * D) * D.transpose();
        }
        for (int a = 0; a < d.nodes(); ++a) g.segment<3>(3 * elements(e, a)) += ge.col(a);
      }
    });
  }
}

template <int N>
bool ElasticForm::add_invariant_gradient(Eigen::Index e, const Eigen::Matrix<double, 3, N>& xe,
                                         Eigen::Matrix<double, 3, N>& ge) const {
  // Material::pk1's arithmetic (InvariantMaterial::pk1_impl) with one call for the material's
  // derivatives per element instead of the domain check and three virtual calls per point:
  // bitwise the same gradient. Points outside the domain go to the caller's pk1 loop, which
  // reports them.
  const Discretization& d = *disc_;
  constexpr int max_points = 8;
  const int points = d.quadrature_points();
  if (!invariant_ || points > max_points) return false;
  Mat3 F[max_points];
  double Ic[max_points], J[max_points];
  const bool positive_j = invariant_->domain() == Domain::PositiveJ;
  for (int q = 0; q < points; ++q) {
    F[q] = xe * gradients<N>(d, e, q);
    if (!F[q].allFinite()) return false;
    Ic[q] = F[q].squaredNorm();
    J[q] = F[q].determinant();
    if (positive_j && !(J[q] > 0.0)) return false;
  }
  InvariantMaterial::Derivatives derivatives[max_points];
  invariant_->curvature_derivatives_at(points, Ic, J, derivatives);
  for (int q = 0; q < points; ++q) {
    const Mat3 P = 2.0 * derivatives[q].dI * F[q] + derivatives[q].dJ * cofactor(F[q]);
    ge.noalias() += d.weight(e, q) * P * gradients<N>(d, e, q).transpose();
  }
  return true;
}

void ElasticForm::add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const { add_hessian_projected(x, H, projection_); }

void ElasticForm::add_exact_hessian(const Eigen::VectorXd& x, BlockHessian& H) const {
  add_hessian_projected(x, H, Projection::None);
}

void ElasticForm::add_hessian_projected(const Eigen::VectorXd& x, BlockHessian& H, Projection projection) const {
  if (disc_->nodes() == 8) return add_hessian_fixed<8>(x, H, projection);
  if (disc_->nodes() == 4) return add_hessian_fixed<4>(x, H, projection);
  throw Error("the elastic Hessian supports hexahedra and tetrahedra", "assembly");
}

template <int N, class Body>
void ElasticForm::for_each_element_stiffness(const Eigen::VectorXd& x, Projection projection, const Body& body) const {
  const Discretization& d = *disc_;
  for (const auto& runs : d.run_colors()) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, runs.size(), 1), [&](const auto& r) {
      fixed_element::SymmetricBlocks<N> K, K1;
      HexGradientLanes scratch, scratch1;
      for (size_t run = r.begin(); run != r.end(); ++run)
      for (Eigen::Index e = runs[run].first; e != runs[run].end; ++e) {
        const auto xe = positions<N>(d, e, x);
        K.set_zero();
        if constexpr (N == 8) {
          // The batched kernel where it applies, two elements of the run at a time; the generic
          // loop below reports bad points.
          const HexGradientLanes* lanes = hex_lanes(e, scratch);
          if (lanes && e + 1 != runs[run].end) {
            const auto xe1 = positions<N>(d, e + 1, x);
            const HexGradientLanes* lanes1 = hex_lanes(e + 1, scratch1);
            K1.set_zero();
            if (add_hex_invariant_stiffness_pair(*invariant_, projection, *lanes, xe, K, *lanes1, xe1, K1)) {
              K.symmetrize_diagonal();
              body(e, K);
              K1.symmetrize_diagonal();
              body(++e, K1);
              continue;
            }
          }
          if (lanes && add_hex_invariant_stiffness(*invariant_, projection, *lanes, xe, K)) {
            K.symmetrize_diagonal();
            body(e, K);
            continue;
          }
        }
        for (int q = 0; q < d.quadrature_points(); ++q) {
          const auto D = gradients<N>(d, e, q);
          fixed_element::add_stiffness<N>(D, material_->projected_hessian(xe * D, projection), d.weight(e, q), K);
        }
        K.symmetrize_diagonal();  // the assembled matrix is then exactly symmetric
        body(e, K);
      }
    });
  }
}

template <int N>
void ElasticForm::add_hessian_fixed(const Eigen::VectorXd& x, BlockHessian& H, Projection projection) const {
  const auto& elements = disc_->mesh().elements;
  const std::vector<std::uint16_t>& slots = scatter_map(H);
  const Eigen::Index num_elements = disc_->num_elements();
  for_each_element_stiffness<N>(x, projection, [&](Eigen::Index e, const fixed_element::SymmetricBlocks<N>& K) {
    // Upper blocks only; the lower ones are their transposes (K is symmetric). Runs of one
    // colour share no vertex, so no two tasks write the same block. Each node's columns are
    // looked up once per element.
    const std::uint16_t* slot = slots.data() + static_cast<size_t>(e) * N * N;
    BlockHessian::Columns columns[N];
    for (int b = 0; b < N; ++b) columns[b] = H.columns(elements(e, b));
    for (int a = 0; a < N; ++a) {
      columns[a].add(slot[a * N + a], K.K[a][a]);
      for (int b = a + 1; b < N; ++b) {
        columns[b].add(slot[a * N + b], K.K[a][b]);
        columns[a].add_transposed(slot[b * N + a], K.K[a][b]);
      }
    }
    // The blocks of the element two on load while the next stiffness is computed (runs are
    // consecutive elements, taken two at a time; at a run's end this only warms blocks another
    // task may visit).
    if (e + 2 < num_elements) {
      const std::uint16_t* next = slot + 2 * N * N;
      for (int b = 0; b < N; ++b) {
        const BlockHessian::Columns c = H.columns(elements(e + 2, b));
        for (int a = 0; a < N; ++a) c.prefetch(next[a * N + b]);
      }
    }
  });
}

void ElasticForm::prepare_hessian_product(const Eigen::VectorXd& x, bool exact) {
  const Projection projection = exact ? Projection::None : projection_;
  if (disc_->nodes() == 8) return prepare_hessian_product_fixed<8>(x, projection);
  if (disc_->nodes() == 4) return prepare_hessian_product_fixed<4>(x, projection);
  throw Error("the matrix-free Hessian supports hexahedra and tetrahedra", "solver.linear.hessian");
}

template <int N>
void ElasticForm::prepare_hessian_product_fixed(const Eigen::VectorXd& x, Projection projection) {
  if (element_matrices_.empty()) element_matrices_.resize(*disc_);
  for_each_element_stiffness<N>(x, projection, [&](Eigen::Index e, const fixed_element::SymmetricBlocks<N>& K) {
    for (int a = 0; a < N; ++a)
      for (int b = a; b < N; ++b) element_matrices_.store(e, a, b, K.K[a][b]);
  });
}

void ElasticForm::add_hessian_product(const Eigen::VectorXd& p, Eigen::VectorXd& y) const {
  element_matrices_.add_product(p, y);
}

Eigen::Index ElasticForm::hessian_product_elements() const {
  return element_matrices_.empty() ? 0 : disc_->num_elements();
}

int ElasticForm::hessian_product_element(Eigen::Index e, int* vertices, ElementMatrix* K) const {
  const int n = disc_->nodes();
  for (int a = 0; a < n; ++a) vertices[a] = disc_->mesh().elements(e, a);
  if (K) element_matrices_.unpack(e, K->topLeftCorner(3 * n, 3 * n));
  return n;
}

void ElasticForm::add_hessian_diagonal(std::vector<Mat3>& diagonal) const { element_matrices_.add_diagonal(diagonal); }

const std::vector<std::uint16_t>& ElasticForm::scatter_map(const BlockHessian& H) const {
  std::lock_guard<std::mutex> lock(scatter_mutex_);
  if (scatter_pattern_ == H.pattern_id()) return scatter_slots_;
  const Discretization& d = *disc_;
  const auto& elements = d.mesh().elements;
  const int n = d.nodes();
  if (H.max_slots() > std::numeric_limits<std::uint16_t>::max())
    throw Error("a vertex is coupled to more than 65,535 others; the element scatter map cannot index it",
                "assembly");
  scatter_slots_.resize(static_cast<size_t>(d.num_elements()) * n * n);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, d.num_elements(), 1024), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end(); ++e)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const int k = H.slot(elements(e, a), elements(e, b));
          if (k < 0) throw Error("an element's vertex pair is not in the Hessian pattern", "assembly");
          scatter_slots_[(static_cast<size_t>(e) * n + a) * n + b] = static_cast<std::uint16_t>(k);
        }
  });
  scatter_pattern_ = H.pattern_id();
  return scatter_slots_;
}

double ElasticForm::element_value(Eigen::Index e, const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  double U = 0.0;
  for (int q = 0; q < d.quadrature_points(); ++q) U += d.weight(e, q) * material_->psi(xe * d.gradients(e, q));
  return U;
}

Eigen::VectorXd ElasticForm::element_gradient(Eigen::Index e, const Eigen::VectorXd& x, JacobianKind kind) const {
  if (kind != JacobianKind::Exact)
    throw Error("a hyperelastic material has no warped-force Jacobian; use \"exact\"", "jacobian");
  const Discretization& d = *disc_;
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  Eigen::Matrix3Xd ge = Eigen::Matrix3Xd::Zero(3, d.nodes());
  for (int q = 0; q < d.quadrature_points(); ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    ge += d.weight(e, q) * material_->pk1(xe * D) * D.transpose();
  }
  return ge.reshaped();
}

Eigen::MatrixXd ElasticForm::element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * d.nodes(), 3 * d.nodes());
  for (int q = 0; q < d.quadrature_points(); ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    add_element_hessian(D, material_->projected_hessian(xe * D, projection_), d.weight(e, q), K);
  }
  return K;
}

bool ElasticForm::is_valid(const Eigen::VectorXd& x) const {
  if (material_->domain() == Domain::All) return x.allFinite();
  const Discretization& d = *disc_;
  std::atomic<bool> ok{true};
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, d.num_elements(), 256), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end() && ok.load(std::memory_order_relaxed); ++e) {
      const Eigen::Matrix3Xd xe = d.element_positions(e, x);
      for (int q = 0; q < d.quadrature_points(); ++q)
        if (!material_->in_domain(xe * d.gradients(e, q))) ok = false;
    }
  });
  return ok;
}

ElasticForm::ElementFields ElasticForm::element_fields(const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  ElementFields f;
  const Eigen::Index m = d.num_elements();
  f.energy.resize(m);
  f.J.resize(m);
  f.energy_density.resize(m);
  f.stress_norm.resize(m);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, m, 256), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end(); ++e) {
      const Eigen::Matrix3Xd xe = d.element_positions(e, x);
      double energy = 0.0, J = 0.0, stress = 0.0, volume = 0.0;
      for (int q = 0; q < d.quadrature_points(); ++q) {
        const Mat3 F = xe * d.gradients(e, q);
        const double w = d.weight(e, q);
        const bool defined = material_->in_domain(F);
        energy += defined ? w * material_->psi(F) : std::numeric_limits<double>::infinity();
        stress += defined ? w * material_->pk1(F).norm() : std::numeric_limits<double>::infinity();
        J += w * F.determinant();
        volume += w;
      }
      f.energy(e) = energy;
      f.J(e) = J / volume;
      f.energy_density(e) = energy / volume;
      f.stress_norm(e) = stress / volume;
    }
  });
  return f;
}

}  // namespace sinew
