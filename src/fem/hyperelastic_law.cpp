// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/hyperelastic_law.hpp"

namespace roifem::fem {

static_assert(HyperelasticLawType<NeoHookean> && HyperelasticLawType<Ogden>);

HyperelasticLaw hyperelastic_law(const Material& material) {
  if (material.model == MaterialModel::ogden) return Ogden::of(material);
  return NeoHookean::of(material);
}

}  // namespace roifem::fem
