// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file VariantCatalog.h
 * @brief The one list of surface definitions: each Variant's names and its composition from a
 *        direction rule and an energy (the paper's table, Sections 2, 4 and 5).
 *
 * Every face takes its choices from here: pss::parseVariant and variantName (the CLI's
 * `--variant`), makeSurface (everything that builds a definition); a test checks the VTK enum
 * (vtkPointSetSurface::VariantType) and the plugin XML's entries against it.
 */
#pragma once

#include "pss/Types.h"

#include <array>
#include <memory>

namespace pss
{

class DirectionRule;
class Energy;
class PointIndex;
struct SurfaceParameters;

/// One row of the table.
struct VariantInfo
{
  Variant variant;
  const char* name;       ///< canonical lower-case name (CLI, Python): "levin"
  const char* identifier; ///< the enum's spelling (SetVariantTo<identifier> in VTK): "LevinMLS"
  const char* label;      ///< display text (the plugin's drop-down): "Levin MLS"
  /// The direction rule n(x) and the energy e(y, a) (parameters already validated).
  std::unique_ptr<DirectionRule> (*direction)(const PointIndex&, const SurfaceParameters&);
  std::unique_ptr<Energy> (*energy)(const PointIndex&, const SurfaceParameters&);
};

/// The rows, in the order of the Variant values (row i is Variant i).
const std::array<VariantInfo, VariantCount>& variantTable();

/// The row of @p v. Throws std::invalid_argument for a value outside the table.
const VariantInfo& variantInfo(Variant v);

} // namespace pss
