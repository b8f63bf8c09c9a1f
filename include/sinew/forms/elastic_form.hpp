#pragma once
// Hyperelastic energy of a mesh: sum over elements and quadrature points of w Psi(F).
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "sinew/element/element_matrix_cache.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/element_form.hpp"
#include "sinew/material/material.hpp"

namespace sinew {

struct HexGradientLanes;  // forms/hex_invariant_stiffness.hpp (internal)

class ElasticForm final : public ElementForm {
 public:
  ElasticForm(std::shared_ptr<const Discretization> disc, std::shared_ptr<const Material> material,
              Projection projection = Projection::Clamp);
  ~ElasticForm() override;

  std::string name() const override { return "elastic"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  bool projects_hessian() const override { return projection_ != Projection::None; }
  void add_exact_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  bool is_valid(const Eigen::VectorXd& x) const override;

  // Matrix-free: element stiffness matrices kept in single precision (element_matrix_cache.hpp).
  bool supports_hessian_product() const override { return true; }
  void prepare_hessian_product(const Eigen::VectorXd& x, bool exact) override;
  void add_hessian_product(const Eigen::VectorXd& p, Eigen::VectorXd& y) const override;
  void add_hessian_diagonal(std::vector<Mat3>& diagonal) const override;
  std::size_t hessian_product_bytes() const override { return element_matrices_.bytes(); }
  Eigen::Index hessian_product_elements() const override;
  int hessian_product_element(Eigen::Index e, int* vertices, ElementMatrix* K) const override;

  // Per-element fields for output: energy (integrated), mean J, volume-averaged energy
  // density and Frobenius norm of P.
  struct ElementFields {
    Eigen::VectorXd energy, J, energy_density, stress_norm;
  };
  ElementFields element_fields(const Eigen::VectorXd& x) const;

  // Per element: U_e = sum_q w_q Psi(F_q), its exact gradient sum_q w_q P(F_q) dN/dX, and
  // sum_q w_q dF/dx^T proj(d2Psi/dF2) dF/dx with the form's projection.
  const Discretization& discretization() const override { return *disc_; }
  double element_value(Eigen::Index e, const Eigen::VectorXd& x) const override;
  Eigen::VectorXd element_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                   JacobianKind kind = JacobianKind::Exact) const override;
  Eigen::MatrixXd element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const override;

  const Material& material() const { return *material_; }

 private:
  void add_hessian_projected(const Eigen::VectorXd& x, BlockHessian& H, Projection projection) const;
  // Fixed-size loops for N-node elements (fixed_element.hpp).
  template <int N>
  double value_fixed(const Eigen::VectorXd& x) const;
  template <int N>
  void add_gradient_fixed(const Eigen::VectorXd& x, Eigen::VectorXd& g) const;
  // ge += element e's gradient at node positions xe for an invariant material (one call to its
  // derivatives per element); false, with ge unchanged, when the material is not one or a point
  // is outside its domain.
  template <int N>
  bool add_invariant_gradient(Eigen::Index e, const Eigen::Matrix<double, 3, N>& xe, Eigen::Matrix<double, 3, N>& ge) const;
  // Element stiffness K_e (upper node-pair blocks) at x: body(e, K) for every element, in
  // parallel over colour groups.
  template <int N, class Body>
  void for_each_element_stiffness(const Eigen::VectorXd& x, Projection projection, const Body& body) const;
  template <int N>
  void add_hessian_fixed(const Eigen::VectorXd& x, BlockHessian& H, Projection projection) const;
  template <int N>
  void prepare_hessian_product_fixed(const Eigen::VectorXd& x, Projection projection);
  // Scatter map: slot of node a's rows in node b's column, per element (N x N each), for the
  // pattern of H; rebuilt when the pattern changes.
  const std::vector<std::uint16_t>& scatter_map(const BlockHessian& H) const;

  // The batched hexahedron kernel's gradients (forms/hex_invariant_stiffness.hpp), one set per
  // rest shape when the mesh has few (a lattice has one); null when the kernel does not apply
  // (not 8-node, 8-point hexahedra of an invariant material).
  const HexGradientLanes* hex_lanes(Eigen::Index e, HexGradientLanes& scratch) const;

  std::shared_ptr<const Discretization> disc_;
  std::shared_ptr<const Material> material_;
  const InvariantMaterial* invariant_ = nullptr;  // material_ when it is one
  std::vector<HexGradientLanes> shape_lanes_;  // per rest shape, when few
  Projection projection_;
  ElementMatrixCache element_matrices_;
  mutable std::mutex scatter_mutex_;
  mutable std::uint64_t scatter_pattern_ = 0;
  mutable std::vector<std::uint16_t> scatter_slots_;
};

}  // namespace sinew
