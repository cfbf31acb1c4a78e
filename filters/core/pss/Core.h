// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Core.h
 * @brief Umbrella header of the VTK-free PointSetSurfaces core.
 */
#pragma once

#include "pss/DepthCamera.h"
#include "pss/DirectionRulesAndEnergies.h"
#include "pss/Domain.h"
#include "pss/ExtremalSurface.h"
#include "pss/Kernel.h"
#include "pss/NormalOrientation.h"
#include "pss/Parallel.h"
#include "pss/PointIndex.h"
#include "pss/Quadrature.h"
#include "pss/SurfaceDefinition.h"
#include "pss/SurfaceMesh.h"
#include "pss/SyntheticClouds.h"
#include "pss/Types.h"
#include "pss/VariantCatalog.h"
#include "pss/Workspace.h"
