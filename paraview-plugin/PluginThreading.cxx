// SPDX-License-Identifier: BSD-3-Clause
// Runs once when ParaView loads the plugin's library (GUI, pvpython, pvbatch, pvserver): ParaView
// starts vtkSMPTools on its Sequential backend, so without this the filters would use one core.
// Loading the plugin is where the application chooses; the filters themselves never change this
// process-wide setting (see vtkPointSetSurface::UseThreadedBackend).
#include "vtkPointSetSurface.h"

namespace
{
const char* const BackendAtLoad = vtkPointSetSurface::UseThreadedBackend();
}
