#include "sinew/material/catalog.hpp"
#include "sinew/material/corotational.hpp"

namespace sinew {

void register_table1_materials(std::vector<MaterialInfo>& out) {
  out.push_back({"linear_corotational", "Linear corotational", "paper 002 Table 1; paper 000 Eq. 3",
                 "mu sum (s_i - 1)^2 + lambda/2 (s_0 + s_1 + s_2 - 3)^2",
                 {{"lambda", 1.0, "first Lame parameter"}, {"mu", 1.0, "shear modulus"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<LinearCorotational>(p.values.at("lambda"),
                                                               p.values.at("mu"));
                 }});
}

}  // namespace sinew
