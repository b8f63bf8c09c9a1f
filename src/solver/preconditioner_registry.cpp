// The preconditioner registry. The built-in preconditioners are registered when the registry is
// first used (not by static initialisers, which a static library's linker may drop).
#include <fmt/format.h>

#include <algorithm>
#include <mutex>

#include "sinew/core/error.hpp"
#include "sinew/solver/amg_preconditioner.hpp"
#include "sinew/solver/diagonal_preconditioners.hpp"
#include "sinew/solver/lagged_cholesky_preconditioner.hpp"
#include "sinew/solver/multigrid_preconditioner.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {
namespace {

struct Entry {
  std::string name, description;
  PreconditionerFactory factory;
};

class Registry {
 public:
  Registry() {
    entries_.push_back({"jacobi", "inverse diagonal entries", [] {
                          return std::make_unique<DiagonalPreconditioner>(DiagonalPreconditioner::Blocks::Scalar);
                        }});
    entries_.push_back({"block_jacobi", "inverse 3x3 vertex blocks (default)", [] {
                          return std::make_unique<DiagonalPreconditioner>(DiagonalPreconditioner::Blocks::Vertex3);
                        }});
    entries_.push_back({"lagged_cholesky", "sparse Cholesky of an earlier matrix, refreshed when it no longer pays",
                        [] { return std::make_unique<LaggedCholeskyPreconditioner>(); }});
    entries_.push_back({"multigrid",
                        "geometric multigrid V-cycle on the coarsened lattice (Galerkin, Chebyshev smoothing); "
                        "block_jacobi on meshes without a lattice grid",
                        [] { return std::make_unique<MultigridPreconditioner>(); }});
    entries_.push_back({"amg",
                        "algebraic multigrid V-cycle (hypre BoomerAMG, systems AMG for 3 unknowns per vertex); "
                        "any mesh",
                        [] { return std::make_unique<AmgPreconditioner>(); }});
  }

  void add(const std::string& name, const std::string& description, PreconditionerFactory factory) {
    const std::lock_guard lock(mutex_);
    if (name.empty()) throw Error("a preconditioner needs a name", "preconditioner registry");
    if (!factory) throw Error(fmt::format("'{}' has no factory", name), "preconditioner registry");
    if (find(name)) throw Error(fmt::format("'{}' is already registered", name), "preconditioner registry");
    entries_.push_back({name, description, std::move(factory)});
  }

  std::unique_ptr<Preconditioner> make(const std::string& name) const {
    PreconditionerFactory factory;
    {
      const std::lock_guard lock(mutex_);
      const Entry* e = find(name);
      if (!e) throw Error(fmt::format("unknown preconditioner '{}' (registered: {})", name, list()), "preconditioner");
      factory = e->factory;
    }
    std::unique_ptr<Preconditioner> p = factory();
    if (!p) throw Error(fmt::format("the factory of '{}' made no preconditioner", name), "preconditioner registry");
    return p;
  }

  std::vector<std::string> names() const {
    const std::lock_guard lock(mutex_);
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }

  std::string description(const std::string& name) const {
    const std::lock_guard lock(mutex_);
    const Entry* e = find(name);
    return e ? e->description : std::string();
  }

 private:
  const Entry* find(const std::string& name) const {
    auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
    return it == entries_.end() ? nullptr : &*it;
  }
  std::string list() const {
    std::string out;
    for (const auto& e : entries_) out += (out.empty() ? "" : ", ") + e.name;
    return out;
  }

  mutable std::mutex mutex_;
  std::vector<Entry> entries_;
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

void register_preconditioner(const std::string& name, const std::string& description, PreconditionerFactory factory) {
  registry().add(name, description, std::move(factory));
}

std::unique_ptr<Preconditioner> make_preconditioner(const std::string& name) { return registry().make(name); }

std::vector<std::string> registered_preconditioners() { return registry().names(); }

std::string preconditioner_description(const std::string& name) { return registry().description(name); }

}  // namespace sinew
