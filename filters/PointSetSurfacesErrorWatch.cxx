// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesErrorWatch.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkOutputWindow.h"
#include "vtkNew.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace pss_vtk
{

namespace
{

// An upstream error recorded against a data object. The weak pointer turns null when the object
// is deleted, so a later object at the same address never inherits the error; the modification
// time tells a changed object (re-executed upstream) from the one that failed.
struct FailedInput
{
  vtkWeakPointer<vtkDataObject> Object;
  vtkMTimeType MTime = 0;
  std::string Error;
};

// Every error message vtkOutputWindow displays in this process, numbered, the last few kept; and
// the upstream errors recorded against data objects still alive and unchanged.
struct ErrorLog
{
  std::mutex Lock;
  vtkWeakPointer<vtkOutputWindow> Window; // the instance observed (an application may replace it)
  std::uint64_t Count = 0;
  std::deque<std::pair<std::uint64_t, std::string>> Recent;
  std::vector<FailedInput> Failed;

  static ErrorLog& Get()
  {
    static ErrorLog log;
    return log;
  }

  static void OnError(vtkObject*, unsigned long, void*, void* callData)
  {
    // The text is "ERROR: In file, line n\nvtkClass (0x...): message": keep its last line.
    std::string text = callData ? static_cast<const char*>(callData) : "";
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
    {
      text.pop_back();
    }
    const std::size_t cut = text.rfind('\n');
    if (cut != std::string::npos)
    {
      text = text.substr(cut + 1);
    }
    ErrorLog& log = Get();
    const std::lock_guard<std::mutex> guard(log.Lock);
    log.Recent.emplace_back(++log.Count, text);
    if (log.Recent.size() > 16)
    {
      log.Recent.pop_front();
    }
  }

  // Observes the output window in use (once per instance).
  void Observe()
  {
    vtkOutputWindow* window = vtkOutputWindow::GetInstance();
    const std::lock_guard<std::mutex> guard(Lock);
    if (window == Window.GetPointer() || !window)
    {
      return;
    }
    vtkNew<vtkCallbackCommand> callback;
    callback->SetCallback(&ErrorLog::OnError);
    window->AddObserver(vtkCommand::ErrorEvent, callback);
    Window = window;
  }

  // Forgets the records of deleted or modified objects: their errors can no longer apply, and a
  // long session that updates many pipelines keeps only what may still be asked for.
  void Prune()
  {
    Failed.erase(std::remove_if(Failed.begin(), Failed.end(),
                   [](const FailedInput& f) { return !f.Object || f.Object->GetMTime() != f.MTime; }),
      Failed.end());
  }

  FailedInput* Find(vtkDataObject* input)
  {
    const auto found =
      std::find_if(Failed.begin(), Failed.end(), [input](const FailedInput& f) { return f.Object == input; });
    return found == Failed.end() ? nullptr : &*found;
  }
};

} // namespace

void UpstreamErrorWatch::Arm()
{
  ErrorLog& log = ErrorLog::Get();
  log.Observe();
  const std::lock_guard<std::mutex> guard(log.Lock);
  this->Mark = log.Count;
  this->Armed = true;
}

std::string UpstreamErrorWatch::Check(const std::vector<vtkDataObject*>& inputs)
{
  ErrorLog& log = ErrorLog::Get();
  const std::lock_guard<std::mutex> guard(log.Lock);
  std::string error;
  if (this->Armed)
  {
    // Every error since Arm() (the last 16 at most): a reader's own summary often follows the
    // error of a part of it that failed first.
    for (const auto& entry : log.Recent)
    {
      if (entry.first > this->Mark)
      {
        error += (error.empty() ? "" : "; ") + entry.second;
      }
    }
    this->Armed = false;
  }
  log.Prune();
  for (vtkDataObject* input : inputs)
  {
    if (!input)
    {
      continue;
    }
    FailedInput* recorded = log.Find(input);
    if (!error.empty())
    {
      if (recorded)
      {
        recorded->MTime = input->GetMTime();
        recorded->Error = error;
      }
      else
      {
        log.Failed.push_back({ input, input->GetMTime(), error });
      }
      continue;
    }
    if (recorded)
    {
      error = recorded->Error; // unchanged since it failed: Prune() dropped it otherwise
    }
  }
  return error;
}

}
