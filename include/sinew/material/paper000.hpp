#pragma once
// Paper 000 (Stable Neo-Hookean Flesh Simulation): the stable Neo-Hookean energies with their
// closed-form eigensystems, the Fung and Arruda-Boyce extensions (§5.3), and the comparison
// models of §5-6. Co-rotational (Eq. 3) is LinearCorotational (corotational.hpp).
#include "sinew/material/paper000/arruda_boyce.hpp"
#include "sinew/material/paper000/fixed_corotational.hpp"
#include "sinew/material/paper000/fung.hpp"
#include "sinew/material/paper000/general_model.hpp"
#include "sinew/material/paper000/neo_hookean_filtered.hpp"
#include "sinew/material/paper000/stable_neo_hookean.hpp"
#include "sinew/material/paper000/stable_neo_hookean_eq13.hpp"
#include "sinew/material/paper000/stvk.hpp"
#include "sinew/material/paper000/stvk_kikuuwe.hpp"
