// SPDX-License-Identifier: BSD-3-Clause
// The command line of the example programs: long GNU-style options ("--name VALUE" or
// "--name=VALUE"), flags, --help, and exit status 2 for a bad command line.
#ifndef SplatCommandLine_h
#define SplatCommandLine_h

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatexample
{
/// Thrown for a bad command line (exit status 2); std::runtime_error for bad data (status 1).
struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Takes an option's name (for messages) and its value.
using OptionHandler = std::function<void(const std::string& name, const std::string& value)>;

/// Hands each option's value to its handler, runs the flags (options without a value), prints
/// `usage` and exits for --help, and hands the other arguments to `positional`. Without
/// `positional` every argument must be an option.
inline void ParseArguments(int argc, char* argv[], const char* usage,
  const std::map<std::string, OptionHandler>& options,
  const std::map<std::string, std::function<void()>>& flags = {},
  const std::function<void(const std::string&)>& positional = nullptr)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument == "--help")
    {
      std::cout << usage;
      std::exit(EXIT_SUCCESS);
    }
    const auto flag = flags.find(argument);
    if (flag != flags.end())
    {
      flag->second();
      continue;
    }
    if (positional && (argument.size() < 2 || argument[0] != '-'))
    {
      positional(argument);
      continue;
    }
    const auto equals = argument.find('=');
    const std::string name = argument.substr(0, equals);
    const auto handler = options.find(name);
    if (handler == options.end())
    {
      // Where only options are allowed, any unknown word is an unknown argument.
      throw UsageError(std::string(positional ? "unknown option '" : "unknown argument '") + name +
        "' (see --help)");
    }
    if (equals == std::string::npos && i + 1 == argc)
    {
      throw UsageError(name + " needs a value (see --help)");
    }
    handler->second(name, equals == std::string::npos ? argv[++i] : argument.substr(equals + 1));
  }
}

/// A whole number from `low` to `high` in decimal.
inline long long ParseCount(
  const std::string& option, const std::string& text, long long low, long long high)
{
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < low || value > high)
  {
    throw UsageError(option + ": expected a whole number from " + std::to_string(low) + " to " +
      std::to_string(high) + ", got '" + text + "'");
  }
  return value;
}

/// A comma-separated list of names, each one of `allowed`.
inline std::vector<std::string> SplitList(
  const std::string& option, const std::string& text, const std::vector<std::string>& allowed)
{
  std::vector<std::string> items;
  std::istringstream fields(text);
  std::string item;
  while (std::getline(fields, item, ','))
  {
    if (std::find(allowed.begin(), allowed.end(), item) == allowed.end())
    {
      std::string names;
      for (const auto& name : allowed)
      {
        names += (names.empty() ? "" : ", ") + name;
      }
      throw UsageError(option + ": unknown '" + item + "' (choose from " + names + ")");
    }
    items.push_back(item);
  }
  if (items.empty())
  {
    throw UsageError(option + ": the list is empty");
  }
  return items;
}

/// Runs a program's body and turns its exceptions into a message on stderr and the exit status:
/// 2 for a UsageError, 1 for any other.
inline int RunProgram(const char* program, const std::function<int()>& body)
{
  try
  {
    return body();
  }
  catch (const UsageError& e)
  {
    std::cerr << program << ": " << e.what() << "\n";
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << program << ": error: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
}
}

#endif
