#include "sinew/material/catalog.hpp"

namespace sinew {

void register_paper000_materials(std::vector<MaterialInfo>&) {}

}  // namespace sinew
