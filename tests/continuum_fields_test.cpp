// Output fields (element/continuum_fields.hpp, run/frame_output.hpp): under a homogeneous
// deformation x = F X of a distorted mesh every element and every vertex has the exact J,
// principal stretches, Green-Lagrange strain, Cauchy stress and von Mises stress, the stress
// checked against P F^T / J from the material's P, from differences of its energy, and (for
// Neo-Hookean) against the closed form.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "sinew/element/continuum_fields.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/families/neo_hookean.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/frame_output.hpp"

namespace sinew {
namespace {

// A 3x2x2 box whose interior and boundary vertices are moved at random (elements stay valid),
// so no element is a cube.
VolumeMesh distorted_box(ElementKind kind) {
  VolumeMesh m = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.5, 1.0, 0.8), Eigen::Vector3i(3, 2, 2));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.08, 0.08);
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    for (int i = 0; i < 3; ++i) m.vertices(v, i) += u(rng);
  m.lattice.reset();  // no longer a lattice
  return kind == ElementKind::Hex8 ? m : tetrahedralize_hexes(m);
}

// F = R1 diag(1.3, 0.8, 1.1) R2^T: singular values 1.3, 1.1, 0.8 by construction.
Mat3 homogeneous_F() {
  const Mat3 R1 = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Mat3 R2 = Eigen::AngleAxisd(-0.7, Vec3(-2, 1, 0.5).normalized()).toRotationMatrix();
  return R1 * Vec3(1.3, 0.8, 1.1).asDiagonal() * R2.transpose();
}

Eigen::VectorXd place(const VolumeMesh& m, const Mat3& F) {
  Eigen::VectorXd x(3 * m.num_vertices());
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) x.segment<3>(3 * v) = F * m.vertices.row(v).transpose();
  return x;
}

Mat3 tensor_at(const Eigen::VectorXd& values, Eigen::Index i) {
  Mat3 A;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) A(r, c) = values(9 * i + 3 * r + c);
  return A;
}

// P = dPsi/dF by central differences of the energy (independent of the material's pk1).
Mat3 pk1_by_differences(const Material& m, const Mat3& F) {
  Mat3 P;
  const double h = 1e-6;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      Mat3 Fp = F, Fm = F;
      Fp(r, c) += h;
      Fm(r, c) -= h;
      P(r, c) = (m.psi(Fp) - m.psi(Fm)) / (2 * h);
    }
  return P;
}

struct Expected {
  double J;
  Vec3 stretches;
  Mat3 E, sigma;
  double mises;
};

Expected expected_fields(const Material& material, const Mat3& F) {
  Expected x;
  x.J = F.determinant();
  x.stretches = Vec3(1.3, 1.1, 0.8);
  x.E = 0.5 * (F.transpose() * F - Mat3::Identity());
  x.sigma = material.pk1(F) * F.transpose() / x.J;
  // von Mises from the principal stresses.
  const Vec3 s = Eigen::SelfAdjointEigenSolver<Mat3>(x.sigma).eigenvalues();
  x.mises = std::sqrt(0.5 * ((s(0) - s(1)) * (s(0) - s(1)) + (s(1) - s(2)) * (s(1) - s(2)) + (s(2) - s(0)) * (s(2) - s(0))));
  return x;
}

void expect_fields(const ContinuumFields& f, const Discretization& d, const Expected& x, bool vertices) {
  const Eigen::Index n = vertices ? d.mesh().num_vertices() : d.num_elements();
  auto field = [&](const Eigen::VectorXd& values, int components) {
    return vertices ? average_to_vertices(d, values, components) : values;
  };
  const Eigen::VectorXd J = field(f.J, 1), stretches = field(f.principal_stretches, 3),
                        E = field(f.green_lagrange, 9), sigma = field(f.cauchy, 9), mises = field(f.von_mises, 1);
  ASSERT_EQ(J.size(), n);
  const double scale = x.sigma.norm();
  for (Eigen::Index i = 0; i < n; ++i) {
    SCOPED_TRACE((vertices ? "vertex " : "element ") + std::to_string(i));
    EXPECT_NEAR(J(i), x.J, 1e-13);
    EXPECT_LE((stretches.segment<3>(3 * i) - x.stretches).norm(), 1e-13);
    EXPECT_LE((tensor_at(E, i) - x.E).norm(), 1e-13);
    EXPECT_LE((tensor_at(sigma, i) - x.sigma).norm(), 1e-12 * scale);
    EXPECT_NEAR(mises(i), x.mises, 1e-12 * scale);
  }
}

class HomogeneousDeformation : public ::testing::TestWithParam<ElementKind> {};

TEST_P(HomogeneousDeformation, EveryElementAndVertexHasTheExactFields) {
  const Discretization d(distorted_box(GetParam()));
  const Mat3 F = homogeneous_F();
  const Eigen::VectorXd x = place(d.mesh(), F);
  for (const char* family : {"neo_hookean", "stable_neo_hookean", "stvk", "mooney_rivlin"}) {
    SCOPED_TRACE(family);
    const auto material = MaterialCatalog::instance().make(family);
    const Expected e = expected_fields(*material, F);
    // The stress the expectation uses is the energy's derivative, not just the material's pk1.
    const Mat3 sigma_fd = pk1_by_differences(*material, F) * F.transpose() / F.determinant();
    EXPECT_LE((sigma_fd - e.sigma).norm(), 1e-7 * e.sigma.norm());
    EXPECT_LE((e.sigma - e.sigma.transpose()).norm(), 1e-12 * e.sigma.norm());  // objective material
    EXPECT_GT(e.mises, 0.0);
    const ContinuumFields f = continuum_fields(d, material.get(), x);
    expect_fields(f, d, e, false);
    expect_fields(f, d, e, true);
  }
}

TEST_P(HomogeneousDeformation, NeoHookeanStressMatchesItsClosedForm) {
  // sigma = (mu (B - I) + lambda ln J I) / J for Psi = mu/2 (I_C - 3) - mu ln J + lambda/2 ln^2 J.
  const double lambda = 2.0, mu = 1.5;
  const NeoHookean material(lambda, mu);
  const Discretization d(distorted_box(GetParam()));
  const Mat3 F = homogeneous_F();
  const double J = F.determinant();
  const Mat3 sigma = (mu * (F * F.transpose() - Mat3::Identity()) + lambda * std::log(J) * Mat3::Identity()) / J;
  const ContinuumFields f = continuum_fields(d, &material, place(d.mesh(), F));
  for (Eigen::Index e = 0; e < d.num_elements(); ++e) EXPECT_LE((tensor_at(f.cauchy, e) - sigma).norm(), 1e-12);
}

TEST_P(HomogeneousDeformation, WithoutAMaterialOnlyTheKinematicFields) {
  const Discretization d(distorted_box(GetParam()));
  const ContinuumFields f = continuum_fields(d, nullptr, place(d.mesh(), homogeneous_F()));
  EXPECT_EQ(f.green_lagrange.size(), 9 * d.num_elements());
  EXPECT_EQ(f.cauchy.size(), 0);
  EXPECT_EQ(f.von_mises.size(), 0);
}

INSTANTIATE_TEST_SUITE_P(Elements, HomogeneousDeformation, ::testing::Values(ElementKind::Hex8, ElementKind::Tet4),
                         [](const auto& p) { return std::string(to_string(p.param)); });

TEST(ContinuumFields, AtRestStrainAndStressVanishAndStretchesAreOne) {
  const Discretization d(distorted_box(ElementKind::Hex8));
  const auto material = MaterialCatalog::instance().make("stable_neo_hookean");
  const ContinuumFields f = continuum_fields(d, material.get(), d.mesh().rest_positions());
  EXPECT_LE((f.principal_stretches.array() - 1.0).abs().maxCoeff(), 1e-13);
  EXPECT_LE(f.green_lagrange.cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LE(f.cauchy.cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LE(f.von_mises.cwiseAbs().maxCoeff(), 1e-10);
}

TEST(ContinuumFields, VertexValuesAreRestVolumeWeightedMeans) {
  // Two elements of different volumes and values: their shared vertices get the weighted mean.
  const VolumeMesh m = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 1, 1), Eigen::Vector3i(2, 1, 1));
  VolumeMesh stretched = m;
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    if (m.vertices(v, 0) > 2.0) stretched.vertices(v, 0) = 4.0;  // element 1 becomes 2.5 x as long
  const Discretization d(stretched);
  ASSERT_NEAR(d.rest_volume(1) / d.rest_volume(0), 2.5 / 1.5, 1e-12);
  Eigen::VectorXd values(2);
  values << 1.0, 5.0;
  const Eigen::VectorXd at = average_to_vertices(d, values, 1);
  const double shared = (1.5 * 1.0 + 2.5 * 5.0) / 4.0;
  for (Eigen::Index v = 0; v < stretched.num_vertices(); ++v) {
    const double X = stretched.vertices(v, 0);
    EXPECT_NEAR(at(v), X < 1.0 ? 1.0 : (X < 2.0 ? shared : 5.0), 1e-14) << "vertex " << v;
  }
}

TEST(ContinuumFields, FrameOutputWritesEveryFieldPerElementAndPerVertex) {
  // Through the model a run writes: a box scene, placed homogeneously.
  const nlohmann::json j = nlohmann::json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]}, "cells": [2, 1, 1]},
    "material": {"family": "neo_hookean", "E": 1000, "nu": 0.3}})");
  const Model model = build_model(parse_scene(j, "scene.json"));
  const Mat3 F = homogeneous_F();
  const Eigen::VectorXd x = place(model.disc->mesh(), F);
  VtuFields vf;
  add_continuum_fields(model, x, vf);
  const Expected e = expected_fields(model.hyperelastic->material(), F);
  const Eigen::Index ne = model.disc->num_elements(), nv = model.disc->mesh().num_vertices();
  std::vector<std::string> cells, points;
  for (const auto& a : vf.cell_arrays) {
    cells.push_back(a.name);
    EXPECT_EQ(a.values.size(), a.components * ne) << a.name;
  }
  for (const auto& a : vf.point_arrays) {
    points.push_back(a.name);
    EXPECT_EQ(a.values.size(), a.components * nv) << a.name;
    if (a.name == "cauchy_stress") {
      for (Eigen::Index v = 0; v < nv; ++v) EXPECT_LE((tensor_at(a.values, v) - e.sigma).norm(), 1e-12 * e.sigma.norm());
    }
    if (a.name == "von_mises") {
      for (Eigen::Index v = 0; v < nv; ++v) EXPECT_NEAR(a.values(v), e.mises, 1e-12 * e.mises);
    }
  }
  EXPECT_EQ(cells, (std::vector<std::string>{"principal_stretches", "green_lagrange_strain", "cauchy_stress", "von_mises"}));
  EXPECT_EQ(points,
            (std::vector<std::string>{"J", "principal_stretches", "green_lagrange_strain", "cauchy_stress", "von_mises"}));
}

}  // namespace
}  // namespace sinew
