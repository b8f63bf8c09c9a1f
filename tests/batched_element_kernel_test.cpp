// The batched kernels: lane-parallel SVD and 3x3 eigensystems against Eigen's, and the
// batched hexahedron stiffness against the generic per-point path (material.projected_hessian
// + add_element_hessian), at random deformations including inverted and degenerate ones.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "sinew/assembly/problem.hpp"
#include "sinew/core/batched_eigen3.hpp"
#include "sinew/core/svd.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/linalg/block_hessian.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {
namespace {

constexpr int W = 8;

// Random F of every kind the kernels meet: generic, inverted, rank 2, rank 1, zero, repeated
// singular values, nearly repeated ones, tiny and huge scales.
std::vector<Mat3> test_matrices(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  auto rotation = [&] {
    const Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    return Mat3(q.normalized().toRotationMatrix());
  };
  std::vector<Mat3> out;
  for (int i = 0; i < 40; ++i) out.push_back(Mat3::NullaryExpr([&] { return n(rng); }));
  for (const Vec3& s : {Vec3(1, 1, 1), Vec3(2, 2, 0.5), Vec3(3, 1, 1), Vec3(1, 1, -1), Vec3(2, 1, 0), Vec3(1, 0, 0),
                       Vec3(0, 0, 0), Vec3(1 + 1e-9, 1, 1 - 1e-9), Vec3(1, 1 - 1e-13, -1e-12), Vec3(1.8, 0.75, -0.75),
                       Vec3(1e-9, 5e-10, 1e-10), Vec3(1e8, 3e7, -2e7)})
    for (int i = 0; i < 4; ++i) out.push_back(rotation() * s.asDiagonal() * rotation().transpose());
  return out;
}

TEST(BatchedEigen3, SignedSvdMatchesTheRotationVariantSvd) {
  std::mt19937 rng(7);
  const std::vector<Mat3> Fs = test_matrices(rng);
  for (size_t start = 0; start + W <= Fs.size(); start += W) {
    double F[9][W], U[9][W], sigma[3][W], V[9][W];
    for (int l = 0; l < W; ++l)
      for (int m = 0; m < 9; ++m) F[m][l] = Fs[start + l].data()[m];
    batched::signed_svd<W>(F, U, sigma, V);
    for (int l = 0; l < W; ++l) {
      const Mat3& A = Fs[start + l];
      Mat3 Ul, Vl;
      Vec3 s;
      for (int m = 0; m < 9; ++m) {
        Ul.data()[m] = U[m][l];
        Vl.data()[m] = V[m][l];
      }
      for (int k = 0; k < 3; ++k) s(k) = sigma[k][l];
      const double scale = std::max(A.norm(), 1e-300);
      SCOPED_TRACE(testing::Message() << "F =\n" << A);
      EXPECT_LT((Ul.transpose() * Ul - Mat3::Identity()).norm(), 1e-13);
      EXPECT_LT((Vl.transpose() * Vl - Mat3::Identity()).norm(), 1e-13);
      EXPECT_NEAR(Ul.determinant(), 1.0, 1e-13);
      EXPECT_NEAR(Vl.determinant(), 1.0, 1e-13);
      EXPECT_LT((Ul * s.asDiagonal() * Vl.transpose() - A).norm(), 1e-13 * scale);
      EXPECT_LT((s - signed_svd(A).sigma).norm(), 1e-12 * scale);
    }
  }
}

TEST(BatchedEigen3, LaneGroupsSweepAsIfAlone) {
  // Two groups of 8 lanes in one call (how the stiffness kernel pairs elements) give bitwise
  // what each group gives alone, whichever group needs more sweeps: a diagonal group (no sweep)
  // beside generic ones, and generic groups beside degenerate and huge ones.
  std::mt19937 rng(13);
  std::vector<Mat3> Fs = test_matrices(rng);
  for (int l = 0; l < W; ++l) Fs.push_back(Vec3(1.0 + l, 2.0, 0.5).asDiagonal());
  ASSERT_EQ(Fs.size() % W, 0u);
  const int groups = static_cast<int>(Fs.size() / W);
  int compared = 0;
  for (int g0 = 0; g0 < groups; ++g0)
    for (int g1 = 0; g1 < groups; g1 += 3) {
      double F[9][2 * W], U[9][2 * W], sigma[3][2 * W], V[9][2 * W];
      double C[6][2 * W], values[3][2 * W], Q[9][2 * W];
      for (int l = 0; l < 2 * W; ++l) {
        const Mat3& A = Fs[static_cast<size_t>((l < W ? g0 : g1) * W + l % W)];
        for (int m = 0; m < 9; ++m) F[m][l] = A.data()[m];
        const Mat3 S = A.transpose() * A;
        const double c[6] = {S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(0, 2), S(1, 2)};
        for (int m = 0; m < 6; ++m) C[m][l] = c[m];
      }
      batched::signed_svd<2 * W, W>(F, U, sigma, V);
      batched::symmetric_eigen3<2 * W, W>(C, values, Q);
      for (int half = 0; half < 2; ++half) {
        double Fh[9][W], Uh[9][W], sh[3][W], Vh[9][W], Ch[6][W], vh[3][W], Qh[9][W];
        for (int l = 0; l < W; ++l) {
          const Mat3& A = Fs[static_cast<size_t>((half == 0 ? g0 : g1) * W + l)];
          for (int m = 0; m < 9; ++m) Fh[m][l] = A.data()[m];
          const Mat3 S = A.transpose() * A;
          const double c[6] = {S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(0, 2), S(1, 2)};
          for (int m = 0; m < 6; ++m) Ch[m][l] = c[m];
        }
        batched::signed_svd<W>(Fh, Uh, sh, Vh);
        batched::symmetric_eigen3<W>(Ch, vh, Qh);
        for (int l = 0; l < W; ++l) {
          const int L = half * W + l;
          for (int m = 0; m < 9; ++m) {
            EXPECT_EQ(U[m][L], Uh[m][l]) << g0 << " " << g1 << " lane " << L;
            EXPECT_EQ(V[m][L], Vh[m][l]) << g0 << " " << g1 << " lane " << L;
            EXPECT_EQ(Q[m][L], Qh[m][l]) << g0 << " " << g1 << " lane " << L;
          }
          for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(sigma[k][L], sh[k][l]) << g0 << " " << g1 << " lane " << L;
            EXPECT_EQ(values[k][L], vh[k][l]) << g0 << " " << g1 << " lane " << L;
          }
        }
      }
      ++compared;
    }
  EXPECT_GT(compared, 20);
}

TEST(BatchedEigen3, SymmetricEigensystemMatchesEigen) {
  std::mt19937 rng(11);
  std::vector<Mat3> As;
  for (const Mat3& F : test_matrices(rng)) As.push_back(F + F.transpose());
  for (size_t start = 0; start + W <= As.size(); start += W) {
    double a[6][W], values[3][W], V[9][W];
    for (int l = 0; l < W; ++l) {
      const Mat3& A = As[start + l];
      a[0][l] = A(0, 0), a[1][l] = A(1, 1), a[2][l] = A(2, 2), a[3][l] = A(0, 1), a[4][l] = A(0, 2), a[5][l] = A(1, 2);
    }
    batched::symmetric_eigen3<W>(a, values, V);
    for (int l = 0; l < W; ++l) {
      const Mat3& A = As[start + l];
      Mat3 Vl;
      Vec3 d;
      for (int m = 0; m < 9; ++m) Vl.data()[m] = V[m][l];
      for (int k = 0; k < 3; ++k) d(k) = values[k][l];
      const double scale = std::max(A.norm(), 1e-300);
      SCOPED_TRACE(testing::Message() << "A =\n" << A);
      EXPECT_LT((Vl.transpose() * Vl - Mat3::Identity()).norm(), 1e-13);
      EXPECT_NEAR(Vl.determinant(), 1.0, 1e-13);
      EXPECT_LT((A * Vl - Vl * d.asDiagonal()).norm(), 2e-15 * 8 * scale);
      EXPECT_GE(d(0), d(1));
      EXPECT_GE(d(1), d(2));
      const Vec3 reference = Eigen::SelfAdjointEigenSolver<Mat3>(A).eigenvalues().reverse();
      EXPECT_LT((d - reference).norm(), 1e-14 * 8 * scale);
    }
  }
}

// The element stiffness of every element the generic way (per point, 9x9 projected Hessian).
Eigen::MatrixXd generic_stiffness(const Discretization& d, const Material& m, Projection mode, Eigen::Index e,
                                  const Eigen::VectorXd& x) {
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(24, 24);
  for (int q = 0; q < d.quadrature_points(); ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    add_element_hessian(D, m.projected_hessian(xe * D, mode), d.weight(e, q), K);
  }
  return K;
}

struct Case {
  const char* family;
  double nu;
  bool inverted;  // whether the deformation may invert points (not for J > 0 materials)
};

void expect_batched_matches_generic(const VolumeMesh& mesh, double amplitude, unsigned seed) {
  for (const Case c : {Case{"stable_neo_hookean", 0.49, true}, Case{"stable_neo_hookean", 0.3, true},
                       Case{"fung", 0.45, true}, Case{"arruda_boyce", 0.4, true}, Case{"neo_hookean", 0.45, false},
                       Case{"neo_hookean_decoupled", 0.49, false}}) {
    MaterialSpec spec;
    spec.family = c.family;
    spec.target = YoungPoisson{1e5, c.nu};
    const auto material = build_material(spec);
    ASSERT_NE(dynamic_cast<const InvariantMaterial*>(material.get()), nullptr) << c.family;
    auto disc = std::make_shared<Discretization>(mesh);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd x = mesh.rest_positions();
    const double a = c.inverted ? amplitude : 0.1 * amplitude;
    for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = (i % 3 == 0 ? 1.6 : 0.8) * x(i) + a * u(rng);
    for (const Projection mode : {Projection::Clamp, Projection::Abs, Projection::None}) {
      SCOPED_TRACE(testing::Message() << c.family << " nu " << c.nu << " projection " << to_string(mode));
      Problem problem(mesh.num_vertices());
      problem.add_form(std::make_shared<ElasticForm>(disc, material, mode));
      const Eigen::SparseMatrix<double> A = *problem.hessian(x).matrix();
      Eigen::MatrixXd reference = Eigen::MatrixXd::Zero(x.size(), x.size());
      for (Eigen::Index e = 0; e < disc->num_elements(); ++e) {
        const Eigen::MatrixXd K = generic_stiffness(*disc, *material, mode, e, x);
        for (int p = 0; p < 8; ++p)
          for (int r = 0; r < 8; ++r)
            reference.block<3, 3>(3 * mesh.elements(e, p), 3 * mesh.elements(e, r)) += K.block<3, 3>(3 * p, 3 * r);
      }
      const Eigen::MatrixXd batched = Eigen::MatrixXd(A);
      EXPECT_LT((batched - reference).norm(), 1e-11 * reference.norm());
      EXPECT_EQ((batched - batched.transpose()).norm(), 0.0);
    }
  }
}

TEST(BatchedHexStiffness, CurvatureDerivativesAreTheInvariantDerivativesWithoutPsi) {
  for (const char* family : {"stable_neo_hookean", "fung", "arruda_boyce", "neo_hookean", "neo_hookean_decoupled"}) {
    MaterialSpec spec;
    spec.family = family;
    spec.target = YoungPoisson{1e5, 0.45};
    const auto material = build_material(spec);
    const auto& m = dynamic_cast<const InvariantMaterial&>(*material);
    for (const auto& [Ic, J] : {std::pair{3.0, 1.0}, std::pair{4.2, 1.3}, std::pair{2.1, 0.4}, std::pair{5.0, 2.0}}) {
      const auto full = m.invariant_derivatives(Ic, J), curvature = m.curvature_derivatives(Ic, J);
      EXPECT_EQ(curvature.dI, full.dI) << family;
      EXPECT_EQ(curvature.dJ, full.dJ) << family;
      EXPECT_EQ(curvature.dII, full.dII) << family;
      EXPECT_EQ(curvature.dIJ, full.dIJ) << family;
      EXPECT_EQ(curvature.dJJ, full.dJJ) << family;
    }
  }
}

// Forwards to a material without being an InvariantMaterial, so ElasticForm takes its per-point
// Material::pk1 path for it.
class OpaqueMaterial final : public Material {
 public:
  explicit OpaqueMaterial(std::shared_ptr<const Material> m) : m_(std::move(m)) {}
  std::string name() const override { return m_->name(); }
  Domain domain() const override { return m_->domain(); }
  double psi_stretch(const Vec3& s) const override { return m_->psi_stretch(s); }
  Vec3 grad_stretch(const Vec3& s) const override { return m_->grad_stretch(s); }
  Mat3 hess_stretch(const Vec3& s) const override { return m_->hess_stretch(s); }

 protected:
  double psi_impl(const Mat3& F) const override { return m_->psi(F); }
  Mat3 pk1_impl(const Mat3& F) const override { return m_->pk1(F); }

 private:
  std::shared_ptr<const Material> m_;
};

TEST(BatchedHexStiffness, ElementGradientOfInvariantMaterialsIsBitwiseThePerPointOne) {
  // The gradient loop calls an invariant material's derivatives once per element instead of
  // Material::pk1 per point; same arithmetic, so the same bits (solves depend on them: the
  // elbow's self-contact frame ends elsewhere at a 1e-13 difference).
  const VolumeMesh mesh = box_lattice(Vec3::Zero(), Vec3(1.0, 0.7, 0.5), Eigen::Vector3i(4, 3, 3));
  auto disc = std::make_shared<Discretization>(mesh);
  for (const char* family : {"stable_neo_hookean", "fung", "arruda_boyce", "neo_hookean", "neo_hookean_decoupled"}) {
    MaterialSpec spec;
    spec.family = family;
    spec.target = YoungPoisson{1e5, 0.45};
    const auto material = build_material(spec);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd x = mesh.rest_positions();
    const double a = material->domain() == Domain::PositiveJ ? 0.02 : 0.2;
    for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = (i % 3 == 0 ? 1.6 : 0.8) * x(i) + a * u(rng);
    Problem direct(mesh.num_vertices()), per_point(mesh.num_vertices());
    direct.add_form(std::make_shared<ElasticForm>(disc, material, Projection::Clamp));
    per_point.add_form(std::make_shared<ElasticForm>(disc, std::make_shared<OpaqueMaterial>(material), Projection::Clamp));
    const Eigen::VectorXd g = direct.gradient(x), reference = per_point.gradient(x);
    ASSERT_GT(reference.norm(), 0.0) << family;
    EXPECT_EQ((g - reference).cwiseAbs().maxCoeff(), 0.0) << family;
  }
}

TEST(BatchedHexStiffness, LatticeMatchesTheGenericPath) {
  // 3 x 3 x 3 cells share one rest shape: the kernel reads the per-shape gradient lanes.
  const VolumeMesh mesh = box_lattice(Vec3::Zero(), Vec3(1.0, 0.7, 0.5), Eigen::Vector3i::Constant(3));
  expect_batched_matches_generic(mesh, 0.25, 3);
}

TEST(BatchedHexStiffness, DistortedHexahedraMatchTheGenericPath) {
  // Every rest shape differs: gradients are gathered per element.
  VolumeMesh mesh = box_lattice(Vec3::Zero(), Vec3::Constant(1.0), Eigen::Vector3i(2, 2, 1));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.08, 0.08);
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    for (int i = 0; i < 3; ++i) mesh.vertices(v, i) += u(rng);
  expect_batched_matches_generic(mesh, 0.3, 9);
}

}  // namespace
}  // namespace sinew
