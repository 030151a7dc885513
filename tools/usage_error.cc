#include "tools/usage_error.h"

#include <cctype>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "core/closest_name.h"
#include "core/errors.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

/// The first word of the command line that is neither an option nor --config's value: what
/// the user meant as the subcommand ("" when there is none).
std::string FirstWord(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--config") == 0) {
      ++i;
    } else if (argv[i][0] != '-') {
      return argv[i];
    }
  }
  return {};
}

/// The subcommand the command line named, or nullptr before one was recognised.
const CLI::App* ChosenCommand(const CLI::App& app) {
  const std::vector<CLI::App*> chosen = app.get_subcommands();
  return chosen.empty() ? nullptr : chosen.front();
}

/// The long options `command` takes, its own and the global ones it hands to the app.
std::vector<std::string> LongOptions(const CLI::App& app, const CLI::App* command) {
  std::vector<std::string> names;
  for (const CLI::App* a : {command, &app}) {
    if (a == nullptr) continue;
    for (const CLI::Option* option : a->get_options()) {
      for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    }
  }
  return names;
}

/// "unknown option '--outt' (did you mean '--out'?)" for the first option CLI11 left unparsed,
/// or "". CLI11 checks required options before it names extras, so without this a mistyped
/// `--out` was reported as "--out is required". After an unknown subcommand, "" (its options
/// are unknown only because it is).
std::string UnknownOption(const CLI::App& app, int argc, char** argv) {
  if (ChosenCommand(app) == nullptr && !FirstWord(argc, argv).empty()) return {};
  for (const std::string& arg : app.remaining(true)) {
    // Options only: a positional left over, "-", or a negative number is CLI11's to report.
    if (arg.size() < 2 || arg[0] != '-' || std::isdigit(static_cast<unsigned char>(arg[1])) ||
        arg[1] == '.') {
      continue;
    }
    const std::string name = arg.substr(0, arg.find('='));
    return "unknown option '" + name + "'" +
           (name.rfind("--", 0) == 0 ? DidYouMean(name, LongOptions(app, ChosenCommand(app)))
                                     : std::string());
  }
  return {};
}

/// CLI11's message, or the unknown subcommand (CLI11 says "A subcommand is required") with the
/// closest known one.
std::string ParseErrorText(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  const std::string word = FirstWord(argc, argv);
  if (word.empty() || ChosenCommand(app) != nullptr) return e.what();
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->check_name(word)) return e.what();
    commands.push_back(sub->get_name());
  }
  return "unknown subcommand '" + word + "'" + DidYouMean(word, commands);
}

/// A command-line error, pointing to the help of the command it is about.
int Usage(const CLI::App& app, const std::string& what) {
  const CLI::App* command = ChosenCommand(app);
  std::cerr << "uwbsar: error: " << what << " (see uwbsar "
            << (command ? command->get_name() + " " : std::string()) << "--help)\n";
  return kExitUsage;
}

}  // namespace

int ReportError(const CLI::App& app, int argc, char** argv) {
  const std::string unknown = UnknownOption(app, argc, argv);
  try {
    throw;
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return Usage(app, unknown.empty() ? ParseErrorText(app, e, argc, argv) : unknown);
  } catch (const InputError& e) {
    // An option's value checked (an input path) before CLI11 came to the unknown option.
    if (!unknown.empty()) return Usage(app, unknown);
    std::cerr << "uwbsar: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "uwbsar: error: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace uwbsar::tools
