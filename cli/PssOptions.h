// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PssOptions.h
 * @brief A small declarative flag parser for the `pss` subcommands: every flag is declared once
 *        with its help text and default, and --help is generated from those declarations.
 */
#ifndef PssOptions_h
#define PssOptions_h

#include <functional>
#include <string>
#include <utility>
#include <vector>

class vtkPointSetSurface;

namespace pss_cli
{

/// Thrown for bad command lines; main() prints the message and exits with status 2.
struct UsageError
{
  std::string message;
};

class OptionTable
{
public:
  /// A flag taking a value: --name VALUE (or --name=VALUE).
  void Value(const std::string& name, const std::string& hint, const std::string& help,
    std::function<void(const std::string&)> apply);
  /// A switch without value: --name.
  void Switch(const std::string& name, const std::string& help, std::function<void()> apply);

  /// Applies every flag in @p args; returns the positional arguments. Throws UsageError.
  std::vector<std::string> Parse(const std::vector<std::string>& args) const;

  /// One line per flag: "  --name HINT   help".
  std::string Help() const;

private:
  struct Entry
  {
    std::string name;
    std::string hint; // empty for switches
    std::string help;
    std::function<void(const std::string&)> apply;
  };
  std::vector<Entry> Entries;
};

/// Strict conversions for flag values; they throw UsageError naming the flag.
double ToDouble(const std::string& flag, const std::string& text);
int ToInt(const std::string& flag, const std::string& text);
/// A number within [@p lo, @p hi] (@p unit, e.g. " (in units of h)", is said in the message): the
/// filters clamp (VTK's convention), the command line refuses what they would change
/// (std::runtime_error naming the flag and the range).
double ToNumberIn(const std::string& flag, const std::string& text, double lo, double hi, const std::string& unit = "");

/// The surface definition's flags (--variant, --h, the kernel, APSS's and RIMLS's parameters),
/// setting @p s (PssSurfaceOptions.cxx).
void AddSurfaceOptions(OptionTable& t, vtkPointSetSurface* s);
/// "NX,NY,NZ" (or "NX,NY" for NZ = 1).
void ToDimensions(const std::string& flag, const std::string& text, int dims[3]);
/// "WxH", each in [1, @p largest]: an image's pixels across and down (width, height).
std::pair<int, int> ToImageSize(const std::string& flag, const std::string& text, int largest);
/// Index of @p text in @p names (case-insensitive, '-' and '_' equivalent).
int ToChoice(const std::string& flag, const std::string& text, const std::vector<std::string>& names);

}

#endif
