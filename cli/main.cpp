// panelrad command-line program: dispatches sub-commands (CLI11 sub-commands of one App).
#include "commands.hpp"
#include "hints.hpp"
#include "options.hpp"

#include <panelrad/support/version.hpp>

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>
#include <vector>

namespace {
const char* kUsage =
    "usage: panelrad <command> [options]\n"
    "commands:\n"
    "  check MESH | check --builtin cube|prism:K|tetrahedron|octahedron\n"
    "      validate a closed convex polyhedral mesh (OFF or OBJ)\n"
    "  cube [options]   the paper's cube example (Table 1; --help for options)\n"
    "  solve SCENE [options]   solve an OBJ+MTL or OFF+JSON scene, write CSV/PLY/VTK/PNG (--help)\n"
    "  version\n"
    "  help [COMMAND]\n";

std::string quoted(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) s += (s.empty() ? "'" : " '") + a + "'";
  return s;
}

/// The arguments no option or positional took, in command-line order (CLI11's own message
/// lists them in reverse): the first one as an unknown option, or as an unexpected argument
/// after the positional arguments already taken.
std::string describe_extras(const CLI::App& command, const std::vector<std::string>& extras) {
  const std::string& first = extras.front();
  std::string what;
  if (first.size() > 1 && first[0] == '-') {
    what = "unknown option '" + first + "'";
  } else {
    what = "unexpected argument '" + first + "'";
    for (const CLI::Option* p : command.get_options([](const CLI::Option* o) { return o->get_positional(); }))
      if (p->count() > 0) what += " after " + p->get_name() + " '" + p->results().front() + "'";
  }
  if (extras.size() > 1) what += " (not taken: " + quoted(extras) + ")";
  return what;
}
}  // namespace

int main(int argc, char** argv) {
  using panelrad::cli::Command;
  CLI::App panelrad{"", "panelrad"};
  panelrad::cli::set_usage(panelrad, kUsage);
  // One command; a further command name is then an argument of the first (an error).
  panelrad.require_subcommand(0, 1);
  const std::vector<Command> commands = {panelrad::cli::add_check(panelrad), panelrad::cli::add_cube(panelrad),
                                         panelrad::cli::add_solve(panelrad)};
  const std::string version_line = "panelrad " + panelrad::version();
  CLI::App* version = panelrad.add_subcommand("version", "the program's version");
  CLI::App* help = panelrad.add_subcommand("help", "the commands, or one command's options");
  std::string help_topic;  // panelrad help COMMAND: that command's usage, as COMMAND --help
  help->add_option("COMMAND", help_topic)->check(panelrad::cli::one_of({"check", "cube", "solve"}));
  panelrad.set_version_flag("--version", version_line);

  try {
    panelrad.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const std::vector<CLI::App*> given = panelrad.get_subcommands();
    const CLI::App& command = given.empty() ? panelrad : *given.front();
    if (dynamic_cast<const CLI::CallForVersion*>(&e)) {
      std::cout << e.what() << "\n";
      return 0;
    }
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {  // --help
      std::cout << command.help();
      return 0;
    }
    std::string message = e.what();
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
      std::vector<std::string> extras = command.remaining();
      if (extras.empty()) extras = panelrad.remaining();  // after "--", back at the top
      if (given.empty()) {
        std::cerr << "panelrad: unknown command '" << extras.front() << "'\n" << kUsage;
        return 2;
      }
      message = describe_extras(command, extras);
    }
    std::cerr << (given.empty() ? std::string("panelrad") : "panelrad " + command.get_name()) << ": " << message
              << "\n"
              << command.help();
    return 2;
  }
  if (version->parsed()) {
    std::cout << version_line << "\n";
    return 0;
  }
  if (help->parsed()) {
    std::cout << (help_topic.empty() ? std::string(kUsage) : panelrad.get_subcommand(help_topic)->help());
    return 0;
  }
  for (const Command& c : commands) {
    if (!c.app->parsed()) continue;
    const std::string name = c.app->get_name();
    try {
      return c.run();
    } catch (const panelrad::cli::UsageError& e) {
      std::cerr << "panelrad " << name << ": " << e.what() << "\n" << c.app->help();
      return 2;
    } catch (const std::exception& e) {
      std::cerr << "panelrad " << name << ": error: " << e.what() << "\n";
      if (const std::string hint = panelrad::cli::hint_for(e); !hint.empty())
        std::cerr << "panelrad " << name << ": " << hint << "\n";
      return 1;
    }
  }
  std::cerr << kUsage;  // no command
  return 2;
}
