// The library's derivative checker (forms/derivative_check.hpp) run over every energy term the
// library has, each at a deformed state with its lagged data set up; adding a Form to the
// library is one line in every_form(). And the checker itself: it must catch a wrong gradient, a
// wrong Hessian, and a projected Hessian that is not PSD.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "sinew/element/discretization.hpp"
#include "sinew/element/mass.hpp"
#include "sinew/forms/bone_spring_form.hpp"
#include "sinew/forms/derivative_check.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/forms/inertia_form.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/forms/self_contact_form.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/motion/obstacle.hpp"
#include "sinew/motion/rig.hpp"

namespace sinew {
namespace {

Eigen::VectorXd perturbed(const Eigen::VectorXd& x, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Eigen::VectorXd y = x;
  for (Eigen::Index i = 0; i < y.size(); ++i) y(i) += u(rng);
  return y;
}

std::shared_ptr<Discretization> block(ElementKind kind) {
  VolumeMesh m = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.0, 0.8, 0.6), Eigen::Vector3i(2, 2, 1));
  return std::make_shared<Discretization>(kind == ElementKind::Hex8 ? m : tetrahedralize_hexes(m));
}

// A stretched, twisted and randomly perturbed state of the block: far enough from rest that
// projected element Hessians differ from the exact ones, J > 0 everywhere.
Eigen::VectorXd deformed(const Discretization& d, unsigned seed) {
  const Eigen::MatrixX3d X = d.mesh().vertices;
  Eigen::VectorXd x(3 * X.rows());
  for (Eigen::Index v = 0; v < X.rows(); ++v) {
    const Eigen::Vector3d p = X.row(v).transpose();
    const Mat3 R = Eigen::AngleAxisd(0.6 * p.x(), Eigen::Vector3d::UnitX()).toRotationMatrix();
    x.segment<3>(3 * v) = R * Eigen::Vector3d(1.3 * p.x(), 0.9 * p.y(), p.z());
  }
  return perturbed(x, 0.03, seed);
}

struct FormCase {
  std::shared_ptr<Form> form;
  Eigen::VectorXd x;
};

struct FormEntry {
  std::string name;
  std::function<FormCase()> make;
};

FormEntry elastic(ElementKind kind, const std::string& family, Projection projection = Projection::Clamp) {
  const std::string name = std::string("elastic_") + (kind == ElementKind::Hex8 ? "hex_" : "tet_") + family +
                           (projection == Projection::Clamp ? "" : std::string("_") + to_string(projection));
  return {name, [=] {
            auto d = block(kind);
            std::shared_ptr<const Material> m = MaterialCatalog::instance().make(family);
            return FormCase{std::make_shared<ElasticForm>(d, m, projection), deformed(*d, 3)};
          }};
}

FormCase external_case() {
  auto d = block(ElementKind::Hex8);
  Eigen::VectorXd f = gravity_forces(lumped_mass(*d, 900.0), Eigen::Vector3d(0.3, 0, -9.81));
  f.segment<3>(6) += Eigen::Vector3d(5, -2, 1);  // a point load
  return {std::make_shared<ExternalForceForm>(f), deformed(*d, 4)};
}

FormCase inertia_case(MassKind kind) {
  auto d = block(ElementKind::Tet4);
  auto inertia = std::make_shared<InertiaForm>(std::make_shared<MassMatrix>(*d, 1200.0, kind), 0.01);
  const Eigen::VectorXd rest = d->mesh().rest_positions();
  inertia->set_prediction(rest, perturbed(Eigen::VectorXd::Zero(rest.size()), 1.0, 5));
  return {inertia, deformed(*d, 6)};
}

FormCase damping_case() {
  auto d = block(ElementKind::Hex8);
  auto mass = std::make_shared<MassMatrix>(*d, 1000.0, MassKind::Consistent);
  auto elastic_form = std::make_shared<ElasticForm>(d, MaterialCatalog::instance().make("stable_neo_hookean"));
  auto damping = std::make_shared<DampingForm>(mass, elastic_form, d->mesh().num_vertices(), 0.5, 0.01, 0.02);
  damping->begin_step(deformed(*d, 7));
  return {damping, deformed(*d, 8)};
}

// Boundary vertices of a block pressed into a tilted ground plane and a sphere that both move
// over the step, with friction lagged at the step's start.
FormCase contact_case(bool project) {
  auto d = block(ElementKind::Hex8);
  std::vector<std::shared_ptr<const Obstacle>> obstacles{
      std::make_shared<Obstacle>("ground",
                                 std::make_shared<PlaneObstacle>(Eigen::Vector3d(0, 0, 0.15), Eigen::Vector3d(0.2, 0.1, 1)),
                                 Translation{Eigen::Vector3d(0.02, -0.01, 0.01)}),
      std::make_shared<Obstacle>("ball", std::make_shared<SphereObstacle>(Eigen::Vector3d(1.45, 0.36, 0.3), 0.3),
                                 Translation{Eigen::Vector3d(-0.01, 0.0, 0.02)})};
  std::vector<ContactParameters> params{{2e3, 0.4}, {5e3, 0.3}};
  std::vector<int> vertices(d->mesh().num_vertices());
  for (size_t v = 0; v < vertices.size(); ++v) vertices[v] = static_cast<int>(v);
  const Eigen::VectorXd areas = Eigen::VectorXd::Constant(d->mesh().num_vertices(), 0.05);
  auto form = std::make_shared<PenaltyContactForm>(obstacles, params, vertices, areas, project);
  const Eigen::VectorXd x_n = deformed(*d, 9);
  form->begin_step(x_n, 3.0, 4.0, 1e-3);
  const Eigen::VectorXd x = perturbed(x_n, 0.01, 10);
  EXPECT_GT(form->stats(x).contacts, 3);
  return {form, x};
}

// Two blocks side by side, the second pushed into the first: refresh() finds the contacts.
FormCase self_contact_case() {
  const VolumeMesh a = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i::Constant(2));
  const VolumeMesh b = box_lattice(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 1, 1), Eigen::Vector3i::Constant(2));
  VolumeMesh m;
  m.vertices.resize(a.num_vertices() + b.num_vertices(), 3);
  m.vertices << a.vertices, b.vertices;
  m.elements.resize(a.num_elements() + b.num_elements(), 8);
  m.elements << a.elements, (b.elements.array() + static_cast<int>(a.num_vertices())).matrix();
  SelfContactSettings s;
  s.stiffness = 3e3;
  auto form = std::make_shared<SelfContactForm>(m, s);
  Eigen::VectorXd x = m.rest_positions();
  for (Eigen::Index v = a.num_vertices(); v < m.num_vertices(); ++v) x(3 * v) -= 0.2;
  x = perturbed(x, 0.03, 11);
  EXPECT_TRUE(form->refresh(x));
  return {form, x};
}

FormCase bone_springs_case() {
  auto rig = std::make_shared<Rig>();
  Bone bone;
  bone.name = "b";
  bone.shape = std::make_shared<CapsuleShape>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.6);
  bone.keys.push_back(BoneKey{});
  BoneKey k;
  k.frame = 2.0;
  k.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  k.translation = Eigen::Vector3d(0.1, -0.2, 0.3);
  bone.keys.push_back(k);
  rig->bones.push_back(bone);
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i(2, 2, 2));
  auto form = std::make_shared<BoneSpringForm>(rig, bind_rig(*rig, mesh.vertices), mesh.vertices, 37.0);
  form->set_frame(1.3);
  return {form, perturbed(mesh.rest_positions(), 0.2, 12)};
}

// Every energy term of the library, in the configurations its users build. One line per form.
std::vector<FormEntry> every_form() {
  std::vector<FormEntry> forms;
  for (ElementKind kind : {ElementKind::Hex8, ElementKind::Tet4})
    for (const char* family : {"stable_neo_hookean", "neo_hookean", "stvk", "fixed_corotational", "mooney_rivlin"})
      forms.push_back(elastic(kind, family));
  forms.push_back(elastic(ElementKind::Hex8, "stable_neo_hookean", Projection::None));
  forms.push_back(elastic(ElementKind::Hex8, "stvk", Projection::Abs));
  forms.push_back({"external", external_case});
  forms.push_back({"inertia_lumped", [] { return inertia_case(MassKind::Lumped); }});
  forms.push_back({"inertia_consistent", [] { return inertia_case(MassKind::Consistent); }});
  forms.push_back({"damping", damping_case});
  forms.push_back({"contact_friction", [] { return contact_case(true); }});
  forms.push_back({"contact_friction_unprojected", [] { return contact_case(false); }});
  forms.push_back({"self_contact", self_contact_case});
  forms.push_back({"bone_springs", bone_springs_case});
  return forms;
}

class EveryForm : public ::testing::TestWithParam<FormEntry> {};

TEST_P(EveryForm, DerivativesMatchFiniteDifferences) {
  const FormCase c = GetParam().make();
  const FormCheck check = check_form(*c.form, c.x);
  EXPECT_TRUE(check.coordinate);  // small enough to check every DOF
  EXPECT_LE(check.gradient_error, 1e-6);
  EXPECT_LE(check.hessian_error, 1e-6);
  EXPECT_LE(check.asymmetry, 1e-10);
  if (check.projected) {
    EXPECT_GE(check.min_eigenvalue, -1e-10);
  }
  EXPECT_TRUE(check.passed());
  // The form does something at this state (a check of a zero form proves nothing).
  Eigen::VectorXd g = Eigen::VectorXd::Zero(c.x.size());
  c.form->add_gradient(c.x, g);
  EXPECT_GT(g.norm(), 0.0);
}

TEST_P(EveryForm, RandomDirectionsAgreeWithCoordinateOnes) {
  // Large scenes are checked along random directions: same verdict on the same form.
  const FormCase c = GetParam().make();
  FormCheckOptions o;
  o.max_coordinate_dofs = 0;
  o.max_dense_dofs = 0;
  const FormCheck check = check_form(*c.form, c.x, o);
  EXPECT_FALSE(check.coordinate);
  EXPECT_EQ(check.directions, o.random_directions);
  EXPECT_LE(check.gradient_error, 1e-6);
  EXPECT_LE(check.hessian_error, 1e-6);
  EXPECT_TRUE(check.passed());
}

INSTANTIATE_TEST_SUITE_P(Library, EveryForm, ::testing::ValuesIn(every_form()),
                         [](const auto& p) { return p.param.name; });

TEST(FormCheck, ProjectedHessianEqualsTheExactOneAtRest) {
  // At rest every element Hessian is PSD, so clamping changes nothing (any other state has
  // slightly negative eigenvalues along the zero-energy rotations); compressed, the projection
  // must act.
  auto d = block(ElementKind::Hex8);
  const ElasticForm form(d, MaterialCatalog::instance().make("stvk"));
  const FormCheck near = check_form(form, d->mesh().rest_positions());
  EXPECT_TRUE(near.projected);
  EXPECT_LE(near.projection_gap, 1e-12);
  EXPECT_TRUE(near.passed());
  Eigen::VectorXd far = d->mesh().rest_positions();
  for (Eigen::Index v = 0; v < far.size() / 3; ++v) far(3 * v + 2) *= 0.2;  // compressed to 20%
  const FormCheck squeezed = check_form(form, far);
  EXPECT_GT(squeezed.projection_gap, 1e-3);
  EXPECT_GE(squeezed.min_eigenvalue, -1e-10);
  EXPECT_LE(squeezed.hessian_error, 1e-6);
}

// A form with a deliberate mistake, to show the checker catches each kind.
class Broken final : public Form {
 public:
  enum class Fault { Gradient, Hessian, Asymmetric, Indefinite };
  explicit Broken(Fault fault) : fault_(fault) {}
  std::string name() const override { return "broken"; }
  // E = sum_i x_i^4 / 4 + x_0 x_1.
  double value(const Eigen::VectorXd& x) const override { return x.array().pow(4).sum() / 4 + x(0) * x(1); }
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override {
    g += x.array().pow(3).matrix();
    g(0) += x(1);
    g(1) += (fault_ == Fault::Gradient ? 1.1 : 1.0) * x(0);
  }
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override {
    Mat3 B = (3.0 * x.head<3>().array().square()).matrix().asDiagonal();
    B(0, 1) += 1.0;
    B(1, 0) += fault_ == Fault::Asymmetric ? 0.5 : 1.0;
    if (fault_ == Fault::Hessian) B(2, 2) *= 1.02;
    if (fault_ == Fault::Indefinite) B(2, 2) = -1.0;
    H.add_block(0, 0, B);
    for (int v = 1; v < x.size() / 3; ++v)
      H.add_block(v, v, Mat3((3.0 * x.segment<3>(3 * v).array().square()).matrix().asDiagonal()));
  }
  bool projects_hessian() const override { return fault_ == Fault::Indefinite; }
  void add_exact_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override {
    if (fault_ != Fault::Indefinite) return add_hessian(x, H);
    Broken(Fault::Gradient).add_hessian(x, H);  // the correct one
  }

 private:
  Fault fault_;
};

TEST(FormCheck, CatchesEachKindOfMistake) {
  const Eigen::VectorXd x = perturbed(Eigen::VectorXd::Constant(6, 1.0), 0.3, 2);
  const FormCheck gradient = check_form(Broken(Broken::Fault::Gradient), x);
  EXPECT_GT(gradient.gradient_error, 1e-3);
  EXPECT_FALSE(gradient.passed());
  const FormCheck hessian = check_form(Broken(Broken::Fault::Hessian), x);
  EXPECT_LE(hessian.gradient_error, 1e-8);
  EXPECT_GT(hessian.hessian_error, 1e-3);
  EXPECT_FALSE(hessian.passed());
  const FormCheck asymmetric = check_form(Broken(Broken::Fault::Asymmetric), x);
  EXPECT_GT(asymmetric.asymmetry, 1e-3);
  EXPECT_FALSE(asymmetric.passed());
  const FormCheck indefinite = check_form(Broken(Broken::Fault::Indefinite), x);
  EXPECT_LE(indefinite.hessian_error, 1e-8);
  EXPECT_LT(indefinite.min_eigenvalue, -1e-3);
  EXPECT_FALSE(indefinite.passed());
}

TEST(FormCheck, StepScalesWithTheProblem) {
  // The same body in millimetres: same relative errors, a step 1000x larger.
  auto d = block(ElementKind::Tet4);
  const ElasticForm form(d, MaterialCatalog::instance().make("neo_hookean"));
  const Eigen::VectorXd x = deformed(*d, 13);
  VolumeMesh mm = d->mesh();
  mm.vertices *= 1000.0;
  const ElasticForm form_mm(std::make_shared<Discretization>(mm), MaterialCatalog::instance().make("neo_hookean"));
  const FormCheck m = check_form(form, x), millimetres = check_form(form_mm, 1000.0 * x);
  EXPECT_NEAR(millimetres.step, 1000.0 * m.step, 1e-9 * millimetres.step);
  EXPECT_LE(millimetres.gradient_error, 1e-6);
  EXPECT_LE(millimetres.hessian_error, 1e-6);
}

}  // namespace
}  // namespace sinew
