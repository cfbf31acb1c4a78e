// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ErrorObserver.h
 * @brief Records the errors and warnings an algorithm (and its executive) reports, so tests can
 *        assert on them instead of letting them scroll by on stderr.
 *
 * With an observer attached, vtkErrorMacro/vtkWarningMacro invoke it instead of printing.
 */
#pragma once

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"

#include <string>
#include <vector>

class ErrorObserver : public vtkCommand
{
public:
  static ErrorObserver* New() { return new ErrorObserver; }

  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const std::string message = data ? static_cast<const char*>(data) : "";
    if (event == vtkCommand::ErrorEvent)
    {
      this->Errors.push_back(message);
    }
    else if (event == vtkCommand::WarningEvent)
    {
      this->Warnings.push_back(message);
    }
  }

  /// Observes @p algorithm and its executive ("returned failure" messages come from the latter).
  void Attach(vtkAlgorithm* algorithm)
  {
    for (vtkObject* o : { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
    {
      o->AddObserver(vtkCommand::ErrorEvent, this);
      o->AddObserver(vtkCommand::WarningEvent, this);
    }
  }

  static bool Contains(const std::vector<std::string>& messages, const std::string& text)
  {
    for (const std::string& m : messages)
    {
      if (m.find(text) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }
  bool HasError(const std::string& text = "") const { return Contains(this->Errors, text); }
  bool HasWarning(const std::string& text = "") const { return Contains(this->Warnings, text); }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }

  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};
