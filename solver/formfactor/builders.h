// Factories of the three row builders (one .cc each); MakeRowBuilder picks one.
#pragma once

#include <memory>

#include "solver/formfactor/row_builder.h"

namespace radflux {

std::unique_ptr<RowBuilder> MakeMonteCarloBuilder(const RowContext& context,
                                                  const FormFactorOptions& options);
std::unique_ptr<RowBuilder> MakeHemicubeBuilder(const RowContext& context,
                                                const FormFactorOptions& options);
std::unique_ptr<RowBuilder> MakeAnalyticBuilder(const RowContext& context,
                                                const FormFactorOptions& options);

}  // namespace radflux
