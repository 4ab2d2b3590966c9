// What the subcommands (glint render, merge, farm) share on their command line: -h/--help
// prints the usage (exit 0), a bad argument is reported with the usage (exit 2).
#pragma once

#include <cstdio>
#include <string>

#include "renderer/parse_number.h"

namespace glint {

struct UsageError {
  std::string message;
};

// An integer option's value from lo to hi (renderer/parse_number.h); throws UsageError naming
// the option and the range.
inline long parse_integer_option(const std::string& option, const std::string& text, long lo, long hi) {
  if (const std::optional<long> v = parse_integer(text, lo, hi)) return *v;
  throw UsageError{integer_expected(option, lo, hi, text)};
}

// One argument of a command whose options are tables (glint render, glint farm): `flags` of
// (name, void set(Options&)) and `values` of (name, void set(Options&, option as typed, value)).
// Sets argv[i] in `options` when it is one of them (an option with a value takes argv[i + 1]
// and advances i) and returns true; throws UsageError for any other argument that starts with
// '-', and returns false for the rest (the command's positional arguments).
template <class Options, class Flags, class Values>
bool parse_table_option(Options& options, const Flags& flags, const Values& values, int argc, char** argv,
                        int& i) {
  const std::string a = argv[i];
  for (const auto& [name, set] : flags)
    if (a == name) {
      set(options);
      return true;
    }
  for (const auto& [name, set] : values)
    if (a == name) {
      if (i + 1 >= argc) throw UsageError{a + " needs a value"};
      set(options, a, argv[++i]);
      return true;
    }
  if (!a.empty() && a[0] == '-') throw UsageError{"unknown option " + a};
  return false;
}

// Fills `options` from `parse(argc, argv)` (which throws UsageError) and returns -1 to go on,
// or the exit code once the help or a usage error has been printed.
template <class Options, class Parse>
int parse_command_line(const char* command, const char* usage, int argc, char** argv, Parse parse,
                       Options& options) {
  for (int i = 0; i < argc; ++i)
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help") {
      std::fputs(usage, stdout);
      return 0;
    }
  try {
    options = parse(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\n\n%s", command, e.message.c_str(), usage);
    return 2;
  }
  return -1;
}

}  // namespace glint
